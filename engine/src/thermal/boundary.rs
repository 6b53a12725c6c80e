//! Boundary terms of heat conduction on a boundary facet: a heat flux `q`
//! gives nodal heat `int N_a q dA`; a convection film `h` gives the matrix
//! `int h N_a N_b dA` and the load `int h T_ambient N_a dA`
//! ([`facet_integrals`], both dimensions).
//!
//! Planar edges `[a, b]` (linear shape functions, integrated exactly):
//! plane `dA = t ds`; axisymmetric `dA = 2 pi r ds` with `r` linear along
//! the edge (the same consistent rule as the contact tributary areas,
//! `contact::tributary`), totals over the full ring. Faces of a solid
//! (tri3, quad4, tri6, quad8, quad9): the face cell's mass rule through the
//! face quadrature of the pressure loads (`solve::loads::face_points`),
//! `dA = |dx/dxi x dx/deta| dxi deta`: `N_a N_b` exact on flat tri3 faces
//! and on parallelogram quad4 faces (3x3 Gauss).

use crate::mesh::Facet;
use crate::model::{AnalysisKind, Model};
use std::f64::consts::PI;

/// `int N_a dA` and `int N_a N_b dA` of one boundary facet, in the facet's
/// node order.
#[derive(Debug, Clone, PartialEq)]
pub struct FacetIntegrals {
    /// `int N_a dA` per facet node.
    pub weights: Vec<f64>,
    /// `int N_a N_b dA`, `mass[a][b]`.
    pub mass: Vec<Vec<f64>>,
}

/// The integrals of facet `facet` of `model` (reference configuration): a
/// 2-node planar edge by [`edge_weights`] / [`edge_mass`], a face of a
/// solid by its face quadrature; other facets (3-node planar edges) are
/// empty.
pub fn facet_integrals<const D: usize>(model: &Model<D>, facet: &Facet) -> FacetIntegrals {
    let nodes = &model.mesh.nodes;
    let f = facet.nodes();
    if D == 2 {
        if let &[a, b] = f {
            let (pa, pb) = ([nodes[a][0], nodes[a][1]], [nodes[b][0], nodes[b][1]]);
            let (kind, thick) = (model.analysis.kind, model.analysis.thickness);
            let w = edge_weights(pa, pb, kind, thick);
            let m = edge_mass(pa, pb, kind, thick);
            return FacetIntegrals {
                weights: w.to_vec(),
                mass: m.iter().map(|r| r.to_vec()).collect(),
            };
        }
        return FacetIntegrals {
            weights: Vec::new(),
            mass: Vec::new(),
        };
    }
    let nn = f.len();
    let mut out = FacetIntegrals {
        weights: vec![0.0; nn],
        mass: vec![vec![0.0; nn]; nn],
    };
    crate::solve::loads::face_points(nodes, f, true, |w, n, an| {
        let da = w * (an[0] * an[0] + an[1] * an[1] + an[2] * an[2]).sqrt();
        for a in 0..nn {
            out.weights[a] += n[a] * da;
            for b in 0..nn {
                out.mass[a][b] += n[a] * n[b] * da;
            }
        }
    });
    out
}

/// `int N_a dA` for the two nodes of edge `pa -> pb`.
pub fn edge_weights(pa: [f64; 2], pb: [f64; 2], kind: AnalysisKind, thickness: f64) -> [f64; 2] {
    let len = (pb[0] - pa[0]).hypot(pb[1] - pa[1]);
    match kind {
        AnalysisKind::PlaneStrain | AnalysisKind::PlaneStress | AnalysisKind::Solid => {
            let w = 0.5 * len * thickness;
            [w, w]
        }
        AnalysisKind::Axisymmetric => {
            let (ra, rb) = (pa[0].max(0.0), pb[0].max(0.0));
            [
                2.0 * PI * len * (2.0 * ra + rb) / 6.0,
                2.0 * PI * len * (ra + 2.0 * rb) / 6.0,
            ]
        }
    }
}

