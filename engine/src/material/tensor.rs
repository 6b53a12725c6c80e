//! Second-order tensors of three-dimensional space, for the constitutive
//! laws (which are always 3D: planar analyses embed into them, see
//! `crate::element::planar`).
//!
//! - [`Sym`]: symmetric tensor `[xx, yy, zz, xy, xz, yz]` (tensor shear,
//!   not engineering; the first four entries are the components of the
//!   planar analyses, whose `xz`, `yz` vanish);
//! - [`Deformation`]: deformation gradient `F` (3x3);
//! - [`isotropic`]: an isotropic function of a symmetric tensor by
//!   eigen-decomposition (planar tensors, whose `xz, yz` vanish, use the
//!   closed form of their 2x2 block: the same function, exactly
//!   differentiable too), with its exact first derivative along every
//!   dual-number direction by the Daleckii-Krein formula (divided
//!   differences of the eigenvalues, the derivative itself at equal
//!   eigenvalues), so [`log`] and [`exp`] stay smooth and exactly
//!   differentiable at repeated eigenvalues (the undeformed state).

use super::dual::Scalar;
use nalgebra::Matrix3;

/// Symmetric tensor `[xx, yy, zz, xy, xz, yz]` (tensor shear components).
pub type Sym<T> = [T; 6];

/// Row and column of each component of a [`Sym`].
pub const PAIRS: [(usize, usize); 6] = [(0, 0), (1, 1), (2, 2), (0, 1), (0, 2), (1, 2)];

/// Component of `(i, j)` (any order) in a [`Sym`].
#[inline]
pub const fn voigt(i: usize, j: usize) -> usize {
    match (i, j) {
        (0, 0) => 0,
        (1, 1) => 1,
        (2, 2) => 2,
        (0, 1) | (1, 0) => 3,
        (0, 2) | (2, 0) => 4,
        _ => 5,
    }
}

/// The identity.
pub fn identity<T: Scalar>() -> Sym<T> {
    let (o, z) = (T::cst(1.0), T::cst(0.0));
    [o, o, o, z, z, z]
}

/// Values of a tensor of constants.
pub fn constant<T: Scalar>(a: &Sym<f64>) -> Sym<T> {
    a.map(T::cst)
}

/// The values (derivatives dropped).
pub fn values<T: Scalar>(a: &Sym<T>) -> Sym<f64> {
    a.map(|v| v.re())
}

/// Trace.
pub fn trace<T: Scalar>(a: &Sym<T>) -> T {
    a[0] + a[1] + a[2]
}

/// Deviatoric part.
pub fn deviator<T: Scalar>(a: &Sym<T>) -> Sym<T> {
    let m = trace(a) / 3.0;
    [a[0] - m, a[1] - m, a[2] - m, a[3], a[4], a[5]]
}

/// `A : A`.
pub fn norm2<T: Scalar>(a: &Sym<T>) -> T {
    a[0] * a[0] + a[1] * a[1] + a[2] * a[2] + (a[3] * a[3] + a[4] * a[4] + a[5] * a[5]) * 2.0
}

/// The 3x3 matrix of a symmetric tensor.
pub fn to_matrix(a: &Sym<f64>) -> Matrix3<f64> {
    Matrix3::new(a[0], a[3], a[4], a[3], a[1], a[5], a[4], a[5], a[2])
}

/// The symmetric tensor of a 3x3 matrix (its symmetric part).
pub fn from_matrix(m: &Matrix3<f64>) -> Sym<f64> {
    PAIRS.map(|(i, j)| 0.5 * (m[(i, j)] + m[(j, i)]))
}

/// Deformation gradient `F[i][j] = d x_i / d X_j`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Deformation<T> {
    /// The components.
    pub f: [[T; 3]; 3],
}

impl<T: Scalar> Deformation<T> {
    /// The identity.
    pub fn identity() -> Self {
        let (o, z) = (T::cst(1.0), T::cst(0.0));
        Deformation {
            f: [[o, z, z], [z, o, z], [z, z, o]],
        }
    }

