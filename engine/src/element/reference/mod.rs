//! Reference cells: nodes, faces, shape functions, their gradients and the
//! quadrature rules of each element type, behind one trait.
//!
//! An element type is one file here (an implementation of
//! [`ReferenceCell`]) plus one line in the kernel registry
//! (`crate::element::kernel`): the kinematics, B-bar / F-bar, the laws,
//! the assembly, the recovery and the output are generic over it. Faces
//! are listed with the node order whose facet normal
//! (`crate::geom::Dimension::facet_normal`) points out of the cell: an
//! edge walked with the cell on its left (2D), a face counter-clockwise
//! seen from outside (3D).
//!
//! - [`tri3`], [`quad4`]: planar (2D) cells;
//! - [`tet4`], [`hex8`]: solid (3D) cells, gmsh / VTK node order.

pub mod hex8;
pub mod quad4;
pub mod tet4;
pub mod tri3;

use crate::mesh::CellKind;

pub use hex8::Hex8;
pub use quad4::Quad4;
pub use tet4::Tet4;
pub use tri3::Tri3;

/// A reference cell of dimension `D` with `NN` nodes.
pub trait ReferenceCell<const D: usize, const NN: usize>: 'static {
    /// The mesh cell kind.
    const KIND: CellKind;
    /// Reference coordinates of the nodes.
    const NODES: [[f64; D]; NN];
    /// Local node lists of the faces (edges in 2D), outward order.
    const FACES: &'static [&'static [usize]];
    /// Full-integration rule: points and weights (the weights sum to the
    /// reference measure).
    const QUADRATURE: &'static [([f64; D], f64)];
    /// The centre of the cell (the point of B-bar / F-bar).
    const CENTRE: [f64; D];
    /// Rule of the mass matrix `int rho N_a N_b dV`: exact for `N_a N_b`
    /// times the Jacobian (and the radius of axisymmetric analyses) of an
    /// undistorted cell. The default, the full rule, suits a cell whose
    /// full rule is already that accurate; a cell whose full rule is not
    /// (one-point simplices, quadratic cells) must give its own, or its
    /// consistent mass is singular (the property tests of
    /// `element::kernel` check every registered kernel).
    const MASS_QUADRATURE: &'static [([f64; D], f64)] = Self::QUADRATURE;

    /// Shape function values at `xi`.
    fn shape(xi: &[f64; D]) -> [f64; NN];

    /// Shape function gradients `dN / dxi` at `xi`.
    fn gradients(xi: &[f64; D]) -> [[f64; D]; NN];

    /// Weight of quadrature point `point` in the value recovered at node
    /// `node` (extrapolation of the integration-point values to the nodes).
    fn extrapolation(node: usize, point: usize) -> f64;

    /// The reference measure (area or volume of the reference cell).
    fn measure() -> f64 {
        Self::QUADRATURE.iter().map(|q| q.1).sum()
    }
}

/// Shape function values of a cell of kind `kind` at its integration point
/// `point` (full quadrature, in quadrature order).
pub fn quadrature_shape(kind: CellKind, point: usize) -> Vec<f64> {
    fn at<const D: usize, const NN: usize, C: ReferenceCell<D, NN>>(point: usize) -> Vec<f64> {
        let q = &C::QUADRATURE[point % C::QUADRATURE.len()];
        C::shape(&q.0).to_vec()
    }
    match kind {
        CellKind::Tri3 => at::<2, 3, Tri3>(point),
        CellKind::Quad4 => at::<2, 4, Quad4>(point),
        CellKind::Tet4 => at::<3, 4, Tet4>(point),
        CellKind::Hex8 => at::<3, 8, Hex8>(point),
    }
}

/// `det(dx / dxi)` of a cell of reference type `C` with node coordinates
/// `x` (each at least `D` long) at the reference point `xi`.
fn jacobian_det<const D: usize, const NN: usize, C: ReferenceCell<D, NN>>(
    x: &[&[f64]],
    xi: &[f64; D],
) -> f64 {
    let g = C::gradients(xi);
    let mut j = [[0.0; D]; D];
    for (a, ga) in g.iter().enumerate() {
        for r in 0..D {
            for k in 0..D {
                j[r][k] += x[a][r] * ga[k];
            }
        }
    }
    match D {
        2 => j[0][0] * j[1][1] - j[1][0] * j[0][1],
        3 => {
            j[0][0] * (j[1][1] * j[2][2] - j[1][2] * j[2][1])
                - j[0][1] * (j[1][0] * j[2][2] - j[1][2] * j[2][0])
                + j[0][2] * (j[1][0] * j[2][1] - j[1][1] * j[2][0])
        }
        _ => j[0][0],
    }
}

