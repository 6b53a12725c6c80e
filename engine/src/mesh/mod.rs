//! Mesh storage: nodes, cells and named node / edge / face sets, in 2D
//! (planar) or 3D (solid).
//!
//! Conventions (relied upon by elements, loads and contact):
//! - planar cells are counter-clockwise (positive area); solid cells follow
//!   the gmsh node order with a positive volume;
//! - boundary edges `[a, b]` are oriented with the body on their **left**,
//!   so the outward normal of edge a->b is `(dy, -dx) / len`; boundary faces
//!   are counter-clockwise seen from outside (outward normal by the
//!   right-hand rule, `crate::geom::Dimension::facet_normal`).
//!
//! - [`cell`]: cell kinds and the compressed-row cell storage;
//! - [`facet`]: boundary edges and faces; [`elevate`]: linear to
//!   quadratic cells;
//! - [`generate`]: built-in generators; [`gmsh`]: the gmsh reader;
//! - [`select`]: geometric selections; [`validate`], [`quality`]: checks.

pub mod cell;
pub mod elevate;
pub mod facet;
pub mod generate;
pub mod gmsh;
pub mod quality;
pub mod select;
pub mod validate;

pub use cell::{Cell, CellKind, CellRef, Cells};
pub use facet::Facet;

use std::collections::BTreeMap;

/// A mesh of dimension `D` (2: planar, 3: solid) with named sets.
/// Node coordinates are stored as plain arrays (`crate::geom::Point` is
/// their nalgebra view for computation). `Mesh` without a parameter is the
/// planar mesh.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Mesh<const D: usize = 2> {
    /// Node coordinates (x, y[, z]) — (r, z) for axisymmetric analyses.
    pub nodes: Vec<[f64; D]>,
    /// Cells.
    pub cells: Cells,
    /// Named node sets (sorted, unique node numbers).
    pub node_sets: BTreeMap<String, Vec<usize>>,
    /// Named boundary edge sets of planar meshes (edges oriented with the
    /// body on the left); empty for solid meshes.
    pub edge_sets: BTreeMap<String, Vec<[usize; 2]>>,
    /// Named boundary face sets of solid meshes (faces counter-clockwise
    /// seen from outside); empty for planar meshes.
    pub face_sets: BTreeMap<String, Vec<Facet>>,
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

impl<const D: usize> Mesh<D> {
    /// A mesh of `nodes` and `cells`, without sets.
    pub fn new(nodes: Vec<[f64; D]>, cells: Vec<Cell>) -> Self {
        Mesh {
            nodes,
            cells: cells.into_iter().collect(),
            ..Default::default()
        }
    }

    /// [`Mesh::edge_midsides`] of a planar mesh (empty in 3D).
    pub(crate) fn planar_midsides(&self) -> std::collections::HashMap<(usize, usize), usize> {
        let mut out = std::collections::HashMap::new();
        if D == 2 {
            for cell in self.cells.iter() {
                if cell.kind.order() != 2 || cell.kind.dimension() != 2 {
                    continue;
                }
                for face in cell.kind.faces() {
                    if let &[a, b, m] = *face {
                        let (a, b) = (cell.nodes[a], cell.nodes[b]);
                        out.insert((a.min(b), a.max(b)), cell.nodes[m]);
                    }
                }
            }
        }
        out
    }

    /// Coordinates of the nodes of cell `c`, as points.
    pub fn cell_points(&self, c: usize) -> Vec<crate::geom::Point<D>> {
        self.cells
            .nodes(c)
            .iter()
            .map(|&n| crate::geom::Point::<D>::from(self.nodes[n]))
            .collect()
    }

    /// The boundary facets (edges in 2D, faces in 3D) of the cells in
    /// `cells`: the cell faces that belong to one cell only, with the
    /// outward node order of their cell, in a deterministic order (sorted
    /// by their sorted node lists).
    pub fn boundary_facets(&self, cells: std::ops::Range<usize>) -> Vec<Facet> {
        let mut count: BTreeMap<Vec<usize>, (usize, Facet)> = BTreeMap::new();
        for c in cells {
            let cell = self.cells.get(c);
            for face in cell.kind.faces() {
                let nodes: Vec<usize> = face.iter().map(|&a| cell.nodes[a]).collect();
                let mut key = nodes.clone();
                key.sort_unstable();
                count.entry(key).or_insert((0, Facet::new(&nodes))).0 += 1;
            }
        }
        count
            .into_values()
            .filter(|(k, _)| *k == 1)
            .map(|(_, f)| f)
            .collect()
    }

