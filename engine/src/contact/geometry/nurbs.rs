//! NURBS curve: evaluation (Cox–de Boor derivatives, Piegl & Tiller A2.3,
//! rational quotient rule) and closest-point projection, one entity per
//! non-empty knot span.
//!
//! Projection on a span `[ua, ub]` minimises `f(u) = |C(u) - x|^2 / 2`:
//! 1. sample `f` at `4 (p + 1) + 4` evenly spaced parameters;
//! 2. every sampled local minimum (endpoints included) is refined by a
//!    safeguarded Newton iteration on `f'(u) = (C - x) . C'` inside its
//!    bracket, falling back to bisection whenever the Newton step leaves the
//!    bracket, does not shrink fast enough or `f'' <= 0` (singular points);
//!    the parameter is therefore always clamped to the span;
//! 3. the smallest of the refined minima is the span's closest point
//!    (several local minima -> the closest one).
//!
//! A closest point strictly inside the span (or orthogonal at an end) gives
//! the curve normal and curvature `kappa = -(C' x C'') / |C'|^3` (positive
//! when convex seen from the free side, which is on the left of increasing
//! `u`); a closest point clamped at a span end is a corner shared with the
//! neighbouring span (C0 knot, seam of a closed curve) or a free end of the
//! curve, see [`super::corner`].

use super::corner::{corner, end_cap};
use super::{finite, Projection};
use crate::contact::vec2::{cross, dot, left, norm, scale, sub, unit};
use crate::geom::Aabb;

/// Highest supported degree (keeps the basis evaluation on the stack).
pub const MAX_DEGREE: usize = ctc_geom::nurbs::basis::MAX_DEGREE;

/// A NURBS curve prepared for projection.
#[derive(Debug, Clone, PartialEq)]
pub struct Nurbs {
    /// Polynomial degree `p >= 1`.
    pub degree: usize,
    /// Control points.
    pub points: Vec<[f64; 2]>,
    /// Positive weights.
    pub weights: Vec<f64>,
    /// Knot vector (`points.len() + degree + 1` values).
    pub knots: Vec<f64>,
    /// Knot index `k` of each non-empty span `[knots[k], knots[k+1]]`.
    pub spans: Vec<usize>,
    /// Whether the curve's end point coincides with its start point.
    pub closed: bool,
    /// Bounding box of each span (convex hull of its control points).
    boxes: Vec<Aabb<2>>,
    /// One-sided unit normal at the start of each span.
    start_normals: Vec<[f64; 2]>,
    /// One-sided unit normal at the end of each span.
    end_normals: Vec<[f64; 2]>,
}

/// Point and first two derivatives of the curve at a parameter.
#[derive(Debug, Clone, Copy)]
struct Eval {
    /// Point `C(u)`.
    c: [f64; 2],
    /// `C'(u)`.
    d1: [f64; 2],
    /// `C''(u)`.
    d2: [f64; 2],
}

