//! A tool's rigid placement at one instant.
//!
//! A point `X` of the reference geometry is at `x = Q (X - c) + c + u`, with
//! `Q` a rotation about an axis through the centre `c` and `u` a translation.
//! Time functions (the motion) stay in the engine: it evaluates the angle and
//! the translation at the current time and builds a `Placement`. A node is
//! brought into the reference frame (`X = Q^T (x - c - u) + c`), projected
//! there, and the result is mapped back by [`Placement::to_current`]: the
//! point is placed, the normal rotated, the curvature conjugated
//! (`Q W Q^T`); gaps are invariant.
//!
//! For friction the engine needs the velocity of the tool's material point at
//! the foot: with the angular velocity `omega` (about the placement's axis)
//! and the translation rate `du/dt`, [`Placement::velocity`] gives
//! `omega × (x - c - u) + du/dt`.

use crate::projection::Projection;
use crate::{Mat3, Vec3};
use nalgebra::{Rotation3, Unit};

/// Rigid placement `x = Q (X - c) + c + u`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Placement {
    /// The rotation `Q`.
    pub rotation: Rotation3<f64>,
    /// The centre of rotation `c` (reference frame).
    pub center: Vec3,
    /// The translation `u`.
    pub translation: Vec3,
}

impl Placement {
    /// The identity.
    pub fn identity() -> Self {
        Placement {
            rotation: Rotation3::identity(),
            center: Vec3::zeros(),
            translation: Vec3::zeros(),
        }
    }

    /// A translation only.
    pub fn translation(u: Vec3) -> Self {
        Placement {
            translation: u,
            ..Placement::identity()
        }
    }

    /// Rotation by `angle` (radians, right-handed) about the axis through
    /// `center` along `axis`, then the translation `u`. `None` when the axis
    /// is zero or not finite.
    pub fn about_axis(axis: Vec3, angle: f64, center: Vec3, u: Vec3) -> Option<Self> {
        if !(axis.norm() > 0.0 && axis.iter().all(|c| c.is_finite()) && angle.is_finite()) {
            return None;
        }
        Some(Placement {
            rotation: Rotation3::from_axis_angle(&Unit::new_normalize(axis), angle),
            center,
            translation: u,
        })
    }

    /// The current position of the reference point `xr`.
    pub fn apply(&self, xr: &Vec3) -> Vec3 {
        self.rotation * (xr - self.center) + self.center + self.translation
    }

    /// The reference point currently at `x`.
    pub fn to_reference(&self, x: &Vec3) -> Vec3 {
        self.rotation.inverse() * (x - self.center - self.translation) + self.center
    }

    /// A reference-frame projection expressed in the current frame.
    pub fn to_current(&self, p: &Projection) -> Projection {
        let q: &Mat3 = self.rotation.matrix();
        Projection {
            point: self.apply(&p.point),
            normal: q * p.normal,
            curvature: q * p.curvature * q.transpose(),
            ..*p
        }
    }

    /// Velocity of the tool's material point currently at `x`, for an
    /// angular velocity `omega` (vector, current frame) and a translation
    /// rate `du_dt`.
    pub fn velocity(&self, x: &Vec3, omega: &Vec3, du_dt: &Vec3) -> Vec3 {
        omega.cross(&(x - self.center - self.translation)) + du_dt
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn round_trip_and_velocity() {
        let p = Placement::about_axis(
            Vec3::new(1.0, 2.0, 2.0),
            0.7,
            Vec3::new(1.0, 0.0, -1.0),
            Vec3::new(0.3, -0.2, 0.5),
        )
        .unwrap();
        let x = Vec3::new(0.4, 2.0, 3.0);
        assert!((p.apply(&p.to_reference(&x)) - x).norm() < 1e-14);
        // The centre moves by the translation only.
        assert!((p.apply(&p.center) - p.center - p.translation).norm() < 1e-15);
        // Velocity by finite differences of the angle.
        let axis = Vec3::new(1.0, 2.0, 2.0) / 3.0;
        let h = 1e-6;
        let xr = p.to_reference(&x);
        let q = |a: f64| Placement::about_axis(axis, a, p.center, p.translation).unwrap();
        let fd = (q(0.7 + h).apply(&xr) - q(0.7 - h).apply(&xr)) / (2.0 * h);
        let v = p.velocity(&x, &axis, &Vec3::zeros());
        assert!((fd - v).norm() < 1e-8);
        assert!(Placement::about_axis(Vec3::zeros(), 1.0, x, x).is_none());
    }
}
