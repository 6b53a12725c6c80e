//! Polyline: connected straight segments, one entity per segment.
//!
//! Free side on the left of the walk. Closed when the first and last points
//! coincide (then the seam is an ordinary corner). A segment projects a node
//! on its interior when the foot parameter `xi` lies in `[0, 1]`; otherwise
//! its closest point is an end vertex, which is either a corner shared with
//! the neighbouring segment (radius-0 circle rule, see
//! [`super::corner`]) or a free end of the polyline (rounded on the free
//! side, nothing behind it).
//!
//! Choice at kinks (documented behaviour): the tool gap is the signed
//! distance to the closest point of the whole polyline (smallest `|gap|`).
//! - concave corner seen from the free side (a valley): a free node whose
//!   feet fall inside both segments takes the nearer one (smallest positive
//!   gap) — the larger gap would let the node go through the nearer segment
//!   unnoticed; a node penetrating behind both segments near the corner
//!   lies in the corner's fan and is pushed back towards the corner;
//! - convex corner (a punch edge): a free node in the fan between the two
//!   normals projects on the vertex (normal from vertex to node, gap =
//!   distance); a penetrating node behind both segments takes the segment
//!   it penetrates least (largest, i.e. closest-to-zero, negative gap).

use super::corner::{corner, end_cap};
use super::{finite, Foot, Projection};
use crate::contact::vec2::{add, cross, dot, left, norm, scale, sub};
use crate::geom::Aabb;

/// A polyline prepared for projection.
#[derive(Debug, Clone, PartialEq)]
pub struct Polyline {
    /// Distinct vertices in walking order (a closed polyline does not repeat
    /// its first point).
    pub points: Vec<[f64; 2]>,
    /// Whether the last vertex connects back to the first.
    pub closed: bool,
    /// Unit tangent of each segment.
    pub tangents: Vec<[f64; 2]>,
    /// Unit normal of each segment (tangent rotated by +90 degrees).
    pub normals: Vec<[f64; 2]>,
    /// Length of each segment.
    pub lengths: Vec<f64>,
}

impl Polyline {
    /// Builds the polyline from its vertices (at least 2 distinct points).
    pub fn new(points: &[[f64; 2]]) -> Result<Self, String> {
        if points.len() < 2 {
            return Err(format!(
                "polyline tool: needs at least 2 points (got {})",
                points.len()
            ));
        }
        if let Some(i) = points.iter().position(|p| !finite(*p)) {
            return Err(format!("polyline tool: point {} is not finite", i + 1));
        }
        let extent = {
            let b = Aabb::around(points);
            (b.max[0] - b.min[0]).max(b.max[1] - b.min[1])
        };
        let mut pts = points.to_vec();
        let closed =
            points.len() > 3 && norm(sub(points[0], points[points.len() - 1])) <= 1e-12 * extent;
        if closed {
            pts.pop();
        }
        let count = if closed { pts.len() } else { pts.len() - 1 };
        let mut tangents = Vec::with_capacity(count);
        let mut lengths = Vec::with_capacity(count);
        for i in 0..count {
            let d = sub(pts[(i + 1) % pts.len()], pts[i]);
            let l = norm(d);
            if l <= 1e-12 * extent {
                return Err(format!(
                    "polyline tool: points {} and {} coincide; remove the duplicate",
                    i + 1,
                    (i + 1) % pts.len() + 1
                ));
            }
            tangents.push(scale(1.0 / l, d));
            lengths.push(l);
        }
        let turns = if closed { count } else { count - 1 };
        for i in 0..turns {
            let (a, b) = (tangents[i], tangents[(i + 1) % count]);
            if dot(a, b) < 0.0 && cross(a, b).abs() <= 1e-9 {
                return Err(format!(
                    "polyline tool: the walk turns back by 180 degrees at point {}; \
                     a zero-thickness spike has no free side",
                    (i + 1) % pts.len() + 1
                ));
            }
        }
        let normals = tangents.iter().map(|t| left(*t)).collect();
        Ok(Polyline {
            points: pts,
            closed,
            tangents,
            normals,
            lengths,
        })
    }

    /// Number of segments.
    pub fn segment_count(&self) -> usize {
        self.lengths.len()
    }

    /// Whether the polyline is closed.
    pub fn is_closed(&self) -> bool {
        self.closed
    }

    /// End points of segment `i`.
    fn ends(&self, i: usize) -> ([f64; 2], [f64; 2]) {
        (self.points[i], self.points[(i + 1) % self.points.len()])
    }

    /// Bounding box of segment `i`.
    pub fn bounding_box(&self, i: usize) -> Aabb<2> {
        let (a, b) = self.ends(i);
        Aabb::around(&[a, b])
    }

