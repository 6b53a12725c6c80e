//! 9-node Lagrange quadrilateral on `[-1, 1]^2`: the quad8 nodes, then
//! the centre (gmsh / VTK order); 3x3 Gauss points.

use super::{lagrange_tensor, tensor_extrapolation3, ReferenceCell, GAUSS3X3};
use crate::mesh::CellKind;

/// The biquadratic quadrilateral.
#[derive(Debug, Clone, Copy)]
pub struct Quad9;

const NODES: [[f64; 2]; 9] = [
    [-1.0, -1.0],
    [1.0, -1.0],
    [1.0, 1.0],
    [-1.0, 1.0],
    [0.0, -1.0],
    [1.0, 0.0],
    [0.0, 1.0],
    [-1.0, 0.0],
    [0.0, 0.0],
];

impl ReferenceCell<2, 9> for Quad9 {
    const KIND: CellKind = CellKind::Quad9;
    const NODES: [[f64; 2]; 9] = NODES;
    const FACES: &'static [&'static [usize]] = super::quad8::FACES;
    const QUADRATURE: &'static [([f64; 2], f64)] = &GAUSS3X3;
    const CENTRE: [f64; 2] = [0.0, 0.0];

    fn shape(xi: &[f64; 2]) -> [f64; 9] {
        NODES.map(|c| lagrange_tensor(&c, xi).0)
    }

    fn gradients(xi: &[f64; 2]) -> [[f64; 2]; 9] {
        NODES.map(|c| lagrange_tensor(&c, xi).1)
    }

    fn extrapolation(node: usize, point: usize) -> f64 {
        tensor_extrapolation3(&NODES[node], &GAUSS3X3[point].0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::element::reference::testing::{
        check_exactness, check_extrapolation, check_reference, check_stiffness,
    };

    #[test]
    fn quad9_reference_cell() {
        check_reference::<2, 9, Quad9>(4.0);
        check_exactness::<2, 9, Quad9>(5, true);
        check_extrapolation::<2, 9, Quad9>(|x| 1.0 + x[0] - x[1] + x[0] * x[0] * x[1] * x[1]);
    }

    #[test]
    fn quad9_stiffness_symmetric_with_rigid_body_modes() {
        use crate::model::AnalysisKind;
        check_stiffness::<2, 9, 18, Quad9>(&[
            (AnalysisKind::PlaneStrain, 3),
            (AnalysisKind::PlaneStress, 3),
            (AnalysisKind::Axisymmetric, 1),
        ]);
    }
}
