//! Forward-mode automatic differentiation: dual numbers `v + sum_k d_k e_k`
//! with `N` independent directions, and the [`Scalar`] trait that lets one
//! stress update serve both for values (`f64`) and for exact derivatives
//! ([`Dual`]).
//!
//! The nonlinear element kernels seed the element displacements as the `N`
//! directions, so the internal force comes out with its exact Jacobian: the
//! consistent tangent (material and geometric parts, return mapping
//! included) to round-off, without hand-derived fourth-order tensors.
//! Local Newton iterations (return mapping) run in `f64`; one final Newton
//! correction in dual arithmetic then carries the implicit-function
//! derivative exactly.

use std::ops::{Add, Div, Mul, Neg, Sub};

/// Arithmetic needed by the constitutive updates, for `f64` and [`Dual`].
pub trait Scalar:
    Copy
    + std::fmt::Debug
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
    + Add<f64, Output = Self>
    + Sub<f64, Output = Self>
    + Mul<f64, Output = Self>
    + Div<f64, Output = Self>
{
    /// A constant (zero derivatives).
    fn cst(v: f64) -> Self;
    /// The value (derivatives dropped).
    fn re(self) -> f64;
    /// Natural logarithm.
    fn ln(self) -> Self;
    /// Exponential.
    fn exp(self) -> Self;
    /// Square root.
    fn sqrt(self) -> Self;
    /// Real power.
    fn powf(self, p: f64) -> Self;
    /// Number of derivative directions (0 for `f64`).
    const DIRECTIONS: usize;
    /// Derivative along direction `k < DIRECTIONS`.
    fn direction(&self, k: usize) -> f64;
    /// The number with value `v` and derivative `d(k)` along each
    /// direction `k` (a matrix function applies its own chain rule, e.g.
    /// `crate::material::tensor::isotropic`).
    fn from_parts(v: f64, d: impl FnMut(usize) -> f64) -> Self;
}

impl Scalar for f64 {
    fn cst(v: f64) -> Self {
        v
    }
    fn re(self) -> f64 {
        self
    }
    fn ln(self) -> Self {
        f64::ln(self)
    }
    fn exp(self) -> Self {
        f64::exp(self)
    }
    fn sqrt(self) -> Self {
        f64::sqrt(self)
    }
    fn powf(self, p: f64) -> Self {
        f64::powf(self, p)
    }
    const DIRECTIONS: usize = 0;
    fn direction(&self, _k: usize) -> f64 {
        0.0
    }
    fn from_parts(v: f64, _d: impl FnMut(usize) -> f64) -> Self {
        v
    }
}

/// A dual number: value and `N` partial derivatives.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Dual<const N: usize> {
    /// Value.
    pub v: f64,
    /// Partial derivatives with respect to the `N` seeded variables.
    pub d: [f64; N],
}

impl<const N: usize> Dual<N> {
    /// The `k`-th independent variable with value `v`.
    pub fn var(v: f64, k: usize) -> Self {
        let mut d = [0.0; N];
        d[k] = 1.0;
        Dual { v, d }
    }

    /// `f(self)` with derivative `df` at the value (chain rule).
    #[inline]
    fn chain(self, f: f64, df: f64) -> Self {
        let mut d = self.d;
        for x in &mut d {
            *x *= df;
        }
        Dual { v: f, d }
    }
}

impl<const N: usize> Add for Dual<N> {
    type Output = Self;
    #[inline]
    fn add(mut self, o: Self) -> Self {
        self.v += o.v;
        for (a, b) in self.d.iter_mut().zip(o.d) {
            *a += b;
        }
        self
    }
}

impl<const N: usize> Sub for Dual<N> {
    type Output = Self;
    #[inline]
    fn sub(mut self, o: Self) -> Self {
        self.v -= o.v;
        for (a, b) in self.d.iter_mut().zip(o.d) {
            *a -= b;
        }
        self
    }
}

impl<const N: usize> Mul for Dual<N> {
    type Output = Self;
    #[inline]
    fn mul(self, o: Self) -> Self {
        let mut d = [0.0; N];
        for (k, x) in d.iter_mut().enumerate() {
            *x = self.d[k] * o.v + self.v * o.d[k];
        }
        Dual { v: self.v * o.v, d }
    }
}

impl<const N: usize> Div for Dual<N> {
    type Output = Self;
    #[inline]
    fn div(self, o: Self) -> Self {
        let inv = 1.0 / o.v;
        let v = self.v * inv;
        let mut d = [0.0; N];
        for (k, x) in d.iter_mut().enumerate() {
            *x = (self.d[k] - v * o.d[k]) * inv;
        }
        Dual { v, d }
    }
}

impl<const N: usize> Neg for Dual<N> {
    type Output = Self;
    #[inline]
    fn neg(self) -> Self {
        self.chain(-self.v, -1.0)
    }
}

impl<const N: usize> Add<f64> for Dual<N> {
    type Output = Self;
    #[inline]
    fn add(mut self, o: f64) -> Self {
        self.v += o;
        self
    }
}

impl<const N: usize> Sub<f64> for Dual<N> {
    type Output = Self;
    #[inline]
    fn sub(mut self, o: f64) -> Self {
        self.v -= o;
        self
    }
}

impl<const N: usize> Mul<f64> for Dual<N> {
    type Output = Self;
    #[inline]
    fn mul(self, o: f64) -> Self {
        self.chain(self.v * o, o)
    }
}

impl<const N: usize> Div<f64> for Dual<N> {
    type Output = Self;
    #[inline]
    fn div(self, o: f64) -> Self {
        self.chain(self.v / o, 1.0 / o)
    }
}

impl<const N: usize> Scalar for Dual<N> {
    fn cst(v: f64) -> Self {
        Dual { v, d: [0.0; N] }
    }
    fn re(self) -> f64 {
        self.v
    }
    fn ln(self) -> Self {
        self.chain(self.v.ln(), 1.0 / self.v)
    }
    fn exp(self) -> Self {
        let e = self.v.exp();
        self.chain(e, e)
    }
    fn sqrt(self) -> Self {
        let s = self.v.sqrt();
        self.chain(s, 0.5 / s)
    }
    fn powf(self, p: f64) -> Self {
        self.chain(self.v.powf(p), p * self.v.powf(p - 1.0))
    }
    const DIRECTIONS: usize = N;
    fn direction(&self, k: usize) -> f64 {
        self.d[k]
    }
    fn from_parts(v: f64, mut d: impl FnMut(usize) -> f64) -> Self {
        let mut out = [0.0; N];
        for (k, x) in out.iter_mut().enumerate() {
            *x = d(k);
        }
        Dual { v, d: out }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dual_derivatives_match_calculus() {
        let x = Dual::<2>::var(1.3, 0);
        let y = Dual::<2>::var(0.7, 1);
        // f = x y / (x + y) + ln(x) exp(y) + sqrt(x)^3 - x^2.5
        let f = x * y / (x + y) + x.ln() * y.exp() + x.sqrt() * x.sqrt() * x.sqrt() - x.powf(2.5)
            + (-y) * 2.0
            - 1.0;
        let (a, b) = (1.3f64, 0.7f64);
        let dfdx = b * b / (a + b).powi(2) + b.exp() / a + 1.5 * a.sqrt() - 2.5 * a.powf(1.5);
        let dfdy = a * a / (a + b).powi(2) + a.ln() * b.exp() - 2.0;
        assert!((f.d[0] - dfdx).abs() < 1e-13, "{} {}", f.d[0], dfdx);
        assert!((f.d[1] - dfdy).abs() < 1e-13);
    }
}
