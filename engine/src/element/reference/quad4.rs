//! 4-node bilinear quadrilateral on `[-1, 1]^2`, nodes counter-clockwise;
//! 2x2 Gauss points ordered like the nodes (point `g` is nearest node `g`).

use super::{tensor_extrapolation, ReferenceCell, GAUSS2X2, GAUSS3X3};
use crate::mesh::CellKind;

/// The bilinear quadrilateral.
#[derive(Debug, Clone, Copy)]
pub struct Quad4;

const CORNERS: [[f64; 2]; 4] = [[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]];

impl ReferenceCell<2, 4> for Quad4 {
    const KIND: CellKind = CellKind::Quad4;
    const NODES: [[f64; 2]; 4] = CORNERS;
    const FACES: &'static [&'static [usize]] = &[&[0, 1], &[1, 2], &[2, 3], &[3, 0]];
    const QUADRATURE: &'static [([f64; 2], f64)] = &GAUSS2X2;
    const CENTRE: [f64; 2] = [0.0, 0.0];
    // 3^2 Gauss points: N_a N_b det(J) (r) of a distorted cell
    const MASS_QUADRATURE: &'static [([f64; 2], f64)] = &GAUSS3X3;

    fn shape(xi: &[f64; 2]) -> [f64; 4] {
        CORNERS.map(|c| 0.25 * (1.0 + c[0] * xi[0]) * (1.0 + c[1] * xi[1]))
    }

    fn gradients(xi: &[f64; 2]) -> [[f64; 2]; 4] {
        CORNERS.map(|c| {
            [
                0.25 * c[0] * (1.0 + c[1] * xi[1]),
                0.25 * c[1] * (1.0 + c[0] * xi[0]),
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
    fn quad4_reference_cell() {
        super::super::testing::check_reference::<2, 4, Quad4>(4.0);
    }

    #[test]
    fn quad4_extrapolation_reproduces_bilinear_fields() {
        // a bilinear field f = 1 + 2 xi - 3 eta + 4 xi eta sampled at the Gauss points
        let f = |x: &[f64; 2]| 1.0 + 2.0 * x[0] - 3.0 * x[1] + 4.0 * x[0] * x[1];
        for (node, c) in CORNERS.iter().enumerate() {
            let v: f64 = Quad4::QUADRATURE
                .iter()
                .enumerate()
                .map(|(p, q)| Quad4::extrapolation(node, p) * f(&q.0))
                .sum();
            assert!((v - f(c)).abs() < 1e-13);
        }
    }
}
