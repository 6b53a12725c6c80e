//! 20-node serendipity hexahedron on `[-1, 1]^3` (VTK / Abaqus C3D20
//! order): the hex8 corners, the midpoints of the bottom edges (0,1),
//! (1,2), (2,3), (3,0), of the top edges (4,5), (5,6), (6,7), (7,4), then
//! of the vertical edges (0,4), (1,5), (2,6), (3,7). [`Hex20`] integrates
//! with 3x3x3 Gauss points, [`Hex20R`] (Abaqus C3D20R) with the reduced
//! 2x2x2 rule.

use super::{
    gauss2_sign, serendipity, tensor_extrapolation, tensor_extrapolation3, ReferenceCell,
    GAUSS2X2X2, GAUSS3X3X3,
};
use crate::mesh::CellKind;

/// The serendipity hexahedron, full (3x3x3) integration.
#[derive(Debug, Clone, Copy)]
pub struct Hex20;

/// The serendipity hexahedron, reduced (2x2x2) integration.
#[derive(Debug, Clone, Copy)]
pub struct Hex20R;

/// Node coordinates (corners, then edge midpoints).
pub const NODES: [[f64; 3]; 20] = [
    [-1.0, -1.0, -1.0],
    [1.0, -1.0, -1.0],
    [1.0, 1.0, -1.0],
    [-1.0, 1.0, -1.0],
    [-1.0, -1.0, 1.0],
    [1.0, -1.0, 1.0],
    [1.0, 1.0, 1.0],
    [-1.0, 1.0, 1.0],
    [0.0, -1.0, -1.0],
    [1.0, 0.0, -1.0],
    [0.0, 1.0, -1.0],
    [-1.0, 0.0, -1.0],
    [0.0, -1.0, 1.0],
    [1.0, 0.0, 1.0],
    [0.0, 1.0, 1.0],
    [-1.0, 0.0, 1.0],
    [-1.0, -1.0, 0.0],
    [1.0, -1.0, 0.0],
    [1.0, 1.0, 0.0],
    [-1.0, 1.0, 0.0],
];

/// The faces: the hex8 faces (counter-clockwise seen from outside), then
/// their edge midpoints in the same cyclic order.
pub const FACES: &[&[usize]] = &[
    &[0, 3, 2, 1, 11, 10, 9, 8],
    &[4, 5, 6, 7, 12, 13, 14, 15],
    &[0, 1, 5, 4, 8, 17, 12, 16],
    &[1, 2, 6, 5, 9, 18, 13, 17],
    &[2, 3, 7, 6, 10, 19, 14, 18],
    &[3, 0, 4, 7, 11, 16, 15, 19],
];

fn shape(xi: &[f64; 3]) -> [f64; 20] {
    NODES.map(|c| serendipity(&c, xi).0)
}

fn gradients(xi: &[f64; 3]) -> [[f64; 3]; 20] {
    NODES.map(|c| serendipity(&c, xi).1)
}

impl ReferenceCell<3, 20> for Hex20 {
    const KIND: CellKind = CellKind::Hex20;
    const NODES: [[f64; 3]; 20] = NODES;
    const FACES: &'static [&'static [usize]] = FACES;
    const QUADRATURE: &'static [([f64; 3], f64)] = &GAUSS3X3X3;
    const CENTRE: [f64; 3] = [0.0, 0.0, 0.0];

    fn shape(xi: &[f64; 3]) -> [f64; 20] {
        shape(xi)
    }

    fn gradients(xi: &[f64; 3]) -> [[f64; 3]; 20] {
        gradients(xi)
    }

    fn extrapolation(node: usize, point: usize) -> f64 {
        tensor_extrapolation3(&NODES[node], &GAUSS3X3X3[point].0)
    }
}

impl ReferenceCell<3, 20> for Hex20R {
    const KIND: CellKind = CellKind::Hex20R;
    const NODES: [[f64; 3]; 20] = NODES;
    const FACES: &'static [&'static [usize]] = FACES;
    const QUADRATURE: &'static [([f64; 3], f64)] = &GAUSS2X2X2;
    const CENTRE: [f64; 3] = [0.0, 0.0, 0.0];
    const SELECTIVE_REDUCED: bool = false;
    const MASS_QUADRATURE: &'static [([f64; 3], f64)] = &GAUSS3X3X3;

    fn shape(xi: &[f64; 3]) -> [f64; 20] {
        shape(xi)
    }

    fn gradients(xi: &[f64; 3]) -> [[f64; 3]; 20] {
        gradients(xi)
    }

    fn extrapolation(node: usize, point: usize) -> f64 {
        tensor_extrapolation(&NODES[node], &gauss2_sign(&GAUSS2X2X2[point].0))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::element::reference::testing::{
        check_exactness, check_extrapolation, check_reference, check_stiffness,
    };

    #[test]
    fn hex20_reference_cell() {
        check_reference::<3, 20, Hex20>(8.0);
        check_exactness::<3, 20, Hex20>(5, true);
        check_extrapolation::<3, 20, Hex20>(|x| 1.0 + x[0] * x[0] * x[1] * x[2] * x[2] - x[2]);
    }

    #[test]
    fn hex20r_reference_cell() {
        check_reference::<3, 20, Hex20R>(8.0);
        check_exactness::<3, 20, Hex20R>(3, true);
        check_extrapolation::<3, 20, Hex20R>(|x| 1.0 + x[0] * x[1] * x[2] - 2.0 * x[1]);
    }

    #[test]
    fn hex20_stiffness_symmetric_with_rigid_body_modes() {
        use crate::model::AnalysisKind;
        check_stiffness::<3, 20, 60, Hex20>(&[(AnalysisKind::Solid, 6)]);
    }

    #[test]
    fn hex20r_stiffness_symmetric_with_rigid_body_modes() {
        use crate::model::AnalysisKind;
        check_stiffness::<3, 20, 60, Hex20R>(&[(AnalysisKind::Solid, 12)]);
    }
}
