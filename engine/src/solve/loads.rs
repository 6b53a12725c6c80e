//! External load vector at a time: nodal forces and consistent nodal forces
//! of pressures and dead tractions on boundary edges (planar) and faces
//! (solid), in the reference configuration.
//!
//! Pressure `p` on edge `a -> b` (body on the left) acts along the inward
//! normal `(-dy, dx) / L`. Plane kinds: each node gets `p t L / 2`.
//! Axisymmetric: `int N_a p 2 pi r ds` with `r` linear along the edge, i.e.
//! `2 pi p L (2 r_a + r_b) / 6` on `a` (totals over the full ring).
//!
//! Gravity: `f_a = g int rho N_a dV`, the row sums of each cell's
//! consistent mass (the kernel's own mass rule, so plane, axisymmetric and
//! solid cells share it) times `g`, plus `m g` at point masses.

use crate::element::kernel::kernel_of;
use crate::element::Section;
use crate::geom::Dimension;
use crate::model::{AnalysisKind, Discrete, Load, MassMatrix, Model};
use nalgebra::Const;

/// Writes the external forces of `model` at time `t` into `f` (`D` per
/// node).
pub fn external_forces<const D: usize>(model: &Model<D>, t: f64, f: &mut [f64])
where
    Const<D>: Dimension<D>,
{
    f.fill(0.0);
    let nodes = &model.mesh.nodes;
    for load in &model.loads {
        match load {
            Load::Gravity {
                component, value, ..
            } => {
                let g = value.eval(t);
                if g == 0.0 {
                    continue;
                }
                for (n, m) in gravity_masses(model).iter().enumerate() {
                    f[D * n + component] += g * m;
                }
            }
            Load::NodalForce {
                nodes: set,
                component,
                value,
                ..
            } => {
                let v = value.eval(t);
                for &n in set {
                    f[D * n + component] += v;
                }
            }
            Load::FacetPressure { facets, value, .. } => {
                let p = value.eval(t);
                if p == 0.0 {
                    continue;
                }
                for facet in facets {
                    if let (2, &[a, b, m]) = (D, facet.nodes()) {
                        edge3_quadrature(model, nodes, [a, b, m], |node, w, t| {
                            // the inward normal (-t_y, t_x) times the measure
                            f[D * node] += p * w * -t[1];
                            f[D * node + 1] += p * w * t[0];
                        });
                    } else {
                        facet_pressure(nodes, facet.nodes(), p, f);
                    }
                }
            }
            Load::FacetTraction {
                facets,
                component,
                value,
                ..
            } => {
                let t = value.eval(t);
                if t == 0.0 {
                    continue;
                }
                for facet in facets {
                    match facet.nodes() {
                        &[a, b] => {
                            let (wa, wb) = edge_measure(model, nodes, a, b);
                            f[D * a + component] += t * wa;
                            f[D * b + component] += t * wb;
                        }
                        &[a, b, m] if D == 2 => {
                            edge3_quadrature(model, nodes, [a, b, m], |node, w, tan| {
                                f[D * node + component] += t * w * tan[0].hypot(tan[1]);
                            });
                        }
                        face => {
                            face_quadrature(nodes, face, |node, w, n, area_normal| {
                                let da = (area_normal[0].powi(2)
                                    + area_normal[1].powi(2)
                                    + area_normal[2].powi(2))
                                .sqrt();
                                f[D * node + component] += t * w * n * da;
                            });
                        }
                    }
                }
            }
            // on the deformed surface: `solve/follower.rs`, per evaluation
            // configuration dependent: with the follower loads
            // (`rigid_body::add_moments`)
            Load::FollowerPressure { .. } | Load::RigidMoment { .. } => {}
            Load::Pressure { edges, value, .. } => {
                let p = value.eval(t);
                if p == 0.0 {
                    continue;
                }
                for &[a, b] in edges {
                    let (xa, xb) = (nodes[a], nodes[b]);
                    // (-dy, dx) = inward normal times the edge length
                    let n = [-(xb[1] - xa[1]), xb[0] - xa[0]];
                    let (wa, wb) = match model.analysis.kind {
                        AnalysisKind::Axisymmetric => {
                            let c = 2.0 * std::f64::consts::PI * p / 6.0;
                            (c * (2.0 * xa[0] + xb[0]), c * (xa[0] + 2.0 * xb[0]))
                        }
                        AnalysisKind::PlaneStrain
                        | AnalysisKind::PlaneStress
                        | AnalysisKind::Solid => {
                            let c = 0.5 * p * model.analysis.thickness;
                            (c, c)
                        }
                    };
                    for k in 0..2 {
                        f[D * a + k] += wa * n[k];
                        f[D * b + k] += wb * n[k];
                    }
                }
            }
        }
    }
}

