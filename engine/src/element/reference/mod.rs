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
//! - [`tet4`], [`hex8`]: solid (3D) cells, gmsh / VTK node order;
//! - [`tri6`], [`quad8`] (serendipity, and the 2x2 reduced `quad8r`),
//!   [`quad9`]: quadratic planar cells;
//! - [`tet10`], [`hex20`] (serendipity, and the 2x2x2 reduced `hex20r`),
//!   [`hex27`]: quadratic solid cells, VTK node order (corners, then the
//!   edge midpoints, then face and body centres; the gmsh reader maps
//!   gmsh's order to it).
//!
//! A quadratic face lists its corners in outward order, then its edge
//! midpoints in the same cyclic order (then its centre): the line3, tri6,
//! quad8 and quad9 facet orders of gmsh and VTK.

pub mod hex20;
pub mod hex27;
pub mod hex8;
pub mod quad4;
pub mod quad8;
pub mod quad9;
pub mod tet10;
pub mod tet4;
pub mod tri3;
pub mod tri6;

use crate::mesh::CellKind;

pub use hex20::{Hex20, Hex20R};
pub use hex27::Hex27;
pub use hex8::Hex8;
pub use quad4::Quad4;
pub use quad8::{Quad8, Quad8R};
pub use quad9::Quad9;
pub use tet10::Tet10;
pub use tet4::Tet4;
pub use tri3::Tri3;
pub use tri6::Tri6;

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
    /// Whether `formulation = selective_reduced` (B-bar / F-bar with one
    /// dilatation per cell) is stable on this cell; where it is not (tri6,
    /// tet10 and the reduced-integration quad8r, hex20r: spurious zero
    /// energy modes) the formulation is full integration.
    const SELECTIVE_REDUCED: bool = true;

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
        CellKind::Tri6 => at::<2, 6, Tri6>(point),
        CellKind::Quad8 => at::<2, 8, Quad8>(point),
        CellKind::Quad8R => at::<2, 8, Quad8R>(point),
        CellKind::Quad9 => at::<2, 9, Quad9>(point),
        CellKind::Tet10 => at::<3, 10, Tet10>(point),
        CellKind::Hex20 => at::<3, 20, Hex20>(point),
        CellKind::Hex20R => at::<3, 20, Hex20R>(point),
        CellKind::Hex27 => at::<3, 27, Hex27>(point),
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
/// `x` at each of its nodes, then at each of its integration points (the
/// cell is valid when all are positive: a quadratic cell may be inverted
/// between its nodes), and
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
            .chain(C::QUADRATURE.iter().map(|q| &q.0))
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
        CellKind::Tri6 => of::<2, 6, Tri6>(x),
        CellKind::Quad8 => of::<2, 8, Quad8>(x),
        CellKind::Quad8R => of::<2, 8, Quad8R>(x),
        CellKind::Quad9 => of::<2, 9, Quad9>(x),
        CellKind::Tet10 => of::<3, 10, Tet10>(x),
        CellKind::Hex20 => of::<3, 20, Hex20>(x),
        CellKind::Hex20R => of::<3, 20, Hex20R>(x),
        CellKind::Hex27 => of::<3, 27, Hex27>(x),
    }
}

/// Reference coordinates of the nodes of a cell of kind `kind`.
pub fn node_coordinates(kind: CellKind) -> Vec<Vec<f64>> {
    fn of<const D: usize, const NN: usize, C: ReferenceCell<D, NN>>() -> Vec<Vec<f64>> {
        C::NODES.iter().map(|p| p.to_vec()).collect()
    }
    match kind {
        CellKind::Tri3 => of::<2, 3, Tri3>(),
        CellKind::Quad4 => of::<2, 4, Quad4>(),
        CellKind::Tet4 => of::<3, 4, Tet4>(),
        CellKind::Hex8 => of::<3, 8, Hex8>(),
        CellKind::Tri6 => of::<2, 6, Tri6>(),
        CellKind::Quad8 => of::<2, 8, Quad8>(),
        CellKind::Quad8R => of::<2, 8, Quad8R>(),
        CellKind::Quad9 => of::<2, 9, Quad9>(),
        CellKind::Tet10 => of::<3, 10, Tet10>(),
        CellKind::Hex20 => of::<3, 20, Hex20>(),
        CellKind::Hex20R => of::<3, 20, Hex20R>(),
        CellKind::Hex27 => of::<3, 27, Hex27>(),
    }
}

