//! Mass redistribution at contact boundaries for implicit dynamics
//! (Khenous, Laborde & Renard 2008, "Mass redistribution method for
//! finite element contact problems in elastodynamics", Eur. J. Mech.
//! A/Solids 27:918; Hager, Hüeber & Wohlmuth 2008, "A stable energy
//! conserving approach for frictional contact problems based on
//! quadrature formulas", IJNME 73:205).
//!
//! A node on a contact surface that carries mass bounces: the unilateral
//! constraint switches within a time increment, the implicit integrator
//! sees an impulse it cannot represent, and the contact does positive
//! work (chatter, energy growth). With no mass on the contact nodes the
//! semi-discrete problem is a well-posed differential system (its
//! solution is Lipschitz in time), the contact nodes follow the
//! constraint quasi-statically, and the trapezoidal rule conserves the
//! energy of an impact up to the penalty spring's.
//!
//! Each cell with nodes on a contact surface gets the lumped mass of its
//! consistent matrix (row sums, HRZ where needed) with the contact nodes'
//! masses moved to its other nodes in proportion to their own: the cell's
//! mass is unchanged, so is the kinetic energy and momentum of every rigid
//! translation; the centre of mass moves inward by at most a cell, a
//! perturbation confined to one layer of cells that vanishes with the mesh
//! size. Cells away from contact keep the chosen mass (consistent or
//! lumped). A cell whose nodes are all on contact surfaces (a one-cell
//! layer in contact on both sides) keeps its lumped mass and is counted.
//!
//! Each body's centre of mass is then put back ([`restore_centre`]):
//! Khenous, Laborde & Renard ask the redistributed matrix to keep the
//! total mass, the centre of gravity and (where it can) the moments of
//! inertia. The per-cell shares above keep the mass; the first moment is
//! restored by the least change (weighted by the received mass) of the
//! masses the body's contact-layer nodes received, `delta_b = w_b (X_b -
//! X_w) . lambda`, which keeps the total. It stays within the contact
//! layer, and where that layer's receiving nodes cannot carry the missing
//! moment (they lie in a plane parallel to the contact face, as behind the
//! impact face of a bar: the shift is along the face's normal), or a
//! receiver would fall below its own lumped mass, the body keeps the
//! per-cell masses and the run's notes give the shift of its centre. Why
//! it matters: the one-cell-thick slice of `examples/blade_loss_3d.ctc`
//! has a released blade whose every node is a contact node (its cells keep
//! their lumped mass, its centre stays) while the other blades' tip and
//! side masses move to their middle nodes (their centres move inward): the
//! rotor was unbalanced from the first increment (orbit 4e-3 mm at the
//! release against 1e-7 mm in 2D).
//!
//! A body cut by symmetry planes (coordinate planes at its extent whose
//! nodes all have the normal displacement held at zero,
//! [`free_directions`]) is restored along the planes only: it is part of
//! its mirrored whole, whose centre stays on the planes, and its plane
//! nodes carry their share of the whole's masses, so the part's masses are
//! the whole's restricted to it. Restored along the normals too, a
//! quarter tube's centre (off the axis, moved inward) was put back by a
//! mass change linear in x and y, heaviest at 45 degrees: a perfect
//! quarter was not axisymmetric (issue 19).

use crate::element::kernel::lump;
use crate::model::{ContactMaster, Model, SurfaceShape, TimeFunction, ToolGeometry};
use ctc_geom::analytic::Analytic;

/// Replaces the `nn x nn` cell mass `m` (row-major) by its lumped mass
/// with the masses of the nodes flagged `massless` moved to the others in
/// proportion to their own. Returns false (and leaves the lumped mass)
/// when every node is flagged or the other nodes carry no mass.
pub fn redistribute(m: &mut [f64], nn: usize, massless: &[bool]) -> bool {
    lump(m, nn);
    let total: f64 = (0..nn).map(|a| m[a * nn + a]).sum();
    let kept: f64 = (0..nn)
        .filter(|&a| !massless[a])
        .map(|a| m[a * nn + a])
        .sum();
    if kept <= 0.0 {
        return false;
    }
    let scale = total / kept;
    for a in 0..nn {
        let d = &mut m[a * nn + a];
        *d = if massless[a] { 0.0 } else { *d * scale };
    }
    true
}

