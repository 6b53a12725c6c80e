//! 4-node linear tetrahedron: nodes (0,0,0), (1,0,0), (0,1,0), (0,0,1)
//! (gmsh / VTK order, positive volume); one integration point at the
//! centroid (constant strain).

use super::ReferenceCell;
use crate::mesh::CellKind;

/// The 4-point rule (degree 2) on the unit tetrahedron, weights summing to
/// 1/6: exact for `N_a N_b` (the Jacobian is constant).
const MASS_RULE: [([f64; 3], f64); 4] = {
    const A: f64 = 0.585_410_196_624_968_5;
    const B: f64 = 0.138_196_601_125_010_5;
    const W: f64 = 1.0 / 24.0;
    [
        ([B, B, B], W),
        ([A, B, B], W),
        ([B, A, B], W),
        ([B, B, A], W),
    ]
};

/// The linear tetrahedron.
#[derive(Debug, Clone, Copy)]
pub struct Tet4;

impl ReferenceCell<3, 4> for Tet4 {
    const KIND: CellKind = CellKind::Tet4;
    const NODES: [[f64; 3]; 4] = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
    ];
    // counter-clockwise seen from outside
    const FACES: &'static [&'static [usize]] = &[&[0, 2, 1], &[0, 1, 3], &[1, 2, 3], &[0, 3, 2]];
    const QUADRATURE: &'static [([f64; 3], f64)] = &[([0.25, 0.25, 0.25], 1.0 / 6.0)];
    const CENTRE: [f64; 3] = [0.25, 0.25, 0.25];
    const MASS_QUADRATURE: &'static [([f64; 3], f64)] = &MASS_RULE;

    fn shape(xi: &[f64; 3]) -> [f64; 4] {
        [1.0 - xi[0] - xi[1] - xi[2], xi[0], xi[1], xi[2]]
    }

    fn gradients(_xi: &[f64; 3]) -> [[f64; 3]; 4] {
        [
            [-1.0, -1.0, -1.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0],
        ]
    }

    fn extrapolation(_node: usize, _point: usize) -> f64 {
        1.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tet4_reference_cell() {
        super::super::testing::check_reference::<3, 4, Tet4>(1.0 / 6.0);
    }
}
