//! Non-smooth points of a tool: corners between two entities and free ends.
//!
//! A corner is treated as a circle of radius 0. If the closest point of the
//! tool to a node is a corner `p`, the node lies in the corner's normal fan
//! (between the two one-sided normals on the convex side, between their
//! opposites on the concave side). The gap is `±|x - p|` and the normal is
//! `±(x - p)/|x - p|`, the sign being that of `(x - p) . (n_before +
//! n_after)`: positive in the fan of a convex corner (free side), negative in
//! the fan of a concave corner (the node is inside the tool and the closest
//! free point is the corner). This makes the normal field continuous around
//! convex corners and leaves no region where a penetrating node has no
//! projection. The normal rate is `1 / gap` (so the penalty force of a
//! penetrating node is the linear spring `-alpha (x - p)`, tangent `alpha I`).

use super::{Foot, Projection};
use crate::contact::vec2::{add, dot, norm, sub, unit};

/// Candidate of a corner `p` shared by an entity with normal `n_before` at
/// its end and one with normal `n_after` at its start.
pub fn corner(
    x: [f64; 2],
    p: [f64; 2],
    n_before: [f64; 2],
    n_after: [f64; 2],
    param: f64,
) -> Projection {
    let d = sub(x, p);
    let dist = norm(d);
    let bisector = unit(add(n_before, n_after)).unwrap_or(n_before);
    if dist == 0.0 {
        return Projection {
            point: p,
            gap: 0.0,
            normal: bisector,
            normal_rate: 0.0,
            foot: Foot::Corner,
            param,
        };
    }
    let s = if dot(d, bisector) >= 0.0 { 1.0 } else { -1.0 };
    Projection {
        point: p,
        gap: s * dist,
        normal: [s * d[0] / dist, s * d[1] / dist],
        normal_rate: s / dist,
        foot: Foot::Corner,
        param,
    }
}

/// Candidate of a free end `p` of an open curve: a rounded end, gap =
/// distance to the end, normal from the end to the node. On the free side
/// this is the radius-0 circle continuation of the curve; behind the end (on
/// the material side of the end's normal `n_end`) the node is past the
/// tool's extent, so it is not inside the tool: the gap is the (positive)
/// distance too, and no force acts. A node penetrating near the end and
/// sliding past it is therefore released, as it physically falls off the
/// tool's edge.
pub fn end_cap(x: [f64; 2], p: [f64; 2], n_end: [f64; 2], param: f64) -> Projection {
    let d = sub(x, p);
    let dist = norm(d);
    if dist == 0.0 {
        return Projection {
            point: p,
            gap: 0.0,
            normal: n_end,
            normal_rate: 0.0,
            foot: Foot::End,
            param,
        };
    }
    Projection {
        point: p,
        gap: dist,
        normal: [d[0] / dist, d[1] / dist],
        normal_rate: 1.0 / dist,
        foot: Foot::End,
        param,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn convex_corner_fan_gives_positive_distance() {
        // Corner at the origin between normals (0,1) and (1,0): node in the
        // positive quadrant, gap = distance, normal from corner to node.
        let p = corner([3.0, 4.0], [0.0, 0.0], [0.0, 1.0], [1.0, 0.0], 1.0);
        assert_eq!(p.gap, 5.0);
        assert_eq!(p.normal, [0.6, 0.8]);
        assert_eq!(p.normal_rate, 0.2);
        assert_eq!(p.foot, Foot::Corner);
    }

    #[test]
    fn concave_corner_fan_gives_penetration_towards_corner() {
        // Normals (0,1) and (-1,0): free side is the upper-left quadrant, the
        // fan of the corner is the lower-right quadrant (inside the tool).
        let p = corner([3.0, -4.0], [0.0, 0.0], [0.0, 1.0], [-1.0, 0.0], 1.0);
        assert_eq!(p.gap, -5.0);
        assert_eq!(p.normal, [-0.6, 0.8]);
        assert_eq!(p.normal_rate, -0.2);
    }

    #[test]
    fn end_cap_free_side_and_behind() {
        let p = end_cap([4.0, 3.0], [1.0, -1.0], [0.0, 1.0], 0.0);
        assert_eq!(p.gap, 5.0);
        assert_eq!(p.normal, [0.6, 0.8]);
        // Behind the end: past the tool, positive distance, no contact.
        let b = end_cap([4.0, -5.0], [1.0, -1.0], [0.0, 1.0], 0.0);
        assert_eq!((b.gap, b.normal), (5.0, [0.6, -0.8]));
        let on = end_cap([1.0, -1.0], [1.0, -1.0], [0.0, 1.0], 0.0);
        assert_eq!((on.gap, on.normal), (0.0, [0.0, 1.0]));
    }
}
