//! Turns the raw file content into a [`Mesh`]: dense node numbering,
//! counter-clockwise cells, named sets from the physical groups.
//!
//! Second-order cells (tri6 9, quad8 16, quad9 10) keep gmsh's node order,
//! which is the engine's (corners, edge midpoints from edge 0-1 on, the
//! centre); their midside nodes stay where gmsh put them (on the curved
//! geometry). Their boundary lines are 3-node lines (8): the edge sets hold
//! the corner pairs (`Mesh::edge_midsides` finds the midside node), the
//! node sets all three nodes.

use super::raw::{ElementType, RawMesh};
use super::tags::TagIndex;
use crate::mesh::quality::polygon_area;
use crate::mesh::{Cell, CellKind, Mesh, MeshError};
use rustc_hash::{FxHashMap, FxHashSet};
use std::collections::BTreeMap;

/// The sorted nodes of a planar cell (at most 9, the quad9), the key of
/// its duplicates (MSH 2 repeats an element once per physical group).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
struct CellKey([usize; 9]);

impl CellKey {
    /// The key of a cell with nodes `pos` (at most 9).
    fn of(pos: &[usize]) -> Self {
        let mut k = [usize::MAX; 9];
        k[..pos.len()].copy_from_slice(pos);
        k[..pos.len()].sort_unstable();
        CellKey(k)
    }
}

/// What one physical group collects.
#[derive(Default)]
struct Group {
    /// Nodes (new numbers), unsorted, may repeat.
    nodes: Vec<usize>,
    /// Boundary edges, oriented with the body on the left, file order.
    edges: Vec<[usize; 2]>,
    /// Undirected keys of the edges already taken.
    seen: FxHashSet<(usize, usize)>,
    /// Line of the first line element shared by two cells.
    interior_line: Option<usize>,
    /// Line of the first element of the group.
    first_line: usize,
}

