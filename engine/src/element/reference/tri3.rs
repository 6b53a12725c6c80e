//! 3-node linear triangle: nodes (0, 0), (1, 0), (0, 1); one integration
//! point at the centroid (constant strain).

use super::ReferenceCell;
use crate::mesh::CellKind;

/// Dunavant's 6-point rule (degree 4) on the unit triangle, weights summing
/// to 1/2: exact for the axisymmetric mass `N_a N_b r` (degree 3).
const MASS_RULE: [([f64; 2], f64); 6] = {
    const A: f64 = 0.445_948_490_915_965;
    const WA: f64 = 0.5 * 0.223_381_589_678_011;
    const B: f64 = 0.091_576_213_509_771;
    const WB: f64 = 0.5 * 0.109_951_743_655_322;
    [
        ([A, A], WA),
        ([1.0 - 2.0 * A, A], WA),
        ([A, 1.0 - 2.0 * A], WA),
        ([B, B], WB),
        ([1.0 - 2.0 * B, B], WB),
        ([B, 1.0 - 2.0 * B], WB),
    ]
};

/// The linear triangle.
#[derive(Debug, Clone, Copy)]
pub struct Tri3;

impl ReferenceCell<2, 3> for Tri3 {
    const KIND: CellKind = CellKind::Tri3;
    const NODES: [[f64; 2]; 3] = [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]];
    const FACES: &'static [&'static [usize]] = &[&[0, 1], &[1, 2], &[2, 0]];
    const QUADRATURE: &'static [([f64; 2], f64)] = &[([1.0 / 3.0, 1.0 / 3.0], 0.5)];
    const CENTRE: [f64; 2] = [1.0 / 3.0, 1.0 / 3.0];
    const MASS_QUADRATURE: &'static [([f64; 2], f64)] = &MASS_RULE;

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
