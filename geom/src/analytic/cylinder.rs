//! Infinite circular cylinder (a roller from outside, a bore from inside).

use super::{finite, frame, positive, unit};
use crate::{Mat3, Projection, ProjectionError, Side, Vec2, Vec3};

/// A cylinder of radius `radius` around the line through `point` along `axis`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Cylinder {
    /// A point of the axis.
    pub point: Vec3,
    /// Unit axis.
    pub axis: Vec3,
    /// Radius > 0.
    pub radius: f64,
    /// Free side.
    pub side: Side,
}

impl Cylinder {
    /// Checks and builds the cylinder.
    pub fn new(point: Vec3, axis: Vec3, radius: f64, side: Side) -> Result<Self, String> {
        Ok(Cylinder {
            point: finite(point, "cylinder: point")?,
            axis: unit(axis, "cylinder: axis")?,
            radius: positive(radius, "cylinder: radius")?,
            side,
        })
    }

    /// Exact projection; singular on the axis. Parameter: (height along the
    /// axis, angle about it).
    pub fn project(&self, x: &Vec3) -> Result<Projection, ProjectionError> {
        let rel = x - self.point;
        let z = rel.dot(&self.axis);
        let q = rel - self.axis * z;
        let rho = q.norm();
        if rho <= 1e-14 * self.radius {
            return Err(ProjectionError::Singular { at: *x });
        }
        let m = q / rho;
        let s = self.side.sign();
        let proj = Mat3::identity() - self.axis * self.axis.transpose() - m * m.transpose();
        let mut p = Projection::closed_form(
            self.point + self.axis * z + m * self.radius,
            s * (rho - self.radius),
            m * s,
            proj * (s / rho),
        );
        let (e1, e2) = frame(&self.axis);
        p.param = Vec2::new(z, m.dot(&e2).atan2(m.dot(&e1)));
        Ok(p)
    }
}
