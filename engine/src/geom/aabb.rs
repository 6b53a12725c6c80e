//! Axis-aligned bounding boxes in `D` dimensions; infinite extents are
//! allowed (a plane has an unbounded box).

/// A closed axis-aligned box `[min, max]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Aabb<const D: usize> {
    /// Lower corner.
    pub min: [f64; D],
    /// Upper corner.
    pub max: [f64; D],
}

impl<const D: usize> Aabb<D> {
    /// The unbounded box (contains every point).
    pub fn everything() -> Self {
        Aabb {
            min: [f64::NEG_INFINITY; D],
            max: [f64::INFINITY; D],
        }
    }

    /// The empty box (`include` a point to start it).
    pub fn empty() -> Self {
        Aabb {
            min: [f64::INFINITY; D],
            max: [f64::NEG_INFINITY; D],
        }
    }

    /// Smallest box containing all `points` (at least one point).
    pub fn around(points: &[[f64; D]]) -> Self {
        let mut b = Self::empty();
        for p in points {
            b.include(*p);
        }
        b
    }

    /// Grows the box to contain `p`.
    pub fn include(&mut self, p: [f64; D]) {
        for ((lo, hi), v) in self.min.iter_mut().zip(&mut self.max).zip(p) {
            *lo = lo.min(v);
            *hi = hi.max(v);
        }
    }

    /// Euclidean distance from `x` to the box (0 inside).
    pub fn distance(&self, x: [f64; D]) -> f64 {
        let mut s = 0.0;
        for ((v, lo), hi) in x.iter().zip(&self.min).zip(&self.max) {
            let e = if v < lo {
                lo - v
            } else if v > hi {
                v - hi
            } else {
                0.0
            };
            s += e * e;
        }
        s.sqrt()
    }

    /// Whether `x` lies in the box inflated by `margin` in every direction
    /// (a rounded inflation: distance to the box <= margin).
    pub fn contains_within(&self, x: [f64; D], margin: f64) -> bool {
        self.distance(x) <= margin
    }

    /// Whether every extent is finite.
    pub fn is_finite(&self) -> bool {
        self.min.iter().chain(&self.max).all(|v| v.is_finite())
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
        assert_eq!(Aabb::<2>::everything().distance([1e300, -1e300]), 0.0);
        let c = Aabb::around(&[[0.0, 0.0, 0.0], [1.0, 1.0, 1.0]]);
        assert!((c.distance([2.0, 2.0, 2.0]) - 3f64.sqrt()).abs() < 1e-15);
        assert!(c.is_finite() && !Aabb::<3>::everything().is_finite());
    }
}
