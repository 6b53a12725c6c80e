//! The parity (ray-crossing) test: is a point of the parameter plane inside
//! a face bounded by loops of trimming curves?
//!
//! A segment is drawn from the tested point `p` to a point `q` known to be
//! outside (beyond the box of every loop); its crossings with all boundary
//! curves (outer loop and holes alike) are counted: odd = inside, even =
//! outside. The first ray goes in the `-u` direction (horizontal, to the
//! left); when a crossing is **degenerate** — the ray is tangent to a curve,
//! passes through a curve's end (a vertex of a loop) or runs along a line —
//! the count is thrown away and the test restarts with another outer point
//! (the direction turned by the golden angle). A crossing at `p` itself means
//! `p` is on the boundary ([`Containment::Boundary`]: a face is a closed set,
//! so boundary points are inside).
//!
//! Crossings per curve:
//! - line: the sign change of the signed distance to the ray's line;
//! - arc: the two solutions of `cos(theta - phi) = k`, kept when in the sweep;
//! - NURBS: the signed distance `h(t) = nu . (C(t) - p)` has the sign of the
//!   B-spline with coefficients `w_i nu . (P_i - p)`; a span whose
//!   coefficients share a strict sign has no crossing (convex hull);
//!   otherwise sign changes between samples are refined by bisection, and a
//!   sampled local minimum of `|h|` that nearly touches the ray is refined
//!   by golden-section search to detect tangency. Pairs of crossings missed
//!   inside one sample interval leave the parity unchanged. A crossing (or
//!   tangency) near `p` is exact across the ray only, so before it is
//!   counted the foot point of `p` on the curve is refined by Newton's
//!   method and the true distance decides whether `p` is on the boundary.

use super::curve::TrimCurve;
use crate::Vec2;

/// Where a point lies with respect to a face's boundary.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Containment {
    /// Strictly inside (odd number of crossings).
    Inside,
    /// Outside (even number of crossings).
    Outside,
    /// On a boundary curve (within the tolerance).
    Boundary,
}

impl Containment {
    /// Inside or on the boundary.
    pub fn is_in(self) -> bool {
        self != Containment::Outside
    }
}

/// Tolerances of the parity test, in parameter-plane units.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ParityTolerance {
    /// A crossing closer than this to `p` puts `p` on the boundary.
    pub boundary: f64,
    /// A crossing closer than this (along the curve's image) to a curve end
    /// is a crossing through a vertex: degenerate.
    pub vertex: f64,
    /// A crossing at which the sine of the angle between the ray and the
    /// curve is below this is tangent: degenerate.
    pub tangent: f64,
}

impl ParityTolerance {
    /// Tolerances relative to the size `size` of the parameter region.
    pub fn relative(size: f64) -> Self {
        ParityTolerance {
            boundary: 1e-12 * size,
            vertex: 1e-9 * size,
            tangent: 1e-7,
        }
    }
}

/// The outcome of one ray.
enum Ray {
    /// Number of crossings.
    Count(usize),
    /// `p` is on a curve.
    OnBoundary,
    /// Tangent, through a vertex or along a line: restart.
    Degenerate,
}

/// The ray used by attempt `k` (unit direction): the first goes to `-u`.
pub fn ray_direction(k: usize) -> Vec2 {
    let golden = std::f64::consts::PI * (3.0 - 5f64.sqrt());
    let a = std::f64::consts::PI + golden * k as f64;
    Vec2::new(a.cos(), a.sin())
}