/// The lumped diagonal of `nn x nn` cell mass `m` (row-major) and the
/// mass [`redistribute`] moves from node `a` to node `b`, `moved[a * nn +
/// b]` (zero unless `a` is flagged and `b` is not).
pub fn moved_mass(m: &[f64], nn: usize, massless: &[bool]) -> Vec<f64> {
    let mut lumped = m.to_vec();
    lump(&mut lumped, nn);
    let kept: f64 = (0..nn)
        .filter(|&a| !massless[a])
        .map(|a| lumped[a * nn + a])
        .sum();
    let mut moved = vec![0.0; nn * nn];
    if kept <= 0.0 {
        return moved;
    }
    for a in (0..nn).filter(|&a| massless[a]) {
        for b in (0..nn).filter(|&b| !massless[b]) {
            moved[a * nn + b] = lumped[a * nn + a] * lumped[b * nn + b] / kept;
        }
    }
    moved
}

/// The correction of one body's redistributed masses that restores its
/// first moment `sum m_b X_b` ([`restore_centre`]).
#[derive(Debug, Clone, PartialEq)]
pub enum Centre {
    /// The redistribution moved the centre by less than 1e-12 of the
    /// body's size: left as it is.
    Unmoved,
    /// `delta_b / w_b = (X_b - X_w) . lambda`, per receiver (the order of
    /// the `receivers` given).
    Restored(Vec<f64>),
    /// The receivers cannot carry the missing moment (out of their span,
    /// or a receiver would lose more than it received): the shift of the
    /// centre of mass the redistribution leaves.
    Moved(f64),
}

/// The least change of the masses `w_b` the receiving nodes (reference
/// coordinates `x_b`) got from a body's contact nodes that adds the first
/// moment `missing` (the body's `sum m X` before the redistribution minus
/// after) and keeps their total: `delta_b = w_b (x_b - x_w) . lambda`,
/// `A lambda = missing`, `A = sum w_b (x_b - x_w) (x_b - x_w)^T`, `x_w`
/// the receivers' `w`-weighted centre (`A` pseudo-inverted: eigenvalues
/// below 1e-12 of the largest are a direction the receivers do not span).
/// `body_mass` scales the answer's shift; a shift below 1e-12 of `size`
/// (the body's extent) is left alone. Restored only when `A lambda`
/// matches `missing` to 1e-9 of its length (plus 1e-14 of `body_mass` times
/// the receivers' extent) and every receiver keeps at least its own lumped
/// mass (`(x_b - x_w) . lambda >= -1`).
pub fn restore_centre(
    receivers: &[(f64, Vec<f64>)],
    missing: &[f64],
    body_mass: f64,
    size: f64,
) -> Centre {
    let d = missing.len();
    let norm = |v: &[f64]| v.iter().map(|x| x * x).sum::<f64>().sqrt();
    let total: f64 = receivers.iter().map(|r| r.0).sum();
    let shift = if body_mass > 0.0 {
        norm(missing) / body_mass
    } else {
        0.0
    };
    if shift.is_nan() || shift <= 1e-12 * size {
        return Centre::Unmoved;
    }
    if total <= 0.0 || receivers.iter().any(|r| r.1.len() != d) {
        return Centre::Moved(shift);
    }
    let mut centre = vec![0.0; d];
    for (w, x) in receivers {
        for (c, x) in centre.iter_mut().zip(x) {
            *c += w * x;
        }
    }
    for c in &mut centre {
        *c /= total;
    }
    let mut a = nalgebra::DMatrix::<f64>::zeros(d, d);
    let mut extent = 0.0f64;
    for (w, x) in receivers {
        let r: Vec<f64> = x.iter().zip(&centre).map(|(x, c)| x - c).collect();
        for (p, rp) in r.iter().enumerate() {
            extent = extent.max(rp.abs());
            for (q, rq) in r.iter().enumerate() {
                a[(p, q)] += w * rp * rq;
            }
        }
    }
    let eig = a.clone().symmetric_eigen();
    let largest = eig.eigenvalues.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let b = nalgebra::DVector::from_column_slice(missing);
    let mut lambda = nalgebra::DVector::<f64>::zeros(d);
    for (k, &e) in eig.eigenvalues.iter().enumerate() {
        if largest > 0.0 && e > 1e-12 * largest {
            let v = eig.eigenvectors.column(k);
            lambda += v * (v.dot(&b) / e);
        }
    }
    let residual = norm((&a * &lambda - &b).as_slice());
    if residual > 1e-9 * norm(missing) + 1e-14 * body_mass * extent {
        return Centre::Moved(shift);
    }
    let factors: Vec<f64> = receivers
        .iter()
        .map(|(_, x)| {
            x.iter()
                .zip(&centre)
                .zip(lambda.iter())
                .map(|((x, c), l)| (x - c) * l)
                .sum()
        })
        .collect();
    if factors.iter().any(|f| f.is_nan() || *f < -1.0) {
        return Centre::Moved(shift);
    }
    Centre::Restored(factors)
}

