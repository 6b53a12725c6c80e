//! Second-order tensors of 2D analyses (plane strain, axisymmetric): an
//! in-plane 2x2 block plus the out-of-plane (hoop) `zz` entry, which is
//! always a principal direction.
//!
//! - [`Sym`]: symmetric tensor `[xx, yy, zz, xy]` (tensor shear, not
//!   engineering);
//! - [`Deformation`]: deformation gradient `F = [[F11, F12], [F21, F22]] + F33`.
//!
//! Matrix logarithm and exponential of a symmetric tensor use the closed form
//! of the 2x2 block written as a function of the squared eigenvalue
//! half-gap `d^2` (series near `d = 0`), so they stay smooth — and exactly
//! differentiable with [`super::dual::Dual`] — at equal eigenvalues, e.g. in
//! the undeformed state.

use super::dual::Scalar;

/// Symmetric tensor `[xx, yy, zz, xy]` (tensor shear component).
pub type Sym<T> = [T; 4];

/// Deformation gradient of a 2D analysis.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Deformation<T> {
    /// In-plane block `F[i][j] = d x_i / d X_j`.
    pub f: [[T; 2]; 2],
    /// Out-of-plane stretch: 1 (plane strain) or `r / R` (axisymmetric).
    pub f33: T,
}

impl<T: Scalar> Deformation<T> {
    /// The identity.
    pub fn identity() -> Self {
        let (o, z) = (T::cst(1.0), T::cst(0.0));
        Deformation {
            f: [[o, z], [z, o]],
            f33: o,
        }
    }

    /// Determinant of the in-plane block.
    pub fn det2(&self) -> T {
        self.f[0][0] * self.f[1][1] - self.f[0][1] * self.f[1][0]
    }

    /// `J = det F`.
    pub fn det(&self) -> T {
        self.det2() * self.f33
    }

    /// `F A F^T` for a symmetric `A`.
    pub fn push(&self, a: &Sym<T>) -> Sym<T> {
        let f = &self.f;
        // M = F A
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
        [
            m[0][0] * f[0][0] + m[0][1] * f[0][1],
            m[1][0] * f[1][0] + m[1][1] * f[1][1],
            self.f33 * self.f33 * a[2],
            m[0][0] * f[1][0] + m[0][1] * f[1][1],
        ]
    }

    /// The inverse.
    pub fn inverse(&self) -> Self {
        let det = self.det2();
        let f = &self.f;
        Deformation {
            f: [
                [f[1][1] / det, -f[0][1] / det],
                [-f[1][0] / det, f[0][0] / det],
            ],
            f33: T::cst(1.0) / self.f33,
        }
    }

    /// The values (derivatives dropped).
    pub fn re(&self) -> Deformation<f64> {
        Deformation {
            f: [
                [self.f[0][0].re(), self.f[0][1].re()],
                [self.f[1][0].re(), self.f[1][1].re()],
            ],
            f33: self.f33.re(),
        }
    }

    /// First Piola-Kirchhoff stress `P = tau F^-T` of the Kirchhoff stress
    /// `tau`: in-plane block `[[P11, P12], [P21, P22]]` and `P33`.
    pub fn piola(&self, tau: &Sym<T>) -> ([[T; 2]; 2], T) {
        let g = self.inverse().f; // F^-1; F^-T[k][j] = g[j][k]
        let t = [[tau[0], tau[3]], [tau[3], tau[1]]];
        let mut p = [[T::cst(0.0); 2]; 2];
        for i in 0..2 {
            for j in 0..2 {
                p[i][j] = t[i][0] * g[j][0] + t[i][1] * g[j][1];
            }
        }
        (p, tau[2] / self.f33)
    }
}

/// `sum_k y^k c_k` by Horner.
fn series<T: Scalar>(y: T, c: &[f64]) -> T {
    let mut s = T::cst(0.0);
    for ck in c.iter().rev() {
        s = s * y + *ck;
    }
    s
}

/// Trace.
pub fn trace<T: Scalar>(a: &Sym<T>) -> T {
    a[0] + a[1] + a[2]
}

/// Deviatoric part.
pub fn deviator<T: Scalar>(a: &Sym<T>) -> Sym<T> {
    let m = trace(a) / 3.0;
    [a[0] - m, a[1] - m, a[2] - m, a[3]]
}

/// `A : A`.
pub fn norm2<T: Scalar>(a: &Sym<T>) -> T {
    a[0] * a[0] + a[1] * a[1] + a[2] * a[2] + a[3] * a[3] * 2.0
}

/// Matrix logarithm of a symmetric positive definite tensor.
pub fn log<T: Scalar>(a: &Sym<T>) -> Sym<T> {
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
    [
        half_ln_det + g * p,
        half_ln_det - g * p,
        a[2].ln(),
        g * a[3],
    ]
}

/// Matrix exponential of a symmetric tensor.
pub fn exp<T: Scalar>(a: &Sym<T>) -> Sym<T> {
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
    [e * (c + s * p), e * (c - s * p), a[2].exp(), e * s * a[3]]
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: &Sym<f64>, b: &Sym<f64>, tol: f64) -> bool {
        a.iter().zip(b).all(|(x, y)| (x - y).abs() <= tol)
    }

    #[test]
    fn log_and_exp_are_inverse_and_match_eigen_decomposition() {
        for a in [
            [1.0, 1.0, 1.0, 0.0],
            [2.0, 0.5, 1.3, 0.2],
            [1.0 + 1e-9, 1.0, 0.7, 1e-9],
            [3.0, 3.0, 2.0, 1.5],
        ] {
            let l = log(&a);
            assert!(close(&exp(&l), &a, 1e-13), "{a:?}");
            // eigen-decomposition of the 2x2 block
            let m = 0.5 * (a[0] + a[1]);
            let d = (0.25 * (a[0] - a[1]).powi(2) + a[3] * a[3]).sqrt();
            let (l1, l2) = ((m + d).ln(), (m - d).ln());
            // trace and determinant of log block
            assert!((l[0] + l[1] - (l1 + l2)).abs() < 1e-13);
            assert!((l[0] * l[1] - l[3] * l[3] - l1 * l2).abs() < 1e-12);
        }
    }

    #[test]
    fn push_and_piola_of_a_rotation() {
        let (c, s) = (0.6, 0.8);
        let r = Deformation {
            f: [[c, -s], [s, c]],
            f33: 1.0,
        };
        let b = r.push(&[1.0, 1.0, 1.0, 0.0]);
        assert!(close(&b, &[1.0, 1.0, 1.0, 0.0], 1e-15));
        // tau = R diag(2, 0) R^T, P = tau R = R diag(2, 0)
        let tau = r.push(&[2.0, 0.0, 0.0, 0.0]);
        let (p, _) = r.piola(&tau);
        assert!((p[0][0] - 2.0 * c).abs() < 1e-15 && (p[1][0] - 2.0 * s).abs() < 1e-15);
        assert!(p[0][1].abs() < 1e-15 && p[1][1].abs() < 1e-15);
    }
}
