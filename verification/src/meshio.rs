//! Cross-checks with Python's [meshio](https://github.com/nschloe/meshio)
//! through pyo3 (cargo feature `meshio`; issue 9): an independent reader
//! for ctc's VTU output and for the gmsh files ctc's own reader parses.
//!
//! - [`read`]: any file meshio reads, as points, cell blocks, point data
//!   and (gmsh) physical groups;
//! - [`compare_vtu`]: a VTU written by ctc against the mesh, displacements,
//!   reactions and contact data it was written from;
//! - [`compare_gmsh`]: ctc's [`Mesh`] of a `.msh` file against meshio's
//!   reading of the same file, independently of node numbering.
//!
//! Needs a Python with meshio (`pip install meshio`); pyo3 builds against
//! the interpreter `PYO3_PYTHON` names (default: `python3` on the path).

use ctc_engine::contact::{ContactStatus, NodeContact};
use ctc_engine::mesh::{CellKind, Mesh};
use ctc_engine::model::Model;
use pyo3::ffi::c_str;
use pyo3::prelude::*;
use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

pub use crate::cross_check::CrossCheck;
use crate::cross_check::{canonical_cell, key, Key};

/// The Python side: flattens a `meshio.Mesh` into plain lists.
const HELPER: &std::ffi::CStr = c_str!(
    r#"
import meshio
import numpy as np

def read(path):
    m = meshio.read(path)
    points = np.asarray(m.points, dtype=float).reshape(len(m.points), -1)
    points = np.hstack([points, np.zeros((len(points), 3 - points.shape[1]))]).tolist()
    cells = [(b.type, np.asarray(b.data, dtype=np.int64).tolist()) for b in m.cells]
    point_data = {k: np.asarray(v, dtype=float).reshape(len(m.points), -1).tolist()
                  for k, v in m.point_data.items()}
    physical = []
    tags = m.cell_data.get("gmsh:physical")
    if tags is not None:
        names = {(int(v[1]), int(v[0])): k for k, v in m.field_data.items()}
        for b, t in zip(m.cells, tags):
            dim = {"vertex": 0, "line": 1, "triangle": 2, "quad": 2}.get(b.type)
            for cell, tag in zip(np.asarray(b.data).tolist(), np.asarray(t).tolist()):
                physical.append((names.get((dim, int(tag)), "physical_%d" % int(tag)), dim, cell))
    return points, cells, point_data, physical
"#
);

/// A file as meshio reads it.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct MeshioMesh {
    /// Point coordinates (z = 0 added for 2D files).
    pub points: Vec<[f64; 3]>,
    /// Cell blocks: meshio cell type (`triangle`, `quad`, `line`, ...) and
    /// point indices of each cell.
    pub cells: Vec<(String, Vec<Vec<usize>>)>,
    /// Point data: name -> one row of components per point.
    pub point_data: BTreeMap<String, Vec<Vec<f64>>>,
    /// gmsh physical groups: (name, dimension, point indices of one element).
    pub physical: Vec<(String, usize, Vec<usize>)>,
}

/// What the Python helper returns: points, cell blocks, point data and
/// physical-group elements (dimension `None` for other cell types).
type Flattened = (
    Vec<[f64; 3]>,
    Vec<(String, Vec<Vec<usize>>)>,
    BTreeMap<String, Vec<Vec<f64>>>,
    Vec<(String, Option<usize>, Vec<usize>)>,
);

/// Reads `path` with Python's meshio.
pub fn read(path: &Path) -> Result<MeshioMesh, String> {
    let file = path
        .to_str()
        .ok_or_else(|| format!("{}: path is not UTF-8", path.display()))?;
    Python::with_gil(|py| -> PyResult<MeshioMesh> {
        let module =
            PyModule::from_code(py, HELPER, c_str!("ctc_meshio.py"), c_str!("ctc_meshio"))?;
        let (points, cells, point_data, physical): Flattened =
            module.getattr("read")?.call1((file,))?.extract()?;
        Ok(MeshioMesh {
            points,
            cells,
            point_data,
            physical: physical
                .into_iter()
                .filter_map(|(n, d, c)| Some((n, d?, c)))
                .collect(),
        })
    })
    .map_err(|e| format!("meshio could not read {}: {e}", path.display()))
}

