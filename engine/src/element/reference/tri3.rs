//! 3-node linear triangle: nodes (0, 0), (1, 0), (0, 1); one integration
//! point at the centroid (constant strain).

use super::ReferenceCell;
use crate::mesh::CellKind;

/// The linear triangle.
#[derive(Debug, Clone, Copy)]
pub struct Tri3;

impl ReferenceCell<2, 3> for Tri3 {
    const KIND: CellKind = CellKind::Tri3;
    const NODES: [[f64; 2]; 3] = [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]];
    const FACES: &'static [&'static [usize]] = &[&[0, 1], &[1, 2], &[2, 0]];
    const QUADRATURE: &'static [([f64; 2], f64)] = &[([1.0 / 3.0, 1.0 / 3.0], 0.5)];
    const CENTRE: [f64; 2] = [1.0 / 3.0, 1.0 / 3.0];

    fn shape(xi: &[f64; 2]) -> [f64; 3] {
        [1.0 - xi[0] - xi[1], xi[0], xi[1]]
    }

    fn gradients(_xi: &[f64; 2]) -> [[f64; 2]; 3] {
        [[-1.0, -1.0], [1.0, 0.0], [0.0, 1.0]]
    }

    fn extrapolation(_node: usize, _point: usize) -> f64 {
        1.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tri3_reference_cell() {
        super::super::testing::check_reference::<2, 3, Tri3>(0.5);
    }
}
