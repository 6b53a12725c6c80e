//! 6-node quadratic triangle: corners (0, 0), (1, 0), (0, 1), then the
//! edge midpoints of (0,1), (1,2), (2,0) (gmsh / VTK order); the 3-point
//! rule of degree 2 (points at barycentric `(2/3, 1/6, 1/6)`, exact for the
//! stiffness of straight-sided cells).

use super::ReferenceCell;
use crate::mesh::CellKind;

/// The quadratic triangle.
#[derive(Debug, Clone, Copy)]
pub struct Tri6;

/// Barycentric coordinates `(1 - x - y, x, y)` and their gradients.
fn barycentric(xi: &[f64; 2]) -> [f64; 3] {
    [1.0 - xi[0] - xi[1], xi[0], xi[1]]
}
const DL: [[f64; 2]; 3] = [[-1.0, -1.0], [1.0, 0.0], [0.0, 1.0]];
/// The corner pair of each edge midpoint (nodes 3, 4, 5).
const EDGES: [[usize; 2]; 3] = [[0, 1], [1, 2], [2, 0]];

impl ReferenceCell<2, 6> for Tri6 {
    const KIND: CellKind = CellKind::Tri6;
    const NODES: [[f64; 2]; 6] = [
        [0.0, 0.0],
        [1.0, 0.0],
        [0.0, 1.0],
        [0.5, 0.0],
        [0.5, 0.5],
        [0.0, 0.5],
    ];
    const FACES: &'static [&'static [usize]] = &[&[0, 1, 3], &[1, 2, 4], &[2, 0, 5]];
    // point p has barycentric coordinate p equal to 2/3
    const QUADRATURE: &'static [([f64; 2], f64)] = &[
        ([1.0 / 6.0, 1.0 / 6.0], 1.0 / 6.0),
        ([2.0 / 3.0, 1.0 / 6.0], 1.0 / 6.0),
        ([1.0 / 6.0, 2.0 / 3.0], 1.0 / 6.0),
    ];
    const CENTRE: [f64; 2] = [1.0 / 3.0, 1.0 / 3.0];
    const SELECTIVE_REDUCED: bool = false;
    const MASS_QUADRATURE: &'static [([f64; 2], f64)] = &super::COLLAPSED_TRI16;

    fn shape(xi: &[f64; 2]) -> [f64; 6] {
        let l = barycentric(xi);
        std::array::from_fn(|a| {
            if a < 3 {
                l[a] * (2.0 * l[a] - 1.0)
            } else {
                let [i, j] = EDGES[a - 3];
                4.0 * l[i] * l[j]
            }
        })
    }

    fn gradients(xi: &[f64; 2]) -> [[f64; 2]; 6] {
        let l = barycentric(xi);
        std::array::from_fn(|a| {
            std::array::from_fn(|k| {
                if a < 3 {
                    (4.0 * l[a] - 1.0) * DL[a][k]
                } else {
                    let [i, j] = EDGES[a - 3];
                    4.0 * (l[i] * DL[j][k] + l[j] * DL[i][k])
                }
            })
        })
    }

    /// The linear field through the 3 points: `2 L_p(node) - 1/3`.
    fn extrapolation(node: usize, point: usize) -> f64 {
        2.0 * barycentric(&Self::NODES[node])[point] - 1.0 / 3.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::element::reference::testing::{
        check_exactness, check_extrapolation, check_reference, check_stiffness,
    };

    #[test]
    fn tri6_reference_cell() {
        check_reference::<2, 6, Tri6>(0.5);
        check_exactness::<2, 6, Tri6>(2, false);
        check_extrapolation::<2, 6, Tri6>(|x| 1.0 + 2.0 * x[0] - 3.0 * x[1]);
    }

    #[test]
    fn tri6_stiffness_symmetric_with_rigid_body_modes() {
        use crate::model::AnalysisKind;
        check_stiffness::<2, 6, 12, Tri6>(&[
            (AnalysisKind::PlaneStrain, 3),
            (AnalysisKind::PlaneStress, 3),
            (AnalysisKind::Axisymmetric, 1),
        ]);
    }
}