/// The coordinate directions along which a body's first moment is put
/// back ([`restore_centre`]): all but the normals of its symmetry planes.
/// A symmetry plane is a coordinate plane `x_k = c` at the body's least or
/// largest `x_k` (within 1e-9 of its size `size`) whose nodes there (at
/// least `D`, spanning the plane: not all on one line) all have `u_k`
/// held at zero (`held[node][k]`). A model cut by such a plane is half of
/// its mirrored whole, whose centre lies on the plane before and after
/// the redistribution (its two halves move theirs by mirror images): the
/// whole's restoration is along the plane only, and the half's, restored
/// along the plane only with its plane nodes' masses (half the whole's
/// there), is the whole's restricted to it. Restored along `x_k` too, the
/// half's centre, off the plane and moved inward, is put back by a mass
/// change linear in `x_k`, which the mirror image does not have (the
/// quarter tube's radial displacement spread 1.4e-4 mm around the quarter
/// with it, 9e-8 mm with the full mass: `examples/dynamic_buckling_3d.ctc`).
pub fn free_directions<const D: usize>(
    nodes: &[[f64; D]],
    body: std::ops::Range<usize>,
    held: &[[bool; D]],
    size: f64,
) -> [bool; D] {
    let mut free = [true; D];
    for (k, _) in symmetry_planes(nodes, body, held, size) {
        free[k] = false;
    }
    free
}

/// The symmetry planes `x_k = c` of a body (the rule of
/// [`free_directions`]), as `(k, c)`: a coordinate plane at the body's
/// least or largest `x_k` (within 1e-9 of `size`) whose nodes there (at
/// least `D`, spanning the plane) all have `u_k` held at zero. Also the
/// planes the smoothed contact normals are mirrored at
/// (`crate::contact::symmetry`).
pub fn symmetry_planes<const D: usize>(
    nodes: &[[f64; D]],
    body: std::ops::Range<usize>,
    held: &[[bool; D]],
    size: f64,
) -> Vec<(usize, f64)> {
    let mut planes = Vec::new();
    let Some(body_nodes) = nodes.get(body.clone()) else {
        return planes;
    };
    for k in 0..D {
        let lo = body_nodes
            .iter()
            .map(|x| x[k])
            .fold(f64::INFINITY, f64::min);
        let hi = body_nodes
            .iter()
            .map(|x| x[k])
            .fold(f64::NEG_INFINITY, f64::max);
        for c in [lo, hi] {
            let on: Vec<usize> = body
                .clone()
                .filter(|&n| (nodes[n][k] - c).abs() <= 1e-9 * size)
                .collect();
            let all_held = on.iter().all(|&n| held.get(n).is_some_and(|h| h[k]));
            if on.len() >= D && all_held && spans_plane(nodes, &on, k, size) {
                planes.push((k, c));
            }
        }
    }
    planes
}