impl Nurbs {
    /// Validates and prepares a NURBS curve.
    pub fn new(
        degree: usize,
        points: &[[f64; 2]],
        weights: &[f64],
        knots: &[f64],
    ) -> Result<Self, String> {
        let n = points.len();
        if degree == 0 || degree > MAX_DEGREE {
            return Err(format!(
                "nurbs tool: degree must be between 1 and {MAX_DEGREE} (got {degree})"
            ));
        }
        if n < degree + 1 {
            return Err(format!(
                "nurbs tool: degree {degree} needs at least {} control points (got {n})",
                degree + 1
            ));
        }
        if let Some(i) = points.iter().position(|p| !finite(*p)) {
            return Err(format!("nurbs tool: control point {} is not finite", i + 1));
        }
        if weights.len() != n {
            return Err(format!(
                "nurbs tool: {} weights for {n} control points; give one weight per point",
                weights.len()
            ));
        }
        if let Some(i) = weights.iter().position(|w| !(*w > 0.0 && w.is_finite())) {
            return Err(format!(
                "nurbs tool: weight {} is {}; weights must be > 0",
                i + 1,
                weights[i]
            ));
        }
        if knots.len() != n + degree + 1 {
            return Err(format!(
                "nurbs tool: the knot vector has {} values; {n} control points of degree {degree} need {}",
                knots.len(),
                n + degree + 1
            ));
        }
        if knots.iter().any(|k| !k.is_finite()) {
            return Err("nurbs tool: knots must be finite".into());
        }
        if let Some(i) = knots.windows(2).position(|w| w[1] < w[0]) {
            return Err(format!(
                "nurbs tool: knots must not decrease (knot {} = {} > knot {} = {})",
                i + 1,
                knots[i],
                i + 2,
                knots[i + 1]
            ));
        }
        let (u0, u1) = (knots[degree], knots[n]);
        if u0 >= u1 {
            return Err("nurbs tool: the knot vector gives an empty parameter range".into());
        }
        for k in degree + 1..n {
            let mult = knots.iter().filter(|&&v| v == knots[k]).count();
            if knots[k] > u0 && knots[k] < u1 && mult > degree {
                return Err(format!(
                    "nurbs tool: interior knot {} has multiplicity {mult} > degree {degree}: \
                     the curve would be disconnected",
                    knots[k]
                ));
            }
        }
        let spans: Vec<usize> = (degree..n).filter(|&k| knots[k] < knots[k + 1]).collect();
        let boxes = spans
            .iter()
            .map(|&k| Aabb::around(&points[k - degree..=k]))
            .collect();
        let mut curve = Nurbs {
            degree,
            points: points.to_vec(),
            weights: weights.to_vec(),
            knots: knots.to_vec(),
            spans,
            closed: false,
            boxes,
            start_normals: Vec::new(),
            end_normals: Vec::new(),
        };
        for s in 0..curve.spans.len() {
            let k = curve.spans[s];
            let (a, b) = (curve.knots[k], curve.knots[k + 1]);
            let na = curve.normal_at(s, a).ok_or_else(|| {
                format!(
                    "nurbs tool: the tangent vanishes at u = {a}; remove coincident control points"
                )
            })?;
            let nb = curve.normal_at(s, b).ok_or_else(|| {
                format!(
                    "nurbs tool: the tangent vanishes at u = {b}; remove coincident control points"
                )
            })?;
            curve.start_normals.push(na);
            curve.end_normals.push(nb);
        }
        let extent = {
            let b = Aabb::around(points);
            (b.max[0] - b.min[0]).max(b.max[1] - b.min[1])
        };
        let first = curve.eval(0, u0).c;
        let last = curve.eval(curve.spans.len() - 1, u1).c;
        curve.closed = curve.spans.len() > 1 && norm(sub(first, last)) <= 1e-12 * extent;
        Ok(curve)
    }

    /// Number of non-empty knot spans (entities).
    pub fn span_count(&self) -> usize {
        self.spans.len()
    }

    /// Whether the curve is closed.
    pub fn is_closed(&self) -> bool {
        self.closed
    }

    /// Bounding box of span `s`.
    pub fn bounding_box(&self, s: usize) -> Aabb<2> {
        self.boxes[s]
    }

    /// Parameter range `[ua, ub]` of span `s`.
    pub fn span_range(&self, s: usize) -> (f64, f64) {
        let k = self.spans[s];
        (self.knots[k], self.knots[k + 1])
    }

    /// Curve point at `u` evaluated with the polynomial piece of span `s`.
    pub fn point(&self, s: usize, u: f64) -> [f64; 2] {
        self.eval(s, u).c
    }

