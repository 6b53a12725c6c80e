//! Infinite straight line (a flat die, a floor).

use super::{finite, Foot, Projection};
use crate::contact::vec2::{dot, left, scale, sub, unit};

/// A line through `point` with unit `normal` pointing into free space.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Plane {
    /// A point of the line.
    pub point: [f64; 2],
    /// Unit normal towards the free side.
    pub normal: [f64; 2],
}

impl Plane {
    /// Builds the line; the normal is normalised (it must not be zero).
    pub fn new(point: [f64; 2], normal: [f64; 2]) -> Result<Self, String> {
        if !finite(point) || !finite(normal) {
            return Err("plane tool: point and normal must be finite numbers".into());
        }
        let normal = unit(normal).ok_or_else(|| {
            "plane tool: the normal is (0, 0); give a non-zero normal pointing to the free side"
                .to_string()
        })?;
        Ok(Plane { point, normal })
    }

    /// Orthogonal projection of `x`; the gap is `(x - point) . normal`.
    pub fn project(&self, x: [f64; 2]) -> Projection {
        let d = sub(x, self.point);
        let gap = dot(d, self.normal);
        // Tangent = normal rotated by -90 degrees (free side on its left).
        let tangent = [self.normal[1], -self.normal[0]];
        debug_assert!(dot(left(tangent), self.normal) > 0.0);
        Projection {
            point: sub(x, scale(gap, self.normal)),
            gap,
            normal: self.normal,
            normal_rate: 0.0,
            foot: Foot::Interior,
            param: dot(d, tangent),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn plane_gap_is_signed_distance_along_normal() {
        let p = Plane::new([0.0, 1.0], [0.0, 2.0]).unwrap();
        let a = p.project([3.0, 0.25]);
        assert_eq!(a.gap, -0.75);
        assert_eq!(a.normal, [0.0, 1.0]);
        assert_eq!(a.point, [3.0, 1.0]);
        assert_eq!(a.normal_rate, 0.0);
        let q = Plane::new([0.0, 0.0], [1.0, 1.0]).unwrap();
        let b = q.project([1.0, 1.0]);
        assert!((b.gap - 2f64.sqrt()).abs() < 1e-15);
        assert!(Plane::new([0.0, 0.0], [0.0, 0.0]).is_err());
    }
}