/// Whether the points `on` (indices into `nodes`), which share their
/// coordinate `k`, span the (D - 1)-dimensional plane (their scatter in
/// the other coordinates has no eigenvalue below 1e-12 of `size^2`).
fn spans_plane<const D: usize>(nodes: &[[f64; D]], on: &[usize], k: usize, size: f64) -> bool {
    let others: Vec<usize> = (0..D).filter(|&j| j != k).collect();
    let m = others.len();
    if m == 0 {
        return true;
    }
    let count = on.len() as f64;
    let mean: Vec<f64> = others
        .iter()
        .map(|&j| on.iter().map(|&n| nodes[n][j]).sum::<f64>() / count)
        .collect();
    let mut s = nalgebra::DMatrix::<f64>::zeros(m, m);
    for &n in on {
        for (p, &jp) in others.iter().enumerate() {
            for (q, &jq) in others.iter().enumerate() {
                s[(p, q)] += (nodes[n][jp] - mean[p]) * (nodes[n][jq] - mean[q]) / count;
            }
        }
    }
    let eig = s.symmetric_eigen();
    eig.eigenvalues.iter().all(|&e| e > 1e-12 * size * size)
}

/// `held[node][k]`: every prescribed value of component `k` at `node` is
/// the constant zero, and there is one (the condition of a symmetry plane
/// in [`free_directions`]).
pub fn held_at_zero<const D: usize>(model: &Model<D>) -> Vec<[bool; D]> {
    let n = model.mesh.nodes.len();
    let mut zero = vec![[false; D]; n];
    let mut other = vec![[false; D]; n];
    for c in &model.constraints {
        if c.component >= D {
            continue;
        }
        let is_zero = c.value == TimeFunction::Constant(0.0);
        for &node in &c.nodes {
            if node < n {
                if is_zero {
                    zero[node][c.component] = true;
                } else {
                    other[node][c.component] = true;
                }
            }
        }
    }
    for (z, o) in zero.iter_mut().zip(&other) {
        for (z, o) in z.iter_mut().zip(o) {
            *z = *z && !*o;
        }
    }
    zero
}

/// The unit normal of `master` when it is a rigid plane that does not
/// rotate and whose normal is a coordinate axis (`contact_mass = normal`
/// keeps the tangential mass of its contact nodes: with an axis normal,
/// the massless direction is one dof, so the initial acceleration and the
/// mass matrix stay well posed on the others); `None` otherwise.
pub fn axis_plane_normal<const D: usize>(
    model: &Model<D>,
    master: &ContactMaster,
) -> Option<[f64; D]> {
    let &ContactMaster::Tool(i) = master else {
        return None;
    };
    let still = |f: &TimeFunction| *f == TimeFunction::Constant(0.0);
    let n: Vec<f64> = if D == 2 {
        let t = model.tools.get(i)?;
        let ToolGeometry::Plane { normal, .. } = t.geometry else {
            return None;
        };
        if !still(&t.motion.rotation) {
            return None;
        }
        normal.to_vec()
    } else {
        let t = model.surfaces.get(i)?;
        let SurfaceShape::Analytic(Analytic::Plane(p)) = &t.geometry else {
            return None;
        };
        if !still(&t.motion.rotation) {
            return None;
        }
        vec![p.normal.x, p.normal.y, p.normal.z]
    };
    let len = n.iter().map(|x| x * x).sum::<f64>().sqrt();
    let axis = n
        .iter()
        .filter(|x| (x.abs() / len - 1.0).abs() < 1e-12)
        .count()
        == 1
        && n.iter().filter(|x| **x == 0.0).count() == D - 1;
    let mut out = [0.0; D];
    for (o, x) in out.iter_mut().zip(&n) {
        *o = (x / len).round();
    }
    axis.then_some(out)
}

