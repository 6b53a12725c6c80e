//! The isoparametric map of a cell at one reference point: shape values,
//! Cartesian gradients `dN/dX`, the position and the volume weight.

use super::reference::ReferenceCell;
use super::{planar, ElementError, Section};
use crate::geom::{Block, Dimension, Point};
use nalgebra::Const;

/// Shape data of one integration point in the reference configuration.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShapePoint<const D: usize, const NN: usize> {
    /// Shape function values.
    pub n: [f64; NN],
    /// Cartesian gradients `dN_a / dX` per node.
    pub dndx: [Point<D>; NN],
    /// Position (x, y[, z]) — (r, z) for axisymmetric analyses.
    pub position: Point<D>,
    /// Volume weight `w det(J) t`, `w det(J) 2 pi r` (axisymmetric) or
    /// `w det(J)` (solid).
    pub volume: f64,
}

/// Checks that a Jacobian determinant is positive (cells must be
/// counter-clockwise in 2D, positively oriented in 3D, and not
/// degenerate).
pub(crate) fn check_jacobian(det: f64, what: &str, dim: usize) -> Result<(), ElementError> {
    if det > 0.0 && det.is_finite() {
        Ok(())
    } else if dim == 2 {
        Err(ElementError::new(format!(
            "{what}: non-positive Jacobian determinant {det:e} (nodes must be counter-clockwise \
             and the cell must not be degenerate or inverted)"
        )))
    } else {
        Err(ElementError::new(format!(
            "{what}: non-positive Jacobian determinant {det:e} (nodes must follow the gmsh \
             ordering with a positive volume, and the cell must not be degenerate or inverted)"
        )))
    }
}

/// `J^-T g` for the Jacobian `j` (columns `dx/dxi_k`) with determinant
/// `det` (2D: the closed form, the same arithmetic as the planar code
/// always had).
fn inverse_transpose_times<const D: usize>(j: &Block<D>, det: f64, g: &[f64; D]) -> Point<D>
where
    Const<D>: Dimension<D>,
{
    if D == 2 {
        let mut out = Point::<D>::zeros();
        // J = [[x_xi, x_eta], [y_xi, y_eta]]
        out[0] = (j[(1, 1)] * g[0] - j[(1, 0)] * g[1]) / det;
        out[1] = (-j[(0, 1)] * g[0] + j[(0, 0)] * g[1]) / det;
        out
    } else {
        let inv = j.try_inverse().unwrap_or_else(Block::<D>::zeros);
        inv.transpose() * Point::<D>::from_column_slice(g)
    }
}

/// Shape data of the cell with nodes `x` at the reference point `xi`, with
/// volume weight `weight` (quadrature weight; 0 for the centre, whose
/// volume weight is the cell's).
pub fn shape_point<const D: usize, const NN: usize, C: ReferenceCell<D, NN>>(
    x: &[Point<D>; NN],
    xi: &[f64; D],
    weight: f64,
    section: &Section,
) -> Result<ShapePoint<D, NN>, ElementError>
where
    Const<D>: Dimension<D>,
{
    let n = C::shape(xi);
    let dn = C::gradients(xi);
    let mut j = Block::<D>::zeros();
    let mut position = Point::<D>::zeros();
    for a in 0..NN {
        for r in 0..D {
            for k in 0..D {
                j[(r, k)] += x[a][r] * dn[a][k];
            }
            position[r] += n[a] * x[a][r];
        }
    }
    let det = j.determinant();
    check_jacobian(det, C::KIND.name(), D)?;
    let dndx = std::array::from_fn(|a| inverse_transpose_times(&j, det, &dn[a]));
    let w = if weight == 0.0 { C::measure() } else { weight };
    let measure = planar::measure(section, position[0]);
    Ok(ShapePoint {
        n,
        dndx,
        position,
        volume: w * det * measure,
    })
}

/// Shape data at the quadrature points of `C`.
pub fn quadrature_points<const D: usize, const NN: usize, C: ReferenceCell<D, NN>>(
    x: &[Point<D>; NN],
    section: &Section,
) -> Result<Vec<ShapePoint<D, NN>>, ElementError>
where
    Const<D>: Dimension<D>,
{
    C::QUADRATURE
        .iter()
        .map(|(xi, w)| shape_point::<D, NN, C>(x, xi, *w, section))
        .collect()
}

/// Shape data at the centre of `C`, with the volume weight of the cell.
pub fn centre_point<const D: usize, const NN: usize, C: ReferenceCell<D, NN>>(
    x: &[Point<D>; NN],
    section: &Section,
) -> Result<ShapePoint<D, NN>, ElementError>
where
    Const<D>: Dimension<D>,
{
    shape_point::<D, NN, C>(x, &C::CENTRE, 0.0, section)
}
