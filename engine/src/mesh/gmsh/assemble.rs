//! Turns the raw file content into a [`Mesh`]: dense node numbering,
//! counter-clockwise cells, named sets from the physical groups.
//!
//! Second-order cells (tri6 9, quad8 16, quad9 10) keep gmsh's node order,
//! which is the engine's (corners, edge midpoints from edge 0-1 on, the
//! centre); their midside nodes stay where gmsh put them (on the curved
//! geometry). Their boundary lines are 3-node lines (8): the edge sets hold
//! the corner pairs (`Mesh::edge_midsides` finds the midside node), the
//! node sets all three nodes.

use super::raw::{ElementType, RawElement, RawMesh};
use super::tags::TagIndex;
use crate::mesh::quality::polygon_area;
use crate::mesh::{CellKind, Mesh, MeshError};
use rustc_hash::{FxHashMap, FxHashSet};

use std::collections::BTreeMap;

/// The sorted nodes of a planar cell (at most 9, the quad9), the key of
/// its duplicates (MSH 2 repeats an element once per physical group).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
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

    // the raw node position of every element node (flat, as
    // `raw.element_nodes`); an unknown tag is an error at the first
    // element (file order) that uses it
    let mut pos_all: Vec<usize> = Vec::with_capacity(raw.element_nodes.len());
    for e in &raw.elements {
        debug_assert_eq!(pos_all.len(), e.first_node);
        for &t in raw.nodes_of(e) {
            pos_all.push(position(t, e.line)?);
        }
    }
    let pos_of = |e: &RawElement| &pos_all[e.first_node..e.first_node + e.kind.nodes()];

    // cells: the surface elements, deduplicated (MSH 2 repeats an element
    // once per physical group it belongs to): the first of the elements
    // with the same sorted nodes, in file order
    let surface: Vec<&RawElement> = raw.elements.iter().filter(|e| e.kind.dim() == 2).collect();
    let keep = first_of_equal_keys(&surface, raw.nodes.len(), |e| pos_of(e));
    let cells: Vec<&[usize]> = surface
        .iter()
        .zip(&keep)
        .filter(|(_, &k)| k)
        .map(|(e, _)| pos_of(e))
        .collect();
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
        for &p in c.iter() {
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
        // at most 9 nodes (quad9): no allocation per cell
        let mut n = [0usize; 9];
        let n = &mut n[..c.len()];
        for (k, &p) in n.iter_mut().zip(c.iter()) {
            *k = renum(p);
        }
        let kind = match n.len() {
            3 => CellKind::Tri3,
            4 => CellKind::Quad4,
            6 => CellKind::Tri6,
            8 => CellKind::Quad8,
            _ => CellKind::Quad9,
        };
        let corners = kind.corner_count();
        let mut pts = [[0.0; 2]; 4];
        for (p, &k) in pts.iter_mut().zip(&n[..corners]) {
            *p = mesh.nodes[k];
        }
        if polygon_area(&pts[..corners]) < 0.0 {
            // reflect: corners 0, last, .., 1; the midside nodes follow
            let reflection: Vec<usize> = std::iter::once(0).chain((1..corners).rev()).collect();
            let reflected = crate::mesh::elevate::permute_corners(kind, n, &reflection);
            mesh.cells.push_nodes(kind, &reflected);
        } else {
            mesh.cells.push_nodes(kind, n);
        }
    }

    // the nodes of an element of a physical group (new numbers), or the
    // error of an element that is not on the cells
    let group_nodes = |e: &RawElement, out: &mut Vec<usize>| -> Result<(), MeshError> {
        out.clear();
        let tags = raw.nodes_of(e);
        for &t in tags {
            match by_tag.get(t).and_then(|p| new_of[p]) {
                Some(n) => out.push(n),
                None => {
                    return Err(MeshError::at_line(
                        e.line,
                        match e.kind {
                            ElementType::Point => format!(
                                "physical point refers to node tag {}, which belongs to no triangle or quadrangle",
                                tags[0]
                            ),
                            _ => format!(
                                "line element (node tags {} {}) of a physical group is not an edge of any triangle or quadrangle",
                                tags[0], tags[1]
                            ),
                        },
                    ))
                }
            }
        }
        Ok(())
    };
    let is_line = |e: &RawElement| matches!(e.kind, ElementType::Line | ElementType::Line3);
    let mut nodes = Vec::new();

    // the cell edges of the physical lines: undirected key -> (count,
    // direction in its first cell); only these keys are counted
    let mut edges: FxHashMap<(usize, usize), (usize, [usize; 2])> = FxHashMap::default();
    for e in &raw.elements {
        if is_line(e) && !raw.physicals_of(e).is_empty() && group_nodes(e, &mut nodes).is_ok() {
            edges.insert(
                (nodes[0].min(nodes[1]), nodes[0].max(nodes[1])),
                (0, [0, 0]),
            );
        }
    }
    if !edges.is_empty() {
        for c in &mesh.cells {
            let n = c.nodes;
            let corners = c.kind.corner_count();
            for i in 0..corners {
                let (a, b) = (n[i], n[(i + 1) % corners]);
                if let Some(entry) = edges.get_mut(&(a.min(b), a.max(b))) {
                    if entry.0 == 0 {
                        entry.1 = [a, b];
                    }
                    entry.0 += 1;
                }
            }
        }
    }

    // physical groups
    let mut groups: BTreeMap<(usize, i64), Group> = BTreeMap::new();
    for e in &raw.elements {
        let physicals = raw.physicals_of(e);
        if physicals.is_empty() {
            continue;
        }
        let dim = e.kind.dim();
        group_nodes(e, &mut nodes)?;
        let mut edge = None;
        if is_line(e) {
            let key = (nodes[0].min(nodes[1]), nodes[0].max(nodes[1]));
            match edges.get(&key) {
                None | Some(&(0, _)) => {
                    let tags = raw.nodes_of(e);
                    return Err(MeshError::at_line(
                        e.line,
                        format!(
                            "line element (node tags {} {}) of a physical group is not an edge of any triangle or quadrangle",
                            tags[0], tags[1]
                        ),
                    ));
                }
                Some(&(1, dir)) => edge = Some((key, Some(dir))),
                Some(_) => edge = Some((key, None)),
            }
        }
        for &p in physicals {
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
        mesh.node_sets
            .insert(name.clone(), sorted_unique(nodes, mesh.nodes.len()));
        if let Some(e) = edge_set {
            mesh.edge_sets.insert(name.clone(), e);
        }
    }
    Ok(mesh)
}

