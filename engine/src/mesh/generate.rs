//! Built-in structured mesh generators.
//!
//! Each generator returns a single-body [`Mesh`] with named node sets and
//! boundary edge sets (edges oriented with the body on their left).

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
    /// the middle.
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
        /// Tri3 (each quad split in two) or Quad4.
        kind: CellKind,
    },
    /// Half disc below (`upper = false`) or above its diameter, polar
    /// structured (triangles in the innermost ring).
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
        /// middle of the arc, i.e. the pole where contact usually happens).
        circumferential_grading: Grading,
        /// `false`: the half below the diameter (arc at the bottom, pole at
        /// angle -90 degrees); `true`: above.
        upper: bool,
        /// Tri3 or Quad4 (quads except the innermost ring).
        kind: CellKind,
    },
    /// Quarter disc with its straight edges on x = center.x (set `axis`) and
    /// y = center.y (set `flat`); below the centre (`upper = false`) or above,
    /// always on the x >= center.x side (the axisymmetric half-section).
    /// Sets: `arc`, `axis`, `flat`, `center`.
    QuarterDisc {
        /// Centre.
        center: [f64; 2],
        /// Radius > 0.
        radius: f64,
        /// Radial divisions.
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
        /// Tri3 or Quad4.
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
        /// Radial divisions.
        radial: usize,
        /// Circumferential divisions.
        circumferential: usize,
        /// Radial grading.
        radial_grading: Grading,
        /// Tri3 or Quad4.
        kind: CellKind,
    },
}

/// Builds the mesh described by `spec`.
pub fn generate(spec: &MeshSpec) -> Result<Mesh, MeshError> {
    let _ = spec;
    Err(MeshError::new("mesh generators are not implemented yet"))
}
