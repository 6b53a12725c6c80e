//! Quarter disc on the `x >= center.x` side: polar structured with a triangle
//! hub and coarsening towards the centre (see [`super::disc`]).

use super::common::{add_boundary, add_node, chain};
use super::disc::{build, checked_rings, Sector};
use super::Grading;
use crate::mesh::{CellKind, Mesh, MeshError};

const NAME: &str = "quarter_disc";

/// Builds the quarter disc; see [`super::MeshSpec::QuarterDisc`]. The
/// circumferential grading runs from the `flat` end of the arc (first
/// division) to the `axis` end, the pole (last).
#[allow(clippy::too_many_arguments)]
pub fn quarter_disc(
    center: [f64; 2],
    radius: f64,
    radial: usize,
    circumferential: usize,
    radial_grading: Grading,
    circumferential_grading: Grading,
    upper: bool,
    kind: CellKind,
) -> Result<Mesh, MeshError> {
    let (radii, t) = checked_rings(
        NAME,
        center,
        radius,
        radial,
        circumferential,
        1,
        radial_grading,
        circumferential_grading,
    )?;
    // increasing angles: lower quarter -90 (axis) .. 0 (flat), upper 0 .. 90
    let angles: Vec<f64> = if upper {
        t.iter().map(|t| 90.0 * t).collect()
    } else {
        t.iter().rev().map(|t| -90.0 * t).collect()
    };
    // mirror at the pole: the quarter is meshed like the matching half of a
    // half disc
    let mirror = if upper { 90.0 } else { -90.0 };
    let sector = build(&Sector {
        center,
        radii,
        angles,
        mirror,
        kind,
    });
    let mut mesh = sector.mesh;
    let rings = &sector.rings;
    let arc = rings.last().expect("radial >= 1");
    add_boundary(&mut mesh, "arc", chain(arc));
    // ray at the last angle walked inwards, ray at the first angle outwards
    let mut high: Vec<usize> = rings.iter().rev().map(|r| r[r.len() - 1]).collect();
    high.push(sector.center);
    let mut low = vec![sector.center];
    low.extend(rings.iter().map(|r| r[0]));
    let (axis, flat) = if upper { (high, low) } else { (low, high) };
    add_boundary(&mut mesh, "axis", chain(&axis));
    add_boundary(&mut mesh, "flat", chain(&flat));
    add_node(&mut mesh, "center", sector.center);
    Ok(mesh)
}