/// Shape function values of a linear cell of kind `kind` (tri3, quad4,
/// tet4, hex8) at the reference point `xi`; `None` for other kinds or a
/// point of the wrong dimension.
pub fn linear_shape(kind: CellKind, xi: &[f64]) -> Option<Vec<f64>> {
    fn of<const D: usize, const NN: usize, C: ReferenceCell<D, NN>>(
        xi: &[f64],
    ) -> Option<Vec<f64>> {
        let xi: [f64; D] = xi.try_into().ok()?;
        Some(C::shape(&xi).to_vec())
    }
    match kind {
        CellKind::Tri3 => of::<2, 3, Tri3>(xi),
        CellKind::Quad4 => of::<2, 4, Quad4>(xi),
        CellKind::Tet4 => of::<3, 4, Tet4>(xi),
        CellKind::Hex8 => of::<3, 8, Hex8>(xi),
        _ => None,
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

/// Gauss-Legendre abscissa of the 3-point rule, `sqrt(3/5)`.
pub const G3: f64 = 0.774_596_669_241_483_4;

/// The 3x3 tensor Gauss rule on `[-1, 1]^2`, `xi` fastest.
pub const GAUSS3X3: [([f64; 2], f64); 9] = gauss3_tensor::<2, 9>();

/// The 3x3x3 tensor Gauss rule on `[-1, 1]^3`, `xi` fastest.
pub const GAUSS3X3X3: [([f64; 3], f64); 27] = gauss3_tensor::<3, 27>();

/// The 1D quadratic Lagrange function of the node at `c` (-1, 0 or 1)
/// on the nodes -1, 0, 1, at `x`.
pub fn lagrange3(c: f64, x: f64) -> f64 {
    if c == 0.0 {
        1.0 - x * x
    } else {
        0.5 * x * (x + c)
    }
}

/// `d/dx` of [`lagrange3`].
pub fn lagrange3_d(c: f64, x: f64) -> f64 {
    if c == 0.0 {
        -2.0 * x
    } else {
        x + 0.5 * c
    }
}

/// Extrapolation weight of the tensor-product 3-point Gauss rule: the
/// tensor quadratic interpolant through the Gauss points, evaluated at
/// the node `node` (entries -1, 0, 1), for the Gauss point `point`.
pub fn tensor_extrapolation3<const D: usize>(node: &[f64; D], point: &[f64; D]) -> f64 {
    (0..D)
        .map(|k| {
            let (c, s) = (node[k], point[k] / G3);
            if s.abs() < 0.5 {
                1.0 - c * c / (G3 * G3)
            } else {
                c * (c + s * G3) / (2.0 * G3 * G3)
            }
        })
        .product()
}

/// 4-point Gauss-Legendre on `[0, 1]`: (point, weight).
const GAUSS4_01: [(f64, f64); 4] = [
    (
        0.5 * (1.0 - 0.861_136_311_594_052_6),
        0.5 * 0.347_854_845_137_453_8,
    ),
    (
        0.5 * (1.0 - 0.339_981_043_584_856_3),
        0.5 * 0.652_145_154_862_546_1,
    ),
    (
        0.5 * (1.0 + 0.339_981_043_584_856_3),
        0.5 * 0.652_145_154_862_546_1,
    ),
    (
        0.5 * (1.0 + 0.861_136_311_594_052_6),
        0.5 * 0.347_854_845_137_453_8,
    ),
];

/// The conical-product rule of 4 x 4 points on the reference triangle
/// (Stroud 1971, collapsed Gauss: `x = a (1 - b)`, `y = b`, weight times
/// `1 - b`): exact for polynomials of degree 6 — the mass rule of tri6
/// (`N_a N_b` of degree 4, times `r` in axisymmetry).
pub const COLLAPSED_TRI16: [([f64; 2], f64); 16] = {
    let mut out = [([0.0; 2], 0.0); 16];
    let mut i = 0;
    while i < 4 {
        let mut j = 0;
        while j < 4 {
            let (a, wa) = GAUSS4_01[i];
            let (b, wb) = GAUSS4_01[j];
            out[4 * i + j] = ([a * (1.0 - b), b], wa * wb * (1.0 - b));
            j += 1;
        }
        i += 1;
    }
    out
};

/// The conical-product rule of 4 x 4 x 4 points on the reference
/// tetrahedron (`x = a (1 - b) (1 - c)`, `y = b (1 - c)`, `z = c`, weight
/// times `(1 - b) (1 - c)^2`): exact for polynomials of degree 5 — the mass
/// rule of tet10 (`N_a N_b` of degree 4).
pub const COLLAPSED_TET64: [([f64; 3], f64); 64] = {
    let mut out = [([0.0; 3], 0.0); 64];
    let mut i = 0;
    while i < 4 {
        let mut j = 0;
        while j < 4 {
            let mut k = 0;
            while k < 4 {
                let (a, wa) = GAUSS4_01[i];
                let (b, wb) = GAUSS4_01[j];
                let (c, wc) = GAUSS4_01[k];
                out[16 * i + 4 * j + k] = (
                    [a * (1.0 - b) * (1.0 - c), b * (1.0 - c), c],
                    wa * wb * wc * (1.0 - b) * (1.0 - c) * (1.0 - c),
                );
                k += 1;
            }
            j += 1;
        }
        i += 1;
    }
    out
};

/// The 2x2 tensor Gauss rule on `[-1, 1]^2` (points ordered like the
/// quad4 corners).
pub const GAUSS2X2: [([f64; 2], f64); 4] = [
    ([-G2, -G2], 1.0),
    ([G2, -G2], 1.0),
    ([G2, G2], 1.0),
    ([-G2, G2], 1.0),
];

/// The 2x2x2 tensor Gauss rule on `[-1, 1]^3` (points ordered like the
/// hex8 corners).
pub const GAUSS2X2X2: [([f64; 3], f64); 8] = [
    ([-G2, -G2, -G2], 1.0),
    ([G2, -G2, -G2], 1.0),
    ([G2, G2, -G2], 1.0),
    ([-G2, G2, -G2], 1.0),
    ([-G2, -G2, G2], 1.0),
    ([G2, -G2, G2], 1.0),
    ([G2, G2, G2], 1.0),
    ([-G2, G2, G2], 1.0),
];

/// The sign pattern (+-1 per direction) of a 2-point tensor Gauss point.
pub fn gauss2_sign<const D: usize>(point: &[f64; D]) -> [f64; D] {
    point.map(f64::signum)
}

/// Value and gradient of the serendipity (quad8, hex20) shape function of
/// the node at `node` (entries -1, 0, 1; a corner has none zero, an edge
/// midpoint one) at `xi`: corner `2^-D prod(1 + c_k xi_k) (sum(1 + c_k
/// xi_k) - (2D - 1))`, midpoint of the edge along `k`: `2^(1-D) (1 -
/// xi_k^2) prod_(j != k)(1 + c_j xi_j)`.
pub fn serendipity<const D: usize>(node: &[f64; D], xi: &[f64; D]) -> (f64, [f64; D]) {
    let a: [f64; D] = std::array::from_fn(|k| 1.0 + node[k] * xi[k]);
    let prod_except =
        |skip: usize| -> f64 { (0..D).filter(|&j| j != skip).map(|j| a[j]).product::<f64>() };
    match (0..D).find(|&k| node[k] == 0.0) {
        None => {
            let scale = 0.5f64.powi(D as i32);
            let sum: f64 = a.iter().sum::<f64>() - (2 * D - 1) as f64;
            let prod: f64 = a.iter().product();
            let grad = std::array::from_fn(|k| scale * node[k] * prod_except(k) * (sum + a[k]));
            (scale * prod * sum, grad)
        }
        Some(k) => {
            let scale = 0.5f64.powi(D as i32 - 1);
            let bubble = 1.0 - xi[k] * xi[k];
            let rest = prod_except(k);
            let grad = std::array::from_fn(|j| {
                if j == k {
                    -2.0 * xi[k] * scale * rest
                } else {
                    let others: f64 = (0..D).filter(|&i| i != k && i != j).map(|i| a[i]).product();
                    scale * bubble * node[j] * others
                }
            });
            (scale * bubble * rest, grad)
        }
    }
}

/// Value and gradient of the tensor quadratic Lagrange (quad9, hex27)
/// shape function of the node at `node` (entries -1, 0, 1) at `xi`.
pub fn lagrange_tensor<const D: usize>(node: &[f64; D], xi: &[f64; D]) -> (f64, [f64; D]) {
    let l: [f64; D] = std::array::from_fn(|k| lagrange3(node[k], xi[k]));
    let grad = std::array::from_fn(|k| {
        (0..D)
            .map(|j| {
                if j == k {
                    lagrange3_d(node[j], xi[j])
                } else {
                    l[j]
                }
            })
            .product()
    });
    (l.iter().product(), grad)
}

/// Extrapolation weight of the tensor-product 2-point Gauss rule: the
/// multilinear interpolant through the Gauss points, evaluated at the
/// node `corner` (entries -1, 0 or 1), for the Gauss point at `sign` (+-1)
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

    /// The quadrature of `C` integrates every monomial of degree at most
    /// `degree` exactly (in each direction separately for a tensor cell on
    /// `[-1, 1]^D`, `boxed`; in total for a simplex cell).
    pub fn check_exactness<const D: usize, const NN: usize, C: ReferenceCell<D, NN>>(
        degree: u32,
        boxed: bool,
    ) {
        let fact = |n: u32| -> f64 { (1..=n).map(f64::from).product() };
        let count = (degree + 1).pow(D as u32);
        for code in 0..count {
            let e: [u32; D] =
                std::array::from_fn(|k| (code / (degree + 1).pow(k as u32)) % (degree + 1));
            let total: u32 = e.iter().sum();
            if !boxed && total > degree {
                continue;
            }
            let exact = if boxed {
                e.iter()
                    .map(|&a| {
                        if a % 2 == 1 {
                            0.0
                        } else {
                            2.0 / f64::from(a + 1)
                        }
                    })
                    .product::<f64>()
            } else {
                e.iter().map(|&a| fact(a)).product::<f64>() / fact(total + D as u32)
            };
            let q: f64 = C::QUADRATURE
                .iter()
                .map(|(xi, w)| w * (0..D).map(|k| xi[k].powi(e[k] as i32)).product::<f64>())
                .sum();
            assert!(
                (q - exact).abs() < 1e-14,
                "{:?} x^{e:?}: {q} != {exact}",
                C::KIND
            );
        }
        if boxed {
            // and not one degree more (the rule is the one its degree says)
            let e = degree + 1 + (degree + 1) % 2;
            let q: f64 = C::QUADRATURE
                .iter()
                .map(|(xi, w)| w * xi[0].powi(e as i32))
                .sum();
            assert!((q - 2.0f64.powi(D as i32 - 1) * 2.0 / f64::from(e + 1)).abs() > 1e-6);
        }
    }

    /// Extrapolating `f` sampled at the integration points gives `f` at
    /// every node.
    pub fn check_extrapolation<const D: usize, const NN: usize, C: ReferenceCell<D, NN>>(
        f: impl Fn(&[f64; D]) -> f64,
    ) {
        for (node, xa) in C::NODES.iter().enumerate() {
            let v: f64 = C::QUADRATURE
                .iter()
                .enumerate()
                .map(|(p, q)| C::extrapolation(node, p) * f(&q.0))
                .sum();
            assert!(
                (v - f(xa)).abs() < 1e-12,
                "{:?} node {node}: {v} != {}",
                C::KIND,
                f(xa)
            );
        }
    }

    /// The nodes of `C` under a well-conditioned affine map plus a
    /// deterministic perturbation of `jitter` (`sample` picks the map).
    pub fn distorted<const D: usize, const NN: usize, C: ReferenceCell<D, NN>>(
        sample: u64,
        jitter: f64,
    ) -> Vec<crate::geom::Point<D>> {
        let mut state = sample
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        let mut next = move || {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            ((state >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
        };
        let a: [[f64; D]; D] = std::array::from_fn(|i| {
            std::array::from_fn(|j| f64::from(u8::from(i == j)) + 0.25 * next())
        });
        let scale = 0.5 + 2.0 * (next() + 1.0);
        let shift = 3.0 + next();
        C::NODES
            .iter()
            .map(|xi| {
                crate::geom::Point::<D>::from_fn(|i, _| {
                    let m: f64 = (0..D).map(|j| a[i][j] * xi[j]).sum();
                    scale * (m + jitter * next()) + if i == 0 { shift * scale } else { 0.0 }
                })
            })
            .collect()
    }

    /// Linear-elastic stiffness of `C` on distorted cells: symmetric,
    /// positive semi-definite, rigid-body modes in its null space with
    /// exactly `zero_modes` zero eigenvalues (per analysis kind), and
    /// `f_int = K u`.
    pub fn check_stiffness<const D: usize, const NN: usize, const ND: usize, C>(
        cases: &[(crate::model::AnalysisKind, usize)],
    ) where
        C: ReferenceCell<D, NN>,
        nalgebra::Const<D>: crate::geom::Dimension<D>,
    {
        use crate::element::kernel::{CellKernel, Kernel};
        use crate::element::{ElementMatrix, Section};
        use crate::material::LinearElastic;
        use crate::model::Formulation;
        let kernel = Kernel::<C, D, NN, ND>::new();
        for &(kind, zero_modes) in cases {
            for sample in 0..6u64 {
                let x = distorted::<D, NN, C>(sample, 0.05);
                let u: Vec<crate::geom::Point<D>> = distorted::<D, NN, C>(sample + 100, 0.3)
                    .iter()
                    .map(|p| p * 1e-3)
                    .collect();
                let law = LinearElastic::new(200e3, 0.1 + 0.05 * sample as f64, kind).unwrap();
                let section = Section {
                    kind,
                    thickness: 1.5,
                };
                for formulation in [Formulation::Full, Formulation::SelectiveReduced] {
                    let mut r = ElementMatrix::default();
                    kernel
                        .linear(&x, &u, &section, formulation, &law, true, &mut r)
                        .unwrap();
                    crate::element::testing::check_element(&x, &r, &u, kind, zero_modes)
                        .unwrap_or_else(|e| {
                            panic!("{:?} {kind:?} {formulation:?} #{sample}: {e}", C::KIND)
                        });
                }
            }
        }
    }
}

#[cfg(test)]
mod collapsed_rules {
    use super::{COLLAPSED_TET64, COLLAPSED_TRI16};

    fn factorial(n: u32) -> f64 {
        (1..=n).map(f64::from).product()
    }

    /// Integrals of monomials over the reference simplices (Stroud 1971):
    /// `int x^i y^j = i! j! / (i + j + 2)!` and
    /// `int x^i y^j z^k = i! j! k! / (i + j + k + 3)!`, to their degree.
    #[test]
    fn collapsed_gauss_rules_integrate_monomials_to_their_degree() {
        for i in 0..=6u32 {
            for j in 0..=6 - i {
                let q: f64 = COLLAPSED_TRI16
                    .iter()
                    .map(|(x, w)| w * x[0].powi(i as i32) * x[1].powi(j as i32))
                    .sum();
                let exact = factorial(i) * factorial(j) / factorial(i + j + 2);
                assert!((q - exact).abs() < 1e-14, "tri x^{i} y^{j}: {q} vs {exact}");
            }
        }
        for i in 0..=5u32 {
            for j in 0..=5 - i {
                for k in 0..=5 - i - j {
                    let q: f64 = COLLAPSED_TET64
                        .iter()
                        .map(|(x, w)| {
                            w * x[0].powi(i as i32) * x[1].powi(j as i32) * x[2].powi(k as i32)
                        })
                        .sum();
                    let exact =
                        factorial(i) * factorial(j) * factorial(k) / factorial(i + j + k + 3);
                    assert!(
                        (q - exact).abs() < 1e-14,
                        "tet x^{i} y^{j} z^{k}: {q} vs {exact}"
                    );
                }
            }
        }
    }
}
