//! First impact: where, within an increment, a node meets its master.
//!
//! Over one increment the node (and the master) are assumed to move at
//! constant velocity from their converged positions to the current ones.
//! The fraction `tau` of the increment at which the node reaches the master
//! surface gives
//! - the stick point of a node that touches for the first time (friction
//!   acts only on the motion after the impact, see
//!   [`crate::model::FirstImpact::Intersect`]);
//! - the time at which to cut the increment when the deck asks for it
//!   (`cut_at_impact = true`).
//!
//! Against a rigid tool the motion is taken in the tool's reference frame
//! (the relative motion) and the gap along the straight path is bisected.
//! Against a deformable segment `m1 m2` (node-to-segment) the three points
//! move linearly and the node is on the segment's line when
//! `(m2 - m1) x (s - m1) = 0`, a quadratic in `tau`; the root with the
//! projection parameter in `[0, 1]` is the impact.

use super::geometry::ToolShape;
use super::search;

/// Bisection steps of the rigid-tool intersection (`2^-40` of the path).
const BISECTIONS: usize = 40;

/// Where a node met a rigid tool along its path.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Impact {
    /// Fraction `tau` of the increment.
    pub fraction: f64,
    /// The point reached, tool reference frame.
    pub point: [f64; 2],
    /// Gap at the start of the path (`<= 0`: it already penetrated).
    pub start_gap: f64,
}

/// Fraction `tau` in `[0, 1]` of the straight path `x0 -> x1` (tool
/// reference frame) at which the gap to `shape` vanishes, with the point
/// reached. `tau = 0` when `x0` already penetrates; `None` when `x1` does
/// not penetrate. `window` bounds the search (any positive length larger
/// than the path and the gaps involved).
pub fn tool_intersection(
    shape: &ToolShape,
    x0: [f64; 2],
    x1: [f64; 2],
    window: f64,
) -> Option<Impact> {
    let mut tests = 0;
    let gap = |x: [f64; 2], tests: &mut usize| {
        search::closest(shape, x, window, None, None, tests).map(|f| f.projection.gap)
    };
    let at = |tau: f64| [x0[0] + tau * (x1[0] - x0[0]), x0[1] + tau * (x1[1] - x0[1])];
    if gap(x1, &mut tests)? >= 0.0 {
        return None;
    }
    let start_gap = match gap(x0, &mut tests) {
        Some(g) if g > 0.0 => g,
        g => {
            return Some(Impact {
                fraction: 0.0,
                point: x0,
                start_gap: g.unwrap_or(0.0),
            })
        }
    };
    let (mut lo, mut hi) = (0.0, 1.0);
    for _ in 0..BISECTIONS {
        let mid = 0.5 * (lo + hi);
        match gap(at(mid), &mut tests) {
            Some(g) if g > 0.0 => lo = mid,
            _ => hi = mid,
        }
    }
    let tau = 0.5 * (lo + hi);
    Some(Impact {
        fraction: tau,
        point: at(tau),
        start_gap,
    })
}

