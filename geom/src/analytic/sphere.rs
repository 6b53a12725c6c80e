//! Sphere (a ball punch from outside, a spherical cavity from inside).

use super::{finite, positive};
use crate::{Aabb, Mat3, Projection, ProjectionError, Side, Vec2, Vec3};

/// A sphere of centre `center` and radius `radius`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sphere {
    /// Centre.
    pub center: Vec3,
    /// Radius > 0.
    pub radius: f64,
    /// Free side.
    pub side: Side,
}

impl Sphere {
    /// Checks and builds the sphere.
    pub fn new(center: Vec3, radius: f64, side: Side) -> Result<Self, String> {
        Ok(Sphere {
            center: finite(center, "sphere: centre")?,
            radius: positive(radius, "sphere: radius")?,
            side,
        })
    }

    /// Bounding box.
    pub fn bounding_box(&self) -> Aabb {
        Aabb {
            min: self.center.add_scalar(-self.radius),
            max: self.center.add_scalar(self.radius),
        }
    }

    /// Exact projection; singular at the centre. Parameter: (polar angle
    /// from +z, azimuth).
    pub fn project(&self, x: &Vec3) -> Result<Projection, ProjectionError> {
        let d = x - self.center;
        let r = d.norm();
        if r <= 1e-14 * self.radius {
            return Err(ProjectionError::Singular { at: *x });
        }
        let m = d / r;
        let s = self.side.sign();
        let w = (Mat3::identity() - m * m.transpose()) * (s / r);
        let mut p = Projection::closed_form(
            self.center + m * self.radius,
            s * (r - self.radius),
            m * s,
            w,
        );
        p.param = Vec2::new(m.z.clamp(-1.0, 1.0).acos(), m.y.atan2(m.x));
        Ok(p)
    }
}
