//! Forward-mode dual numbers with a fixed number of directions: the value
//! of a quantity and its gradient with respect to `N` coordinates. The
//! mortar integrals are closed-form functions of the coordinates of one
//! slave and one master segment (`N = 8`), so their exact first
//! derivatives come out of the same code that computes them.

use std::ops::{Add, AddAssign, Div, Mul, Neg, Sub};

/// A value and its gradient with respect to `N` variables.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ad<const N: usize> {
    /// Value.
    pub v: f64,
    /// Gradient.
    pub d: [f64; N],
}

impl<const N: usize> Ad<N> {
    /// A constant (zero gradient).
    pub fn cst(v: f64) -> Self {
        Ad { v, d: [0.0; N] }
    }

    /// Variable number `k` with value `v`.
    pub fn var(v: f64, k: usize) -> Self {
        let mut d = [0.0; N];
        d[k] = 1.0;
        Ad { v, d }
    }

    /// Square root (of a positive value).
    pub fn sqrt(self) -> Self {
        let s = self.v.sqrt();
        let f = 0.5 / s;
        self.map(s, f)
    }

    /// The larger of two values, with the gradient of the one chosen.
    pub fn max(self, o: Self) -> Self {
        if o.v > self.v {
            o
        } else {
            self
        }
    }

    /// The smaller of two values, with the gradient of the one chosen.
    pub fn min(self, o: Self) -> Self {
        if o.v < self.v {
            o
        } else {
            self
        }
    }

    /// `f(self)` of value `v` and derivative `df` at `self.v`.
    fn map(self, v: f64, df: f64) -> Self {
        let mut d = self.d;
        for x in &mut d {
            *x *= df;
        }
        Ad { v, d }
    }
}

impl<const N: usize> Add for Ad<N> {
    type Output = Self;
    fn add(mut self, o: Self) -> Self {
        self.v += o.v;
        for (a, b) in self.d.iter_mut().zip(o.d) {
            *a += b;
        }
        self
    }
}

impl<const N: usize> AddAssign for Ad<N> {
    fn add_assign(&mut self, o: Self) {
        *self = *self + o;
    }
}

impl<const N: usize> Sub for Ad<N> {
    type Output = Self;
    fn sub(self, o: Self) -> Self {
        self + (-o)
    }
}

impl<const N: usize> Neg for Ad<N> {
    type Output = Self;
    fn neg(self) -> Self {
        self.map(-self.v, -1.0)
    }
}

impl<const N: usize> Mul for Ad<N> {
    type Output = Self;
    fn mul(self, o: Self) -> Self {
        let mut d = [0.0; N];
        for (k, x) in d.iter_mut().enumerate() {
            *x = self.d[k] * o.v + self.v * o.d[k];
        }
        Ad { v: self.v * o.v, d }
    }
}

impl<const N: usize> Mul<f64> for Ad<N> {
    type Output = Self;
    fn mul(self, o: f64) -> Self {
        self.map(self.v * o, o)
    }
}

impl<const N: usize> Add<f64> for Ad<N> {
    type Output = Self;
    fn add(mut self, o: f64) -> Self {
        self.v += o;
        self
    }
}

impl<const N: usize> Div for Ad<N> {
    type Output = Self;
    fn div(self, o: Self) -> Self {
        let q = self.v / o.v;
        let mut d = [0.0; N];
        for (k, x) in d.iter_mut().enumerate() {
            *x = (self.d[k] - q * o.d[k]) / o.v;
        }
        Ad { v: q, d }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn products_quotients_and_roots_differentiate() {
        let x = Ad::<2>::var(3.0, 0);
        let y = Ad::<2>::var(4.0, 1);
        let r = (x * x + y * y).sqrt();
        assert_eq!(r.v, 5.0);
        assert!((r.d[0] - 0.6).abs() < 1e-15 && (r.d[1] - 0.8).abs() < 1e-15);
        let q = x / y;
        assert!((q.d[0] - 0.25).abs() < 1e-15 && (q.d[1] + 3.0 / 16.0).abs() < 1e-15);
        let m = (x - y).max(Ad::cst(0.0));
        assert_eq!(m.d, [0.0, 0.0]);
        assert_eq!(x.min(y).d, [1.0, 0.0]);
    }
}