/// Assembles the mesh. `eof_line` is the last line of the file (for errors
/// that belong to no line).
pub fn assemble(raw: RawMesh, eof_line: usize) -> Result<Mesh, MeshError> {
    if !raw.has_nodes {
        return Err(MeshError::at_line(
            eof_line,
            "the file has no $Nodes section",
        ));
    }
    if !raw.has_elements {
        return Err(MeshError::at_line(
            eof_line,
            "the file has no $Elements section",
        ));
    }

    // node tag -> position in raw.nodes
    let by_tag = TagIndex::new(&raw.nodes)?;
    let position = |tag: u64, line: usize| -> Result<usize, MeshError> {
        by_tag.get(tag).ok_or_else(|| {
            MeshError::at_line(
                line,
                format!("the element refers to node tag {tag}, which is not in $Nodes"),
            )
        })
    };

    // cells (raw node positions), deduplicated (MSH 2 repeats an element once
    // per physical group it belongs to)
    let mut cells: Vec<Vec<usize>> = Vec::new();
    let mut cell_keys: FxHashSet<CellKey> = FxHashSet::default();
    for e in &raw.elements {
        let mut pos = Vec::with_capacity(e.kind.nodes());
        for &t in &e.nodes[..e.kind.nodes()] {
            pos.push(position(t, e.line)?);
        }
        if e.kind.dim() == 2 && cell_keys.insert(CellKey::of(&pos)) {
            cells.push(pos);
        }
    }
    if cells.is_empty() {
        return Err(MeshError::at_line(
            eof_line,
            "the file has no triangles or quadrangles (type 2, 3, 9, 16 or 10). If physical groups are \
             defined, gmsh saves only their elements: add a Physical Surface, or set \
             Mesh.SaveAll = 1",
        ));
    }

    // dense numbering of the nodes used by cells, in file order
    let mut new_of: Vec<Option<usize>> = vec![None; raw.nodes.len()];
    for c in &cells {
        for &p in c {
            new_of[p] = Some(0);
        }
    }
    let mut mesh = Mesh::default();
    for (i, n) in raw.nodes.iter().enumerate() {
        if new_of[i].is_some() {
            new_of[i] = Some(mesh.nodes.len());
            mesh.nodes.push([n.xyz[0], n.xyz[1]]);
        }
    }
    let renum = |p: usize| new_of[p].expect("cell nodes are numbered");
    for c in &cells {
        let mut n: Vec<usize> = c.iter().map(|&p| renum(p)).collect();
        let kind = match n.len() {
            3 => CellKind::Tri3,
            4 => CellKind::Quad4,
            6 => CellKind::Tri6,
            8 => CellKind::Quad8,
            _ => CellKind::Quad9,
        };
        let corners = kind.corner_count();
        let pts: Vec<[f64; 2]> = n[..corners].iter().map(|&k| mesh.nodes[k]).collect();
        if polygon_area(&pts) < 0.0 {
            // reflect: corners 0, last, .., 1; the midside nodes follow
            let reflection: Vec<usize> = std::iter::once(0).chain((1..corners).rev()).collect();
            n = crate::mesh::elevate::permute_corners(kind, &n, &reflection);
        }
        mesh.cells.push(Cell { kind, nodes: n });
    }

    // every cell edge: undirected key -> (count, direction in its first cell)
    let mut edges: FxHashMap<(usize, usize), (usize, [usize; 2])> = FxHashMap::default();
    edges.reserve(2 * mesh.cells.len() + mesh.nodes.len());
    for c in &mesh.cells {
        let n = c.nodes;
        let corners = c.kind.corner_count();
        for i in 0..corners {
            let (a, b) = (n[i], n[(i + 1) % corners]);
            edges.entry((a.min(b), a.max(b))).or_insert((0, [a, b])).0 += 1;
        }
    }

    // physical groups
    let mut groups: BTreeMap<(usize, i64), Group> = BTreeMap::new();
    for e in &raw.elements {
        if e.physicals.is_empty() {
            continue;
        }
        let dim = e.kind.dim();
        let nodes: Vec<usize> = e.nodes[..e.kind.nodes()]
            .iter()
            .map(|&t| by_tag.get(t).and_then(|p| new_of[p]))
            .collect::<Option<Vec<usize>>>()
            .ok_or_else(|| {
                MeshError::at_line(
                    e.line,
                    match e.kind {
                        ElementType::Point => format!(
                            "physical point refers to node tag {}, which belongs to no triangle or quadrangle",
                            e.nodes[0]
                        ),
                        _ => format!(
                            "line element (node tags {} {}) of a physical group is not an edge of any triangle or quadrangle",
                            e.nodes[0], e.nodes[1]
                        ),
                    },
                )
            })?;
        let mut edge = None;
        if matches!(e.kind, ElementType::Line | ElementType::Line3) {
            let key = (nodes[0].min(nodes[1]), nodes[0].max(nodes[1]));
            match edges.get(&key) {
                None => {
                    return Err(MeshError::at_line(
                        e.line,
                        format!(
                            "line element (node tags {} {}) of a physical group is not an edge of any triangle or quadrangle",
                            e.nodes[0], e.nodes[1]
                        ),
                    ))
                }
                Some(&(1, dir)) => edge = Some((key, Some(dir))),
                Some(_) => edge = Some((key, None)),
            }
        }
        for &p in &e.physicals {
            let g = groups.entry((dim, p)).or_insert_with(|| Group {
                first_line: e.line,
                ..Default::default()
            });
            g.nodes.extend_from_slice(&nodes);
            match edge {
                Some((key, Some(dir))) if g.seen.insert(key) => g.edges.push(dir),
                Some((_, None)) => {
                    g.interior_line.get_or_insert(e.line);
                }
                _ => {}
            }
        }
    }

    // names; groups of different dimensions may share a name only when the
    // file names them so
    let mut by_name: BTreeMap<String, Vec<(usize, i64, bool)>> = BTreeMap::new();
    for &(dim, tag) in groups.keys() {
        let (name, named) = match raw.names.get(&(dim, tag)) {
            Some(n) => (n.clone(), true),
            None => (format!("physical_{tag}"), false),
        };
        by_name.entry(name).or_default().push((dim, tag, named));
    }
    for (name, list) in &by_name {
        if list.len() > 1 && list.iter().any(|g| !g.2) {
            let (d1, t1, _) = list[0];
            let (d2, t2, _) = list[1];
            return Err(MeshError::at_line(
                groups[&(d2, t2)].first_line,
                format!(
                    "physical groups (dimension {d1}, tag {t1}) and (dimension {d2}, tag {t2}) \
                     would both be called '{name}': give them names in gmsh \
                     (e.g. Physical Curve(\"top\") = {{..}})"
                ),
            ));
        }
        let mut nodes = Vec::new();
        let mut edge_set: Option<Vec<[usize; 2]>> = None;
        for &(dim, tag, _) in list {
            let g = &groups[&(dim, tag)];
            nodes.extend_from_slice(&g.nodes);
            if dim == 1 {
                match (g.edges.is_empty(), g.interior_line) {
                    (false, Some(line)) => {
                        return Err(MeshError::at_line(
                            line,
                            format!(
                                "physical group '{name}' mixes boundary lines with a line shared by two cells: \
                                 edge sets (loads, contact) must lie on the boundary"
                            ),
                        ))
                    }
                    (false, None) => edge_set = Some(g.edges.clone()),
                    (true, _) => {} // interior curve: node set only
                }
            }
        }
        nodes.sort_unstable();
        nodes.dedup();
        mesh.node_sets.insert(name.clone(), nodes);
        if let Some(e) = edge_set {
            mesh.edge_sets.insert(name.clone(), e);
        }
    }
    Ok(mesh)
}
