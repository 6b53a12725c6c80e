//! Built-in structured mesh generators: planar ones through [`MeshSpec`],
//! solid (3D) ones in [`solid`] (brick, tube sector, spherical shell
//! octant; hex8 or tet4).
//!
//! Each generator returns a single-body [`Mesh`] with counter-clockwise
//! cells, named node sets and boundary edge sets (edges oriented with the
//! body on their left, listed in walking order along the boundary; a node
//! set of the same name holds the sorted nodes of each edge set).
//! Invalid specs (non-positive sizes, too few divisions, bad ratios, more
//! than [`MAX_NODES`] nodes) return a [`MeshError`].

mod annulus;
mod common;
mod disc;
mod grading;
mod half_disc;
mod quarter_disc;
mod rectangle;
pub mod solid;
pub mod sweep;

pub use common::MAX_NODES;
pub use grading::RATIO_RANGE;

use super::{CellKind, Mesh};
use crate::mesh::MeshError;

/// Spacing of the divisions along one direction.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Grading {
    /// Equal divisions.
    Uniform,
    /// Geometric progression; `ratio` = size of the last division / size of
    /// the first (ratio < 1 refines towards the end, > 1 towards the start).
    Geometric {
        /// last / first division size, > 0.
        ratio: f64,
    },
    /// Symmetric geometric progression refined (ratio > 1) or coarsened
    /// (ratio < 1) towards the middle; `ratio` = size at the ends / size at
    /// the middle (with fewer than 3 divisions there is no middle: uniform).
    /// Ratios must lie in [`RATIO_RANGE`].
    Center {
        /// end / middle division size, > 0.
        ratio: f64,
    },
}

/// What a deck's `mesh = <generator> { .. }` asks for.
#[derive(Debug, Clone, PartialEq)]
pub enum MeshSpec {
    /// Axis-aligned rectangle [x0, x0 + width] x [y0, y0 + height].
    /// Sets: edges and nodes `bottom`, `right`, `top`, `left`; nodes
    /// `corner_bl`, `corner_br`, `corner_tr`, `corner_tl`.
    Rectangle {
        /// Lower-left corner.
        origin: [f64; 2],
        /// Width (> 0) and height (> 0).
        size: [f64; 2],
        /// Divisions along x and y (>= 1).
        divisions: [usize; 2],
        /// Grading along x and y.
        grading: [Grading; 2],
        /// Tri3 (each quad split in two along the diagonal pointing to the
        /// rectangle centre: mirror-symmetric) or Quad4.
        kind: CellKind,
    },
    /// Half disc below (`upper = false`) or above its diameter, polar
    /// structured: straight radial rays, a fan of triangles around the
    /// centre, and 2:1 coarsening of the rings towards the centre where the
    /// circumferential divisions would be much thinner than the radial ones
    /// (so a grading refined at the pole does not send slivers to the
    /// centre). Every arc angle is kept on the arc and on the ring below it:
    /// the surface layer has one regular cell per arc division. A symmetric
    /// circumferential grading gives a mesh symmetric about the pole.
    /// Sets: `arc` (curved boundary), `flat` (the diameter), `center` (node).
    HalfDisc {
        /// Centre of the full circle.
        center: [f64; 2],
        /// Radius > 0.
        radius: f64,
        /// Radial divisions (>= 1).
        radial: usize,
        /// Circumferential divisions over the half circle (>= 2).
        circumferential: usize,
        /// Radial grading (ratio < 1 refines towards the arc).
        radial_grading: Grading,
        /// Circumferential grading (`Center { ratio > 1 }` refines towards the
        /// middle of the arc, i.e. the pole where contact usually happens;
        /// `Geometric` runs from the `x = center.x - radius` end to the
        /// `x = center.x + radius` end).
        circumferential_grading: Grading,
        /// `false`: the half below the diameter (arc at the bottom, pole at
        /// angle -90 degrees); `true`: above.
        upper: bool,
        /// Tri3 or Quad4 (quads except the innermost ring and one triangle
        /// per 2:1 coarsening).
        kind: CellKind,
    },
    /// Quarter disc with its straight edges on x = center.x (set `axis`) and
    /// y = center.y (set `flat`); below the centre (`upper = false`) or above,
    /// always on the x >= center.x side (the axisymmetric half-section).
    /// Same topology as the half disc (it is meshed like the matching half of
    /// one). Sets: `arc`, `axis`, `flat`, `center`.
    QuarterDisc {
        /// Centre.
        center: [f64; 2],
        /// Radius > 0.
        radius: f64,
        /// Radial divisions (>= 1).
        radial: usize,
        /// Circumferential divisions over 90 degrees (>= 1).
        circumferential: usize,
        /// Radial grading.
        radial_grading: Grading,
        /// Circumferential grading (Geometric ratio < 1 refines towards the
        /// axis end of the arc, i.e. the pole).
        circumferential_grading: Grading,
        /// Above (`true`) or below (`false`) the centre.
        upper: bool,
        /// Tri3 or Quad4 (quads except the innermost ring and one triangle
        /// per 2:1 coarsening).
        kind: CellKind,
    },
    /// Annular sector between `inner` and `outer` radii, from `start_angle` to
    /// `end_angle` (degrees, counter-clockwise; 360 apart = full ring).
    /// Sets: `inner`, `outer`, `start`, `end` (the last two absent for a full
    /// ring).
    Annulus {
        /// Centre.
        center: [f64; 2],
        /// Inner radius > 0.
        inner: f64,
        /// Outer radius > inner.
        outer: f64,
        /// Start angle, degrees.
        start_angle: f64,
        /// End angle, degrees (> start, at most start + 360).
        end_angle: f64,
        /// Radial divisions (>= 1).
        radial: usize,
        /// Circumferential divisions (uniform; >= 3 for a full ring, each
        /// spanning less than 180 degrees).
        circumferential: usize,
        /// Radial grading.
        radial_grading: Grading,
        /// Tri3 or Quad4.
        kind: CellKind,
    },
}

/// Builds the mesh described by `spec`.
pub fn generate(spec: &MeshSpec) -> Result<Mesh, MeshError> {
    match *spec {
        MeshSpec::Rectangle {
            origin,
            size,
            divisions,
            grading,
            kind,
        } => rectangle::rectangle(origin, size, divisions, grading, kind),
        MeshSpec::HalfDisc {
            center,
            radius,
            radial,
            circumferential,
            radial_grading,
            circumferential_grading,
            upper,
            kind,
        } => half_disc::half_disc(
            center,
            radius,
            radial,
            circumferential,
            radial_grading,
            circumferential_grading,
            upper,
            kind,
        ),
        MeshSpec::QuarterDisc {
            center,
            radius,
            radial,
            circumferential,
            radial_grading,
            circumferential_grading,
            upper,
            kind,
        } => quarter_disc::quarter_disc(
            center,
            radius,
            radial,
            circumferential,
            radial_grading,
            circumferential_grading,
            upper,
            kind,
        ),
        MeshSpec::Annulus {
            center,
            inner,
            outer,
            start_angle,
            end_angle,
            radial,
            circumferential,
            radial_grading,
            kind,
        } => annulus::annulus(
            center,
            inner,
            outer,
            start_angle,
            end_angle,
            radial,
            circumferential,
            radial_grading,
            kind,
        ),
    }
}