    /// Whether `F` is planar: its `xz, yz, zx, zy` entries are exactly zero
    /// (values and derivatives), so the in-plane block and `F_33`
    /// decouple (planar analyses; the operations below then use the 2x2
    /// closed forms).
    pub fn is_planar(&self) -> bool {
        let f = &self.f;
        exactly_zero(f[0][2])
            && exactly_zero(f[1][2])
            && exactly_zero(f[2][0])
            && exactly_zero(f[2][1])
    }

    /// Determinant of the in-plane block.
    pub fn det2(&self) -> T {
        self.f[0][0] * self.f[1][1] - self.f[0][1] * self.f[1][0]
    }

    /// `J = det F` (expanded along the third row: a planar `F` gives
    /// `det2 F_33` exactly).
    pub fn det(&self) -> T {
        let f = &self.f;
        let planar = self.det2() * f[2][2];
        if self.is_planar() {
            return planar;
        }
        planar + f[2][0] * (f[0][1] * f[1][2] - f[0][2] * f[1][1])
            - f[2][1] * (f[0][0] * f[1][2] - f[0][2] * f[1][0])
    }

    /// The inverse (adjugate over the determinant; block-wise when planar).
    pub fn inverse(&self) -> Self {
        let f = &self.f;
        if self.is_planar() {
            let det = self.det2();
            let z = T::cst(0.0);
            return Deformation {
                f: [
                    [f[1][1] / det, -f[0][1] / det, z],
                    [-f[1][0] / det, f[0][0] / det, z],
                    [z, z, T::cst(1.0) / f[2][2]],
                ],
            };
        }
        let inv_det = T::cst(1.0) / self.det();
        let c = |a: usize, b: usize, c: usize, d: usize| f[a][b] * f[c][d] - f[a][d] * f[c][b];
        Deformation {
            f: [
                [
                    c(1, 1, 2, 2) * inv_det,
                    -c(0, 1, 2, 2) * inv_det,
                    c(0, 1, 1, 2) * inv_det,
                ],
                [
                    -c(1, 0, 2, 2) * inv_det,
                    c(0, 0, 2, 2) * inv_det,
                    -c(0, 0, 1, 2) * inv_det,
                ],
                [
                    c(1, 0, 2, 1) * inv_det,
                    -c(0, 0, 2, 1) * inv_det,
                    c(0, 0, 1, 1) * inv_det,
                ],
            ],
        }
    }

    /// `F A F^T` for a symmetric `A`.
    pub fn push(&self, a: &Sym<T>) -> Sym<T> {
        let f = &self.f;
        if self.is_planar() && is_planar(a) {
            // in-plane block M = F A, then M F^T; zz = F_33^2 A_zz
            let m = [
                [
                    f[0][0] * a[0] + f[0][1] * a[3],
                    f[0][0] * a[3] + f[0][1] * a[1],
                ],
                [
                    f[1][0] * a[0] + f[1][1] * a[3],
                    f[1][0] * a[3] + f[1][1] * a[1],
                ],
            ];
            let z = T::cst(0.0);
            return [
                m[0][0] * f[0][0] + m[0][1] * f[0][1],
                m[1][0] * f[1][0] + m[1][1] * f[1][1],
                f[2][2] * f[2][2] * a[2],
                m[0][0] * f[1][0] + m[0][1] * f[1][1],
                z,
                z,
            ];
        }
        // M = F A
        let mut m = [[T::cst(0.0); 3]; 3];
        for (i, row) in m.iter_mut().enumerate() {
            for (j, mij) in row.iter_mut().enumerate() {
                *mij =
                    f[i][0] * a[voigt(0, j)] + f[i][1] * a[voigt(1, j)] + f[i][2] * a[voigt(2, j)];
            }
        }
        PAIRS.map(|(i, j)| m[i][0] * f[j][0] + m[i][1] * f[j][1] + m[i][2] * f[j][2])
    }

    /// `F F^T` (the left Cauchy-Green tensor `b`).
    pub fn left_cauchy_green(&self) -> Sym<T> {
        let f = &self.f;
        PAIRS.map(|(i, j)| f[i][0] * f[j][0] + f[i][1] * f[j][1] + f[i][2] * f[j][2])
    }

    /// `F s`.
    pub fn scaled(&self, s: T) -> Self {
        Deformation {
            f: self.f.map(|row| row.map(|v| v * s)),
        }
    }