/// What ctc wrote into one VTU file (the data it was written from).
#[derive(Debug, Clone, Copy)]
pub struct WrittenState<'a> {
    /// The model (mesh, contact pairs).
    pub model: &'a Model,
    /// Nodal displacements written.
    pub displacement: &'a [[f64; 2]],
    /// Nodal reactions written (`None`: the field was not requested).
    pub reaction: Option<&'a [[f64; 2]]>,
    /// Contact evaluation per pair written (`None`: not requested).
    pub contact: Option<&'a [Vec<NodeContact>]>,
}

/// Relative tolerance on values read back from a VTU file: ctc writes the
/// shortest decimal that round-trips an f64 and numpy parses it correctly
/// rounded, so values come back exactly; the margin is for safety only.
pub const VTU_TOLERANCE: f64 = 1e-15;

fn vtu_type(kind: CellKind) -> &'static str {
    match kind {
        CellKind::Tri3 => "triangle",
        CellKind::Quad4 => "quad",
        CellKind::Tet4 => "tetra",
        CellKind::Hex8 => "hexahedron",
        CellKind::Tri6 => "triangle6",
        CellKind::Quad8 | CellKind::Quad8R => "quad8",
        CellKind::Quad9 => "quad9",
        CellKind::Tet10 => "tetra10",
        CellKind::Hex20 | CellKind::Hex20R => "hexahedron20",
        CellKind::Hex27 => "hexahedron27",
    }
}

/// Compares the VTU file `path` (read by meshio) with the state it was
/// written from: points (reference coordinates, z = 0), cells (type and
/// connectivity, in order), `displacement`, and when present `reaction`,
/// `contact_gap`, `contact_pressure` and `contact_status`.
pub fn compare_vtu(path: &Path, state: &WrittenState<'_>) -> Result<CrossCheck, String> {
    let m = read(path)?;
    let model = state.model;
    let mut check = CrossCheck::default();
    if m.points.len() != model.mesh.nodes.len() {
        check.mismatches.push(format!(
            "{} points in the VTU, {} nodes in the model",
            m.points.len(),
            model.mesh.nodes.len()
        ));
        return Ok(check);
    }
    for (i, (p, n)) in m.points.iter().zip(&model.mesh.nodes).enumerate() {
        check.value("points.x", i, p[0], n[0], VTU_TOLERANCE);
        check.value("points.y", i, p[1], n[1], VTU_TOLERANCE);
        check.value("points.z", i, p[2], 0.0, VTU_TOLERANCE);
    }
    let read_cells: Vec<(&str, &Vec<usize>)> = m
        .cells
        .iter()
        .flat_map(|(t, list)| list.iter().map(move |c| (t.as_str(), c)))
        .collect();
    if read_cells.len() != model.mesh.cells.len() {
        check.mismatches.push(format!(
            "{} cells in the VTU, {} in the model",
            read_cells.len(),
            model.mesh.cells.len()
        ));
    } else {
        for (i, ((t, nodes), cell)) in read_cells.iter().zip(&model.mesh.cells).enumerate() {
            check.compared += 1;
            if *t != vtu_type(cell.kind) || nodes.as_slice() != cell.nodes {
                check.mismatches.push(format!(
                    "cell {i}: meshio read {t} {nodes:?}, ctc has {} {:?}",
                    vtu_type(cell.kind),
                    cell.nodes
                ));
            }
        }
    }
    let vector =
        |name: &str, values: &[[f64; 2]], check: &mut CrossCheck| match m.point_data.get(name) {
            None => check
                .mismatches
                .push(format!("point data `{name}` missing")),
            Some(rows) => {
                for (i, (row, v)) in rows.iter().zip(values).enumerate() {
                    for (c, &expected) in v.iter().enumerate() {
                        check.value(
                            name,
                            2 * i + c,
                            row.get(c).copied().unwrap_or(f64::NAN),
                            expected,
                            VTU_TOLERANCE,
                        );
                    }
                }
            }
        };
    vector("displacement", state.displacement, &mut check);
    if let Some(r) = state.reaction {
        vector("reaction", r, &mut check);
    }
    if let Some(contact) = state.contact {
        let n = model.mesh.nodes.len();
        let (mut gap, mut pressure, mut status) = (vec![0.0; n], vec![0.0; n], vec![-1.0; n]);
        for cp in &model.contacts {
            for &node in &cp.nodes {
                status[node] = 0.0;
            }
        }
        for c in contact.iter().flatten() {
            gap[c.node] = c.gap;
            pressure[c.node] = c.pressure;
            status[c.node] = if c.status == ContactStatus::Closed {
                1.0
            } else {
                0.0
            };
        }
        for (name, values) in [
            ("contact_gap", &gap),
            ("contact_pressure", &pressure),
            ("contact_status", &status),
        ] {
            match m.point_data.get(name) {
                None => check
                    .mismatches
                    .push(format!("point data `{name}` missing")),
                Some(rows) => {
                    for (i, (row, v)) in rows.iter().zip(values.iter()).enumerate() {
                        check.value(
                            name,
                            i,
                            row.first().copied().unwrap_or(f64::NAN),
                            *v,
                            VTU_TOLERANCE,
                        );
                    }
                }
            }
        }
    }
    Ok(check)
}

