//! Geometry shared by every dimension-generic part of the engine: points
//! and node blocks as fixed-size nalgebra types, the dimension bound,
//! axis-aligned boxes, rotations and Morton codes.
//!
//! The spatial dimension is a const generic `D` (2 or 3) everywhere; one
//! bound, `Const<D>: Dimension<D>`, carries both nalgebra's fixed-size
//! linear algebra (determinants, inverses of [`Block`]) and what differs
//! between 2D and 3D (see [`Dimension`]), as fenris' `SmallDim` does.
//!
//! - [`point`]: [`Point`], [`Block`], [`Dimension`];
//! - [`aabb`]: [`Aabb`], boxes with infinite extents allowed;
//! - [`rotation`]: [`Rotation`] (an angle in 2D, a unit quaternion in 3D);
//! - [`morton`]: Z-order codes of grid cells.

pub mod aabb;
pub mod morton;
pub mod point;
pub mod rotation;

pub use aabb::Aabb;
pub use point::{Block, Dimension, Point};
pub use rotation::Rotation;