    /// Closest point of segment `i` to `x`.
    pub fn project(&self, i: usize, x: [f64; 2]) -> Option<Projection> {
        let (a, b) = self.ends(i);
        let (t, n, l) = (self.tangents[i], self.normals[i], self.lengths[i]);
        let count = self.segment_count();
        let d = sub(x, a);
        let xi = dot(d, t) / l;
        if xi < 0.0 {
            return if i > 0 || self.closed {
                let prev = if i > 0 { i - 1 } else { count - 1 };
                Some(corner(x, a, self.normals[prev], n, i as f64))
            } else {
                Some(end_cap(x, a, n, 0.0))
            };
        }
        if xi > 1.0 {
            return if i + 1 < count || self.closed {
                let next = (i + 1) % count;
                Some(corner(x, b, n, self.normals[next], (i + 1) as f64))
            } else {
                Some(end_cap(x, b, n, count as f64))
            };
        }
        Some(Projection {
            point: add(a, scale(xi * l, t)),
            gap: dot(d, n),
            normal: n,
            normal_rate: 0.0,
            foot: Foot::Interior,
            param: i as f64 + xi,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn best(p: &Polyline, x: [f64; 2]) -> Option<(usize, Projection)> {
        (0..p.segment_count())
            .filter_map(|i| p.project(i, x).map(|q| (i, q)))
            .min_by(|a, b| a.1.gap.abs().total_cmp(&b.1.gap.abs()))
    }

    #[test]
    fn segment_interior_and_ends() {
        let p = Polyline::new(&[[0.0, 0.0], [2.0, 0.0], [2.0, -2.0]]).unwrap();
        // Convex corner at (2, 0) (the walk turns right): free node in the
        // fan projects on the vertex.
        let (e, q) = best(&p, [3.0, 1.0]).unwrap();
        assert_eq!(q.foot, Foot::Corner);
        assert!((q.gap - 2f64.sqrt()).abs() < 1e-15);
        assert!(e == 0, "tie broken by the lowest index: got {e}");
        // Penetrating near the convex corner: the closest segment wins.
        let (e, q) = best(&p, [1.8, -0.1]).unwrap();
        assert_eq!((e, q.foot), (0, Foot::Interior));
        assert!((q.gap + 0.1).abs() < 1e-15);
        let (e, q) = best(&p, [1.9, -0.5]).unwrap();
        assert_eq!(e, 1);
        assert!((q.gap + 0.1).abs() < 1e-15);
        assert_eq!(q.normal, [1.0, 0.0]);
        // Behind the free start (material side, before the first point):
        // past the tool, positive distance to the end.
        let q = p.project(0, [-0.3, -0.4]).unwrap();
        assert_eq!(q.foot, Foot::End);
        assert!((q.gap - 0.5).abs() < 1e-15);
        // In front of the free start: rounded end.
        let q = p.project(0, [-3.0, 4.0]).unwrap();
        assert_eq!((q.gap, q.foot), (5.0, Foot::End));
    }

    #[test]
    fn node_exactly_on_vertex_and_segment_end() {
        let p = Polyline::new(&[[0.0, 0.0], [1.0, 0.0], [2.0, 1.0]]).unwrap();
        let (e, q) = best(&p, [1.0, 0.0]).unwrap();
        assert_eq!((e, q.gap, q.foot), (0, 0.0, Foot::Interior));
        assert_eq!(q.normal, [0.0, 1.0]);
        let q = p.project(1, [1.0, 0.0]).unwrap();
        assert_eq!(q.gap, 0.0);
        assert!((q.normal[0] + 0.5f64.sqrt()).abs() < 1e-15);
        assert!((q.normal[1] - 0.5f64.sqrt()).abs() < 1e-15);
    }

    #[test]
    fn concave_valley_picks_nearer_segment_and_fan_behind() {
        // Walk (-1,0) -> (0,0) -> (0,1): left turn, free side = upper-left.
        let p = Polyline::new(&[[-1.0, 0.0], [0.0, 0.0], [0.0, 1.0]]).unwrap();
        let (e, q) = best(&p, [-0.3, 0.1]).unwrap();
        assert_eq!(e, 0);
        assert!((q.gap - 0.1).abs() < 1e-15);
        let (e, q) = best(&p, [-0.1, 0.3]).unwrap();
        assert_eq!(e, 1);
        assert!((q.gap - 0.1).abs() < 1e-15);
        // Lower-right quadrant: inside the tool, closest free point = corner.
        let (_, q) = best(&p, [0.3, -0.4]).unwrap();
        assert_eq!(q.foot, Foot::Corner);
        assert!((q.gap + 0.5).abs() < 1e-15);
        assert!((q.normal[0] + 0.6).abs() < 1e-15 && (q.normal[1] - 0.8).abs() < 1e-15);
    }

    #[test]
    fn closed_polyline_and_errors() {
        let sq = [[0.0, 0.0], [0.0, 1.0], [1.0, 1.0], [1.0, 0.0], [0.0, 0.0]];
        // Clockwise square: free side outside.
        let p = Polyline::new(&sq).unwrap();
        assert!(p.is_closed());
        assert_eq!(p.segment_count(), 4);
        let (_, q) = best(&p, [-0.5, -0.5]).unwrap();
        assert_eq!(q.foot, Foot::Corner);
        assert!((q.gap - 0.5f64.sqrt()).abs() < 1e-15);
        let (_, q) = best(&p, [0.5, 0.4]).unwrap();
        assert!((q.gap + 0.4).abs() < 1e-15);
        assert!(Polyline::new(&[[0.0, 0.0]]).is_err());
        assert!(Polyline::new(&[[0.0, 0.0], [0.0, 0.0], [1.0, 0.0]]).is_err());
        assert!(Polyline::new(&[[0.0, 0.0], [1.0, 0.0], [0.5, 0.0]]).is_err());
    }
}
