//! Follower pressure: a pressure acting on the deformed surface
//! ([`Load::FollowerPressure`], deck `pressure .. { p = ..  follower = true
//! }`), as Abaqus applies `*DSLOAD` pressure under NLGEOM and as the
//! blow-forming and hydroforming examples need (the gas pressure follows
//! the sheet).
//!
//! The consistent nodal forces on the current configuration `x = X + u`:
//!
//! - solid faces: `f_a = -p int N_a (x_xi x x_eta) dxi deta` (the face's
//!   area normal, outward for faces counter-clockwise seen from outside);
//! - planar edges `a -> b` (body on the left): `f_a = p int N_a m J x_xi
//!   dxi` with `J x_xi = (-y_xi, x_xi)` the inward normal times the length
//!   element and `m` the thickness (plane) or `2 pi r` (axisymmetric, `r =
//!   sum N_c x_c` on the deformed edge).
//!
//! Both are differentiated exactly (the load stiffness): with `skew(v) d =
//! v x d`, `d f_a / d x_b = -p int N_a (-N_b,xi skew(x_eta) + N_b,eta
//! skew(x_xi))` on faces and `p int N_a (m N_b,xi J + 2 pi N_b (J x_xi) (x)
//! e_r)` on axisymmetric edges. The load stiffness is not symmetric, so a
//! model with a follower pressure is solved with the non-symmetric
//! factorization. It enters the free-free block only: a prescribed facet
//! node's column is left out of `K_fp`, which changes the first iteration's
//! predictor of a moving boundary, not the converged state.
//!
//! Under a distributed assembly ([`super::share`], `ctc run --solver petsc`
//! on several MPI ranks) a facet is evaluated by one rank, the rank of its
//! cell ([`FollowerShare`]), as an element is: it adds the facet's forces
//! and the load stiffness of all its rows (its cell's couplings are in
//! that rank's pattern), and the forces are summed over the ranks on the
//! facets' dofs only ([`FollowerShare::sum`]: the same bits on every rank).
//! A node's force is the serial run's bits when all its facets are one
//! rank's (the rank sums them in the serial order and the other ranks add
//! 0); a node on the partition boundary with three or more facets (3D)
//! may get the partial sums in another order, a difference of the order
//! of one rounding of its force (`two_ranks_sum_to_the_serial_forces`).

use super::dofs::{Dof, DofMap};
use super::linalg::{Scatter, MAX_BLOCK, NO_SLOT};
use crate::element::reference::{Quad4, Quad8, Quad9, ReferenceCell, Tri3, Tri6};
use crate::model::{AnalysisKind, Load, Model};
use crate::solve::share::AssemblyShare;

/// Whether `model` has a follower pressure.
pub fn has_follower<const D: usize>(model: &Model<D>) -> bool {
    model
        .loads
        .iter()
        .any(|l| matches!(l, Load::FollowerPressure { .. }))
}

/// The follower facets one rank evaluates under a distributed assembly
/// split over ranks, and the dofs their forces are summed over.
///
/// A facet belongs to the lowest-numbered cell holding all its nodes (a
/// boundary facet has one; the rule only has to give every rank the same
/// answer) and is evaluated by the rank assembling that cell, whose
/// pattern holds the facet's couplings. A facet of no cell (not made by
/// the deck's sets) goes to the owner of its first node; its load
/// stiffness then lacks the entries missing from that rank's pattern.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct FollowerShare {
    /// Per load of the model, per facet: whether this rank evaluates it
    /// (empty for the other loads).
    mine: Vec<Vec<bool>>,
    /// Global dofs (`D node + c`) of every follower facet's nodes, sorted
    /// and unique: the entries of the force vector summed over the ranks.
    dofs: Vec<usize>,
}

