//! Full circle (a punch or roller with the body outside, a container with
//! the body inside).

use super::{finite, Projection};
use crate::contact::vec2::{add, norm, scale, sub};
use crate::geom::Aabb;
use crate::model::ToolSide;

/// A circle with the free side outside or inside.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Circle {
    /// Centre.
    pub center: [f64; 2],
    /// Radius > 0.
    pub radius: f64,
    /// +1 when the body is outside (gap = |x-c| - R), -1 when inside
    /// (gap = R - |x-c|).
    pub orientation: f64,
}

impl Circle {
    /// Builds the circle.
    pub fn new(center: [f64; 2], radius: f64, side: ToolSide) -> Result<Self, String> {
        if !finite(center) {
            return Err("circle tool: the centre must be finite".into());
        }
        if !(radius > 0.0 && radius.is_finite()) {
            return Err(format!("circle tool: radius must be > 0 (got {radius})"));
        }
        let orientation = match side {
            ToolSide::Outside => 1.0,
            ToolSide::Inside => -1.0,
        };
        Ok(Circle {
            center,
            radius,
            orientation,
        })
    }

    /// Bounding box of the disc.
    pub fn bounding_box(&self) -> Aabb<2> {
        let r = self.radius;
        Aabb {
            min: [self.center[0] - r, self.center[1] - r],
            max: [self.center[0] + r, self.center[1] + r],
        }
    }

    /// Exact projection; `None` at the centre, where the normal is undefined.
    pub fn project(&self, x: [f64; 2]) -> Option<Projection> {
        radial_projection(self.center, self.radius, self.orientation, x)
    }
}

/// Projection on the circle of centre `c`, radius `r` and orientation `o`
/// (+1: free outside, -1: free inside), ignoring any angular limits.
pub(crate) fn radial_projection(c: [f64; 2], r: f64, o: f64, x: [f64; 2]) -> Option<Projection> {
    let d = sub(x, c);
    let dist = norm(d);
    if dist <= 1e-14 * r {
        return None;
    }
    let radial = scale(1.0 / dist, d);
    Some(Projection::on_curve(
        add(c, scale(r, radial)),
        o * (dist - r),
        scale(o, radial),
        o / r,
        d[1].atan2(d[0]),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn circle_outside_and_inside_gaps() {
        let out = Circle::new([1.0, 2.0], 2.0, ToolSide::Outside).unwrap();
        let p = out.project([1.0, 5.0]).unwrap();
        assert_eq!((p.gap, p.normal, p.point), (1.0, [0.0, 1.0], [1.0, 4.0]));
        // d n / d x = (I - n n) / |x - c| for the outside.
        assert!((p.normal_rate - 1.0 / 3.0).abs() < 1e-15);
        let q = out.project([1.0 + 1.5, 2.0]).unwrap();
        assert_eq!((q.gap, q.normal), (-0.5, [1.0, 0.0]));
        let inside = Circle::new([0.0, 0.0], 2.0, ToolSide::Inside).unwrap();
        let r = inside.project([0.0, -1.5]).unwrap();
        assert_eq!((r.gap, r.normal), (0.5, [0.0, 1.0]));
        assert!((r.normal_rate + 1.0 / 1.5).abs() < 1e-15);
        let s = inside.project([0.0, -2.5]).unwrap();
        assert_eq!(s.gap, -0.5);
        assert!(inside.project([0.0, 0.0]).is_none());
        assert!(Circle::new([0.0, 0.0], 0.0, ToolSide::Inside).is_err());
    }
}
