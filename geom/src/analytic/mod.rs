//! Analytical rigid surfaces with closed-form projections: plane
//! (half-space), sphere, cylinder, cone, torus. Each has a [`Side`]: the free
//! side (where the body is) outside or inside the solid it bounds (a plane's
//! inside is the side opposite its normal).
//!
//! Each projection is exact: the gap, the normal and `dn/dx` follow from the
//! distance function of the shape (see [`crate::offset`]); points where the
//! closest point is not unique (centre, axis) are
//! [`ProjectionError::Singular`].

pub mod cone;
pub mod cylinder;
pub mod plane;
pub mod sphere;
pub mod torus;

pub use cone::Cone;
pub use cylinder::Cylinder;
pub use plane::Plane;
pub use sphere::Sphere;
pub use torus::Torus;

use crate::{Aabb, Projection, ProjectionError, Vec3};

/// One analytical surface.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Analytic {
    /// Half-space bounded by a plane.
    Plane(Plane),
    /// Sphere.
    Sphere(Sphere),
    /// Infinite circular cylinder.
    Cylinder(Cylinder),
    /// Infinite circular cone (one nappe) with its apex.
    Cone(Cone),
    /// Ring torus.
    Torus(Torus),
}

impl Analytic {
    /// Closest-point projection of `x` (reference frame).
    pub fn project(&self, x: &Vec3) -> Result<Projection, ProjectionError> {
        match self {
            Analytic::Plane(s) => Ok(s.project(x)),
            Analytic::Sphere(s) => s.project(x),
            Analytic::Cylinder(s) => s.project(x),
            Analytic::Cone(s) => s.project(x),
            Analytic::Torus(s) => s.project(x),
        }
    }

    /// Bounding box of the surface (unbounded for planes, cylinders, cones).
    pub fn bounding_box(&self) -> Aabb {
        match self {
            Analytic::Sphere(s) => s.bounding_box(),
            Analytic::Torus(s) => s.bounding_box(),
            _ => Aabb::everything(),
        }
    }
}

/// A unit vector from `v`, or an error naming `what`.
pub(crate) fn unit(v: Vec3, what: &str) -> Result<Vec3, String> {
    let n = v.norm();
    if n > 0.0 && n.is_finite() {
        Ok(v / n)
    } else {
        Err(format!("{what} must be a non-zero finite vector"))
    }
}

/// Checks that a point is finite.
pub(crate) fn finite(p: Vec3, what: &str) -> Result<Vec3, String> {
    if p.iter().all(|c| c.is_finite()) {
        Ok(p)
    } else {
        Err(format!("{what} must be finite"))
    }
}

/// Checks that a length is positive and finite.
pub(crate) fn positive(r: f64, what: &str) -> Result<f64, String> {
    if r > 0.0 && r.is_finite() {
        Ok(r)
    } else {
        Err(format!("{what} must be > 0 (got {r})"))
    }
}

/// Two unit vectors completing the unit `a` to a right-handed frame.
pub(crate) fn frame(a: &Vec3) -> (Vec3, Vec3) {
    let helper = if a.x.abs() < 0.9 {
        Vec3::x()
    } else {
        Vec3::y()
    };
    let e1 = (helper - a * a.dot(&helper)).normalize();
    let e2 = a.cross(&e1);
    (e1, e2)
}