/// Jacobian determinants of a cell of kind `kind` with node coordinates
/// `x` at each of its nodes (the cell is valid when all are positive), and
/// its signed measure (area or volume: the integral of the determinant by
/// the cell's quadrature). `None` when `x` does not match the kind.
pub fn corner_jacobians(kind: CellKind, x: &[&[f64]]) -> Option<(Vec<f64>, f64)> {
    fn of<const D: usize, const NN: usize, C: ReferenceCell<D, NN>>(
        x: &[&[f64]],
    ) -> Option<(Vec<f64>, f64)> {
        if x.len() != NN || x.iter().any(|p| p.len() < D) {
            return None;
        }
        let corners = C::NODES
            .iter()
            .map(|xi| jacobian_det::<D, NN, C>(x, xi))
            .collect();
        let measure = C::QUADRATURE
            .iter()
            .map(|(xi, w)| w * jacobian_det::<D, NN, C>(x, xi))
            .sum();
        Some((corners, measure))
    }
    match kind {
        CellKind::Tri3 => of::<2, 3, Tri3>(x),
        CellKind::Quad4 => of::<2, 4, Quad4>(x),
        CellKind::Tet4 => of::<3, 4, Tet4>(x),
        CellKind::Hex8 => of::<3, 8, Hex8>(x),
    }
}

/// The 3-point Gauss-Legendre rule on `[-1, 1]`: abscissae and weights
/// (exact to degree 5).
pub const GAUSS3: [(f64, f64); 3] = [
    (-0.774_596_669_241_483_4, 5.0 / 9.0),
    (0.0, 8.0 / 9.0),
    (0.774_596_669_241_483_4, 5.0 / 9.0),
];

/// The tensor product of [`GAUSS3`] on `[-1, 1]^D` (`3^D` points; `P` must
/// be `3^D`), the first direction fastest.
pub const fn gauss3_tensor<const D: usize, const P: usize>() -> [([f64; D], f64); P] {
    let mut out = [([0.0; D], 0.0); P];
    let mut p = 0;
    while p < P {
        let mut xi = [0.0; D];
        let mut w = 1.0;
        let mut rest = p;
        let mut k = 0;
        while k < D {
            let (x, wk) = GAUSS3[rest % 3];
            xi[k] = x;
            w *= wk;
            rest /= 3;
            k += 1;
        }
        out[p] = (xi, w);
        p += 1;
    }
    out
}

/// Gauss-Legendre abscissa of the 2-point rule.
pub const G2: f64 = 0.577_350_269_189_625_8;

/// Extrapolation weight of the tensor-product 2-point Gauss rule: the
/// multilinear interpolant through the Gauss points, evaluated at the
/// corner `corner` (entries +-1), for the Gauss point at `sign` (+-1)
/// times `G2` in each direction.
pub fn tensor_extrapolation<const D: usize>(corner: &[f64; D], sign: &[f64; D]) -> f64 {
    let s3 = 3f64.sqrt();
    (0..D)
        .map(|k| 0.5 * (1.0 + s3 * corner[k] * sign[k]))
        .product()
}

#[cfg(test)]
pub(crate) mod testing {
    use super::ReferenceCell;

    /// Partition of unity, gradients summing to zero, Kronecker property
    /// at the nodes, gradients matching finite differences of the shape
    /// functions, quadrature weights summing to the measure, and
    /// extrapolation reproducing a constant.
    pub fn check_reference<const D: usize, const NN: usize, C: ReferenceCell<D, NN>>(measure: f64) {
        for (a, xa) in C::NODES.iter().enumerate() {
            let n = C::shape(xa);
            for (b, nb) in n.iter().enumerate() {
                let want = if a == b { 1.0 } else { 0.0 };
                assert!((nb - want).abs() < 1e-14, "{:?} N_{b}({a}) = {nb}", C::KIND);
            }
        }
        let xi: [f64; D] = std::array::from_fn(|k| 0.13 + 0.07 * k as f64);
        let n = C::shape(&xi);
        assert!((n.iter().sum::<f64>() - 1.0).abs() < 1e-14);
        let g = C::gradients(&xi);
        for k in 0..D {
            let s: f64 = g.iter().map(|ga| ga[k]).sum();
            assert!(s.abs() < 1e-14);
            let h = 1e-6;
            let (mut p, mut m) = (xi, xi);
            p[k] += h;
            m[k] -= h;
            let (np, nm) = (C::shape(&p), C::shape(&m));
            for a in 0..NN {
                let fd = (np[a] - nm[a]) / (2.0 * h);
                assert!((fd - g[a][k]).abs() < 1e-8, "{:?} dN_{a}/dxi_{k}", C::KIND);
            }
        }
        assert!((C::measure() - measure).abs() < 1e-14);
        for node in 0..NN {
            let w: f64 = (0..C::QUADRATURE.len())
                .map(|p| C::extrapolation(node, p))
                .sum();
            assert!((w - 1.0).abs() < 1e-14);
        }
        for face in C::FACES {
            assert!(face.iter().all(|&a| a < NN));
        }
    }
}