    /// Point, first and second derivatives at `u` with the piece of span `s`
    /// (one-sided at the span ends).
    fn eval(&self, s: usize, u: f64) -> Eval {
        let p = self.degree;
        let k = self.spans[s];
        let ders = basis_derivatives(k, u, p, &self.knots);
        // Homogeneous sums A = sum N w P, W = sum N w and their derivatives.
        let mut a = [[0.0; 2]; 3];
        let mut w = [0.0; 3];
        for j in 0..=p {
            let idx = k - p + j;
            let (pt, wt) = (self.points[idx], self.weights[idx]);
            for (d, row) in ders.iter().enumerate() {
                let nw = row[j] * wt;
                w[d] += nw;
                a[d][0] += nw * pt[0];
                a[d][1] += nw * pt[1];
            }
        }
        let c = scale(1.0 / w[0], a[0]);
        let d1 = scale(1.0 / w[0], sub(a[1], scale(w[1], c)));
        let d2 = scale(
            1.0 / w[0],
            sub(sub(a[2], scale(2.0 * w[1], d1)), scale(w[2], c)),
        );
        Eval { c, d1, d2 }
    }

    /// Unit tangent of span `s` at `u`; at a vanishing first derivative
    /// (a singular point) the direction of the limit tangent is taken just
    /// inside the span.
    fn tangent_and_curvature(&self, s: usize, u: f64, e: &Eval) -> Option<([f64; 2], f64)> {
        let speed = norm(e.d1);
        let (ua, ub) = self.span_range(s);
        let scale_len = norm(sub(self.eval(s, ua).c, self.eval(s, ub).c)).max(1e-300);
        if speed > 1e-10 * scale_len / (ub - ua) {
            let kappa = -cross(e.d1, e.d2) / (speed * speed * speed);
            return Some((scale(1.0 / speed, e.d1), kappa));
        }
        let h = 1e-7 * (ub - ua);
        let v = if u - ua < ub - u { u + h } else { u - h };
        let f = self.eval(s, v);
        let t = unit(f.d1)?;
        let sp = norm(f.d1);
        Some((t, -cross(f.d1, f.d2) / (sp * sp * sp)))
    }

    /// Point, unit normal (left of increasing `u`, towards free space) and
    /// curvature (positive when convex seen from the free side) of span `s`
    /// at `u`; `None` where the tangent is undefined.
    pub fn frame(&self, s: usize, u: f64) -> Option<([f64; 2], [f64; 2], f64)> {
        let e = self.eval(s, u);
        let (t, kappa) = self.tangent_and_curvature(s, u, &e)?;
        Some((e.c, left(t), kappa))
    }

    /// Unit normal (left of increasing `u`) of span `s` at `u`.
    fn normal_at(&self, s: usize, u: f64) -> Option<[f64; 2]> {
        let e = self.eval(s, u);
        self.tangent_and_curvature(s, u, &e).map(|(t, _)| left(t))
    }

    /// Closest point of span `s` to `x` (see the module documentation).
    pub fn project(&self, s: usize, x: [f64; 2]) -> Option<Projection> {
        let (ua, ub) = self.span_range(s);
        let u = self.closest_parameter(s, x);
        let e = self.eval(s, u);
        let d = sub(x, e.c);
        let dist = norm(d);
        let (t, kappa) = self.tangent_and_curvature(s, u, &e)?;
        let orthogonal = dot(d, t).abs() <= 1e-10 * dist;
        if (u > ua && u < ub) || orthogonal || dist == 0.0 {
            let n = left(t);
            return Some(Projection::on_curve(e.c, dot(d, n), n, kappa, u));
        }
        let last = self.spans.len() - 1;
        if u <= ua {
            if s > 0 || self.closed {
                let prev = if s > 0 { s - 1 } else { last };
                Some(corner(
                    x,
                    e.c,
                    self.end_normals[prev],
                    self.start_normals[s],
                    u,
                ))
            } else {
                Some(end_cap(x, e.c, self.start_normals[s], u))
            }
        } else if s < last || self.closed {
            let next = if s < last { s + 1 } else { 0 };
            Some(corner(
                x,
                e.c,
                self.end_normals[s],
                self.start_normals[next],
                u,
            ))
        } else {
            Some(end_cap(x, e.c, self.end_normals[s], u))
        }
    }