    /// The values (derivatives dropped).
    pub fn re(&self) -> Deformation<f64> {
        Deformation {
            f: self.f.map(|row| row.map(|v| v.re())),
        }
    }

    /// First Piola-Kirchhoff stress `P = tau F^-T` of the Kirchhoff stress
    /// `tau`.
    pub fn piola(&self, tau: &Sym<T>) -> [[T; 3]; 3] {
        let g = self.inverse().f; // F^-1; F^-T[k][j] = g[j][k]
        let mut p = [[T::cst(0.0); 3]; 3];
        if self.is_planar() && is_planar(tau) {
            let t = [[tau[0], tau[3]], [tau[3], tau[1]]];
            for i in 0..2 {
                for j in 0..2 {
                    p[i][j] = t[i][0] * g[j][0] + t[i][1] * g[j][1];
                }
            }
            p[2][2] = tau[2] / self.f[2][2];
            return p;
        }
        for (i, row) in p.iter_mut().enumerate() {
            for (j, pij) in row.iter_mut().enumerate() {
                *pij = tau[voigt(i, 0)] * g[j][0]
                    + tau[voigt(i, 1)] * g[j][1]
                    + tau[voigt(i, 2)] * g[j][2];
            }
        }
        p
    }
}

/// `f(A) = Q diag(f(lambda)) Q^T` for the symmetric `a = Q diag(lambda)
/// Q^T`, with the derivative of every dual direction by the Daleckii-Krein
/// formula `Df(A)[H] = Q (f1 o (Q^T H Q)) Q^T`, `f1(x, y) = divided(x, y)`
/// (`(f(x) - f(y)) / (x - y)`, and `f'(x)` at `x = y`, computed stably by
/// the caller).
pub fn isotropic<T: Scalar>(
    a: &Sym<T>,
    f: impl Fn(f64) -> f64,
    divided: impl Fn(f64, f64) -> f64,
) -> Sym<T> {
    let eig = to_matrix(&values(a)).symmetric_eigen();
    let (lambda, q) = (eig.eigenvalues, eig.eigenvectors);
    let fl = lambda.map(&f);
    let value = from_matrix(&(q * Matrix3::from_diagonal(&fl) * q.transpose()));
    if T::DIRECTIONS == 0 {
        return value.map(T::cst);
    }
    // l[c][d]: derivative of component c of f(A) along component d of A
    let mut f1 = Matrix3::zeros();
    for i in 0..3 {
        for j in 0..3 {
            f1[(i, j)] = divided(lambda[i], lambda[j]);
        }
    }
    let mut l = [[0.0; 6]; 6];
    for (d, &(i, j)) in PAIRS.iter().enumerate() {
        let mut h = Matrix3::zeros();
        h[(i, j)] = 1.0;
        h[(j, i)] = 1.0;
        let b = q.transpose() * h * q;
        let df = q * b.component_mul(&f1) * q.transpose();
        for (c, &(r, s)) in PAIRS.iter().enumerate() {
            l[c][d] = df[(r, s)];
        }
    }
    let mut out = [T::cst(0.0); 6];
    for (c, o) in out.iter_mut().enumerate() {
        *o = T::from_parts(value[c], |k| {
            (0..6).map(|d| l[c][d] * a[d].direction(k)).sum::<f64>()
        });
    }
    out
}

/// Whether `a` is a planar tensor: `xz = yz = 0` exactly, values and
/// derivatives (the tensors of planar analyses). Its in-plane block and
/// its `zz` entry are then decoupled.
pub fn is_planar<T: Scalar>(a: &Sym<T>) -> bool {
    exactly_zero(a[4]) && exactly_zero(a[5])
}

/// Whether `v` is zero with zero derivatives.
#[inline]
fn exactly_zero<T: Scalar>(v: T) -> bool {
    v.re() == 0.0 && (0..T::DIRECTIONS).all(|k| v.direction(k) == 0.0)
}

/// `sum_k y^k c_k` by Horner.
fn series<T: Scalar>(y: T, c: &[f64]) -> T {
    let mut s = T::cst(0.0);
    for ck in c.iter().rev() {
        s = s * y + *ck;
    }
    s
}