/// Classifies `p` against all `curves` (every loop's curves together);
/// `reach` is a length such that `p + reach * e` is outside every loop for
/// any unit `e` (e.g. the distance from `p` to the farthest corner of the
/// loops' box, plus a margin). Returns the containment and the number of
/// rays drawn.
pub fn classify<'a>(
    curves: impl Iterator<Item = &'a TrimCurve> + Clone,
    p: Vec2,
    reach: f64,
    tol: &ParityTolerance,
) -> (Containment, usize) {
    const ATTEMPTS: usize = 64;
    for k in 0..ATTEMPTS {
        let e = ray_direction(k);
        let mut count = 0;
        let mut degenerate = false;
        for c in curves.clone() {
            match crossings(c, p, e, reach, tol) {
                Ray::Count(n) => count += n,
                Ray::OnBoundary => return (Containment::Boundary, k + 1),
                Ray::Degenerate => {
                    degenerate = true;
                    break;
                }
            }
        }
        if !degenerate {
            let c = if count % 2 == 1 {
                Containment::Inside
            } else {
                Containment::Outside
            };
            return (c, k + 1);
        }
    }
    // 64 degenerate rays in a row only happen on the boundary within the
    // vertex tolerance.
    (Containment::Boundary, ATTEMPTS)
}