    /// Parameter in `[ua, ub]` of the closest point of span `s` to `x`.
    pub fn closest_parameter(&self, s: usize, x: [f64; 2]) -> f64 {
        let (ua, ub) = self.span_range(s);
        let m = 4 * (self.degree + 1) + 4;
        let param = |i: usize| {
            if i == m {
                ub
            } else {
                ua + (ub - ua) * i as f64 / m as f64
            }
        };
        let f: Vec<f64> = (0..=m)
            .map(|i| {
                let d = sub(self.eval(s, param(i)).c, x);
                dot(d, d)
            })
            .collect();
        let mut best = (f64::INFINITY, ua);
        for i in 0..=m {
            let left_ok = i == 0 || f[i] <= f[i - 1];
            let right_ok = i == m || f[i] <= f[i + 1];
            if !(left_ok && right_ok) {
                continue;
            }
            let lo = param(i.saturating_sub(1));
            let hi = param((i + 1).min(m));
            let u = self.refine(s, x, lo, hi, param(i));
            let d = sub(self.eval(s, u).c, x);
            let fu = dot(d, d);
            if fu < best.0 {
                best = (fu, u);
            }
        }
        best.1
    }

    /// `(f', f'')` of `f(u) = |C(u) - x|^2 / 2`.
    fn distance_derivatives(&self, s: usize, x: [f64; 2], u: f64) -> (f64, f64) {
        let e = self.eval(s, u);
        let d = sub(e.c, x);
        (dot(d, e.d1), dot(e.d1, e.d1) + dot(d, e.d2))
    }

    /// Minimiser of `f` on `[lo, hi]` starting from `u0`: safeguarded
    /// Newton on `f' = 0` when `f'` changes sign, otherwise the better end.
    fn refine(&self, s: usize, x: [f64; 2], lo: f64, hi: f64, u0: f64) -> f64 {
        let (glo, _) = self.distance_derivatives(s, x, lo);
        let (ghi, _) = self.distance_derivatives(s, x, hi);
        if glo >= 0.0 || ghi <= 0.0 {
            // No interior stationary point bracketed: a minimum at an end.
            let flo = {
                let d = sub(self.eval(s, lo).c, x);
                dot(d, d)
            };
            let fhi = {
                let d = sub(self.eval(s, hi).c, x);
                dot(d, d)
            };
            return if glo >= 0.0 && (ghi > 0.0 || flo <= fhi) {
                lo
            } else {
                hi
            };
        }
        let (mut a, mut b) = (lo, hi);
        let mut u = if u0 > a && u0 < b { u0 } else { 0.5 * (a + b) };
        let tol = 4.0 * f64::EPSILON * (hi - lo).max(lo.abs().max(hi.abs()) * 1e-3);
        let mut dx_old = b - a;
        let mut dx = dx_old;
        for _ in 0..200 {
            let (g, gp) = self.distance_derivatives(s, x, u);
            if g == 0.0 {
                return u;
            }
            if g < 0.0 {
                a = u;
            } else {
                b = u;
            }
            let newton = u - g / gp;
            let use_bisection =
                gp <= 0.0 || newton <= a || newton >= b || (2.0 * g).abs() > (dx_old * gp).abs();
            dx_old = dx;
            if use_bisection {
                dx = 0.5 * (b - a);
                u = a + dx;
            } else {
                dx = g / gp;
                u = newton;
            }
            if dx.abs() <= tol || b - a <= tol {
                break;
            }
        }
        u
    }
}

