//! Points, node blocks and the dimension bound.

use crate::element::kernel::{self, CellKernel};
use crate::mesh::CellKind;
use nalgebra::{Const, DimMin, DimName, SMatrix, SVector};

/// A point or vector of `D`-dimensional space.
pub type Point<const D: usize> = SVector<f64, D>;

/// A `D x D` block: the coupling of two nodes in an element or contact
/// matrix, a deformation gradient, a curvature (Weingarten) map.
pub type Block<const D: usize> = SMatrix<f64, D, D>;

/// The spatial dimensions the engine is instantiated for: implemented by
/// `Const<2>` and `Const<3>` only. Generic code writes the single bound
/// `Const<D>: Dimension<D>`; its supertraits give nalgebra's square-matrix
/// algebra on [`Block<D>`] (determinant, inverse), its items what differs
/// between the planar and the solid case.
pub trait Dimension<const D: usize>: DimName + DimMin<Self, Output = Self> {
    /// `"2d"` or `"3d"` (deck spelling).
    const NAME: &'static str;

    /// Contact in this dimension, as the solver sees it
    /// (`crate::solve::scene`).
    type Contact: crate::solve::scene::ContactScene<D>;

    /// The thermal coupling in this dimension (`crate::solve::scene`).
    type Heat: crate::solve::scene::HeatCoupling<D>;

    /// Unit normal of the facet spanned by the `D - 1` tangent vectors
    /// `tangents` (the columns of the facet's Jacobian), oriented so that
    /// the body is on the side the facet's node order sees it: in 2D the
    /// right-hand normal `(t_y, -t_x)` of an edge walked with the body on
    /// its left; in 3D `t_1 x t_2` of a face numbered counter-clockwise seen
    /// from outside. Also returns the facet's measure element (length or
    /// area per unit reference measure). `None` for a degenerate facet.
    fn facet_normal(tangents: &[Point<D>]) -> Option<(Point<D>, f64)>;

    /// The element kernel of cell kind `kind` in this dimension (the
    /// registry of `crate::element::kernel`); `None` for a cell of the
    /// other dimension.
    fn kernel(kind: CellKind) -> Option<&'static dyn CellKernel<D>>;
}

impl Dimension<2> for Const<2> {
    const NAME: &'static str = "2d";
    type Contact = crate::solve::contact_assembly::ContactAssembly;
    type Heat = crate::thermal::coupling::Coupling;

    fn facet_normal(tangents: &[Point<2>]) -> Option<(Point<2>, f64)> {
        let t = tangents.first()?;
        let len = t.norm();
        (len > 0.0 && len.is_finite()).then(|| (Point::<2>::new(t[1], -t[0]) / len, len))
    }

    fn kernel(kind: CellKind) -> Option<&'static dyn CellKernel<2>> {
        match kind {
            CellKind::Tri3 => Some(&kernel::TRI3),
            CellKind::Quad4 => Some(&kernel::QUAD4),
            CellKind::Tri6 => Some(&kernel::TRI6),
            CellKind::Quad8 => Some(&kernel::QUAD8),
            CellKind::Quad8R => Some(&kernel::QUAD8R),
            CellKind::Quad9 => Some(&kernel::QUAD9),
            _ => None,
        }
    }
}

impl Dimension<3> for Const<3> {
    const NAME: &'static str = "3d";
    type Contact = crate::solve::surface_assembly::SurfaceAssembly;
    type Heat = crate::thermal::coupling::Coupling;

    fn facet_normal(tangents: &[Point<3>]) -> Option<(Point<3>, f64)> {
        let (a, b) = (tangents.first()?, tangents.get(1)?);
        let n = a.cross(b);
        let area = n.norm();
        (area > 0.0 && area.is_finite()).then(|| (n / area, area))
    }

    fn kernel(kind: CellKind) -> Option<&'static dyn CellKernel<3>> {
        match kind {
            CellKind::Tet4 => Some(&kernel::TET4),
            CellKind::Hex8 => Some(&kernel::HEX8),
            CellKind::Tet10 => Some(&kernel::TET10),
            CellKind::Hex20 => Some(&kernel::HEX20),
            CellKind::Hex20R => Some(&kernel::HEX20R),
            CellKind::Hex27 => Some(&kernel::HEX27),
            _ => None,
        }
    }
}

/// `[f64; D]` of a point (for code that stores plain arrays).
#[inline]
pub fn to_array<const D: usize>(p: &Point<D>) -> [f64; D] {
    let mut a = [0.0; D];
    a.copy_from_slice(p.as_slice());
    a
}

#[cfg(test)]
mod tests {
    use super::*;

    fn det<const D: usize>(b: &Block<D>) -> f64
    where
        Const<D>: Dimension<D>,
    {
        b.determinant()
    }

    #[test]
    fn one_bound_gives_the_block_algebra_in_2d_and_3d() {
        assert_eq!(det(&Block::<2>::new(2.0, 1.0, 0.0, 3.0)), 6.0);
        let b = Block::<3>::new(2.0, 0.0, 0.0, 0.0, 3.0, 0.0, 1.0, 0.0, 4.0);
        assert!((det(&b) - 24.0).abs() < 1e-14);
        assert_eq!(<Const<2> as Dimension<2>>::NAME, "2d");
    }

    #[test]
    fn facet_normals_point_outward_for_the_mesh_conventions() {
        // 2D: edge walked along +x with the body on its left (above): -y
        let (n, len) = Const::<2>::facet_normal(&[Point::<2>::new(2.0, 0.0)]).unwrap();
        assert_eq!(n, Point::<2>::new(0.0, -1.0));
        assert_eq!(len, 2.0);
        // 3D: face in z = 0 counter-clockwise seen from +z: +z
        let t = [
            Point::<3>::new(1.0, 0.0, 0.0),
            Point::<3>::new(0.0, 2.0, 0.0),
        ];
        let (n, area) = Const::<3>::facet_normal(&t).unwrap();
        assert_eq!(n, Point::<3>::new(0.0, 0.0, 1.0));
        assert_eq!(area, 2.0);
        assert!(Const::<3>::facet_normal(&[t[0], t[0]]).is_none());
        assert_eq!(to_array(&Point::<3>::new(1.0, 2.0, 3.0)), [1.0, 2.0, 3.0]);
    }
}