/// Crossings of the segment `p -> p + reach e` with one curve.
fn crossings(c: &TrimCurve, p: Vec2, e: Vec2, reach: f64, tol: &ParityTolerance) -> Ray {
    let nu = Vec2::new(-e.y, e.x);
    let h = |q: Vec2| nu.dot(&(q - p));
    let s = |q: Vec2| e.dot(&(q - p));
    // A crossing of the ray's line at the curve point `q` (curve ends
    // `ends`, sine of the crossing angle `sine`): `None` when outside the ray.
    let verdict = |q: Vec2, ends: [Vec2; 2], sine: f64| -> Option<Ray> {
        let along = s(q);
        if (q - p).norm() <= tol.boundary {
            return Some(Ray::OnBoundary);
        }
        if along < -tol.boundary || along > reach {
            return None; // Behind p, or past q (cannot happen for a true outer point).
        }
        if along <= tol.boundary {
            return Some(Ray::OnBoundary);
        }
        if (q - ends[0]).norm() <= tol.vertex
            || (q - ends[1]).norm() <= tol.vertex
            || sine <= tol.tangent
        {
            return Some(Ray::Degenerate);
        }
        Some(Ray::Count(1))
    };
    match c {
        TrimCurve::Line { a, b } => {
            let (ha, hb) = (h(*a), h(*b));
            let len = (b - a).norm();
            let t = if len > 0.0 {
                ((p - a).dot(&(b - a)) / (len * len)).clamp(0.0, 1.0)
            } else {
                0.0
            };
            if (a + (b - a) * t - p).norm() <= tol.boundary {
                return Ray::OnBoundary;
            }
            if ha.abs() <= tol.vertex && hb.abs() <= tol.vertex {
                // Along the ray's line: degenerate if it overlaps the ray.
                return if s(*a).max(s(*b)) >= 0.0 {
                    Ray::Degenerate
                } else {
                    Ray::Count(0)
                };
            }
            if (ha > tol.vertex && hb > tol.vertex) || (ha < -tol.vertex && hb < -tol.vertex) {
                return Ray::Count(0);
            }
            if ha.abs() <= tol.vertex || hb.abs() <= tol.vertex {
                // An end on the ray's line: through a vertex when in front of p.
                let q = if ha.abs() <= hb.abs() { *a } else { *b };
                return if s(q) >= 0.0 {
                    Ray::Degenerate
                } else {
                    Ray::Count(0)
                };
            }
            let q = a + (b - a) * (ha / (ha - hb));
            let sine = ((b - a) / len).dot(&nu).abs();
            verdict(q, [*a, *b], sine).unwrap_or(Ray::Count(0))
        }
        TrimCurve::Arc {
            center,
            radius,
            start,
            sweep,
        } => {
            let ends = [c.start(), c.end()];
            let dc = (center - p).norm();
            if (dc - radius).abs() <= tol.boundary {
                // p on the full circle: on the arc if within the sweep.
                let theta = (p.y - center.y).atan2(p.x - center.x);
                let t = TrimCurve::arc_parameter(*start, *sweep, theta);
                if t <= 1.0
                    || (ends[0] - p).norm() <= tol.boundary
                    || (ends[1] - p).norm() <= tol.boundary
                {
                    return Ray::OnBoundary;
                }
            }
            let k = -nu.dot(&(center - p)) / radius;
            if k.abs() > 1.0 + tol.vertex / radius {
                return Ray::Count(0);
            }
            let phi = nu.y.atan2(nu.x);
            let delta = k.clamp(-1.0, 1.0).acos();
            let mut n = 0;
            for theta in [phi + delta, phi - delta] {
                let t = TrimCurve::arc_parameter(*start, *sweep, theta);
                let q = center + Vec2::new(theta.cos(), theta.sin()) * *radius;
                let in_sweep = t <= 1.0;
                let near_end =
                    (q - ends[0]).norm() <= tol.vertex || (q - ends[1]).norm() <= tol.vertex;
                if !in_sweep && !near_end {
                    continue;
                }
                // sine of the angle between the ray and the arc tangent.
                let tangent = Vec2::new(-theta.sin(), theta.cos());
                let sine = tangent.dot(&nu).abs();
                match verdict(q, ends, sine) {
                    Some(Ray::Count(m)) => n += m,
                    Some(other) => return other,
                    None => {}
                }
            }
            Ray::Count(n)
        }
        TrimCurve::Nurbs(curve) => {
            let ends = [c.start(), c.end()];
            // Convex hull rejection on the control polygon.
            let hs: Vec<f64> = curve.points.iter().map(|q| h(*q)).collect();
            let ss: Vec<f64> = curve.points.iter().map(|q| s(*q)).collect();
            let hmin = hs.iter().cloned().fold(f64::INFINITY, f64::min);
            let hmax = hs.iter().cloned().fold(f64::NEG_INFINITY, f64::max);
            let smax = ss.iter().cloned().fold(f64::NEG_INFINITY, f64::max);
            if hmin > tol.vertex || hmax < -tol.vertex || smax < -tol.boundary {
                return Ray::Count(0);
            }
            let ts = c.pieces();
            let vals: Vec<(f64, Vec2, f64)> = ts
                .iter()
                .map(|&t| {
                    let q = curve.eval(t).p;
                    (t, q, h(q))
                })
                .collect();
            let mut n = 0;
            for (i, w) in vals.windows(2).enumerate() {
                let ((ta, qa, ha), (tb, _, hb)) = (w[0], w[1]);
                if ha == 0.0 {
                    if let Some(r) = verdict(qa, ends, sine_at(curve, ta, nu)) {
                        match r {
                            Ray::Count(_) => return Ray::Degenerate,
                            other => return other,
                        }
                    }
                    continue;
                }
                if ha * hb < 0.0 {
                    let t = bisect(|t| h(curve.eval(t).p), ta, tb, ha);
                    let q = curve.eval(t).p;
                    if near_foot(curve, t, q, p, tol) {
                        return Ray::OnBoundary;
                    }
                    match verdict(q, ends, sine_at(curve, t, nu)) {
                        Some(Ray::Count(m)) => n += m,
                        Some(other) => return other,
                        None => {}
                    }
                } else if i > 0 {
                    // A sampled local minimum of |h| that does not cross: check tangency.
                    let hp = vals[i - 1].2;
                    if ha.abs() <= hp.abs() && ha.abs() <= hb.abs() && ha * hp > 0.0 {
                        let (t0, t1) = (vals[i - 1].0, tb);
                        let t = golden_min(|t| h(curve.eval(t).p).abs(), t0, t1);
                        let q = curve.eval(t).p;
                        let hq = h(q);
                        if hq.abs() <= tol.vertex && s(q) >= -tol.boundary {
                            if near_foot(curve, t, q, p, tol) {
                                return Ray::OnBoundary;
                            }
                            return Ray::Degenerate;
                        }
                    }
                }
            }
            // The last sample (curve end) exactly on the ray.
            let (tl, ql, hl) = *vals.last().unwrap();
            if hl == 0.0 {
                if let Some(r) = verdict(ql, ends, sine_at(curve, tl, nu)) {
                    return match r {
                        Ray::Count(_) => Ray::Degenerate,
                        other => other,
                    };
                }
            }
            // p on the curve between crossings (h small, s ~ 0): caught by verdict.
            Ray::Count(n)
        }
    }
}

