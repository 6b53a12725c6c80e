//! 27-node Lagrange hexahedron on `[-1, 1]^3` (VTK order): the hex20
//! nodes, the centres of the faces x = -1, x = 1, y = -1, y = 1, z = -1,
//! z = 1, then the body centre; 3x3x3 Gauss points.

use super::{lagrange_tensor, tensor_extrapolation3, ReferenceCell, GAUSS3X3X3};
use crate::mesh::CellKind;

/// The triquadratic hexahedron.
#[derive(Debug, Clone, Copy)]
pub struct Hex27;

const NODES: [[f64; 3]; 27] = {
    let mut out = [[0.0; 3]; 27];
    let mut i = 0;
    while i < 20 {
        out[i] = super::hex20::NODES[i];
        i += 1;
    }
    out[20] = [-1.0, 0.0, 0.0];
    out[21] = [1.0, 0.0, 0.0];
    out[22] = [0.0, -1.0, 0.0];
    out[23] = [0.0, 1.0, 0.0];
    out[24] = [0.0, 0.0, -1.0];
    out[25] = [0.0, 0.0, 1.0];
    out
};

impl ReferenceCell<3, 27> for Hex27 {
    const KIND: CellKind = CellKind::Hex27;
    const NODES: [[f64; 3]; 27] = NODES;
    // the hex20 faces, then the face centre
    const FACES: &'static [&'static [usize]] = &[
        &[0, 3, 2, 1, 11, 10, 9, 8, 24],
        &[4, 5, 6, 7, 12, 13, 14, 15, 25],
        &[0, 1, 5, 4, 8, 17, 12, 16, 22],
        &[1, 2, 6, 5, 9, 18, 13, 17, 21],
        &[2, 3, 7, 6, 10, 19, 14, 18, 23],
        &[3, 0, 4, 7, 11, 16, 15, 19, 20],
    ];
    const QUADRATURE: &'static [([f64; 3], f64)] = &GAUSS3X3X3;
    const CENTRE: [f64; 3] = [0.0, 0.0, 0.0];

    fn shape(xi: &[f64; 3]) -> [f64; 27] {
        NODES.map(|c| lagrange_tensor(&c, xi).0)
    }

    fn gradients(xi: &[f64; 3]) -> [[f64; 3]; 27] {
        NODES.map(|c| lagrange_tensor(&c, xi).1)
    }

    fn extrapolation(node: usize, point: usize) -> f64 {
        tensor_extrapolation3(&NODES[node], &GAUSS3X3X3[point].0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::element::reference::testing::{
        check_exactness, check_extrapolation, check_reference, check_stiffness,
    };

    #[test]
    fn hex27_reference_cell() {
        check_reference::<3, 27, Hex27>(8.0);
        check_exactness::<3, 27, Hex27>(5, true);
        check_extrapolation::<3, 27, Hex27>(|x| {
            1.0 + x[0] * x[0] * x[1] * x[1] * x[2] * x[2] - x[2] * x[0]
        });
    }

    #[test]
    fn hex27_stiffness_symmetric_with_rigid_body_modes() {
        use crate::model::AnalysisKind;
        check_stiffness::<3, 27, 81, Hex27>(&[(AnalysisKind::Solid, 6)]);
    }
}
