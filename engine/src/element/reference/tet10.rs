//! 10-node quadratic tetrahedron: corners (0,0,0), (1,0,0), (0,1,0),
//! (0,0,1), then the edge midpoints of (0,1), (1,2), (0,2), (0,3), (1,3),
//! (2,3) (VTK order; gmsh swaps the last two); the 4-point rule of
//! degree 2.

use super::ReferenceCell;
use crate::mesh::CellKind;

/// The quadratic tetrahedron.
#[derive(Debug, Clone, Copy)]
pub struct Tet10;

/// Barycentric coordinate of the 4-point rule's own vertex.
const A: f64 = 0.585_410_196_624_968_5;
/// Barycentric coordinate of the 4-point rule's other vertices.
const B: f64 = 0.138_196_601_125_010_5;

fn barycentric(xi: &[f64; 3]) -> [f64; 4] {
    [1.0 - xi[0] - xi[1] - xi[2], xi[0], xi[1], xi[2]]
}
const DL: [[f64; 3]; 4] = [
    [-1.0, -1.0, -1.0],
    [1.0, 0.0, 0.0],
    [0.0, 1.0, 0.0],
    [0.0, 0.0, 1.0],
];
/// The corner pair of each edge midpoint (nodes 4 to 9).
const EDGES: [[usize; 2]; 6] = [[0, 1], [1, 2], [0, 2], [0, 3], [1, 3], [2, 3]];

impl ReferenceCell<3, 10> for Tet10 {
    const KIND: CellKind = CellKind::Tet10;
    const NODES: [[f64; 3]; 10] = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
        [0.5, 0.0, 0.0],
        [0.5, 0.5, 0.0],
        [0.0, 0.5, 0.0],
        [0.0, 0.0, 0.5],
        [0.5, 0.0, 0.5],
        [0.0, 0.5, 0.5],
    ];
    // the tet4 faces, counter-clockwise seen from outside, then their midpoints
    const FACES: &'static [&'static [usize]] = &[
        &[0, 2, 1, 6, 5, 4],
        &[0, 1, 3, 4, 8, 7],
        &[1, 2, 3, 5, 9, 8],
        &[0, 3, 2, 7, 9, 6],
    ];
    // point p has barycentric coordinate p equal to A
    const QUADRATURE: &'static [([f64; 3], f64)] = &[
        ([B, B, B], 1.0 / 24.0),
        ([A, B, B], 1.0 / 24.0),
        ([B, A, B], 1.0 / 24.0),
        ([B, B, A], 1.0 / 24.0),
    ];
    const CENTRE: [f64; 3] = [0.25, 0.25, 0.25];
    const SELECTIVE_REDUCED: bool = false;
    const MASS_QUADRATURE: &'static [([f64; 3], f64)] = &super::COLLAPSED_TET64;

    fn shape(xi: &[f64; 3]) -> [f64; 10] {
        let l = barycentric(xi);
        std::array::from_fn(|a| {
            if a < 4 {
                l[a] * (2.0 * l[a] - 1.0)
            } else {
                let [i, j] = EDGES[a - 4];
                4.0 * l[i] * l[j]
            }
        })
    }

    fn gradients(xi: &[f64; 3]) -> [[f64; 3]; 10] {
        let l = barycentric(xi);
        std::array::from_fn(|a| {
            std::array::from_fn(|k| {
                if a < 4 {
                    (4.0 * l[a] - 1.0) * DL[a][k]
                } else {
                    let [i, j] = EDGES[a - 4];
                    4.0 * (l[i] * DL[j][k] + l[j] * DL[i][k])
                }
            })
        })
    }

    /// The linear field through the 4 points: `(L_p(node) - B) / (A - B)`.
    fn extrapolation(node: usize, point: usize) -> f64 {
        (barycentric(&Self::NODES[node])[point] - B) / (A - B)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::element::reference::testing::{
        check_exactness, check_extrapolation, check_reference, check_stiffness,
    };

    #[test]
    fn tet10_reference_cell() {
        check_reference::<3, 10, Tet10>(1.0 / 6.0);
        check_exactness::<3, 10, Tet10>(2, false);
        check_extrapolation::<3, 10, Tet10>(|x| 1.0 + 2.0 * x[0] - 3.0 * x[1] + 0.5 * x[2]);
    }

    #[test]
    fn tet10_stiffness_symmetric_with_rigid_body_modes() {
        use crate::model::AnalysisKind;
        check_stiffness::<3, 10, 30, Tet10>(&[(AnalysisKind::Solid, 6)]);
    }
}