/// Per element of `elements`, whether it is the first (in their order) of
/// those with its sorted node positions (`positions(e)`, each below
/// `nodes`): the elements bucketed by their smallest node (counting sort,
/// order kept), each bucket sorted by key then order (no hash of the keys;
/// issue 20: the hash set of the 80,000 keys of the tutorial mesh).
fn first_of_equal_keys<'a, E>(
    elements: &[E],
    nodes: usize,
    positions: impl Fn(&E) -> &'a [usize],
) -> Vec<bool> {
    let key = |e: &E| CellKey::of(positions(e));
    let mut start = vec![0usize; nodes + 1];
    for e in elements {
        if let Some(&m) = positions(e).iter().min() {
            start[m + 1] += 1;
        }
    }
    for i in 0..nodes {
        start[i + 1] += start[i];
    }
    let mut fill = start.clone();
    let mut order = vec![0usize; start[nodes]];
    for (i, e) in elements.iter().enumerate() {
        if let Some(&m) = positions(e).iter().min() {
            order[fill[m]] = i;
            fill[m] += 1;
        }
    }
    let mut keep = vec![true; elements.len()];
    let mut bucket: Vec<(CellKey, usize)> = Vec::new();
    for m in 0..nodes {
        let members = &order[start[m]..start[m + 1]];
        if members.len() < 2 {
            continue;
        }
        bucket.clear();
        bucket.extend(members.iter().map(|&i| (key(&elements[i]), i)));
        bucket.sort_unstable();
        for w in bucket.windows(2) {
            if w[0].0 == w[1].0 {
                keep[w[1].1] = false;
            }
        }
    }
    keep
}

/// `nodes` (each below `count`) sorted, without repetitions.
fn sorted_unique(mut nodes: Vec<usize>, count: usize) -> Vec<usize> {
    if nodes.len() < count / 8 {
        nodes.sort_unstable();
        nodes.dedup();
        return nodes;
    }
    // many nodes: a mark per node, read in order
    let mut mark = vec![false; count];
    for &n in &nodes {
        mark[n] = true;
    }
    nodes.clear();
    nodes.extend((0..count).filter(|&n| mark[n]));
    nodes
}
