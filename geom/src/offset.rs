//! The derivative of the normal, `dn/dx`, for the three kinds of foot point.
//!
//! Each follows from differentiating the foot-point equations with respect
//! to the query point `x` (the closest point moves with `x`):
//!
//! - **surface** `S(u, v)`, `x = S + g n`: `(x - S) . S_a = 0` gives
//!   `(A - g B) du = J^T dx` with the metric `A_ab = S_a . S_b`, the second
//!   fundamental form `B_ab = n . S_ab` and `J = [S_u S_v]`; with the
//!   Weingarten equations `n_a = -S_c (A^-1 B)_ca`:
//!   `dn/dx = -J A^-1 B (A - g B)^-1 J^T`
//!   (a sphere of radius `R` seen from outside: `(I - n n) / (R + g)`);
//! - **curve** `C(t)` (an edge: cylinder of radius 0), `d = x - C`:
//!   `(x - C) . C' = 0` gives `dt = C' . dx / (|C'|^2 - d . C'')` and
//!   `dn/dx = s [(I - m m) - C' C'^T / (|C'|^2 - d . C'')] / |d|`,
//!   `m = d / |d|`, `s = ±1` the side;
//! - **point** `P` (a vertex: sphere of radius 0): `dn/dx = s (I - m m) / |d|`.
//!
//! Each returns `None` at a focal point, where the closest point is not
//! unique and `dn/dx` does not exist.

use crate::{Mat3, Vec3};
use nalgebra::{Matrix2, Matrix3x2};

/// Relative size under which a denominator is taken as zero (focal point).
const FOCAL: f64 = 1e-12;

/// `dn/dx` at a surface foot with tangents `su`, `sv`, second derivatives
/// `suu`, `suv`, `svv`, free-side unit normal `n` and signed gap `g`.
///
/// Computed in the orthonormal tangent frame `e1 = S_u / |S_u|`, `e2` from
/// Gram–Schmidt on `S_v` (`[S_u S_v] = [e1 e2] T`, `T` upper triangular):
/// `B_o = T^-T B T^-1` and `dn/dx = -E B_o (I - g B_o)^-1 E^T`, the same map
/// as `-J A^-1 B (A - g B)^-1 J^T` but without inverting the metric, which
/// is ill-conditioned near a pole.
pub fn surface(
    su: Vec3,
    sv: Vec3,
    suu: Vec3,
    suv: Vec3,
    svv: Vec3,
    n: Vec3,
    g: f64,
) -> Option<Mat3> {
    let lu = su.norm();
    if lu.is_nan() || lu <= 0.0 {
        return None;
    }
    let e1 = su / lu;
    let t12 = sv.dot(&e1);
    let perp = sv - e1 * t12;
    let t22 = perp.norm();
    if t22.is_nan() || t22 <= 1e-12 * lu.max(sv.norm()) {
        return None;
    }
    let e2 = perp / t22;
    let b = Matrix2::new(n.dot(&suu), n.dot(&suv), n.dot(&suv), n.dot(&svv));
    let t_inv = Matrix2::new(1.0 / lu, -t12 / (lu * t22), 0.0, 1.0 / t22);
    let bo = t_inv.transpose() * b * t_inv;
    let m = Matrix2::identity() - bo * g;
    let det_m = m.determinant();
    if det_m.abs() <= FOCAL || !det_m.is_finite() {
        return None;
    }
    let e = Matrix3x2::from_columns(&[e1, e2]);
    let w = -(e * bo * m.try_inverse()? * e.transpose());
    Some((w + w.transpose()) * 0.5)
}

/// `dn/dx` for the distance to a curve point `c` with derivatives `c1`,
/// `c2`, seen from `x`, with side `s = ±1`.
pub fn curve(x: Vec3, c: Vec3, c1: Vec3, c2: Vec3, s: f64) -> Option<Mat3> {
    let d = x - c;
    let dist = d.norm();
    let den = c1.norm_squared() - d.dot(&c2);
    if dist == 0.0 || den.abs() <= FOCAL * c1.norm_squared() {
        return None;
    }
    let m = d / dist;
    let w = (Mat3::identity() - m * m.transpose() - c1 * c1.transpose() / den) * (s / dist);
    Some((w + w.transpose()) * 0.5)
}

/// `dn/dx` for the distance to a point `p` seen from `x`, side `s = ±1`.
pub fn point(x: Vec3, p: Vec3, s: f64) -> Option<Mat3> {
    let d = x - p;
    let dist = d.norm();
    if dist == 0.0 {
        return None;
    }
    let m = d / dist;
    Some((Mat3::identity() - m * m.transpose()) * (s / dist))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sphere_from_outside_and_inside() {
        // Sphere of radius 2 at the origin, foot (0, 0, 2), u along x, v along y.
        let (r, g) = (2.0, 0.5);
        let su = Vec3::new(r, 0.0, 0.0);
        let sv = Vec3::new(0.0, r, 0.0);
        let suu = Vec3::new(0.0, 0.0, -r);
        let svv = suu;
        let n = Vec3::z();
        let w = surface(su, sv, suu, Vec3::zeros(), svv, n, g).unwrap();
        let expect = (Mat3::identity() - n * n.transpose()) / (r + g);
        assert!((w - expect).norm() < 1e-14);
        // Free side inside: normal -z, gap measured inwards.
        let w = surface(su, sv, suu, Vec3::zeros(), svv, -n, g).unwrap();
        let expect = -(Mat3::identity() - n * n.transpose()) / (r - g);
        assert!((w - expect).norm() < 1e-14);
        // The centre of the sphere is a focal point.
        assert!(surface(su, sv, suu, Vec3::zeros(), svv, -n, r).is_none());
    }

    #[test]
    fn straight_edge_and_vertex() {
        let x = Vec3::new(0.0, 3.0, 4.0);
        let w = curve(x, Vec3::zeros(), Vec3::x() * 2.0, Vec3::zeros(), 1.0).unwrap();
        let m = Vec3::new(0.0, 0.6, 0.8);
        let expect =
            (Mat3::identity() - m * m.transpose() - Vec3::x() * Vec3::x().transpose()) / 5.0;
        assert!((w - expect).norm() < 1e-14);
        let w = point(x, Vec3::zeros(), -1.0).unwrap();
        assert!((w + (Mat3::identity() - m * m.transpose()) / 5.0).norm() < 1e-14);
        assert!(point(x, x, 1.0).is_none());
    }
}
