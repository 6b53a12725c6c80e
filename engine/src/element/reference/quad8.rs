//! 8-node serendipity quadrilateral on `[-1, 1]^2`: the quad4 corners,
//! then the edge midpoints of (0,1), (1,2), (2,3), (3,0) (gmsh / VTK
//! order). [`Quad8`] integrates with 3x3 Gauss points, [`Quad8R`] (the
//! CPE8R / CAX8R of Abaqus) with the reduced 2x2 rule, whose single-cell
//! spurious mode does not propagate through a mesh.

use super::{
    gauss2_sign, serendipity, tensor_extrapolation, tensor_extrapolation3, ReferenceCell, GAUSS2X2,
    GAUSS3X3,
};
use crate::mesh::CellKind;

/// The serendipity quadrilateral, full (3x3) integration.
#[derive(Debug, Clone, Copy)]
pub struct Quad8;

/// The serendipity quadrilateral, reduced (2x2) integration.
#[derive(Debug, Clone, Copy)]
pub struct Quad8R;

/// Node coordinates (corners, then edge midpoints).
pub const NODES: [[f64; 2]; 8] = [
    [-1.0, -1.0],
    [1.0, -1.0],
    [1.0, 1.0],
    [-1.0, 1.0],
    [0.0, -1.0],
    [1.0, 0.0],
    [0.0, 1.0],
    [-1.0, 0.0],
];

/// The edges: two corners, then the midpoint (outward order).
pub const FACES: &[&[usize]] = &[&[0, 1, 4], &[1, 2, 5], &[2, 3, 6], &[3, 0, 7]];

fn shape(xi: &[f64; 2]) -> [f64; 8] {
    NODES.map(|c| serendipity(&c, xi).0)
}

fn gradients(xi: &[f64; 2]) -> [[f64; 2]; 8] {
    NODES.map(|c| serendipity(&c, xi).1)
}

impl ReferenceCell<2, 8> for Quad8 {
    const KIND: CellKind = CellKind::Quad8;
    const NODES: [[f64; 2]; 8] = NODES;
    const FACES: &'static [&'static [usize]] = FACES;
    const QUADRATURE: &'static [([f64; 2], f64)] = &GAUSS3X3;
    const CENTRE: [f64; 2] = [0.0, 0.0];

    fn shape(xi: &[f64; 2]) -> [f64; 8] {
        shape(xi)
    }

    fn gradients(xi: &[f64; 2]) -> [[f64; 2]; 8] {
        gradients(xi)
    }

    fn extrapolation(node: usize, point: usize) -> f64 {
        tensor_extrapolation3(&NODES[node], &GAUSS3X3[point].0)
    }
}

impl ReferenceCell<2, 8> for Quad8R {
    const KIND: CellKind = CellKind::Quad8R;
    const NODES: [[f64; 2]; 8] = NODES;
    const FACES: &'static [&'static [usize]] = FACES;
    const QUADRATURE: &'static [([f64; 2], f64)] = &GAUSS2X2;
    const CENTRE: [f64; 2] = [0.0, 0.0];
    const SELECTIVE_REDUCED: bool = false;
    const MASS_QUADRATURE: &'static [([f64; 2], f64)] = &GAUSS3X3;

    fn shape(xi: &[f64; 2]) -> [f64; 8] {
        shape(xi)
    }

    fn gradients(xi: &[f64; 2]) -> [[f64; 2]; 8] {
        gradients(xi)
    }

    fn extrapolation(node: usize, point: usize) -> f64 {
        tensor_extrapolation(&NODES[node], &gauss2_sign(&GAUSS2X2[point].0))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::element::reference::testing::{
        check_exactness, check_extrapolation, check_reference, check_stiffness,
    };

    #[test]
    fn quad8_reference_cell() {
        check_reference::<2, 8, Quad8>(4.0);
        check_exactness::<2, 8, Quad8>(5, true);
        check_extrapolation::<2, 8, Quad8>(|x| 1.0 + x[0] - x[1] + x[0] * x[0] * x[1] * x[1]);
    }

    #[test]
    fn quad8r_reference_cell() {
        check_reference::<2, 8, Quad8R>(4.0);
        check_exactness::<2, 8, Quad8R>(3, true);
        check_extrapolation::<2, 8, Quad8R>(|x| 1.0 + 2.0 * x[0] - 3.0 * x[1] + x[0] * x[1]);
    }

    #[test]
    fn quad8_stiffness_symmetric_with_rigid_body_modes() {
        use crate::model::AnalysisKind;
        check_stiffness::<2, 8, 16, Quad8>(&[
            (AnalysisKind::PlaneStrain, 3),
            (AnalysisKind::PlaneStress, 3),
            (AnalysisKind::Axisymmetric, 1),
        ]);
    }

    #[test]
    fn quad8r_stiffness_symmetric_with_rigid_body_modes() {
        use crate::model::AnalysisKind;
        check_stiffness::<2, 8, 16, Quad8R>(&[
            (AnalysisKind::PlaneStrain, 4),
            (AnalysisKind::Axisymmetric, 1),
        ]);
    }

    #[test]
    fn quad8_with_a_midside_node_past_the_quarter_point_is_inverted() {
        // Barsoum: a midside node at the quarter point makes det J vanish at
        // the corner; beyond it the cell folds over
        let mut x: Vec<Vec<f64>> = NODES.iter().map(|p| p.to_vec()).collect();
        let (dets, _) =
            crate::element::reference::corner_jacobians(CellKind::Quad8, &refs(&x)).unwrap();
        assert!(dets.iter().all(|&d| d > 0.0));
        x[4] = vec![-0.6, -1.0];
        let (dets, _) =
            crate::element::reference::corner_jacobians(CellKind::Quad8, &refs(&x)).unwrap();
        assert!(dets.iter().any(|&d| d <= 0.0), "{dets:?}");
    }

    fn refs(x: &[Vec<f64>]) -> Vec<&[f64]> {
        x.iter().map(|p| p.as_slice()).collect()
    }
}