/// The mass each node carries under gravity: `int rho N_a dV` over the
/// cells of every body (row sums of the consistent cell mass; totals over
/// the ring in axisymmetry, times the thickness in plane analyses) plus its
/// point masses. A cell whose mass cannot be formed (inverted) adds none:
/// the element evaluation reports it.
pub fn gravity_masses<const D: usize>(model: &Model<D>) -> Vec<f64>
where
    Const<D>: Dimension<D>,
{
    let mut out = vec![0.0; model.mesh.nodes.len()];
    let section = Section::new(&model.analysis);
    for b in &model.bodies {
        let rho = model.materials.get(b.material).map_or(0.0, |m| m.density);
        if rho == 0.0 {
            continue;
        }
        for c in b.cells.clone() {
            let cell = model.mesh.cells.nodes(c);
            let Ok(kernel) = kernel_of::<D>(model.mesh.cells.kind(c)) else {
                continue;
            };
            let x: Vec<crate::geom::Point<D>> = cell
                .iter()
                .map(|&n| crate::geom::Point::<D>::from(model.mesh.nodes[n]))
                .collect();
            let Ok(m) = kernel.mass(&x, &section, rho, MassMatrix::Consistent) else {
                continue;
            };
            let nn = cell.len();
            for (a, &na) in cell.iter().enumerate() {
                out[na] += m[a * nn..(a + 1) * nn].iter().sum::<f64>();
            }
        }
    }
    for d in &model.discrete {
        if let Discrete::Mass { nodes, mass, .. } = d {
            for &n in nodes {
                if let Some(x) = out.get_mut(n) {
                    *x += mass;
                }
            }
        }
    }
    out
}

/// `[x, y, z]` of a node (z = 0 in 2D).
fn xyz<const D: usize>(p: &[f64; D]) -> [f64; 3] {
    std::array::from_fn(|k| if k < D { p[k] } else { 0.0 })
}

/// `int N_a dA` of the two nodes of the planar boundary edge `a -> b`: `t L
/// / 2` each in plane analyses, `2 pi L (2 r_a + r_b) / 6` (and symmetric)
/// axisymmetric (totals over the ring).
fn edge_measure<const D: usize>(
    model: &Model<D>,
    nodes: &[[f64; D]],
    a: usize,
    b: usize,
) -> (f64, f64) {
    let (xa, xb) = (xyz(&nodes[a]), xyz(&nodes[b]));
    let len = ((xb[0] - xa[0]).powi(2) + (xb[1] - xa[1]).powi(2) + (xb[2] - xa[2]).powi(2)).sqrt();
    match model.analysis.kind {
        AnalysisKind::Axisymmetric => {
            let c = 2.0 * std::f64::consts::PI * len / 6.0;
            (c * (2.0 * xa[0] + xb[0]), c * (xa[0] + 2.0 * xb[0]))
        }
        AnalysisKind::PlaneStrain | AnalysisKind::PlaneStress | AnalysisKind::Solid => {
            let c = 0.5 * len * model.analysis.thickness;
            (c, c)
        }
    }
}

/// Visits the 3 Gauss points of the quadratic planar boundary edge
/// `[a, b, m]` (corners `a -> b`, midpoint `m`): for every point and edge
/// node, `visit(node, w N_a t_or_2_pi_r, dx/dxi)`; exact for a straight edge
/// with its midpoint in the middle (a uniform load gives 1/6, 4/6, 1/6 of
/// the total in plane analyses).
fn edge3_quadrature<const D: usize>(
    model: &Model<D>,
    nodes: &[[f64; D]],
    edge: [usize; 3],
    mut visit: impl FnMut(usize, f64, [f64; 2]),
) {
    let g = (0.6f64).sqrt();
    for (xi, w) in [(-g, 5.0 / 9.0), (0.0, 8.0 / 9.0), (g, 5.0 / 9.0)] {
        let n = [0.5 * xi * (xi - 1.0), 0.5 * xi * (xi + 1.0), 1.0 - xi * xi];
        let dn = [xi - 0.5, xi + 0.5, -2.0 * xi];
        let (mut t, mut r) = ([0.0; 2], 0.0);
        for (a, &node) in edge.iter().enumerate() {
            let x = xyz(&nodes[node]);
            t[0] += dn[a] * x[0];
            t[1] += dn[a] * x[1];
            r += n[a] * x[0];
        }
        let measure = match model.analysis.kind {
            AnalysisKind::Axisymmetric => 2.0 * std::f64::consts::PI * r,
            AnalysisKind::PlaneStrain | AnalysisKind::PlaneStress | AnalysisKind::Solid => {
                model.analysis.thickness
            }
        };
        for (a, &node) in edge.iter().enumerate() {
            visit(node, w * n[a] * measure, t);
        }
    }
}

