//! Rational tensor-product B-spline surface: evaluation with first and
//! second derivatives (homogeneous derivatives from the basis of
//! [`super::basis`], then the rational quotient rule of The NURBS Book A4.4).

use super::basis::{check_knots, ders_basis, find_span};
use crate::{Aabb, Vec2, Vec3};

/// A point of the surface with its derivatives.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SurfaceDerivs {
    /// `S(u, v)`.
    pub p: Vec3,
    /// `dS/du`.
    pub su: Vec3,
    /// `dS/dv`.
    pub sv: Vec3,
    /// `d2S/du2`.
    pub suu: Vec3,
    /// `d2S/dudv`.
    pub suv: Vec3,
    /// `d2S/dv2`.
    pub svv: Vec3,
}

/// A NURBS surface. Control point `(i, j)` (`i` along `u`, `j` along `v`) is
/// `points[j * counts[0] + i]` (the order of an IGES 128 entity).
#[derive(Debug, Clone, PartialEq)]
pub struct NurbsSurface {
    /// Degrees `(p, q)` in `u` and `v`.
    pub degree: [usize; 2],
    /// Numbers of control points in `u` and `v`.
    pub counts: [usize; 2],
    /// Knot vectors in `u` and `v`.
    pub knots: [Vec<f64>; 2],
    /// Control points.
    pub points: Vec<Vec3>,
    /// Positive weights, one per control point.
    pub weights: Vec<f64>,
    /// Whether the surface closes on itself in `u` / `v` (the first and last
    /// rows of control points coincide): a periodic parameter.
    pub closed: [bool; 2],
    /// Whether an edge of the parameter rectangle collapses to a point (a
    /// pole): `[[u = u0, u = u1], [v = v0, v = v1]]`.
    pub degenerate: [[bool; 2]; 2],
    /// Seeds of the projection: a grid of `(u, v, S(u, v))`, `degree + 1`
    /// intervals per knot span and direction.
    pub samples: Vec<(Vec2, Vec3)>,
    /// Diagonal of the control net's box (the length scale of tolerances).
    pub size: f64,
}

impl NurbsSurface {
    /// Validates and builds a surface; errors say what is wrong.
    #[allow(clippy::needless_range_loop)] // indices follow the algorithm's notation
    pub fn new(
        degree: [usize; 2],
        counts: [usize; 2],
        knots: [Vec<f64>; 2],
        points: Vec<Vec3>,
        weights: Vec<f64>,
    ) -> Result<Self, String> {
        check_knots("NURBS surface (u)", counts[0], degree[0], &knots[0])?;
        check_knots("NURBS surface (v)", counts[1], degree[1], &knots[1])?;
        let n = counts[0] * counts[1];
        if points.len() != n {
            return Err(format!(
                "NURBS surface: {} control points for a {} x {} net",
                points.len(),
                counts[0],
                counts[1]
            ));
        }
        if weights.len() != n {
            return Err(format!(
                "NURBS surface: {} weights for {n} control points",
                weights.len()
            ));
        }
        if let Some(i) = points.iter().position(|p| !p.iter().all(|c| c.is_finite())) {
            return Err(format!(
                "NURBS surface: control point {} is not finite",
                i + 1
            ));
        }
        if let Some(i) = weights.iter().position(|w| !(*w > 0.0 && w.is_finite())) {
            return Err(format!(
                "NURBS surface: weight {} is {}; weights must be > 0",
                i + 1,
                weights[i]
            ));
        }
        let mut s = NurbsSurface {
            degree,
            counts,
            knots,
            points,
            weights,
            closed: [false; 2],
            degenerate: [[false; 2]; 2],
            samples: Vec::new(),
            size: 0.0,
        };
        s.size = s.bounding_box().diagonal().max(f64::MIN_POSITIVE);
        let tol = 1e-10 * s.size;
        let [nu, nv] = counts;
        let row = |s: &NurbsSurface, dir: usize, k: usize| -> Vec<Vec3> {
            if dir == 0 {
                (0..nv).map(|j| s.points[j * nu + k]).collect()
            } else {
                (0..nu).map(|i| s.points[k * nu + i]).collect()
            }
        };
        for dir in 0..2 {
            let last = counts[dir] - 1;
            let first_row = row(&s, dir, 0);
            let last_row = row(&s, dir, last);
            s.closed[dir] = first_row
                .iter()
                .zip(&last_row)
                .all(|(a, b)| (a - b).norm() <= tol);
            for (e, r) in [first_row, last_row].iter().enumerate() {
                s.degenerate[dir][e] = r.iter().all(|p| (p - r[0]).norm() <= tol);
            }
        }
        let grid = |dir: usize| -> Vec<f64> {
            let b = s.breaks(dir);
            let m = s.degree[dir] + 1;
            let mut t: Vec<f64> = b
                .windows(2)
                .flat_map(|w| (0..m).map(move |i| w[0] + (w[1] - w[0]) * i as f64 / m as f64))
                .collect();
            if !s.closed[dir] {
                t.push(*b.last().unwrap());
            }
            t
        };
        let (gu, gv) = (grid(0), grid(1));
        let dom = s.domain();
        let mut samples = Vec::with_capacity(gu.len() * gv.len());
        for (jv, &v) in gv.iter().enumerate() {
            for (iu, &u) in gu.iter().enumerate() {
                // A degenerate edge (pole) is one point: one sample.
                let on = |k: usize, t: f64| (0..2).any(|e| s.degenerate[k][e] && t == dom[k][e]);
                if (on(0, u) && jv > 0) || (on(1, v) && iu > 0) {
                    continue;
                }
                let uv = Vec2::new(u, v);
                samples.push((uv, s.point(uv)));
            }
        }
        s.samples = samples;
        Ok(s)
    }

