//! Trimming curves in a face's parameter plane: straight lines, circular
//! arcs and rational NURBS curves.

use crate::nurbs::{CurveDerivs, NurbsCurve};
use crate::Vec2;
use std::f64::consts::TAU;

/// One trimming curve, parameter `t` in [`TrimCurve::domain`].
#[derive(Debug, Clone, PartialEq)]
pub enum TrimCurve {
    /// The segment from `a` to `b`, `t` in `[0, 1]`.
    Line {
        /// Start.
        a: Vec2,
        /// End.
        b: Vec2,
    },
    /// The arc `center + radius (cos, sin)(start + sweep t)`, `t` in
    /// `[0, 1]`; `sweep > 0` counter-clockwise.
    Arc {
        /// Centre.
        center: Vec2,
        /// Radius > 0.
        radius: f64,
        /// Angle at `t = 0` (radians).
        start: f64,
        /// Signed angle swept, `0 < |sweep| <= 2 pi`.
        sweep: f64,
    },
    /// A rational B-spline curve.
    Nurbs(NurbsCurve<2>),
}

impl TrimCurve {
    /// A line; errors when its ends are not finite.
    pub fn line(a: Vec2, b: Vec2) -> Result<Self, String> {
        if !(a.iter().chain(b.iter()).all(|c| c.is_finite())) {
            return Err("trimming line: the end points must be finite".into());
        }
        Ok(TrimCurve::Line { a, b })
    }

    /// An arc; errors on a non-positive radius or a zero sweep.
    pub fn arc(center: Vec2, radius: f64, start: f64, sweep: f64) -> Result<Self, String> {
        if !(radius > 0.0 && radius.is_finite()) {
            return Err(format!(
                "trimming arc: the radius must be > 0 (got {radius})"
            ));
        }
        if !(sweep != 0.0 && sweep.abs() <= TAU * (1.0 + 1e-12) && start.is_finite()) {
            return Err(format!(
                "trimming arc: the swept angle must be in (0, 2 pi] (got {sweep})"
            ));
        }
        if !center.iter().all(|c| c.is_finite()) {
            return Err("trimming arc: the centre must be finite".into());
        }
        Ok(TrimCurve::Arc {
            center,
            radius,
            start,
            sweep,
        })
    }

    /// Parameter range.
    pub fn domain(&self) -> [f64; 2] {
        match self {
            TrimCurve::Nurbs(c) => c.domain(),
            _ => [0.0, 1.0],
        }
    }

    /// Point and first two derivatives.
    pub fn eval(&self, t: f64) -> CurveDerivs<2> {
        match self {
            TrimCurve::Line { a, b } => CurveDerivs {
                p: a + (b - a) * t,
                d1: b - a,
                d2: Vec2::zeros(),
            },
            TrimCurve::Arc {
                center,
                radius,
                start,
                sweep,
            } => {
                let (s, c) = (start + sweep * t).sin_cos();
                CurveDerivs {
                    p: center + Vec2::new(c, s) * *radius,
                    d1: Vec2::new(-s, c) * (radius * sweep),
                    d2: Vec2::new(-c, -s) * (radius * sweep * sweep),
                }
            }
            TrimCurve::Nurbs(c) => c.eval(t),
        }
    }

    /// Start point.
    pub fn start(&self) -> Vec2 {
        self.eval(self.domain()[0]).p
    }

    /// End point.
    pub fn end(&self) -> Vec2 {
        self.eval(self.domain()[1]).p
    }

    /// Parameters splitting the curve into pieces that are smooth and turn
    /// little (NURBS: `4 (p + 1)` pieces per knot span; arc: one per 10
    /// degrees; line: one).
    pub fn pieces(&self) -> Vec<f64> {
        match self {
            TrimCurve::Line { .. } => vec![0.0, 1.0],
            TrimCurve::Arc { sweep, .. } => {
                let n = ((sweep.abs() / 10f64.to_radians()).ceil() as usize).max(1);
                (0..=n).map(|i| i as f64 / n as f64).collect()
            }
            TrimCurve::Nurbs(c) => {
                let m = 4 * (c.degree + 1);
                let b = c.breaks();
                let mut t: Vec<f64> = b
                    .windows(2)
                    .flat_map(|w| (0..m).map(move |i| w[0] + (w[1] - w[0]) * i as f64 / m as f64))
                    .collect();
                t.push(*b.last().unwrap());
                t
            }
        }
    }

    /// A polyline through `n + 1` points per piece (for brute-force checks
    /// and boxes).
    pub fn polyline(&self, n: usize) -> Vec<Vec2> {
        let pieces = self.pieces();
        let mut pts = vec![self.eval(pieces[0]).p];
        for w in pieces.windows(2) {
            for i in 1..=n {
                pts.push(self.eval(w[0] + (w[1] - w[0]) * i as f64 / n as f64).p);
            }
        }
        pts
    }

    /// The same curve walked backwards.
    pub fn reversed(&self) -> Self {
        match self {
            TrimCurve::Line { a, b } => TrimCurve::Line { a: *b, b: *a },
            TrimCurve::Arc {
                center,
                radius,
                start,
                sweep,
            } => TrimCurve::Arc {
                center: *center,
                radius: *radius,
                start: start + sweep,
                sweep: -sweep,
            },
            TrimCurve::Nurbs(c) => TrimCurve::Nurbs(c.reversed()),
        }
    }

    /// Whether `t` (radians) lies in the arc's swept range, and its
    /// parameter there.
    pub(crate) fn arc_parameter(start: f64, sweep: f64, theta: f64) -> f64 {
        let rel = (theta - start) * sweep.signum();
        rel.rem_euclid(TAU) / sweep.abs()
    }
}