/// Visits the quadrature points of the face `face` (3 or 4 nodes,
/// counter-clockwise seen from outside) of a solid mesh: for every point
/// and face node, `visit(node, w, N_a, n dA / (dxi deta))` with the area
/// normal `dx/dxi x dx/deta`; 1-point (tri3, exact: the area over 3 on
/// each node), 2x2 Gauss (quad4, exact for flat faces), the tri6 3-point
/// rule (6 nodes) or 3x3 Gauss (quad8: 8 nodes, quad9: 9 nodes; exact for
/// flat faces with centred midpoints). Other node counts are not visited
/// (refused by `check_model`).
fn face_quadrature<const D: usize>(
    nodes: &[[f64; D]],
    face: &[usize],
    mut visit: impl FnMut(usize, f64, f64, [f64; 3]),
) {
    face_points(nodes, face, false, |w, n, area_normal| {
        for (a, &node) in face.iter().enumerate() {
            visit(node, w, n[a], area_normal);
        }
    });
}

/// The quadrature points of [`face_quadrature`], one call per point:
/// `visit(w, [N_a], n dA / (dxi deta))` (shape values in face node order);
/// `mass`: the face cell's mass rule instead (`ReferenceCell::MASS_QUADRATURE`,
/// exact for `N_a N_b` on flat faces: the tri3 face's 1-point rule is not).
pub(crate) fn face_points<const D: usize>(
    nodes: &[[f64; D]],
    face: &[usize],
    mass: bool,
    mut visit: impl FnMut(f64, &[f64], [f64; 3]),
) {
    use crate::element::reference::{Quad4, Quad8, Quad9, ReferenceCell, Tri3, Tri6};
    fn on<const D: usize, const NN: usize, C: ReferenceCell<2, NN>>(
        nodes: &[[f64; D]],
        face: &[usize],
        mass: bool,
        visit: &mut impl FnMut(f64, &[f64], [f64; 3]),
    ) {
        let rule = if mass {
            C::MASS_QUADRATURE
        } else {
            C::QUADRATURE
        };
        for (xi, w) in rule {
            let (n, g) = (C::shape(xi), C::gradients(xi));
            let mut t = [[0.0; 3]; 2];
            for (a, &node) in face.iter().enumerate() {
                let x = xyz(&nodes[node]);
                for (k, tk) in t.iter_mut().enumerate() {
                    for c in 0..3 {
                        tk[c] += g[a][k] * x[c];
                    }
                }
            }
            let [t1, t2] = t;
            let area_normal = [
                t1[1] * t2[2] - t1[2] * t2[1],
                t1[2] * t2[0] - t1[0] * t2[2],
                t1[0] * t2[1] - t1[1] * t2[0],
            ];
            visit(*w, &n[..], area_normal);
        }
    }
    match face.len() {
        3 => on::<D, 3, Tri3>(nodes, face, mass, &mut visit),
        4 => on::<D, 4, Quad4>(nodes, face, mass, &mut visit),
        6 => on::<D, 6, Tri6>(nodes, face, mass, &mut visit),
        8 => on::<D, 8, Quad8>(nodes, face, mass, &mut visit),
        9 => on::<D, 9, Quad9>(nodes, face, mass, &mut visit),
        _ => {}
    }
}

