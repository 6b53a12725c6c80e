//! External load vector at a time: nodal forces and consistent nodal forces
//! of pressures and dead tractions on boundary edges (planar) and faces
//! (solid), in the reference configuration.
//!
//! Pressure `p` on edge `a -> b` (body on the left) acts along the inward
//! normal `(-dy, dx) / L`. Plane kinds: each node gets `p t L / 2`.
//! Axisymmetric: `int N_a p 2 pi r ds` with `r` linear along the edge, i.e.
//! `2 pi p L (2 r_a + r_b) / 6` on `a` (totals over the full ring).

use crate::model::{AnalysisKind, Load, Model};

/// Writes the external forces of `model` at time `t` into `f` (`D` per
/// node).
pub fn external_forces<const D: usize>(model: &Model<D>, t: f64, f: &mut [f64]) {
    f.fill(0.0);
    let nodes = &model.mesh.nodes;
    for load in &model.loads {
        match load {
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
                    facet_pressure(nodes, facet.nodes(), p, f);
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

/// Visits the quadrature points of the face `face` (3 or 4 nodes,
/// counter-clockwise seen from outside) of a solid mesh: for every point
/// and face node, `visit(node, w, N_a, n dA / (dxi deta))` with the area
/// normal `dx/dxi x dx/deta`; 1-point (tri3, exact: the area over 3 on
/// each node) or 2x2 Gauss (quad4, exact for flat faces) quadrature. Other
/// node counts are not visited (refused by `check_model`).
fn face_quadrature<const D: usize>(
    nodes: &[[f64; D]],
    face: &[usize],
    mut visit: impl FnMut(usize, f64, f64, [f64; 3]),
) {
    use crate::element::reference::{Quad4, ReferenceCell, Tri3};
    fn on<const D: usize, const NN: usize, C: ReferenceCell<2, NN>>(
        nodes: &[[f64; D]],
        face: &[usize],
        visit: &mut impl FnMut(usize, f64, f64, [f64; 3]),
    ) {
        for (xi, w) in C::QUADRATURE {
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
            for (a, &node) in face.iter().enumerate() {
                visit(node, *w, n[a], area_normal);
            }
        }
    }
    match face.len() {
        3 => on::<D, 3, Tri3>(nodes, face, &mut visit),
        4 => on::<D, 4, Quad4>(nodes, face, &mut visit),
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
