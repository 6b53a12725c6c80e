//! 8-node trilinear hexahedron on `[-1, 1]^3` (gmsh / VTK order: the
//! bottom face `z = -1` counter-clockwise seen from above, then the top
//! face); 2x2x2 Gauss points ordered like the nodes.

use super::{tensor_extrapolation, ReferenceCell, GAUSS2X2X2, GAUSS3X3X3};
use crate::mesh::CellKind;

/// The trilinear hexahedron.
#[derive(Debug, Clone, Copy)]
pub struct Hex8;

const CORNERS: [[f64; 3]; 8] = [
    [-1.0, -1.0, -1.0],
    [1.0, -1.0, -1.0],
    [1.0, 1.0, -1.0],
    [-1.0, 1.0, -1.0],
    [-1.0, -1.0, 1.0],
    [1.0, -1.0, 1.0],
    [1.0, 1.0, 1.0],
    [-1.0, 1.0, 1.0],
];

impl ReferenceCell<3, 8> for Hex8 {
    const KIND: CellKind = CellKind::Hex8;
    const NODES: [[f64; 3]; 8] = CORNERS;
    // counter-clockwise seen from outside
    const FACES: &'static [&'static [usize]] = &[
        &[0, 3, 2, 1],
        &[4, 5, 6, 7],
        &[0, 1, 5, 4],
        &[1, 2, 6, 5],
        &[2, 3, 7, 6],
        &[3, 0, 4, 7],
    ];
    const QUADRATURE: &'static [([f64; 3], f64)] = &GAUSS2X2X2;
    const CENTRE: [f64; 3] = [0.0, 0.0, 0.0];
    // 3^3 Gauss points: N_a N_b det(J) (r) of a distorted cell
    const MASS_QUADRATURE: &'static [([f64; 3], f64)] = &GAUSS3X3X3;

    fn shape(xi: &[f64; 3]) -> [f64; 8] {
        CORNERS.map(|c| 0.125 * (1.0 + c[0] * xi[0]) * (1.0 + c[1] * xi[1]) * (1.0 + c[2] * xi[2]))
    }

    fn gradients(xi: &[f64; 3]) -> [[f64; 3]; 8] {
        CORNERS.map(|c| {
            let (a, b, d) = (1.0 + c[0] * xi[0], 1.0 + c[1] * xi[1], 1.0 + c[2] * xi[2]);
            [
                0.125 * c[0] * b * d,
                0.125 * c[1] * a * d,
                0.125 * c[2] * a * b,
            ]
        })
    }

    fn extrapolation(node: usize, point: usize) -> f64 {
        tensor_extrapolation(&CORNERS[node], &CORNERS[point])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hex8_reference_cell() {
        super::super::testing::check_reference::<3, 8, Hex8>(8.0);
    }

    #[test]
    fn hex8_extrapolation_reproduces_trilinear_fields() {
        let f = |x: &[f64; 3]| 1.0 + 2.0 * x[0] - x[1] + 0.5 * x[2] + x[0] * x[1] * x[2];
        for (node, c) in CORNERS.iter().enumerate() {
            let v: f64 = Hex8::QUADRATURE
                .iter()
                .enumerate()
                .map(|(p, q)| Hex8::extrapolation(node, p) * f(&q.0))
                .sum();
            assert!((v - f(c)).abs() < 1e-13);
        }
    }
}