/// Matrix logarithm of a symmetric positive definite tensor: by
/// eigen-decomposition ([`isotropic`]); a planar tensor by the closed form
/// of its 2x2 block written with the squared eigenvalue half-gap `d^2`
/// (series near `d = 0`), the same function, smooth at equal eigenvalues.
pub fn log<T: Scalar>(a: &Sym<T>) -> Sym<T> {
    if is_planar(a) {
        return planar_log(a);
    }
    isotropic(a, f64::ln, |x, y| {
        // ln(x / y) / (x - y) = ln(1 + r) / (r y), r = (x - y) / y
        let r = (x - y) / y;
        if r == 0.0 {
            1.0 / y
        } else {
            r.ln_1p() / (r * y)
        }
    })
}

fn planar_log<T: Scalar>(a: &Sym<T>) -> Sym<T> {
    let m = (a[0] + a[1]) * 0.5;
    let p = (a[0] - a[1]) * 0.5;
    let d2 = p * p + a[3] * a[3];
    let y = d2 / (m * m);
    // g = atanh(x) / (x m) with x^2 = y: (ln(m + d) - ln(m - d)) / (2 d)
    let g = if y.re() < 1e-3 {
        series(
            y,
            &[
                1.0,
                1.0 / 3.0,
                1.0 / 5.0,
                1.0 / 7.0,
                1.0 / 9.0,
                1.0 / 11.0,
                1.0 / 13.0,
            ],
        ) / m
    } else {
        let d = d2.sqrt();
        ((m + d).ln() - (m - d).ln()) / (d * 2.0)
    };
    let half_ln_det = (a[0] * a[1] - a[3] * a[3]).ln() * 0.5;
    let z = T::cst(0.0);
    [
        half_ln_det + g * p,
        half_ln_det - g * p,
        a[2].ln(),
        g * a[3],
        z,
        z,
    ]
}

/// Matrix exponential of a symmetric tensor (as [`log`]: eigen-decomposition,
/// or the closed form of a planar tensor).
pub fn exp<T: Scalar>(a: &Sym<T>) -> Sym<T> {
    if is_planar(a) {
        return planar_exp(a);
    }
    isotropic(a, f64::exp, |x, y| {
        // (e^x - e^y) / (x - y) = e^y expm1(d) / d, d = x - y
        let d = x - y;
        if d == 0.0 {
            y.exp()
        } else {
            y.exp() * d.exp_m1() / d
        }
    })
}

