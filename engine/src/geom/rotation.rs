//! Rotations of `D`-dimensional space: an angle in 2D, a unit quaternion
//! (or an axis and an angle) in 3D, both stored as their matrix.

use super::{Block, Point};
use nalgebra::{Unit, UnitQuaternion, Vector3};

/// A proper rotation `Q` (`Q^T Q = I`, `det Q = 1`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Rotation<const D: usize> {
    /// The rotation matrix.
    pub matrix: Block<D>,
}

impl<const D: usize> Rotation<D> {
    /// The identity.
    pub fn identity() -> Self {
        Rotation {
            matrix: Block::<D>::identity(),
        }
    }

    /// `Q v`.
    #[inline]
    pub fn apply(&self, v: &Point<D>) -> Point<D> {
        self.matrix * v
    }

    /// `Q^T v`.
    #[inline]
    pub fn apply_inverse(&self, v: &Point<D>) -> Point<D> {
        self.matrix.tr_mul(v)
    }

    /// `Q A Q^T` of a tensor `A`.
    pub fn conjugate(&self, a: &Block<D>) -> Block<D> {
        self.matrix * a * self.matrix.transpose()
    }
}

impl Rotation<2> {
    /// Counter-clockwise rotation by `angle` radians.
    pub fn angle(angle: f64) -> Self {
        let (s, c) = angle.sin_cos();
        Rotation {
            matrix: Block::<2>::new(c, -s, s, c),
        }
    }
}

impl Rotation<3> {
    /// The rotation of a unit quaternion.
    pub fn quaternion(q: &UnitQuaternion<f64>) -> Self {
        Rotation {
            matrix: q.to_rotation_matrix().into_inner(),
        }
    }

    /// Rotation by `angle` radians about `axis` (right-hand rule); `None`
    /// when the axis is zero or not finite.
    pub fn axis_angle(axis: [f64; 3], angle: f64) -> Option<Self> {
        let a = Vector3::from(axis);
        let n = a.norm();
        if !(n > 0.0 && n.is_finite() && angle.is_finite()) {
            return None;
        }
        let q = UnitQuaternion::from_axis_angle(&Unit::new_unchecked(a / n), angle);
        Some(Self::quaternion(&q))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::FRAC_PI_2;

    #[test]
    fn quarter_turns_in_2d_and_about_an_axis_in_3d() {
        let r = Rotation::angle(FRAC_PI_2);
        let v = r.apply(&Point::<2>::new(1.0, 0.0));
        assert!((v - Point::<2>::new(0.0, 1.0)).norm() < 1e-15);
        assert!((r.apply_inverse(&v) - Point::<2>::new(1.0, 0.0)).norm() < 1e-15);
        let q = Rotation::axis_angle([0.0, 0.0, 2.0], FRAC_PI_2).unwrap();
        let w = q.apply(&Point::<3>::new(1.0, 0.0, 0.0));
        assert!((w - Point::<3>::new(0.0, 1.0, 0.0)).norm() < 1e-15);
        // about (1, 1, 1) by 120 degrees: x -> y -> z -> x
        let c = Rotation::axis_angle([1.0, 1.0, 1.0], 2.0 * std::f64::consts::PI / 3.0).unwrap();
        let w = c.apply(&Point::<3>::new(1.0, 0.0, 0.0));
        assert!((w - Point::<3>::new(0.0, 1.0, 0.0)).norm() < 1e-15);
        assert!((c.matrix.determinant() - 1.0).abs() < 1e-15);
        assert!(Rotation::axis_angle([0.0; 3], 1.0).is_none());
        let a = Block::<3>::from_diagonal(&Point::<3>::new(1.0, 2.0, 3.0));
        let ra = c.conjugate(&a);
        assert!((ra[(0, 0)] - 3.0).abs() < 1e-14 && (ra[(1, 1)] - 1.0).abs() < 1e-14);
    }
}
