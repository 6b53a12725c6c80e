//! Axis-aligned bounding boxes of tool entities (in the tool's reference
//! frame; the search transforms the query point instead of the boxes, which
//! is the same as boxes that move with the tool).

/// A closed axis-aligned box `[min, max]`; infinite extents are allowed
/// (a plane has an unbounded box).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Aabb {
    /// Lower-left corner.
    pub min: [f64; 2],
    /// Upper-right corner.
    pub max: [f64; 2],
}

impl Aabb {
    /// The unbounded box (contains every point).
    pub fn everything() -> Self {
        Aabb {
            min: [f64::NEG_INFINITY; 2],
            max: [f64::INFINITY; 2],
        }
    }

    /// Smallest box containing all `points` (at least one point).
    pub fn around(points: &[[f64; 2]]) -> Self {
        let mut b = Aabb {
            min: [f64::INFINITY; 2],
            max: [f64::NEG_INFINITY; 2],
        };
        for p in points {
            b.include(*p);
        }
        b
    }

    /// Grows the box to contain `p`.
    pub fn include(&mut self, p: [f64; 2]) {
        self.min = [self.min[0].min(p[0]), self.min[1].min(p[1])];
        self.max = [self.max[0].max(p[0]), self.max[1].max(p[1])];
    }

    /// Euclidean distance from `x` to the box (0 inside).
    pub fn distance(&self, x: [f64; 2]) -> f64 {
        let excess = |v: f64, lo: f64, hi: f64| {
            if v < lo {
                lo - v
            } else if v > hi {
                v - hi
            } else {
                0.0
            }
        };
        let ex = excess(x[0], self.min[0], self.max[0]);
        let ey = excess(x[1], self.min[1], self.max[1]);
        (ex * ex + ey * ey).sqrt()
    }

    /// Whether `x` lies in the box inflated by `margin` in every direction
    /// (a rounded inflation: distance to the box <= margin).
    pub fn contains_within(&self, x: [f64; 2], margin: f64) -> bool {
        self.distance(x) <= margin
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn box_distance_inside_edge_and_corner() {
        let b = Aabb::around(&[[0.0, 0.0], [2.0, 1.0]]);
        assert_eq!(b.distance([1.0, 0.5]), 0.0);
        assert_eq!(b.distance([3.0, 0.5]), 1.0);
        assert!((b.distance([5.0, 5.0]) - 5.0).abs() < 1e-15);
        assert!(b.contains_within([2.5, 0.5], 0.5));
        assert!(!b.contains_within([2.6, 0.5], 0.5));
        assert_eq!(Aabb::everything().distance([1e300, -1e300]), 0.0);
    }
}