    /// Parameter domain `[[u0, u1], [v0, v1]]`.
    pub fn domain(&self) -> [[f64; 2]; 2] {
        let d = |k: usize| [self.knots[k][self.degree[k]], self.knots[k][self.counts[k]]];
        [d(0), d(1)]
    }

    /// Box of the control net (holds the surface).
    pub fn bounding_box(&self) -> Aabb {
        Aabb::around(&self.points)
    }

    /// The distinct knot values bounding non-empty spans in direction `dir`.
    pub fn breaks(&self, dir: usize) -> Vec<f64> {
        let (p, n) = (self.degree[dir], self.counts[dir]);
        let mut b: Vec<f64> = self.knots[dir][p..=n].to_vec();
        b.dedup();
        b
    }

    /// Point only.
    pub fn point(&self, uv: Vec2) -> Vec3 {
        self.eval_order(uv, 0).p
    }

    /// Point, first and second derivatives at `uv`. Parameters outside the
    /// domain evaluate the extension of the end polynomial pieces.
    pub fn eval(&self, uv: Vec2) -> SurfaceDerivs {
        self.eval_order(uv, 2)
    }

    /// Point and derivatives up to order `nd` (the others are zero).
    #[allow(clippy::needless_range_loop)] // indices follow the algorithm's notation
    pub fn eval_order(&self, uv: Vec2, nd: usize) -> SurfaceDerivs {
        let [p, q] = self.degree;
        let [nu, nv] = self.counts;
        let su = find_span(nu, p, uv.x, &self.knots[0]);
        let sv = find_span(nv, q, uv.y, &self.knots[1]);
        let bu = ders_basis(su, uv.x, p, nd, &self.knots[0]);
        let bv = ders_basis(sv, uv.y, q, nd, &self.knots[1]);
        // Homogeneous derivatives A_kl (xyz * w) and w_kl, k + l <= 2.
        let mut a = [[Vec3::zeros(); 3]; 3];
        let mut w = [[0.0; 3]; 3];
        for l in 0..=q {
            let j = sv - q + l;
            // Partial sums along u for this row: temp_k = sum_i N_i^(k) Pw_ij.
            let mut ta = [Vec3::zeros(); 3];
            let mut tw = [0.0; 3];
            for r in 0..=p {
                let i = su - p + r;
                let idx = j * nu + i;
                let wt = self.weights[idx];
                let pw = self.points[idx] * wt;
                for k in 0..=nd {
                    ta[k] += pw * bu[k][r];
                    tw[k] += wt * bu[k][r];
                }
            }
            for k in 0..=nd {
                for m in 0..=(nd - k) {
                    a[k][m] += ta[k] * bv[m][l];
                    w[k][m] += tw[k] * bv[m][l];
                }
            }
        }
        let s = a[0][0] / w[0][0];
        let mut d = SurfaceDerivs {
            p: s,
            su: Vec3::zeros(),
            sv: Vec3::zeros(),
            suu: Vec3::zeros(),
            suv: Vec3::zeros(),
            svv: Vec3::zeros(),
        };
        if nd >= 1 {
            d.su = (a[1][0] - s * w[1][0]) / w[0][0];
            d.sv = (a[0][1] - s * w[0][1]) / w[0][0];
        }
        if nd >= 2 {
            d.suu = (a[2][0] - d.su * (2.0 * w[1][0]) - s * w[2][0]) / w[0][0];
            d.suv = (a[1][1] - d.su * w[0][1] - d.sv * w[1][0] - s * w[1][1]) / w[0][0];
            d.svv = (a[0][2] - d.sv * (2.0 * w[0][1]) - s * w[0][2]) / w[0][0];
        }
        d
    }