/// Coordinates of a point as exact bit patterns (for numbering-free sets).
/// Compares ctc's [`Mesh`] of a gmsh file with meshio's reading of the
/// same file: the sets of node coordinates used by cells, the cells (as
/// counter-clockwise coordinate cycles, so independent of numbering and
/// orientation), and for every named physical group of dimension 1 ctc's
/// edge set against meshio's lines (unordered coordinate pairs).
pub fn compare_gmsh(path: &Path, mesh: &Mesh) -> Result<CrossCheck, String> {
    let m = read(path)?;
    let mut check = CrossCheck::default();
    let pts: Vec<[f64; 2]> = m.points.iter().map(|p| [p[0], p[1]]).collect();
    let mut meshio_cells = BTreeSet::new();
    let mut used = BTreeSet::new();
    for (t, list) in &m.cells {
        if t != "triangle" && t != "quad" {
            continue;
        }
        for c in list {
            let corners: Vec<[f64; 2]> = c.iter().map(|&i| pts[i]).collect();
            used.extend(corners.iter().map(|&p| key(p)));
            meshio_cells.insert(canonical_cell(&corners));
        }
    }
    let ctc_nodes: BTreeSet<Key> = mesh.nodes.iter().map(|&p| key(p)).collect();
    check.compared += ctc_nodes.len();
    if ctc_nodes != used || ctc_nodes.len() != mesh.nodes.len() {
        check.mismatches.push(format!(
            "nodes: ctc has {} ({} distinct), meshio's cells use {}",
            mesh.nodes.len(),
            ctc_nodes.len(),
            used.len()
        ));
    }
    let ctc_cells: BTreeSet<Vec<Key>> = mesh
        .cells
        .iter()
        .map(|c| {
            let corners: Vec<[f64; 2]> = c.nodes.iter().map(|&i| mesh.nodes[i]).collect();
            canonical_cell(&corners)
        })
        .collect();
    check.compared += ctc_cells.len();
    if ctc_cells != meshio_cells || ctc_cells.len() != mesh.cells.len() {
        let only_ctc = ctc_cells.difference(&meshio_cells).count();
        let only_meshio = meshio_cells.difference(&ctc_cells).count();
        check.mismatches.push(format!(
            "cells: {} in ctc, {} distinct in meshio; {only_ctc} only in ctc, {only_meshio} only in meshio",
            mesh.cells.len(),
            meshio_cells.len()
        ));
    }
    let mut groups: BTreeMap<&str, BTreeSet<[Key; 2]>> = BTreeMap::new();
    for (name, dim, cell) in &m.physical {
        if *dim == 1 && cell.len() == 2 {
            let (a, b) = (key(pts[cell[0]]), key(pts[cell[1]]));
            groups.entry(name).or_default().insert([a.min(b), a.max(b)]);
        }
    }
    for (name, lines) in groups {
        check.compared += lines.len();
        let Some(edges) = mesh.edge_sets.get(name) else {
            // Interior-only groups become node sets only (documented in gmsh.rs).
            if !mesh.node_sets.contains_key(name) {
                check.mismatches.push(format!(
                    "physical group `{name}`: no set of that name in ctc"
                ));
            }
            continue;
        };
        let ctc: BTreeSet<[Key; 2]> = edges
            .iter()
            .map(|&[a, b]| {
                let (ka, kb) = (key(mesh.nodes[a]), key(mesh.nodes[b]));
                [ka.min(kb), ka.max(kb)]
            })
            .collect();
        if ctc != lines {
            check.mismatches.push(format!(
                "physical group `{name}`: ctc has {} edges, meshio {} lines, {} in common",
                ctc.len(),
                lines.len(),
                ctc.intersection(&lines).count()
            ));
        }
    }
    Ok(check)
}
