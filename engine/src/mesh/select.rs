//! Geometric selections of nodes and boundary edges.

use super::Mesh;

/// A geometric selection, evaluated on reference coordinates with a tolerance
/// relative to the body size.
#[derive(Debug, Clone, PartialEq)]
pub enum Selection {
    /// Nodes with x = value (within tolerance).
    XEquals(f64),
    /// Nodes with y = value (within tolerance).
    YEquals(f64),
    /// Nodes inside the closed box [min, max].
    Box {
        /// Lower corner.
        min: [f64; 2],
        /// Upper corner.
        max: [f64; 2],
    },
    /// The single node closest to the point.
    Nearest([f64; 2]),
}

/// Nodes among `candidates` (global numbers) selected by `sel`, sorted.
pub fn select_nodes(mesh: &Mesh, candidates: &[usize], sel: &Selection) -> Vec<usize> {
    let _ = (mesh, candidates, sel);
    Vec::new()
}

/// Boundary edges among `boundary` whose two nodes are both selected by `sel`.
pub fn select_edges(mesh: &Mesh, boundary: &[[usize; 2]], sel: &Selection) -> Vec<[usize; 2]> {
    let _ = (mesh, boundary, sel);
    Vec::new()
}
