//! Plane: the boundary of a half-space.

use super::{finite, frame, unit};
use crate::{Mat3, Projection, Side, Vec2, Vec3};

/// A plane through `point`; the free side is the side of `normal`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Plane {
    /// A point of the plane.
    pub point: Vec3,
    /// Unit normal pointing into free space.
    pub normal: Vec3,
}

impl Plane {
    /// The plane through `point` with normal `normal`; [`Side::Inside`] puts
    /// the free side opposite the normal.
    pub fn new(point: Vec3, normal: Vec3, side: Side) -> Result<Self, String> {
        Ok(Plane {
            point: finite(point, "plane: point")?,
            normal: unit(normal, "plane: normal")? * side.sign(),
        })
    }

    /// Exact projection: `g = n . (x - p)`, `dn/dx = 0`. The parameter is the
    /// foot's coordinates in a frame of the plane.
    pub fn project(&self, x: &Vec3) -> Projection {
        let g = self.normal.dot(&(x - self.point));
        let foot = x - self.normal * g;
        let (e1, e2) = frame(&self.normal);
        let d = foot - self.point;
        let mut p = Projection::closed_form(foot, g, self.normal, Mat3::zeros());
        p.param = Vec2::new(d.dot(&e1), d.dot(&e2));
        p
    }
}
