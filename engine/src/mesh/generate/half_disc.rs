//! Half disc: polar structured with a triangle hub and coarsening towards the
//! centre (see [`super::disc`]).

use super::common::{add_boundary, add_node, chain};
use super::disc::{build, checked_rings, Sector};
use super::Grading;
use crate::mesh::{CellKind, Mesh, MeshError};

const NAME: &str = "half_disc";

/// Builds the half disc; see [`super::MeshSpec::HalfDisc`]. The
/// circumferential grading runs from the `x = center.x - radius` end of the
/// diameter (first division) to the `x = center.x + radius` end (last).
#[allow(clippy::too_many_arguments)]
pub fn half_disc(
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
        2,
        radial_grading,
        circumferential_grading,
    )?;
    let angles: Vec<f64> = if upper {
        t.iter().rev().map(|t| 180.0 - 180.0 * t).collect()
    } else {
        t.iter().map(|t| 180.0 + 180.0 * t).collect()
    };
    let mirror = if upper { 90.0 } else { 270.0 };
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
    // the diameter, walked from the ring ends at the last angle inwards,
    // through the centre, out to the first angle
    let mut flat: Vec<usize> = rings.iter().rev().map(|r| r[r.len() - 1]).collect();
    flat.push(sector.center);
    flat.extend(rings.iter().map(|r| r[0]));
    add_boundary(&mut mesh, "flat", chain(&flat));
    add_node(&mut mesh, "center", sector.center);
    Ok(mesh)
}
