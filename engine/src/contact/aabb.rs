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
        for k in 0..2 {
            self.min[k] = self.min[k].min(p[k]);
            self.max[k] = self.max[k].max(p[k]);
        }
    }

    /// Euclidean distance from `x` to the box (0 inside).
    pub fn distance(&self, x: [f64; 2]) -> f64 {
        let mut d2 = 0.0;
        for k in 0..2 {
            let e = if x[k] < self.min[k] {
                self.min[k] - x[k]
            } else if x[k] > self.max[k] {
                x[k] - self.max[k]
            } else {
                0.0
            };
            d2 += e * e;
        }
        d2.sqrt()
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