impl FollowerShare {
    /// The facets of `model`'s follower pressures that the rank of `share`
    /// evaluates.
    pub fn new<const D: usize>(model: &Model<D>, share: &AssemblyShare) -> Self {
        let cells = &model.mesh.cells;
        // cells around each node (CSR), for the facets' cells
        let nn = model.mesh.nodes.len();
        let mut start = vec![0usize; nn + 1];
        for c in 0..cells.len() {
            for &n in cells.nodes(c) {
                start[n + 1] += 1;
            }
        }
        for n in 0..nn {
            start[n + 1] += start[n];
        }
        let mut at = start.clone();
        let mut around = vec![0usize; start[nn]];
        for c in 0..cells.len() {
            for &n in cells.nodes(c) {
                around[at[n]] = c;
                at[n] += 1;
            }
        }
        let mut dofs = Vec::new();
        let mine = model
            .loads
            .iter()
            .map(|load| {
                let Load::FollowerPressure { facets, .. } = load else {
                    return Vec::new();
                };
                facets
                    .iter()
                    .map(|facet| {
                        let nodes = facet.nodes();
                        dofs.extend(nodes.iter().flat_map(|&n| (0..D).map(move |c| D * n + c)));
                        // cells are listed increasing around a node: the
                        // first holding every facet node is the lowest
                        let cell = around[start[nodes[0]]..start[nodes[0] + 1]]
                            .iter()
                            .copied()
                            .find(|&c| nodes.iter().all(|n| cells.nodes(c).contains(n)));
                        match cell {
                            Some(c) => share.owns_cell(c),
                            None => share.owns_node(nodes[0]),
                        }
                    })
                    .collect()
            })
            .collect();
        dofs.sort_unstable();
        dofs.dedup();
        FollowerShare { mine, dofs }
    }

    /// Whether this rank evaluates facet `k` of load `load`.
    #[inline]
    pub fn evaluates(&self, load: usize, k: usize) -> bool {
        self.mine
            .get(load)
            .and_then(|m| m.get(k))
            .copied()
            .unwrap_or(false)
    }

    /// Number of facets this rank evaluates.
    pub fn facets(&self) -> usize {
        self.mine.iter().flatten().filter(|&&m| m).count()
    }

    /// Sums the rank's partial forces `f` (`D` per node) over the ranks on
    /// the facets' dofs: packs them, calls `sum` (the linear system's
    /// `sum_over_ranks`, collective) and unpacks the totals.
    pub fn sum(&self, f: &mut [f64], sum: impl FnOnce(&mut [f64])) {
        let mut packed: Vec<f64> = self.dofs.iter().map(|&g| f[g]).collect();
        sum(&mut packed);
        for (&g, v) in self.dofs.iter().zip(&packed) {
            f[g] = *v;
        }
    }
}

/// Adds to `f` (`D` per node) the nodal forces of every follower pressure
/// of `model` at time `t` on the configuration `X + u`, load `i` scaled by
/// `scales[i]` (a pressure controller's factor; 1 when absent); with
/// `tangent`, subtracts their derivative `d f / d u` from the free-free
/// entries of the tangent `values` (the residual is `f_int - f_ext - ..`).
/// With `share`, only the facets this rank evaluates (the partial forces
/// to sum over the ranks, [`FollowerShare::sum`]).
pub fn add_follower_forces<const D: usize>(
    model: &Model<D>,
    t: f64,
    scales: &[f64],
    u: &[[f64; D]],
    f: &mut [f64],
    mut tangent: Option<(&Scatter, &DofMap<D>, &mut [f64])>,
    share: Option<&FollowerShare>,
) {
    let measure = Measure::of(model);
    for (i, load) in model.loads.iter().enumerate() {
        let Load::FollowerPressure { facets, value, .. } = load else {
            continue;
        };
        let p = value.eval(t) * scales.get(i).copied().unwrap_or(1.0);
        if p == 0.0 {
            continue;
        }
        for (k, facet) in facets.iter().enumerate() {
            if share.is_some_and(|s| !s.evaluates(i, k)) {
                continue;
            }
            let nodes = facet.nodes();
            let x: Vec<[f64; D]> = nodes
                .iter()
                .map(|&n| std::array::from_fn(|c| model.mesh.nodes[n][c] + u[n][c]))
                .collect();
            let Some((fe, ke)) = facet_force(measure, &x, p) else {
                continue;
            };
            let nn = nodes.len();
            for (a, &na) in nodes.iter().enumerate() {
                for c in 0..D {
                    f[D * na + c] += fe[D * a + c];
                }
            }
            let Some((scatter, dofs, values)) = tangent.as_mut() else {
                continue;
            };
            for (a, &na) in nodes.iter().enumerate() {
                for (b, &nb) in nodes.iter().enumerate() {
                    // facet nodes share a cell: the block is in the
                    // pattern (split over ranks: the pattern of the rank
                    // assembling that cell, the one evaluating the facet)
                    let Some(slots) = block_slots(scatter, dofs, na, nb) else {
                        continue;
                    };
                    for j in 0..D {
                        for i in 0..D {
                            let s = slots[i + D * j];
                            if s != NO_SLOT {
                                values[s as usize] -= ke[(D * a + i) * nn * D + D * b + j];
                            }
                        }
                    }
                }
            }
        }
    }
}