/// Flags of the nodes of every contact surface of the pairs (`slave`
/// node lists and the deformable masters' node lists), `n` nodes.
pub fn contact_nodes<'a>(n: usize, lists: impl IntoIterator<Item = &'a [usize]>) -> Vec<bool> {
    let mut flags = vec![false; n];
    for list in lists {
        for &node in list {
            if let Some(f) = flags.get_mut(node) {
                *f = true;
            }
        }
    }
    flags
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A quad4 cell of mass 4 (consistent mass of a unit square, rho = 4):
    /// the contact edge's nodes 0 and 1 lose their mass to nodes 2 and 3.
    #[test]
    fn contact_nodes_lose_their_mass_and_the_cell_keeps_its_total() {
        let mut m = vec![0.0; 16];
        let base = [4.0, 2.0, 1.0, 2.0];
        for a in 0..4 {
            for b in 0..4 {
                // circulant consistent mass of a square, rho A = 4: / 9
                m[a * 4 + b] = base[(b + 4 - a) % 4] * 4.0 / 36.0;
            }
        }
        assert!(redistribute(&mut m, 4, &[true, true, false, false]));
        let diag: Vec<f64> = (0..4).map(|a| m[a * 4 + a]).collect();
        assert_eq!(diag[0], 0.0);
        assert_eq!(diag[1], 0.0);
        assert!((diag[2] - 2.0).abs() < 1e-14 && (diag[3] - 2.0).abs() < 1e-14);
        assert!((diag.iter().sum::<f64>() - 4.0).abs() < 1e-14);
        let off: f64 = (0..16).filter(|k| k % 5 != 0).map(|k| m[k].abs()).sum();
        assert_eq!(off, 0.0);
    }

    /// The mass moved from each contact node to each other node is what
    /// `redistribute` adds to the latter (`contact_mass = normal` gives it
    /// back tangentially): nodes 0, 1 (1 each) to nodes 2, 3 (1 each).
    #[test]
    fn moved_mass_is_what_redistribution_adds() {
        let mut m = vec![0.0; 16];
        let base = [4.0, 2.0, 1.0, 2.0];
        for a in 0..4 {
            for b in 0..4 {
                m[a * 4 + b] = base[(b + 4 - a) % 4] * 4.0 / 36.0;
            }
        }
        let flags = [true, true, false, false];
        let moved = moved_mass(&m, 4, &flags);
        let mut r = m.clone();
        assert!(redistribute(&mut r, 4, &flags));
        for b in 2..4 {
            let gained: f64 = (0..4).map(|a| moved[a * 4 + b]).sum();
            assert!((1.0 + gained - r[b * 4 + b]).abs() < 1e-14, "{moved:?}");
        }
        for a in 0..2 {
            let lost: f64 = (0..4).map(|b| moved[a * 4 + b]).sum();
            assert!((lost - 1.0).abs() < 1e-14, "{moved:?}");
        }
        assert!(moved[2 * 4 + 3] == 0.0 && moved[1] == 0.0);
    }

    #[test]
    fn a_cell_with_every_node_in_contact_keeps_its_lumped_mass() {
        let mut m = vec![1.0, 0.5, 0.5, 1.0];
        assert!(!redistribute(&mut m, 2, &[true, true]));
        assert_eq!(m, vec![1.5, 0.0, 0.0, 1.5]);
    }

    /// Receivers on a line (x = 0, 1, 2; masses 1, 2, 1) restore a first
    /// moment along the line, keep their total, and refuse one across it
    /// (the shift reported) or one that would take more than a receiver
    /// got.
    #[test]
    fn the_receivers_put_the_centre_back_when_they_span_the_shift() {
        let receivers: Vec<(f64, Vec<f64>)> = vec![
            (1.0, vec![0.0, 5.0]),
            (2.0, vec![1.0, 5.0]),
            (1.0, vec![2.0, 5.0]),
        ];
        let Centre::Restored(f) = restore_centre(&receivers, &[0.5, 0.0], 10.0, 2.0) else {
            panic!("along the line")
        };
        let delta: Vec<f64> = receivers.iter().zip(&f).map(|(r, f)| r.0 * f).collect();
        assert!(delta.iter().sum::<f64>().abs() < 1e-15, "{delta:?}");
        let moment: f64 = receivers.iter().zip(&delta).map(|(r, d)| d * r.1[0]).sum();
        assert!((moment - 0.5).abs() < 1e-15, "{moment}");
        assert!(
            delta[1].abs() < 1e-15 && (delta[2] - 0.25).abs() < 1e-15,
            "{delta:?}"
        );
        // across the line: the shift |missing| / M
        assert_eq!(
            restore_centre(&receivers, &[0.0, 0.5], 10.0, 2.0),
            Centre::Moved(0.05)
        );
        // more than the receivers got: node 0 would go below its own mass
        assert!(matches!(
            restore_centre(&receivers, &[3.0, 0.0], 10.0, 2.0),
            Centre::Moved(_)
        ));
        // a round-off shift is left alone
        assert_eq!(
            restore_centre(&receivers, &[1e-15, 0.0], 10.0, 2.0),
            Centre::Unmoved
        );
    }

    /// A half model with a symmetry plane has the masses of the full
    /// model's half (issue 19: the 3D tube quarter's restored centre was
    /// not axisymmetric). A plane-strain block, x in [-1, 1], y in [0,
    /// 3], 8 x 12 quad4, its bottom and both sides in contact (rigid
    /// lines), against its half x in [0, 1], 4 x 12, `ux = 0` at x = 0:
    ///
    /// ```text
    ///   full  |---:---|       half  :---|
    ///         |   :   |             :   |   ux = 0 on x = 0
    ///         |___:___|             :___|   contact: bottom, outer side
    /// ```
    ///
    /// The full block's centre lies on x = 0 before and after the
    /// redistribution (its mirror halves); its restoration is along y
    /// only. The half's own centre lies at x > 0 and moves inward: put
    /// back along x (as before the fix) it adds mass linearly in x. Node
    /// by node, the half's lumped masses are the full block's, halved on
    /// the plane (the mirror image of a plane node is itself).
    #[test]
    fn a_half_model_with_a_symmetry_plane_has_the_full_models_masses() {
        use crate::model::{
            ContactMass, ContactMethod, Dynamic, MassMatrix, PenaltyKind, Rayleigh, Scheme,
            ToolMotion,
        };
        use crate::solve::dynamics::Dynamics;
        use crate::testkit::grid::{grid, grid_node};
        use crate::testkit::ModelBuilder;
        let ny = 12;
        let penalty = ContactMethod::Penalty {
            kind: PenaltyKind::Area,
            stiffness: 1e6,
        };
        let masses = |nx: usize, x0: f64, half: bool| {
            let w = 2.0 * nx as f64 / 8.0;
            let mesh = grid(nx, ny, [x0, 0.0], [w, 3.0], 0.0, 1, false);
            let bottom: Vec<[usize; 2]> = (0..nx)
                .map(|i| [grid_node(nx, i, 0), grid_node(nx, i + 1, 0)])
                .collect();
            let side = |i: usize| -> Vec<[usize; 2]> {
                (0..ny)
                    .map(|j| [grid_node(nx, i, j), grid_node(nx, i, j + 1)])
                    .collect()
            };
            let line = |x: f64, n: [f64; 2]| ToolGeometry::Plane {
                point: [x, 0.0],
                normal: n,
            };
            let mut b = ModelBuilder::plane_strain()
                .elastic("steel", 200e3, 0.3)
                .density(7.8e-9)
                .body("block", mesh, "steel")
                .tool("floor", line(0.0, [0.0, 1.0]), ToolMotion::fixed())
                .tool("right", line(1.0, [-1.0, 0.0]), ToolMotion::fixed())
                .contact_tool("floor", "block", bottom, "floor", penalty.clone())
                .contact_tool("right", "block", side(nx), "right", penalty.clone());
            if half {
                b = b.fix((0..=ny).map(|j| grid_node(nx, 0, j)).collect::<Vec<_>>(), 0);
            } else {
                b = b
                    .tool("left", line(-1.0, [1.0, 0.0]), ToolMotion::fixed())
                    .contact_tool("left", "block", side(0), "left", penalty.clone());
            }
            let model = b.step("s", 1.0, 1).build();
            let d = Dynamic {
                scheme: Scheme::GeneralizedAlpha { rho_inf: 0.9 },
                mass: MassMatrix::Consistent,
                contact_mass: ContactMass::Redistributed,
                rayleigh: Rayleigh::default(),
                adaptive: None,
                max_rotation: None,
                energy_tol: None,
            };
            let mut dy = Dynamics::new(&model);
            dy.build_mass(&model, &d).expect("masses");
            let n = model.mesh.nodes.len();
            let mut m = vec![0.0; 2 * n];
            dy.mass_times(&model, &vec![1.0; 2 * n], &mut m);
            let per_cell = {
                let mut dy = Dynamics::new(&model);
                let d = Dynamic {
                    contact_mass: ContactMass::Full,
                    ..d
                };
                dy.build_mass(&model, &d).expect("masses");
                let mut m = vec![0.0; 2 * n];
                dy.mass_times(&model, &vec![1.0; 2 * n], &mut m);
                m
            };
            (model, m, per_cell, dy.mass_notes)
        };
        let (full, m_full, c_full, notes_full) = masses(8, -1.0, false);
        let (half, m_half, _, notes_half) = masses(4, 0.0, true);
        assert!(
            notes_full.is_empty() && notes_half.is_empty(),
            "{notes_full:?} {notes_half:?}"
        );
        // the full block's centre of mass is its consistent mass's
        let centre = |m: &[f64]| -> [f64; 2] {
            let total: f64 = m.chunks_exact(2).map(|v| v[0]).sum();
            std::array::from_fn(|k| {
                m.chunks_exact(2)
                    .zip(&full.mesh.nodes)
                    .map(|(v, x)| v[k] * x[k])
                    .sum::<f64>()
                    / total
            })
        };
        let (a, b) = (centre(&m_full), centre(&c_full));
        assert!(
            (a[0] - b[0]).abs() < 1e-14 && (a[1] - b[1]).abs() < 1e-14,
            "{a:?} {b:?}"
        );
        let mut worst = 0.0f64;
        for j in 0..=ny {
            for i in 0..=4 {
                let h = grid_node(4, i, j);
                let f = grid_node(8, i + 4, j);
                assert_eq!(half.mesh.nodes[h], full.mesh.nodes[f]);
                let share = if i == 0 { 0.5 } else { 1.0 };
                for k in 0..2 {
                    let (mh, mf) = (m_half[2 * h + k], share * m_full[2 * f + k]);
                    worst = worst.max((mh - mf).abs() / mf.abs().max(1e-300));
                }
            }
        }
        assert!(worst < 1e-13, "half against full: relative {worst:e}");
    }

    #[test]
    fn contact_node_flags_ignore_out_of_range_nodes() {
        let a = [0usize, 2];
        let b = [2usize, 7];
        assert_eq!(
            contact_nodes(4, [&a[..], &b[..]]),
            vec![true, false, true, false]
        );
    }
}