fn planar_exp<T: Scalar>(a: &Sym<T>) -> Sym<T> {
    let m = (a[0] + a[1]) * 0.5;
    let p = (a[0] - a[1]) * 0.5;
    let d2 = p * p + a[3] * a[3];
    let (c, s) = if d2.re() < 1e-2 {
        (
            series(
                d2,
                &[
                    1.0,
                    0.5,
                    1.0 / 24.0,
                    1.0 / 720.0,
                    1.0 / 40320.0,
                    1.0 / 3628800.0,
                    1.0 / 479001600.0,
                ],
            ),
            series(
                d2,
                &[
                    1.0,
                    1.0 / 6.0,
                    1.0 / 120.0,
                    1.0 / 5040.0,
                    1.0 / 362880.0,
                    1.0 / 39916800.0,
                    1.0 / 6227020800.0,
                ],
            ),
        )
    } else {
        let d = d2.sqrt();
        let (ep, em) = (d.exp(), (-d).exp());
        ((ep + em) * 0.5, (ep - em) / (d * 2.0))
    };
    let e = m.exp();
    let z = T::cst(0.0);
    [
        e * (c + s * p),
        e * (c - s * p),
        a[2].exp(),
        e * s * a[3],
        z,
        z,
    ]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::dual::Dual;

    fn close(a: &Sym<f64>, b: &Sym<f64>, tol: f64) -> bool {
        a.iter().zip(b).all(|(x, y)| (x - y).abs() <= tol)
    }

    #[test]
    fn log_and_exp_are_inverse_and_match_the_planar_closed_form() {
        for a in [
            [1.0, 1.0, 1.0, 0.0, 0.0, 0.0],
            [2.0, 0.5, 1.3, 0.2, 0.0, 0.0],
            [1.0 + 1e-9, 1.0, 0.7, 1e-9, 0.0, 0.0],
            [3.0, 3.0, 2.0, 1.5, 0.0, 0.0],
            [2.0, 1.5, 1.2, 0.3, -0.2, 0.4],
        ] {
            let l = log(&a);
            assert!(close(&exp(&l), &a, 1e-13), "{a:?}");
            if a[4] == 0.0 && a[5] == 0.0 {
                // the in-plane block: eigenvalues m +- d
                let m = 0.5 * (a[0] + a[1]);
                let d = (0.25 * (a[0] - a[1]).powi(2) + a[3] * a[3]).sqrt();
                let (l1, l2) = ((m + d).ln(), (m - d).ln());
                assert!((l[0] + l[1] - (l1 + l2)).abs() < 1e-13);
                assert!((l[0] * l[1] - l[3] * l[3] - l1 * l2).abs() < 1e-12);
                assert!((l[2] - a[2].ln()).abs() < 1e-15);
                assert!(l[4].abs() < 1e-15 && l[5].abs() < 1e-15);
            }
        }
    }

    #[test]
    fn isotropic_derivatives_match_finite_differences_at_repeated_eigenvalues() {
        // directions: a random symmetric perturbation of each argument
        let h = [0.3, -0.2, 0.1, 0.25, -0.15, 0.05];
        for a in [
            [1.0, 1.0, 1.0, 0.0, 0.0, 0.0],
            [1.2, 1.2, 0.8, 0.0, 0.0, 0.0],
            [2.0, 1.5, 1.2, 0.3, -0.2, 0.4],
        ] {
            let ad: Sym<Dual<1>> = std::array::from_fn(|c| Dual { v: a[c], d: [h[c]] });
            for (name, f) in [
                ("log", log::<Dual<1>> as fn(&Sym<Dual<1>>) -> Sym<Dual<1>>),
                ("exp", exp::<Dual<1>>),
            ] {
                let out = f(&ad);
                let e = 1e-5;
                let g = |s: f64| {
                    let x: Sym<f64> = std::array::from_fn(|c| a[c] + s * h[c]);
                    if name == "log" {
                        log(&x)
                    } else {
                        exp(&x)
                    }
                };
                let (p, m) = (g(e), g(-e));
                for c in 0..6 {
                    let fd = (p[c] - m[c]) / (2.0 * e);
                    assert!(
                        (out[c].d[0] - fd).abs() < 1e-8 * (1.0 + fd.abs()),
                        "{name} {a:?} component {c}: {} vs {fd}",
                        out[c].d[0]
                    );
                }
            }
        }
    }

    #[test]
    fn determinant_inverse_push_and_piola_of_a_rotation_and_stretch() {
        let (c, s) = (0.6, 0.8);
        let r = Deformation {
            f: [[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]],
        };
        assert!((r.det() - 1.0).abs() < 1e-15);
        let b = r.left_cauchy_green();
        assert!(close(&b, &[1.0, 1.0, 1.0, 0.0, 0.0, 0.0], 1e-15));
        // tau = R diag(2, 0, 0) R^T, P = tau R = R diag(2, 0, 0)
        let tau = r.push(&[2.0, 0.0, 0.0, 0.0, 0.0, 0.0]);
        let p = r.piola(&tau);
        assert!((p[0][0] - 2.0 * c).abs() < 1e-15 && (p[1][0] - 2.0 * s).abs() < 1e-15);
        assert!(p[0][1].abs() < 1e-15 && p[1][1].abs() < 1e-15);
        let f = Deformation {
            f: [[1.1, 0.2, -0.1], [0.05, 0.9, 0.3], [0.0, -0.2, 1.3]],
        };
        let g = f.inverse();
        for i in 0..3 {
            for j in 0..3 {
                let v: f64 = (0..3).map(|k| f.f[i][k] * g.f[k][j]).sum();
                assert!((v - if i == j { 1.0 } else { 0.0 }).abs() < 1e-15);
            }
        }
        assert!(close(&f.push(&identity()), &f.left_cauchy_green(), 1e-15));
        assert_eq!(voigt(2, 1), 5);
    }
}