/// The free-free slots of the `D x D` block of rows of node `a` and
/// columns of node `b`, column-major (`i + D j`), searched in the pattern
/// (`NO_SLOT` for a prescribed or inactive dof; `None` if a free-free entry
/// is missing). Unlike [`Scatter::pair_slots`] a node's self block too:
/// under a distributed assembly that one gives the node's owner alone its
/// self block (contact rows), while a facet's rows are all added by the
/// rank of its cell, as the cell's element rows are.
fn block_slots<const D: usize>(
    scatter: &Scatter,
    dofs: &DofMap<D>,
    a: usize,
    b: usize,
) -> Option<[u32; MAX_BLOCK]> {
    let mut out = [NO_SLOT; MAX_BLOCK];
    for j in 0..D {
        for i in 0..D {
            if let (Dof::Free(r), Dof::Free(c)) = (dofs.dofs[D * a + i], dofs.dofs[D * b + j]) {
                out[i + D * j] = u32::try_from(scatter.pattern.find(r, c)?).ok()?;
            }
        }
    }
    Some(out)
}

/// The measure of a planar edge: thickness or the ring `2 pi r`; solids
/// integrate over faces.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Measure {
    /// Plane strain / stress: the out-of-plane thickness.
    Thickness(f64),
    /// Axisymmetric: `2 pi r` on the deformed edge (totals over the ring).
    Ring,
    /// Solid faces.
    Area,
}

impl Measure {
    /// The measure of `model`'s facets.
    pub fn of<const D: usize>(model: &Model<D>) -> Self {
        match model.analysis.kind {
            AnalysisKind::Solid => Measure::Area,
            AnalysisKind::Axisymmetric => Measure::Ring,
            AnalysisKind::PlaneStrain | AnalysisKind::PlaneStress => {
                Measure::Thickness(model.analysis.thickness)
            }
        }
    }
}

/// The nodal forces `fe` (`D` per facet node) of the pressure `p` on the
/// facet with current node positions `x` (planar edges: 2 or 3 nodes
/// `[a, b, m]`; solid faces: 3, 4, 6, 8 or 9 nodes) and their derivative
/// `ke[(D a + i) * (n D) + D b + j] = d fe[D a + i] / d x_b[j]`; `None` for
/// a node count the facet kinds do not have (refused by `check_model`).
pub fn facet_force<const D: usize>(
    measure: Measure,
    x: &[[f64; D]],
    p: f64,
) -> Option<(Vec<f64>, Vec<f64>)> {
    let nd = x.len() * D;
    let mut fe = vec![0.0; nd];
    let mut ke = vec![0.0; nd * nd];
    match (D, x.len(), measure) {
        (2, 2 | 3, Measure::Thickness(_) | Measure::Ring) => {
            edge(measure, x, p, &mut fe, &mut ke);
        }
        (3, 3, Measure::Area) => face::<D, 3, Tri3>(x, p, &mut fe, &mut ke),
        (3, 4, Measure::Area) => face::<D, 4, Quad4>(x, p, &mut fe, &mut ke),
        (3, 6, Measure::Area) => face::<D, 6, Tri6>(x, p, &mut fe, &mut ke),
        (3, 8, Measure::Area) => face::<D, 8, Quad8>(x, p, &mut fe, &mut ke),
        (3, 9, Measure::Area) => face::<D, 9, Quad9>(x, p, &mut fe, &mut ke),
        _ => return None,
    }
    Some((fe, ke))
}