/// Constant-velocity intersection of a slave node with a deformable
/// segment: the node goes `s0 -> s1`, the segment ends `a0 -> a1` and
/// `b0 -> b1` over the increment. Returns the smallest `tau` in `[0, 1]` at
/// which the node lies on the segment (projection parameter in `[0, 1]`),
/// with that parameter: `(tau, xi)`.
pub fn segment_intersection(
    s: [[f64; 2]; 2],
    a: [[f64; 2]; 2],
    b: [[f64; 2]; 2],
) -> Option<(f64, f64)> {
    let lerp = |p: [[f64; 2]; 2], tau: f64| {
        [
            p[0][0] + tau * (p[1][0] - p[0][0]),
            p[0][1] + tau * (p[1][1] - p[0][1]),
        ]
    };
    // f(tau) = (b - a) x (s - a), each factor linear in tau: c0 + c1 tau + c2 tau^2
    let d = |p: [[f64; 2]; 2], q: [[f64; 2]; 2]| {
        (
            [p[0][0] - q[0][0], p[0][1] - q[0][1]],
            [
                (p[1][0] - q[1][0]) - (p[0][0] - q[0][0]),
                (p[1][1] - q[1][1]) - (p[0][1] - q[0][1]),
            ],
        )
    };
    let (e0, e1) = d(b, a);
    let (r0, r1) = d(s, a);
    let cross = |u: [f64; 2], v: [f64; 2]| u[0] * v[1] - u[1] * v[0];
    let c0 = cross(e0, r0);
    let c1 = cross(e0, r1) + cross(e1, r0);
    let c2 = cross(e1, r1);
    let scale = c0.abs().max(c1.abs()).max(c2.abs());
    if scale == 0.0 {
        return None;
    }
    let mut roots = [f64::NAN; 2];
    if c2.abs() <= 1e-12 * scale {
        if c1.abs() > 1e-14 * scale {
            roots[0] = -c0 / c1;
        }
    } else {
        let disc = c1 * c1 - 4.0 * c2 * c0;
        if disc < 0.0 {
            return None;
        }
        // numerically stable pair of roots
        let q = -0.5 * (c1 + c1.signum() * disc.sqrt());
        roots[0] = q / c2;
        if q != 0.0 {
            roots[1] = c0 / q;
        }
    }
    roots.sort_by(|x, y| x.partial_cmp(y).unwrap_or(std::cmp::Ordering::Greater));
    roots
        .into_iter()
        .filter(|t| t.is_finite() && (-1e-12..=1.0 + 1e-12).contains(t))
        .find_map(|tau| {
            let tau = tau.clamp(0.0, 1.0);
            let (pa, pb, ps) = (lerp(a, tau), lerp(b, tau), lerp(s, tau));
            let e = [pb[0] - pa[0], pb[1] - pa[1]];
            let l2 = e[0] * e[0] + e[1] * e[1];
            if l2 == 0.0 {
                return None;
            }
            let xi = ((ps[0] - pa[0]) * e[0] + (ps[1] - pa[1]) * e[1]) / l2;
            (-1e-12..=1.0 + 1e-12)
                .contains(&xi)
                .then_some((tau, xi.clamp(0.0, 1.0)))
        })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::ToolGeometry;

    #[test]
    fn node_falling_on_a_plane_meets_it_at_the_gap_ratio() {
        let plane = ToolShape::new(&ToolGeometry::Plane {
            point: [0.0, 0.0],
            normal: [0.0, 1.0],
        })
        .unwrap();
        // from y = 0.3 to y = -0.1 while moving right: meets at tau = 0.75
        let hit = tool_intersection(&plane, [0.0, 0.3], [1.0, -0.1], 10.0).unwrap();
        let (tau, x) = (hit.fraction, hit.point);
        assert!((tau - 0.75).abs() < 1e-11, "{tau}");
        assert!((x[0] - 0.75).abs() < 1e-11 && x[1].abs() < 1e-11);
        assert!((hit.start_gap - 0.3).abs() < 1e-15);
        assert!(tool_intersection(&plane, [0.0, 0.3], [1.0, 0.1], 10.0).is_none());
        assert_eq!(
            tool_intersection(&plane, [0.0, -0.1], [1.0, -0.2], 10.0),
            Some(Impact {
                fraction: 0.0,
                point: [0.0, -0.1],
                start_gap: -0.1
            })
        );
    }

    #[test]
    fn node_meets_a_moving_segment() {
        // segment rises from y = -1 to y = 1 (x in [0, 2]); node fixed at (0.5, 0)
        let s = [[0.5, 0.0], [0.5, 0.0]];
        let a = [[0.0, -1.0], [0.0, 1.0]];
        let b = [[2.0, -1.0], [2.0, 1.0]];
        let (tau, xi) = segment_intersection(s, a, b).unwrap();
        assert!((tau - 0.5).abs() < 1e-14 && (xi - 0.25).abs() < 1e-14);
        // rotating segment about a: b from (1, -1) to (1, 1), node at (1, 0)
        // meets it half way (both linear: b(tau) = (1, -1 + 2 tau))
        let (tau, xi) = segment_intersection(
            [[1.0, 0.0], [1.0, 0.0]],
            [[0.0, 0.0], [0.0, 0.0]],
            [[1.0, -1.0], [1.0, 1.0]],
        )
        .unwrap();
        assert!((tau - 0.5).abs() < 1e-14 && (xi - 1.0).abs() < 1e-14);
        // a node passing beside the segment does not meet it
        assert!(segment_intersection(
            [[3.0, 1.0], [3.0, -1.0]],
            [[0.0, 0.0], [0.0, 0.0]],
            [[1.0, 0.0], [1.0, 0.0]]
        )
        .is_none());
    }
}