    /// Wraps a parameter of a closed direction into the domain; clamps it in
    /// an open one. Returns the new value and whether it was clamped.
    pub fn fold(&self, dir: usize, t: f64) -> (f64, bool) {
        let [a, b] = self.domain()[dir];
        if self.closed[dir] {
            let len = b - a;
            let mut r = (t - a).rem_euclid(len) + a;
            if r >= b {
                r = a;
            }
            (r, false)
        } else if t < a {
            (a, true)
        } else if t > b {
            (b, true)
        } else {
            (t, false)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::nurbs::build;

    #[test]
    fn derivatives_match_finite_differences_on_a_rational_sphere() {
        let s = build::sphere(Vec3::new(0.5, -1.0, 2.0), 1.5);
        let h = 1e-6;
        for &(u, v) in &[(0.3, 0.2), (0.7, 0.9), (0.51, 0.05), (0.12, 0.63)] {
            let uv = Vec2::new(u, v);
            let d = s.eval(uv);
            // On the sphere.
            assert!(((d.p - Vec3::new(0.5, -1.0, 2.0)).norm() - 1.5).abs() < 1e-13);
            let du = Vec2::new(h, 0.0);
            let dv = Vec2::new(0.0, h);
            let fu = (s.eval(uv + du).p - s.eval(uv - du).p) / (2.0 * h);
            let fv = (s.eval(uv + dv).p - s.eval(uv - dv).p) / (2.0 * h);
            assert!((fu - d.su).norm() < 1e-7 * d.su.norm());
            assert!((fv - d.sv).norm() < 1e-7 * d.sv.norm());
            let fuu = (s.eval(uv + du).su - s.eval(uv - du).su) / (2.0 * h);
            let fuv = (s.eval(uv + dv).su - s.eval(uv - dv).su) / (2.0 * h);
            let fvv = (s.eval(uv + dv).sv - s.eval(uv - dv).sv) / (2.0 * h);
            assert!((fuu - d.suu).norm() < 1e-6 * (1.0 + d.suu.norm()));
            assert!((fuv - d.suv).norm() < 1e-6 * (1.0 + d.suv.norm()));
            assert!((fvv - d.svv).norm() < 1e-6 * (1.0 + d.svv.norm()));
        }
        assert!(s.closed[1] && !s.closed[0]);
        assert_eq!(s.degenerate[0], [true, true]);
    }
}
