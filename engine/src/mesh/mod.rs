//! Mesh storage: nodes, cells and named node / edge sets.
//!
//! Conventions (relied upon by elements, loads and contact):
//! - cells are counter-clockwise (positive area);
//! - boundary edges `[a, b]` are oriented with the body on their **left**,
//!   so the outward normal of edge a->b is `(dy, -dx) / len`.

pub mod generate;
pub mod gmsh;
pub mod quality;
pub mod select;
pub mod validate;

use std::collections::BTreeMap;

/// Cell topology.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum CellKind {
    /// 3-node linear triangle.
    Tri3,
    /// 4-node bilinear quadrilateral.
    Quad4,
}

impl CellKind {
    /// Number of nodes of the cell.
    pub fn node_count(self) -> usize {
        match self {
            CellKind::Tri3 => 3,
            CellKind::Quad4 => 4,
        }
    }
}

/// One cell. For `Tri3` only the first three entries of `nodes` are used
/// (the fourth repeats the third).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Cell {
    /// Topology.
    pub kind: CellKind,
    /// Node numbers, counter-clockwise.
    pub nodes: [usize; 4],
}

impl Cell {
    /// A counter-clockwise triangle.
    pub fn tri(a: usize, b: usize, c: usize) -> Self {
        Cell {
            kind: CellKind::Tri3,
            nodes: [a, b, c, c],
        }
    }

    /// A counter-clockwise quadrilateral.
    pub fn quad(a: usize, b: usize, c: usize, d: usize) -> Self {
        Cell {
            kind: CellKind::Quad4,
            nodes: [a, b, c, d],
        }
    }

    /// The node numbers actually used by this cell.
    pub fn node_slice(&self) -> &[usize] {
        &self.nodes[..self.kind.node_count()]
    }
}

/// A 2D mesh with named sets.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Mesh {
    /// Node coordinates (x, y) — (r, z) for axisymmetric analyses.
    pub nodes: Vec<[f64; 2]>,
    /// Cells.
    pub cells: Vec<Cell>,
    /// Named node sets (sorted, unique node numbers).
    pub node_sets: BTreeMap<String, Vec<usize>>,
    /// Named boundary edge sets (edges oriented with the body on the left).
    pub edge_sets: BTreeMap<String, Vec<[usize; 2]>>,
}

/// An error in building, reading or checking a mesh.
#[derive(Debug, Clone, PartialEq)]
pub struct MeshError {
    /// What is wrong, in words a user understands.
    pub message: String,
    /// 1-based line in the mesh file, when reading a file.
    pub line: Option<usize>,
}

impl MeshError {
    /// An error without a file position.
    pub fn new(message: impl Into<String>) -> Self {
        MeshError {
            message: message.into(),
            line: None,
        }
    }

    /// An error at a 1-based line of a mesh file.
    pub fn at_line(line: usize, message: impl Into<String>) -> Self {
        MeshError {
            message: message.into(),
            line: Some(line),
        }
    }
}

impl std::fmt::Display for MeshError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self.line {
            Some(l) => write!(f, "line {l}: {}", self.message),
            None => f.write_str(&self.message),
        }
    }
}

impl std::error::Error for MeshError {}

impl Mesh {
    /// A mesh of `nodes` and `cells`, without sets.
    pub fn new(nodes: Vec<[f64; 2]>, cells: Vec<Cell>) -> Self {
        Mesh {
            nodes,
            cells,
            ..Default::default()
        }
    }

    /// Boundary edges of the cells in `cells`, oriented with the body on the
    /// left (counter-clockwise cells), in a deterministic order.
    pub fn boundary_edges(&self, cells: std::ops::Range<usize>) -> Vec<[usize; 2]> {
        let mut count: BTreeMap<(usize, usize), (usize, [usize; 2])> = BTreeMap::new();
        for c in &self.cells[cells] {
            let n = c.node_slice();
            for i in 0..n.len() {
                let (a, b) = (n[i], n[(i + 1) % n.len()]);
                let key = (a.min(b), a.max(b));
                count.entry(key).or_insert((0, [a, b])).0 += 1;
            }
        }
        count
            .into_values()
            .filter(|(k, _)| *k == 1)
            .map(|(_, e)| e)
            .collect()
    }
}