/// Is `p` on the curve, given a ray crossing (or a tangency) at `q = C(t)`?
///
/// The crossing found by bisection is exact in `h` (the distance across the
/// ray), not along it: at a shallow crossing (sine `sin`) an error `eps` in
/// `h` moves `q` by `eps / sin` along the ray, so a point lying on the curve
/// can see its crossing farther than `tol.boundary` from it. When `q` is
/// close enough that `p` could be within `tol.boundary` of the curve at a
/// non-tangent crossing (`|q - p| <= tol.boundary / tol.tangent`), the
/// foot point of `p` is refined by Newton's method on `(C(t) - p) . C'(t) = 0`
/// from `t` (clamped to the domain) and the true distance decides.
fn near_foot(
    c: &crate::nurbs::NurbsCurve<2>,
    t: f64,
    q: Vec2,
    p: Vec2,
    tol: &ParityTolerance,
) -> bool {
    let dq = (q - p).norm();
    if dq <= tol.boundary {
        return true;
    }
    if dq > 10.0 * tol.boundary / tol.tangent {
        return false;
    }
    let [t0, t1] = c.domain();
    let mut t = t;
    let mut best = dq;
    for _ in 0..30 {
        let d = c.eval(t);
        let r = d.p - p;
        best = best.min(r.norm());
        if best <= tol.boundary {
            return true;
        }
        let f = r.dot(&d.d1);
        let df = d.d1.dot(&d.d1) + r.dot(&d.d2);
        if df <= 0.0 || !df.is_finite() {
            break;
        }
        let next = (t - f / df).clamp(t0, t1);
        if next == t {
            break;
        }
        t = next;
    }
    best <= tol.boundary
}

/// Sine of the angle between the curve's tangent at `t` and the ray.
fn sine_at(c: &crate::nurbs::NurbsCurve<2>, t: f64, nu: Vec2) -> f64 {
    let d = c.eval(t).d1;
    let n = d.norm();
    if n == 0.0 {
        0.0
    } else {
        (d.dot(&nu) / n).abs()
    }
}

/// Root of `f` in `[a, b]` with `f(a) = fa` of the opposite sign of `f(b)`.
fn bisect(f: impl Fn(f64) -> f64, mut a: f64, mut b: f64, mut fa: f64) -> f64 {
    for _ in 0..200 {
        let m = 0.5 * (a + b);
        if m <= a || m >= b {
            break;
        }
        let fm = f(m);
        if fm == 0.0 {
            return m;
        }
        if fm * fa < 0.0 {
            b = m;
        } else {
            a = m;
            fa = fm;
        }
    }
    0.5 * (a + b)
}

/// Minimiser of a unimodal `f` on `[a, b]` (golden-section search).
fn golden_min(f: impl Fn(f64) -> f64, mut a: f64, mut b: f64) -> f64 {
    let g = 0.5 * (5f64.sqrt() - 1.0);
    let mut c = b - g * (b - a);
    let mut d = a + g * (b - a);
    let (mut fc, mut fd) = (f(c), f(d));
    for _ in 0..100 {
        if (b - a).abs() <= 1e-15 * (a.abs() + b.abs() + 1.0) {
            break;
        }
        if fc < fd {
            b = d;
            d = c;
            fd = fc;
            c = b - g * (b - a);
            fc = f(c);
        } else {
            a = c;
            c = d;
            fc = fd;
            d = a + g * (b - a);
            fd = f(d);
        }
    }
    0.5 * (a + b)
}