/// `int N_a N_b dA` for the two nodes of edge `pa -> pb` (row-major 2x2).
pub fn edge_mass(pa: [f64; 2], pb: [f64; 2], kind: AnalysisKind, thickness: f64) -> [[f64; 2]; 2] {
    let len = (pb[0] - pa[0]).hypot(pb[1] - pa[1]);
    match kind {
        AnalysisKind::PlaneStrain | AnalysisKind::PlaneStress | AnalysisKind::Solid => {
            let d = len * thickness / 3.0;
            let o = len * thickness / 6.0;
            [[d, o], [o, d]]
        }
        AnalysisKind::Axisymmetric => {
            let (ra, rb) = (pa[0].max(0.0), pb[0].max(0.0));
            let c = 2.0 * PI * len / 12.0;
            [
                [c * (3.0 * ra + rb), c * (ra + rb)],
                [c * (ra + rb), c * (ra + 3.0 * rb)],
            ]
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::{Cell, Mesh};

    #[test]
    fn face_integrals_of_a_tri3_and_a_parallelogram_quad4_are_exact() {
        // a triangle and a parallelogram in the tilted plane z = x + y
        let z = |x: f64, y: f64| x + y;
        let pts = [[0.0, 0.0], [2.0, 0.0], [2.5, 1.0], [0.5, 1.0]];
        let nodes: Vec<[f64; 3]> = pts.iter().map(|p| [p[0], p[1], z(p[0], p[1])]).collect();
        let mesh = Mesh::<3>::new(nodes, vec![Cell::tet([0, 1, 2, 3])]);
        let model = crate::testkit::ModelBuilder::<3>::solid()
            .mesh(mesh)
            .build();
        let stretch = 3f64.sqrt(); // dA = sqrt(1 + 1 + 1) dx dy
        let tri = facet_integrals(&model, &Facet::new(&[0, 1, 2]));
        let area = 0.5 * 2.0 * 1.0 * stretch;
        for a in 0..3 {
            assert!((tri.weights[a] - area / 3.0).abs() < 1e-14);
            for b in 0..3 {
                let exact = area / 12.0 * if a == b { 2.0 } else { 1.0 };
                assert!((tri.mass[a][b] - exact).abs() < 1e-14, "{a} {b}");
            }
        }
        let quad = facet_integrals(&model, &Facet::new(&[0, 1, 2, 3]));
        let area = 2.0 * stretch;
        // parallelogram: int N_a N_b dA = A/9 (a = b), A/18 (edge), A/36
        // (opposite)
        for a in 0..4 {
            assert!((quad.weights[a] - area / 4.0).abs() < 1e-14);
            for b in 0..4 {
                let exact = area
                    * match (a + 4 - b) % 4 {
                        0 => 1.0 / 9.0,
                        2 => 1.0 / 36.0,
                        _ => 1.0 / 18.0,
                    };
                assert!((quad.mass[a][b] - exact).abs() < 1e-14, "{a} {b}");
            }
        }
    }

    #[test]
    fn edge_mass_rows_sum_to_the_weights_and_weights_to_the_area() {
        let (pa, pb) = ([1.0, 0.0], [3.0, 1.0]);
        for kind in [AnalysisKind::PlaneStrain, AnalysisKind::Axisymmetric] {
            let w = edge_weights(pa, pb, kind, 2.0);
            let m = edge_mass(pa, pb, kind, 2.0);
            for a in 0..2 {
                assert!((m[a][0] + m[a][1] - w[a]).abs() < 1e-12);
            }
            let len = 5f64.sqrt();
            let area = match kind {
                AnalysisKind::Axisymmetric => 2.0 * PI * 2.0 * len,
                _ => 2.0 * len,
            };
            assert!((w[0] + w[1] - area).abs() < 1e-12);
        }
    }
}
