//! Axis-aligned bounding boxes in 3D.

use crate::placement::Placement;
use crate::Vec3;

/// An axis-aligned box `[min, max]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Aabb {
    /// Lower corner.
    pub min: Vec3,
    /// Upper corner.
    pub max: Vec3,
}

impl Aabb {
    /// The empty box (union identity).
    pub fn empty() -> Self {
        Aabb {
            min: Vec3::repeat(f64::INFINITY),
            max: Vec3::repeat(f64::NEG_INFINITY),
        }
    }

    /// The whole space (an unbounded tool such as a plane).
    pub fn everything() -> Self {
        Aabb {
            min: Vec3::repeat(f64::NEG_INFINITY),
            max: Vec3::repeat(f64::INFINITY),
        }
    }

    /// The smallest box holding `points`.
    pub fn around<'a>(points: impl IntoIterator<Item = &'a Vec3>) -> Self {
        let mut b = Aabb::empty();
        for p in points {
            b.add(p);
        }
        b
    }

    /// Grows the box to hold `p`.
    pub fn add(&mut self, p: &Vec3) {
        self.min = self.min.inf(p);
        self.max = self.max.sup(p);
    }

    /// The union of two boxes.
    pub fn union(&self, o: &Aabb) -> Aabb {
        Aabb {
            min: self.min.inf(&o.min),
            max: self.max.sup(&o.max),
        }
    }

    /// The box grown by `d` on every side.
    pub fn inflated(&self, d: f64) -> Aabb {
        Aabb {
            min: self.min.add_scalar(-d),
            max: self.max.add_scalar(d),
        }
    }

    /// Whether the box holds no point.
    pub fn is_empty(&self) -> bool {
        (0..3).any(|i| self.min[i] > self.max[i])
    }

    /// Euclidean distance from `p` to the box (0 inside).
    pub fn distance(&self, p: &Vec3) -> f64 {
        if self.is_empty() {
            return f64::INFINITY;
        }
        let mut s = 0.0;
        for i in 0..3 {
            let d = (self.min[i] - p[i]).max(p[i] - self.max[i]).max(0.0);
            if d.is_finite() {
                s += d * d;
            }
        }
        s.sqrt()
    }

    /// Length of the diagonal (0 for a point, infinite for unbounded boxes).
    pub fn diagonal(&self) -> f64 {
        if self.is_empty() {
            0.0
        } else {
            (self.max - self.min).norm()
        }
    }

    /// Box of this (reference-frame) box moved by `placement`: the box of
    /// its eight moved corners.
    pub fn placed(&self, placement: &Placement) -> Aabb {
        if self.is_empty() || !self.diagonal().is_finite() {
            return *self;
        }
        let mut b = Aabb::empty();
        for k in 0..8 {
            let c = Vec3::new(
                if k & 1 == 0 { self.min.x } else { self.max.x },
                if k & 2 == 0 { self.min.y } else { self.max.y },
                if k & 4 == 0 { self.min.z } else { self.max.z },
            );
            b.add(&placement.apply(&c));
        }
        b
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn distance_union_and_placement() {
        let b = Aabb::around(&[Vec3::zeros(), Vec3::new(1.0, 2.0, 3.0)]);
        assert_eq!(b.distance(&Vec3::new(0.5, 1.0, 1.0)), 0.0);
        assert_eq!(b.distance(&Vec3::new(4.0, 6.0, 3.0)), 5.0);
        assert!(Aabb::empty().distance(&Vec3::zeros()).is_infinite());
        assert_eq!(Aabb::everything().distance(&Vec3::new(1e9, 0.0, 0.0)), 0.0);
        let moved = b.placed(&Placement::translation(Vec3::new(1.0, 0.0, 0.0)));
        assert_eq!(moved.min, Vec3::new(1.0, 0.0, 0.0));
        assert_eq!(b.union(&moved).max, Vec3::new(2.0, 2.0, 3.0));
    }
}