/// A planar edge of 2 nodes `[a, b]` or 3 nodes `[a, b, m]` (3-point Gauss:
/// exact for the polynomial integrands of straight and curved edges of
/// either order in plane analyses, and of straight ones axisymmetric).
fn edge<const D: usize>(measure: Measure, x: &[[f64; D]], p: f64, fe: &mut [f64], ke: &mut [f64]) {
    let n = x.len();
    let nd = n * D;
    let g = (0.6f64).sqrt();
    for (xi, w) in [(-g, 5.0 / 9.0), (0.0, 8.0 / 9.0), (g, 5.0 / 9.0)] {
        let (sh, dsh): (Vec<f64>, Vec<f64>) = if n == 2 {
            (vec![0.5 * (1.0 - xi), 0.5 * (1.0 + xi)], vec![-0.5, 0.5])
        } else {
            (
                vec![0.5 * xi * (xi - 1.0), 0.5 * xi * (xi + 1.0), 1.0 - xi * xi],
                vec![xi - 0.5, xi + 0.5, -2.0 * xi],
            )
        };
        let (mut tan, mut r) = ([0.0; 2], 0.0);
        for a in 0..n {
            tan[0] += dsh[a] * x[a][0];
            tan[1] += dsh[a] * x[a][1];
            r += sh[a] * x[a][0];
        }
        let two_pi = 2.0 * std::f64::consts::PI;
        let m = match measure {
            Measure::Thickness(t) => t,
            Measure::Ring => two_pi * r,
            Measure::Area => return,
        };
        // J tan: the inward normal times the length element
        let jt = [-tan[1], tan[0]];
        for a in 0..n {
            for i in 0..2 {
                fe[D * a + i] += p * w * sh[a] * m * jt[i];
            }
            for b in 0..n {
                // d(J tan)/d x_b = dsh_b J, J = [[0, -1], [1, 0]]
                let jm = [[0.0, -1.0], [1.0, 0.0]];
                for i in 0..2 {
                    for j in 0..2 {
                        let mut d = m * dsh[b] * jm[i][j];
                        if measure == Measure::Ring && j == 0 {
                            d += two_pi * sh[b] * jt[i];
                        }
                        ke[(D * a + i) * nd + D * b + j] += p * w * sh[a] * d;
                    }
                }
            }
        }
    }
}