    /// The facets of set `name`: the edge set of a planar mesh (3-node
    /// edges where the cells are quadratic) or the face set of a solid mesh.
    pub fn facet_set(&self, name: &str) -> Option<Vec<Facet>> {
        if D == 2 {
            let midsides = self.planar_midsides();
            self.edge_sets
                .get(name)
                .map(|e| e.iter().map(|&e| Mesh::edge_facet(&midsides, e)).collect())
        } else {
            self.face_sets.get(name).cloned()
        }
    }
}

impl Mesh<2> {
    /// Boundary edges of the cells in `cells`, oriented with the body on the
    /// left (counter-clockwise cells), in a deterministic order.
    /// Quadratic cells give the corner pairs of their edges (the midside
    /// node is [`Mesh::edge_midsides`]'s).
    pub fn boundary_edges(&self, cells: std::ops::Range<usize>) -> Vec<[usize; 2]> {
        // every cell edge bucketed by its smaller node (counting sort);
        // an edge met once is on the boundary. Output in increasing
        // (smaller node, larger node) order.
        let edges_of = |c: usize| {
            let n = self.cells.nodes(c);
            let corners = self.cells.kind(c).corner_count();
            (0..corners).map(move |i| [n[i], n[(i + 1) % corners]])
        };
        // the buckets span the cells' nodes only (a body's block)
        let first = cells
            .clone()
            .flat_map(|c| self.cells.nodes(c).iter().copied())
            .min()
            .unwrap_or(0);
        let last = cells
            .clone()
            .flat_map(|c| self.cells.nodes(c).iter().copied())
            .max()
            .unwrap_or(0);
        let nn = if cells.is_empty() {
            0
        } else {
            last - first + 1
        };
        let mut start = vec![0usize; nn + 1];
        for c in cells.clone() {
            for [a, b] in edges_of(c) {
                start[a.min(b) - first + 1] += 1;
            }
        }
        for i in 0..nn {
            start[i + 1] += start[i];
        }
        let mut fill = start.clone();
        // (larger node, the edge as met)
        let mut slots = vec![(0usize, [0usize; 2]); start[nn]];
        for c in cells {
            for [a, b] in edges_of(c) {
                let lo = a.min(b) - first;
                slots[fill[lo]] = (a.max(b), [a, b]);
                fill[lo] += 1;
            }
        }
        let mut out = Vec::new();
        for lo in 0..nn {
            let bucket = &mut slots[start[lo]..start[lo + 1]];
            bucket.sort_unstable_by_key(|e| e.0);
            let mut i = 0;
            while i < bucket.len() {
                let mut j = i + 1;
                while j < bucket.len() && bucket[j].0 == bucket[i].0 {
                    j += 1;
                }
                if j == i + 1 {
                    out.push(bucket[i].1);
                }
                i = j;
            }
        }
        out
    }

    /// The midside node of every edge of the quadratic cells, by the
    /// sorted corner pair of the edge (empty for a linear mesh). Planar
    /// edge sets store corner pairs `[a, b]`; this map makes them the
    /// 3-node edges `[a, b, m]` of the cells ([`Mesh::edge_facet`]).
    pub fn edge_midsides(&self) -> std::collections::HashMap<(usize, usize), usize> {
        self.planar_midsides()
    }

    /// The facet of the boundary edge `[a, b]`: `[a, b, m]` when `midsides`
    /// ([`Mesh::edge_midsides`]) has its midside node, else `[a, b]`.
    pub fn edge_facet(
        midsides: &std::collections::HashMap<(usize, usize), usize>,
        [a, b]: [usize; 2],
    ) -> Facet {
        match midsides.get(&(a.min(b), a.max(b))) {
            Some(&m) => Facet::new(&[a, b, m]),
            None => Facet::new(&[a, b]),
        }
    }
}