/// Adds the consistent nodal forces `-p int N_a n dA` of a pressure `p` on
/// the face `face` (3 or 4 nodes, counter-clockwise seen from outside) of a
/// solid mesh ([`face_quadrature`]).
fn facet_pressure<const D: usize>(nodes: &[[f64; D]], face: &[usize], p: f64, f: &mut [f64]) {
    face_quadrature(nodes, face, |node, w, n, area_normal| {
        for c in 0..D {
            f[D * node + c] -= p * w * n * area_normal[c];
        }
    });
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::Mesh;
    use crate::model::*;

    fn model(kind: AnalysisKind, loads: Vec<Load>) -> Model {
        let mut b = crate::testkit::ModelBuilder::new(kind)
            .thickness(2.0)
            .mesh(Mesh::new(vec![[1.0, 0.0], [3.0, 0.0], [3.0, 1.0]], vec![]));
        for l in loads {
            b = b.load(l);
        }
        b.build()
    }

    fn pressure(edges: Vec<[usize; 2]>, p: f64) -> Load {
        Load::Pressure {
            label: "p".into(),
            edges,
            value: TimeFunction::Ramp {
                t0: 0.0,
                t1: 1.0,
                v0: 0.0,
                v1: p,
            },
        }
    }

    #[test]
    fn plane_pressure_on_bottom_edge_pushes_up_into_the_body() {
        // edge 0 -> 1 along +x has the body on its left (above): p pushes +y
        let m = model(
            AnalysisKind::PlaneStrain,
            vec![pressure(vec![[0, 1]], 10.0)],
        );
        let mut f = vec![0.0; 6];
        external_forces(&m, 0.5, &mut f);
        // p(0.5) = 5, L = 2, t = 2: total 20, half on each node
        assert_eq!(f, vec![0.0, 10.0, 0.0, 10.0, 0.0, 0.0]);
    }

    #[test]
    fn axisymmetric_pressure_total_is_p_times_ring_area() {
        let m = model(
            AnalysisKind::Axisymmetric,
            vec![pressure(vec![[0, 1]], 1.0)],
        );
        let mut f = vec![0.0; 6];
        external_forces(&m, 1.0, &mut f);
        // annulus r in [1, 3]: area pi (9 - 1) = 8 pi
        let total = f[1] + f[3];
        assert!((total - 8.0 * std::f64::consts::PI).abs() < 1e-12);
        // consistent split: (2 r_a + r_b) / 6 vs (r_a + 2 r_b) / 6 times 2 pi L
        assert!((f[1] - 2.0 * std::f64::consts::PI * 2.0 * 5.0 / 6.0).abs() < 1e-12);
    }

    #[test]
    fn facet_pressure_on_a_face_totals_p_times_area_along_the_inward_normal() {
        // a quad face z = 0 of area 6, clockwise seen from +z (so the
        // outward normal is -z: the body lies above), and a triangle of the
        // same plane: p pushes +z, totals p A
        let nodes = vec![
            [0.0, 0.0, 0.0],
            [0.0, 2.0, 0.0],
            [3.0, 2.0, 0.0],
            [3.0, 0.0, 0.0],
        ];
        let mut m = crate::testkit::ModelBuilder::<3>::solid()
            .mesh(Mesh::new(nodes, vec![]))
            .build();
        m.loads.push(Load::FacetPressure {
            label: "p".into(),
            facets: vec![
                crate::mesh::Facet::new(&[0, 1, 2, 3]),
                crate::mesh::Facet::new(&[0, 1, 2]),
            ],
            value: TimeFunction::Constant(2.0),
        });
        let mut f = vec![0.0; 12];
        external_forces(&m, 0.0, &mut f);
        let fz: f64 = (0..4).map(|a| f[3 * a + 2]).sum();
        assert!((fz - 2.0 * (6.0 + 3.0)).abs() < 1e-12, "{f:?}");
        // quad: a quarter on each node; triangle: a third on each of its nodes
        assert!((f[3 * 3 + 2] - 3.0).abs() < 1e-12);
        assert!((f[2] - (3.0 + 2.0)).abs() < 1e-12);
        assert!((0..4).all(|a| f[3 * a].abs() < 1e-14 && f[3 * a + 1].abs() < 1e-14));
    }

    /// The sum over the nodes of component `c` of `f` (`d` per node).
    fn total(f: &[f64], d: usize, c: usize) -> f64 {
        f.iter().skip(c).step_by(d).sum()
    }

    #[test]
    fn facet_traction_totals_traction_times_area_on_tri3_and_quad4_faces() {
        // a flat trapezoid (area 4.5) and a triangle (area 3), tilted out of
        // every coordinate plane by a rotation: the traction is per unit
        // reference area whatever the face orientation
        let (c, s) = (0.6f64, 0.8f64);
        let rot = |p: [f64; 3]| [c * p[0] - s * p[2], p[1], s * p[0] + c * p[2]];
        let nodes: Vec<[f64; 3]> = [
            [0.0, 0.0, 0.0],
            [4.0, 0.0, 0.0],
            [3.0, 1.5, 0.0],
            [1.0, 1.5, 0.0],
            [0.0, 0.0, 0.0],
        ]
        .into_iter()
        .map(rot)
        .collect();
        let quad = crate::mesh::Facet::new(&[0, 1, 2, 3]);
        let tri = crate::mesh::Facet::new(&[4, 1, 3]);
        for (facet, area) in [(quad, 4.5), (tri, 3.0)] {
            let mut m = crate::testkit::ModelBuilder::<3>::solid()
                .mesh(Mesh::new(nodes.clone(), vec![]))
                .build();
            for (component, t) in [(0, 2.0), (1, -3.0), (2, 0.5)] {
                m.loads.push(Load::FacetTraction {
                    label: "t".into(),
                    facets: vec![facet],
                    component,
                    value: TimeFunction::Constant(t),
                });
            }
            let mut f = vec![0.0; 15];
            external_forces(&m, 0.0, &mut f);
            for (c, t) in [(0, 2.0), (1, -3.0), (2, 0.5)] {
                let got = total(&f, 3, c);
                assert!(
                    (got - t * area).abs() <= 1e-14 * area,
                    "{c}: {got} vs {}",
                    t * area
                );
            }
        }
        // the triangle: the area over 3 on each node
        let mut m = crate::testkit::ModelBuilder::<3>::solid()
            .mesh(Mesh::new(nodes.clone(), vec![]))
            .build();
        m.loads.push(Load::FacetTraction {
            label: "t".into(),
            facets: vec![tri],
            component: 1,
            value: TimeFunction::Constant(3.0),
        });
        let mut f = vec![0.0; 15];
        external_forces(&m, 0.0, &mut f);
        for a in [4, 1, 3] {
            assert!((f[3 * a + 1] - 3.0).abs() < 1e-14, "{f:?}");
        }
    }

    #[test]
    fn facet_traction_on_planar_edges_uses_thickness_or_the_ring() {
        let traction = |component| Load::FacetTraction {
            label: "t".into(),
            facets: vec![crate::mesh::Facet::new(&[0, 1])],
            component,
            value: TimeFunction::Constant(4.0),
        };
        // plane strain, t = 2, L = 2: 4 x 2 x 2 = 16, half on each node
        let m = model(AnalysisKind::PlaneStrain, vec![traction(0)]);
        let mut f = vec![0.0; 6];
        external_forces(&m, 0.0, &mut f);
        assert_eq!(f, vec![8.0, 0.0, 8.0, 0.0, 0.0, 0.0]);
        // axisymmetric ring r in [1, 3] at z = 0: 4 x 8 pi
        let m = model(AnalysisKind::Axisymmetric, vec![traction(1)]);
        let mut f = vec![0.0; 6];
        external_forces(&m, 0.0, &mut f);
        let exact = 4.0 * 8.0 * std::f64::consts::PI;
        assert!((total(&f, 2, 1) - exact).abs() < 1e-12 * exact);
        assert_eq!(total(&f, 2, 0), 0.0);
    }

    #[test]
    fn quadratic_edges_get_one_sixth_four_sixths_one_sixth_of_a_uniform_load() {
        // nodes (1,0) (3,0) and the midpoint (2,0): plane strain, t = 2,
        // traction 4 over L = 2: total 16 = (1/6, 1/6, 4/6) x 16
        let mesh = Mesh::new(vec![[1.0, 0.0], [3.0, 0.0], [2.0, 0.0]], vec![]);
        let edge = crate::mesh::Facet::new(&[0, 1, 2]);
        let build = |kind, load| {
            crate::testkit::ModelBuilder::new(kind)
                .thickness(2.0)
                .mesh(mesh.clone())
                .load(load)
                .build()
        };
        let m = build(
            AnalysisKind::PlaneStrain,
            Load::FacetTraction {
                label: "t".into(),
                facets: vec![edge],
                component: 0,
                value: TimeFunction::Constant(4.0),
            },
        );
        let mut f = vec![0.0; 6];
        external_forces(&m, 0.0, &mut f);
        for (node, share) in [(0, 1.0 / 6.0), (1, 1.0 / 6.0), (2, 4.0 / 6.0)] {
            assert!((f[2 * node] - 16.0 * share).abs() < 1e-13, "{f:?}");
            assert_eq!(f[2 * node + 1], 0.0);
        }
        // a pressure on the bottom edge (body above) pushes up (+y), the same
        // shares; axisymmetric: the total is p times the ring area 8 pi
        let pressure = Load::FacetPressure {
            label: "p".into(),
            facets: vec![edge],
            value: TimeFunction::Constant(4.0),
        };
        let m = build(AnalysisKind::PlaneStrain, pressure.clone());
        external_forces(&m, 0.0, &mut f);
        for (node, share) in [(0, 1.0 / 6.0), (1, 1.0 / 6.0), (2, 4.0 / 6.0)] {
            assert!((f[2 * node + 1] - 16.0 * share).abs() < 1e-13, "{f:?}");
        }
        let m = build(AnalysisKind::Axisymmetric, pressure);
        external_forces(&m, 0.0, &mut f);
        let exact = 4.0 * 8.0 * std::f64::consts::PI;
        assert!((total(&f, 2, 1) - exact).abs() < 1e-12 * exact);
    }

    #[test]
    fn quadratic_faces_get_the_consistent_serendipity_and_tri6_shares() {
        // the unit square z = 0 as quad8 / quad9 and the unit right triangle
        // as tri6, counter-clockwise from +z: a uniform traction t gives the
        // classical shares (quad8: corners -1/12, midpoints 1/3; quad9:
        // corners 1/36, midpoints 1/9, centre 4/9; tri6: corners 0,
        // midpoints 1/3 of the total) and a pressure pushes along -z
        let nodes: Vec<[f64; 3]> = vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.5, 0.0, 0.0],
            [1.0, 0.5, 0.0],
            [0.5, 1.0, 0.0],
            [0.0, 0.5, 0.0],
            [0.5, 0.5, 0.0],
        ];
        let tri6 = [0usize, 1, 3, 4, 8, 7];
        let cases: [(&[usize], f64, Vec<f64>); 3] = [
            (
                &[0, 1, 2, 3, 4, 5, 6, 7],
                1.0,
                [vec![-1.0 / 12.0; 4], vec![1.0 / 3.0; 4]].concat(),
            ),
            (
                &[0, 1, 2, 3, 4, 5, 6, 7, 8],
                1.0,
                [vec![1.0 / 36.0; 4], vec![1.0 / 9.0; 4], vec![4.0 / 9.0]].concat(),
            ),
            (&tri6, 0.5, [vec![0.0; 3], vec![1.0 / 3.0; 3]].concat()),
        ];
        for (face, area, shares) in cases {
            for pressure in [false, true] {
                let mut m = crate::testkit::ModelBuilder::<3>::solid()
                    .mesh(Mesh::new(nodes.clone(), vec![]))
                    .build();
                let facets = vec![crate::mesh::Facet::new(face)];
                let value = TimeFunction::Constant(3.0);
                m.loads.push(if pressure {
                    Load::FacetPressure {
                        label: "p".into(),
                        facets,
                        value,
                    }
                } else {
                    Load::FacetTraction {
                        label: "t".into(),
                        facets,
                        component: 2,
                        value,
                    }
                });
                let mut f = vec![0.0; 27];
                external_forces(&m, 0.0, &mut f);
                let sign = if pressure { -1.0 } else { 1.0 };
                for (&node, share) in face.iter().zip(&shares) {
                    let want = sign * 3.0 * area * share;
                    assert!(
                        (f[3 * node + 2] - want).abs() < 1e-14,
                        "{face:?} {node}: {f:?}"
                    );
                }
                assert!((total(&f, 3, 2) - sign * 3.0 * area).abs() < 1e-14);
            }
        }
    }

    #[test]
    fn nodal_force_is_per_node() {
        let m = model(
            AnalysisKind::PlaneStress,
            vec![Load::NodalForce {
                label: "f".into(),
                nodes: vec![1, 2],
                component: 0,
                value: TimeFunction::Constant(-3.0),
            }],
        );
        let mut f = vec![9.0; 6];
        external_forces(&m, 0.0, &mut f);
        assert_eq!(f, vec![0.0, 0.0, -3.0, 0.0, -3.0, 0.0]);
    }
}