/// A solid face with the reference cell `C` (its own quadrature).
fn face<const D: usize, const NN: usize, C: ReferenceCell<2, NN>>(
    x: &[[f64; D]],
    p: f64,
    fe: &mut [f64],
    ke: &mut [f64],
) {
    let nd = NN * D;
    let skew = |v: [f64; 3]| [[0.0, -v[2], v[1]], [v[2], 0.0, -v[0]], [-v[1], v[0], 0.0]];
    for (xi, w) in C::QUADRATURE {
        let (sh, g) = (C::shape(xi), C::gradients(xi));
        let mut t = [[0.0; 3]; 2];
        for a in 0..NN {
            for (k, tk) in t.iter_mut().enumerate() {
                for c in 0..3 {
                    tk[c] += g[a][k] * x[a][c];
                }
            }
        }
        let [t1, t2] = t;
        let area_normal = [
            t1[1] * t2[2] - t1[2] * t2[1],
            t1[2] * t2[0] - t1[0] * t2[2],
            t1[0] * t2[1] - t1[1] * t2[0],
        ];
        let (s1, s2) = (skew(t1), skew(t2));
        for a in 0..NN {
            for i in 0..3 {
                fe[D * a + i] -= p * w * sh[a] * area_normal[i];
            }
            for b in 0..NN {
                for i in 0..3 {
                    for j in 0..3 {
                        let d = -g[b][0] * s2[i][j] + g[b][1] * s1[i][j];
                        ke[(D * a + i) * nd + D * b + j] -= p * w * sh[a] * d;
                    }
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Central differences of `facet_force` against its `ke`.
    fn fd_error<const D: usize>(measure: Measure, x: &[[f64; D]], p: f64) -> f64 {
        let (f0, ke) = facet_force(measure, x, p).unwrap();
        let nd = x.len() * D;
        let h = 1e-6;
        let (mut err, mut scale) = (0.0f64, 0.0f64);
        for b in 0..x.len() {
            for j in 0..D {
                let mut xp = x.to_vec();
                let mut xm = x.to_vec();
                xp[b][j] += h;
                xm[b][j] -= h;
                let (fp, _) = facet_force(measure, &xp, p).unwrap();
                let (fm, _) = facet_force(measure, &xm, p).unwrap();
                for r in 0..nd {
                    let fd = (fp[r] - fm[r]) / (2.0 * h);
                    let k = ke[r * nd + D * b + j];
                    err = err.max((fd - k).abs());
                    scale = scale.max(k.abs());
                }
            }
        }
        assert!(f0.iter().all(|v| v.is_finite()));
        err / scale
    }

    #[test]
    fn load_stiffness_matches_finite_differences_on_every_facet_kind() {
        // distorted, curved facets; the pressure's sign does not matter
        let e2 = [[1.0, 0.2], [1.3, 1.1]];
        let e3 = [[1.0, 0.2], [1.3, 1.1], [1.25, 0.6]];
        for m in [Measure::Thickness(0.7), Measure::Ring] {
            assert!(fd_error::<2>(m, &e2, 3.0) < 1e-8, "{m:?} 2");
            assert!(fd_error::<2>(m, &e3, -2.0) < 1e-8, "{m:?} 3");
        }
        let corners = [
            [0.0, 0.0, 0.1],
            [1.2, 0.1, 0.0],
            [1.0, 0.9, 0.3],
            [0.1, 1.1, -0.1],
        ];
        let mid = |a: [f64; 3], b: [f64; 3], lift: f64| {
            [
                0.5 * (a[0] + b[0]),
                0.5 * (a[1] + b[1]),
                0.5 * (a[2] + b[2]) + lift,
            ]
        };
        let tri3 = [corners[0], corners[1], corners[2]];
        let tri6 = [
            corners[0],
            corners[1],
            corners[2],
            mid(corners[0], corners[1], 0.05),
            mid(corners[1], corners[2], -0.04),
            mid(corners[2], corners[0], 0.03),
        ];
        let mids = [
            mid(corners[0], corners[1], 0.05),
            mid(corners[1], corners[2], -0.04),
            mid(corners[2], corners[3], 0.03),
            mid(corners[3], corners[0], 0.02),
        ];
        let quad8: Vec<[f64; 3]> = corners.iter().chain(&mids).copied().collect();
        let mut quad9 = quad8.clone();
        quad9.push([0.55, 0.5, 0.2]);
        for face in [&tri3[..], &corners[..], &tri6[..], &quad8[..], &quad9[..]] {
            let e = fd_error::<3>(Measure::Area, face, 5.0);
            assert!(e < 1e-8, "{} nodes: {e:e}", face.len());
        }
    }

    #[test]
    fn pressure_on_a_closed_deformed_surface_has_no_resultant() {
        // a unit cube's six quad faces (outward, counter-clockwise seen from
        // outside), sheared: the forces of a uniform pressure sum to zero
        // and each face's resultant is -p times its area vector
        let v = |x: f64, y: f64, z: f64| [x + 0.3 * z, y + 0.1 * x, z];
        let c = [
            v(0., 0., 0.),
            v(1., 0., 0.),
            v(1., 1., 0.),
            v(0., 1., 0.),
            v(0., 0., 1.),
            v(1., 0., 1.),
            v(1., 1., 1.),
            v(0., 1., 1.),
        ];
        let faces = [
            [0, 3, 2, 1],
            [4, 5, 6, 7],
            [0, 1, 5, 4],
            [2, 3, 7, 6],
            [1, 2, 6, 5],
            [0, 4, 7, 3],
        ];
        let mut total = [0.0; 3];
        for f in faces {
            let x: Vec<[f64; 3]> = f.iter().map(|&i| c[i]).collect();
            let (fe, _) = facet_force(Measure::Area, &x, 2.0).unwrap();
            for a in 0..4 {
                for i in 0..3 {
                    total[i] += fe[3 * a + i];
                }
            }
        }
        assert!(total.iter().all(|t| t.abs() < 1e-14), "{total:?}");
        // the top face (z = 1, area 1 after the shear): -p e_z
        let top: Vec<[f64; 3]> = faces[1].iter().map(|&i| c[i]).collect();
        let (fe, _) = facet_force(Measure::Area, &top, 2.0).unwrap();
        let fz: f64 = (0..4).map(|a| fe[3 * a + 2]).sum();
        assert!((fz + 2.0).abs() < 1e-14, "{fz}");
    }

    #[test]
    fn two_ranks_sum_to_the_serial_forces() {
        // a 2 x 2 x 1 hex8 block under a follower pressure on its 4 bottom
        // faces (the middle node of the bottom carries all 4), on a
        // deformed state; the cells split over two ranks like a
        // checkerboard (rank 0: cells 0, 3; rank 1: cells 1, 2), each rank
        // its cells' facets (`FollowerShare`), the forces summed as the
        // MPI reduction does (rank 0's + rank 1's) and the tangents added
        // into the whole pattern (PETSc's ADD_VALUES)
        use crate::mesh::{Cell, Facet, Mesh};
        use crate::model::{Load, MaterialLaw, TimeFunction};
        use crate::solve::share::AssemblyShare;
        use std::sync::Arc;
        let n = |i: usize, j: usize, k: usize| i + 3 * j + 9 * k;
        let mut nodes = Vec::new();
        for k in 0..2 {
            for j in 0..3 {
                for i in 0..3 {
                    nodes.push([i as f64, j as f64, 0.5 * k as f64]);
                }
            }
        }
        let mut cells = Vec::new();
        let mut faces = Vec::new();
        for j in 0..2 {
            for i in 0..2 {
                cells.push(Cell::hex([
                    n(i, j, 0),
                    n(i + 1, j, 0),
                    n(i + 1, j + 1, 0),
                    n(i, j + 1, 0),
                    n(i, j, 1),
                    n(i + 1, j, 1),
                    n(i + 1, j + 1, 1),
                    n(i, j + 1, 1),
                ]));
                // outward (-z): counter-clockwise seen from below
                faces.push(Facet::new(&[
                    n(i, j, 0),
                    n(i, j + 1, 0),
                    n(i + 1, j + 1, 0),
                    n(i + 1, j, 0),
                ]));
            }
        }
        let model = crate::testkit::ModelBuilder::solid()
            .material(
                "m",
                MaterialLaw::LinearElastic {
                    young: 1.0,
                    poisson: 0.3,
                },
            )
            .body("b", Mesh::new(nodes, cells), "m")
            .load(Load::FollowerPressure {
                label: "p".into(),
                facets: faces,
                value: TimeFunction::Constant(1.7),
                control: None,
            })
            .build();
        let nn = model.mesh.nodes.len();
        let u: Vec<[f64; 3]> = (0..nn)
            .map(|a| {
                let s = a as f64;
                [
                    0.013 * (s * 0.7).sin(),
                    -0.021 * (s * 1.3).cos(),
                    0.017 * s.sqrt(),
                ]
            })
            .collect();
        let dofs = DofMap::new(&model);
        let whole = Scatter::new(&model.mesh, &dofs).unwrap();
        let mut f = vec![0.0; 3 * nn];
        let mut k = vec![0.0; whole.n_values()];
        let tangent = Some((&whole, &dofs, &mut k[..]));
        add_follower_forces(&model, 0.0, &[], &u, &mut f, tangent, None);
        let mut partial = Vec::new();
        let mut k_sum = vec![0.0; whole.pattern.nnz()];
        for cells in [[true, false, false, true], [false, true, true, false]] {
            let share = Arc::new(AssemblyShare {
                ranks: 2,
                cells: cells.to_vec(),
                nodes: (0..nn).map(|a| (a % 2 == 0) == cells[0]).collect(),
                exchanged: Vec::new(),
            });
            let fs = FollowerShare::new(&model, &share);
            assert_eq!(fs.facets(), 2);
            let scatter = Scatter::with_share(&model.mesh, &dofs, &[], Some(share)).unwrap();
            let mut fr = vec![0.0; 3 * nn];
            let mut kr = vec![0.0; scatter.n_values()];
            let tangent = Some((&scatter, &dofs, &mut kr[..]));
            add_follower_forces(&model, 0.0, &[], &u, &mut fr, tangent, Some(&fs));
            let p = &scatter.pattern;
            for j in 0..p.n {
                let range = p.col_ptr[j]..p.col_ptr[j + 1];
                for (&i, v) in p.row_idx[range.clone()].iter().zip(&kr[range]) {
                    k_sum[whole.pattern.find(i, j).unwrap()] += v;
                }
            }
            partial.push((fs, fr));
        }
        // the reduction over the packed facet dofs, as `sum_over_ranks`
        let packed: Vec<Vec<f64>> = partial
            .iter()
            .map(|(fs, fr)| {
                let mut v = Vec::new();
                fs.clone().sum(&mut fr.clone(), |p| v = p.to_vec());
                v
            })
            .collect();
        let total: Vec<f64> = packed[0]
            .iter()
            .zip(&packed[1])
            .map(|(a, b)| a + b)
            .collect();
        let mut f_sum = partial[0].1.clone();
        partial[0].0.sum(&mut f_sum, |v| v.copy_from_slice(&total));
        let scale = f.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let mut worst = 0.0f64;
        for a in 0..nn {
            let ranks_of_node: Vec<bool> = (0..4)
                .filter(|&c| model.mesh.cells.nodes(c)[..4].contains(&a) && a < 9)
                .map(|c| c == 0 || c == 3)
                .collect();
            for c in 0..3 {
                let (x, y) = (f_sum[3 * a + c], f[3 * a + c]);
                let one_rank = ranks_of_node.iter().all(|&r| r == ranks_of_node[0]);
                if one_rank {
                    // all its facets on one rank: the serial bits
                    assert_eq!(x.to_bits(), y.to_bits(), "node {a} component {c}");
                } else {
                    worst = worst.max((x - y).abs() / scale);
                }
            }
        }
        // the middle node's partial sums in another order: measured
        // 1.3e-16 of the largest force (`cargo test -p ctc-engine --lib
        // two_ranks_sum -- --nocapture`), about one rounding
        eprintln!("largest difference from the serial forces: {worst:e} of the largest force");
        assert!(worst <= 4.0 * f64::EPSILON, "{worst:e}");
        let k_scale = k.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        for (a, b) in k_sum.iter().zip(&k) {
            assert!((a - b).abs() <= 4.0 * f64::EPSILON * k_scale, "{a} vs {b}");
        }
        assert!(k_scale > 0.0 && scale > 0.0);
    }

    #[test]
    fn planar_edge_forces_total_p_times_length_or_ring_area() {
        // edge from (1, 0) to (1, 2), body on the left (x < 1): inward -x
        let x = [[1.0, 0.0], [1.0, 2.0]];
        let (fe, _) = facet_force(Measure::Thickness(0.5), &x, 3.0).unwrap();
        assert!((fe[0] + fe[2] + 3.0 * 2.0 * 0.5).abs() < 1e-14);
        let (fe, _) = facet_force(Measure::Ring, &x, 3.0).unwrap();
        let ring = 2.0 * std::f64::consts::PI * 1.0 * 2.0;
        assert!((fe[0] + fe[2] + 3.0 * ring).abs() < 1e-12);
        assert!(fe[1].abs() < 1e-14 && fe[3].abs() < 1e-14);
    }
}