/// Basis functions of degree `p` and their first two derivatives at `u`
/// for knot span `k` (Piegl & Tiller, algorithm A2.3, from `ctc-geom`):
/// `ders[d][j]` is the `d`-th derivative of `N_{k-p+j, p}(u)`.
fn basis_derivatives(k: usize, u: f64, p: usize, knots: &[f64]) -> [[f64; MAX_DEGREE + 1]; 3] {
    ctc_geom::nurbs::basis::ders_basis(k, u, p, 2, knots)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::geometry::arc::Arc;
    use crate::contact::geometry::Foot;
    use std::f64::consts::{FRAC_1_SQRT_2, FRAC_PI_2};

    fn quarter_circle() -> Nurbs {
        Nurbs::new(
            2,
            &[[1.0, 0.0], [1.0, 1.0], [0.0, 1.0]],
            &[1.0, FRAC_1_SQRT_2, 1.0],
            &[0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
        )
        .unwrap()
    }

    #[test]
    fn basis_partition_of_unity_and_derivatives_sum_to_zero() {
        let knots = [0.0, 0.0, 0.0, 0.0, 0.3, 0.5, 0.5, 1.0, 1.0, 1.0, 1.0];
        for &(k, u) in &[(3usize, 0.1), (4, 0.4), (6, 0.77), (6, 1.0)] {
            let d = basis_derivatives(k, u, 3, &knots);
            let s0: f64 = d[0][..4].iter().sum();
            let s1: f64 = d[1][..4].iter().sum();
            let s2: f64 = d[2][..4].iter().sum();
            assert!((s0 - 1.0).abs() < 1e-14 && s1.abs() < 1e-12 && s2.abs() < 1e-10);
        }
    }

    #[test]
    fn basis_derivatives_match_finite_differences() {
        let knots = [0.0, 0.0, 0.0, 0.0, 0.3, 0.5, 0.7, 1.0, 1.0, 1.0, 1.0];
        let (k, u, h) = (4usize, 0.4, 1e-5);
        let d = basis_derivatives(k, u, 3, &knots);
        let dp = basis_derivatives(k, u + h, 3, &knots);
        let dm = basis_derivatives(k, u - h, 3, &knots);
        for j in 0..4 {
            let fd1 = (dp[0][j] - dm[0][j]) / (2.0 * h);
            let fd2 = (dp[0][j] - 2.0 * d[0][j] + dm[0][j]) / (h * h);
            assert!((fd1 - d[1][j]).abs() < 1e-7, "N'{j}: {fd1} vs {}", d[1][j]);
            assert!((fd2 - d[2][j]).abs() < 1e-3, "N''{j}: {fd2} vs {}", d[2][j]);
        }
    }

    #[test]
    fn rational_quarter_circle_lies_on_the_unit_circle() {
        let c = quarter_circle();
        for i in 0..=20 {
            let u = i as f64 / 20.0;
            let e = c.eval(0, u);
            assert!((norm(e.c) - 1.0).abs() < 1e-15, "u={u}");
            let (t, kappa) = c.tangent_and_curvature(0, u, &e).unwrap();
            assert!(dot(t, e.c).abs() < 1e-14);
            // Counter-clockwise walk: free side inside, concave: kappa = -1.
            assert!((kappa + 1.0).abs() < 1e-13, "kappa {kappa}");
        }
    }

    #[test]
    fn nurbs_quarter_circle_matches_analytical_arc() {
        let c = quarter_circle();
        let arc = Arc::new([0.0, 0.0], 1.0, 0.0, FRAC_PI_2).unwrap();
        let mut worst: f64 = 0.0;
        for i in 0..40 {
            let theta = 0.01 + (FRAC_PI_2 - 0.02) * i as f64 / 39.0;
            for &r in &[0.3, 0.8, 0.999, 1.0, 1.05, 1.7] {
                let x = [r * theta.cos(), r * theta.sin()];
                let a = arc.project(x).unwrap();
                let b = c.project(0, x).unwrap();
                worst = worst
                    .max((a.gap - b.gap).abs())
                    .max(norm(sub(a.normal, b.normal)))
                    .max((a.normal_rate - b.normal_rate).abs() * (1.0 + a.gap * 0.0));
                assert_eq!(b.foot, Foot::Interior);
            }
        }
        assert!(worst < 1e-12, "worst difference {worst:e}");
    }

    #[test]
    fn nurbs_free_ends_and_c0_kink() {
        let c = quarter_circle();
        // Beyond the start (1, 0), inside the circle: rounded end.
        let p = c.project(0, [0.7, -0.4]).unwrap();
        assert_eq!(p.foot, Foot::End);
        assert!((p.gap - 0.25f64.sqrt()).abs() < 1e-14);
        let b = c.project(0, [1.3, -0.4]).unwrap();
        assert!((b.gap - 0.5).abs() < 1e-14 && b.foot == Foot::End);
        // Linear B-spline = polyline with a convex kink at (1, 0).
        let k = Nurbs::new(
            1,
            &[[0.0, 0.0], [1.0, 0.0], [1.0, -1.0]],
            &[1.0; 3],
            &[0.0, 0.0, 0.5, 1.0, 1.0],
        )
        .unwrap();
        assert_eq!(k.span_count(), 2);
        let q = k.project(0, [2.0, 1.0]).unwrap();
        assert_eq!(q.foot, Foot::Corner);
        assert!((q.gap - 2f64.sqrt()).abs() < 1e-14);
        let r = k.project(1, [0.9, -0.5]).unwrap();
        assert!((r.gap + 0.1).abs() < 1e-14 && (r.normal[0] - 1.0).abs() < 1e-14);
    }

    #[test]
    fn nurbs_projection_is_the_global_minimum_among_several() {
        // One cubic span shaped like a U (and a rational S): many nodes have
        // two or three local minima of the distance on the span.
        let curves = [
            Nurbs::new(
                3,
                &[[0.0, 1.0], [0.0, -1.0], [1.0, -1.0], [1.0, 1.0]],
                &[1.0; 4],
                &[0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0],
            )
            .unwrap(),
            Nurbs::new(
                3,
                &[[0.0, 0.0], [2.0, 1.5], [-1.0, 1.5], [1.0, 3.0]],
                &[1.0, 3.0, 0.5, 1.0],
                &[0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0],
            )
            .unwrap(),
        ];
        let mut worst: f64 = 0.0;
        for c in &curves {
            let dense: Vec<[f64; 2]> = (0..=20000)
                .map(|i| c.point(0, i as f64 / 20000.0))
                .collect();
            for i in 0..15 {
                for j in 0..15 {
                    let x = [-0.5 + 2.0 * i as f64 / 14.0, -1.5 + 4.0 * j as f64 / 14.0];
                    let d_dense = dense
                        .iter()
                        .map(|p| norm(sub(*p, x)))
                        .fold(f64::INFINITY, f64::min);
                    let u = c.closest_parameter(0, x);
                    let d = norm(sub(c.point(0, u), x));
                    // Dense sampling can only overestimate the minimum.
                    assert!(d <= d_dense + 1e-12, "x={x:?}: {d} > dense {d_dense}");
                    worst = worst.max(d - d_dense);
                }
            }
        }
        assert!(
            worst < 1e-6,
            "dense sampling much closer than expected: {worst}"
        );
    }

    #[test]
    fn nurbs_input_errors() {
        let p = [[0.0, 0.0], [1.0, 1.0], [2.0, 0.0]];
        assert!(Nurbs::new(0, &p, &[1.0; 3], &[0.0, 0.0, 1.0, 1.0]).is_err());
        assert!(Nurbs::new(2, &p, &[1.0; 2], &[0.0, 0.0, 0.0, 1.0, 1.0, 1.0]).is_err());
        assert!(Nurbs::new(2, &p, &[1.0, -1.0, 1.0], &[0.0, 0.0, 0.0, 1.0, 1.0, 1.0]).is_err());
        assert!(Nurbs::new(2, &p, &[1.0; 3], &[0.0, 0.0, 0.0, 1.0, 1.0]).is_err());
        assert!(Nurbs::new(2, &p, &[1.0; 3], &[0.0, 0.0, 1.0, 0.5, 1.0, 1.0]).is_err());
        assert!(Nurbs::new(2, &p, &[1.0; 3], &[1.0, 1.0, 1.0, 1.0, 1.0, 1.0]).is_err());
    }
}
