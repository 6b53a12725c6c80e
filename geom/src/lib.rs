//! `ctc-geom`: the geometry of ctc's rigid tools in 3D.
//!
//! Everything here works in a tool's **reference frame** and knows nothing of
//! time, meshes or enforcement: the engine's `RigidSurface<3>` tools are thin
//! adapters that map a node into the reference frame with a [`Placement`]
//! (the tool's rigid motion evaluated at the current time), call
//! `project`, and map the [`Projection`] back.
//!
//! - [`analytic`]: plane (half-space), sphere, cylinder, cone, torus with
//!   closed-form projections;
//! - [`nurbs`]: rational B-spline curves and tensor-product surfaces
//!   (evaluation with first and second derivatives), robust point
//!   projection, constructors (exact sphere, surfaces of revolution);
//! - [`trim`]: trimming curves in the parameter plane (line, arc, NURBS),
//!   loops and the parity (ray-crossing) test;
//! - [`brep`]: faces with holes, edges and vertices (radius-0 cylinders and
//!   spheres), a tool made of faces with adjacency and a neighbour-first
//!   face search with counters;
//! - [`trimesh`]: triangulated rigid surfaces (STL ASCII/binary, triangle
//!   lists), angle-weighted pseudonormals for the inside/outside sign;
//! - [`iges`]: reader and writer of the IGES entities that carry trimmed
//!   NURBS geometry.
//!
//! Conventions shared by every projection (the same as the engine's 2D
//! tools):
//! - the **gap** is the signed distance to the closest point: positive on
//!   the free side (where the body may be), negative inside the tool;
//! - the **normal** is the unit normal at the foot pointing into free space,
//!   so `x = point + gap * normal`; it is the gradient of the gap, `dg/dx`;
//! - the **curvature** is `dn/dx`, the derivative of the normal with respect
//!   to the query point (the Weingarten map of the offset surface through `x`
//!   in ambient 3x3 form: `W (I - g W)^{-1}`-like, symmetric, zero along the
//!   normal). Its 2D form is the engine's `normal_rate * t ⊗ t`. It is what the
//!   penalty's consistent tangent needs: `d(g n)/dx = n ⊗ n + g dn/dx`.
//! - a point at which the closest point is not unique (the centre of a
//!   sphere, the axis of a cylinder) or a projection that does not converge
//!   is a typed [`ProjectionError`], never a guess.

pub mod aabb;
pub mod analytic;
pub mod bench;
pub mod brep;
pub mod iges;
pub mod nurbs;
pub mod offset;
pub mod placement;
pub mod projection;
pub mod trim;
pub mod trimesh;

pub use aabb::Aabb;
pub use placement::Placement;
pub use projection::{FootKind, Projection, ProjectionError, Side};

/// A point or vector of the parameter plane.
pub type Vec2 = nalgebra::Vector2<f64>;
/// A point or vector of 3D space.
pub type Vec3 = nalgebra::Vector3<f64>;
/// A 3x3 matrix (the curvature `dn/dx`, rotations).
pub type Mat3 = nalgebra::Matrix3<f64>;
