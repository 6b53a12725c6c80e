//! Rational B-spline curve in `D` dimensions (2: a trimming curve in a
//! parameter plane; 3: a model-space curve), with first and second
//! derivatives.

use super::basis::{check_knots, ders_basis, find_span};
use nalgebra::SVector;

/// A point of a curve with its first two derivatives.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CurveDerivs<const D: usize> {
    /// `C(t)`.
    pub p: SVector<f64, D>,
    /// `C'(t)`.
    pub d1: SVector<f64, D>,
    /// `C''(t)`.
    pub d2: SVector<f64, D>,
}

/// A NURBS curve of degree `degree`.
#[derive(Debug, Clone, PartialEq)]
pub struct NurbsCurve<const D: usize> {
    /// Degree >= 1.
    pub degree: usize,
    /// Knot vector (`points.len() + degree + 1` values).
    pub knots: Vec<f64>,
    /// Control points.
    pub points: Vec<SVector<f64, D>>,
    /// Positive weights.
    pub weights: Vec<f64>,
}

impl<const D: usize> NurbsCurve<D> {
    /// Validates and builds the curve.
    pub fn new(
        degree: usize,
        knots: Vec<f64>,
        points: Vec<SVector<f64, D>>,
        weights: Vec<f64>,
    ) -> Result<Self, String> {
        check_knots("NURBS curve", points.len(), degree, &knots)?;
        if weights.len() != points.len() {
            return Err(format!(
                "NURBS curve: {} weights for {} control points",
                weights.len(),
                points.len()
            ));
        }
        if let Some(i) = points.iter().position(|p| !p.iter().all(|c| c.is_finite())) {
            return Err(format!(
                "NURBS curve: control point {} is not finite",
                i + 1
            ));
        }
        if let Some(i) = weights.iter().position(|w| !(*w > 0.0 && w.is_finite())) {
            return Err(format!(
                "NURBS curve: weight {} is {}; weights must be > 0",
                i + 1,
                weights[i]
            ));
        }
        Ok(NurbsCurve {
            degree,
            knots,
            points,
            weights,
        })
    }

    /// Parameter range `[t0, t1]`.
    pub fn domain(&self) -> [f64; 2] {
        [self.knots[self.degree], self.knots[self.points.len()]]
    }

    /// The distinct knots bounding non-empty spans.
    pub fn breaks(&self) -> Vec<f64> {
        let mut b = self.knots[self.degree..=self.points.len()].to_vec();
        b.dedup();
        b
    }

    /// Point and derivatives at `t` (outside the range: the end pieces
    /// extended).
    #[allow(clippy::needless_range_loop)] // indices follow the algorithm's notation
    pub fn eval(&self, t: f64) -> CurveDerivs<D> {
        let p = self.degree;
        let n = self.points.len();
        let s = find_span(n, p, t, &self.knots);
        let b = ders_basis(s, t, p, 2, &self.knots);
        let mut a = [SVector::<f64, D>::zeros(); 3];
        let mut w = [0.0; 3];
        for r in 0..=p {
            let i = s - p + r;
            let wt = self.weights[i];
            for k in 0..3 {
                a[k] += self.points[i] * (wt * b[k][r]);
                w[k] += wt * b[k][r];
            }
        }
        let c = a[0] / w[0];
        let d1 = (a[1] - c * w[1]) / w[0];
        let d2 = (a[2] - d1 * (2.0 * w[1]) - c * w[2]) / w[0];
        CurveDerivs { p: c, d1, d2 }
    }

    /// The curve walked backwards (same image, reversed parameter
    /// `t -> t0 + t1 - t`).
    pub fn reversed(&self) -> Self {
        let [a, b] = self.domain();
        let mut knots: Vec<f64> = self.knots.iter().rev().map(|k| a + b - k).collect();
        // Keep the knots exactly non-decreasing after the reflection.
        for i in 1..knots.len() {
            if knots[i] < knots[i - 1] {
                knots[i] = knots[i - 1];
            }
        }
        NurbsCurve {
            degree: self.degree,
            knots,
            points: self.points.iter().rev().copied().collect(),
            weights: self.weights.iter().rev().copied().collect(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Vector2;

    /// The quarter circle of radius 1 as a rational quadratic.
    fn quarter() -> NurbsCurve<2> {
        let h = std::f64::consts::FRAC_1_SQRT_2;
        NurbsCurve::new(
            2,
            vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
            vec![
                Vector2::new(1.0, 0.0),
                Vector2::new(1.0, 1.0),
                Vector2::new(0.0, 1.0),
            ],
            vec![1.0, h, 1.0],
        )
        .unwrap()
    }

    #[test]
    fn rational_quarter_circle_is_exact_and_derivatives_match() {
        let c = quarter();
        let h = 1e-6;
        for &t in &[0.0, 0.2, 0.5, 0.9, 1.0] {
            let d = c.eval(t);
            assert!((d.p.norm() - 1.0).abs() < 1e-15);
            if (h..=1.0 - h).contains(&t) {
                let fd = (c.eval(t + h).p - c.eval(t - h).p) / (2.0 * h);
                assert!((fd - d.d1).norm() < 1e-8);
                let fd2 = (c.eval(t + h).d1 - c.eval(t - h).d1) / (2.0 * h);
                assert!((fd2 - d.d2).norm() < 1e-6);
            }
        }
        let r = c.reversed();
        assert!((r.eval(0.3).p - c.eval(0.7).p).norm() < 1e-15);
    }
}
