//! Geometric selections of nodes and boundary edges.
//!
//! Coordinates are compared with a tolerance of [`RELATIVE_TOLERANCE`] times
//! the diagonal of the bounding box of the candidate nodes, so `x = 0`
//! selects nodes at `x = 1e-17` on a body of size 1 but not at `x = 1e-3`.

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

/// Tolerance of the coordinate comparisons, relative to the diagonal of the
/// candidates' bounding box.
pub const RELATIVE_TOLERANCE: f64 = 1e-6;

/// Absolute tolerance for `nodes`: [`RELATIVE_TOLERANCE`] x the diagonal of
/// their bounding box (0 for fewer than two distinct points; non-finite
/// coordinates are ignored).
pub fn tolerance(mesh: &Mesh, nodes: impl Iterator<Item = usize>) -> f64 {
    let mut lo = [f64::INFINITY; 2];
    let mut hi = [f64::NEG_INFINITY; 2];
    for i in nodes {
        let p = mesh.nodes[i];
        if p.iter().all(|v| v.is_finite()) {
            for d in 0..2 {
                lo[d] = lo[d].min(p[d]);
                hi[d] = hi[d].max(p[d]);
            }
        }
    }
    if lo[0] > hi[0] {
        return 0.0;
    }
    RELATIVE_TOLERANCE * (hi[0] - lo[0]).hypot(hi[1] - lo[1])
}

/// Whether the point `p` is selected by `sel` with absolute tolerance `tol`
/// (`Nearest` is not a per-point test: always false here).
fn matches(p: [f64; 2], sel: &Selection, tol: f64) -> bool {
    match *sel {
        Selection::XEquals(x) => (p[0] - x).abs() <= tol,
        Selection::YEquals(y) => (p[1] - y).abs() <= tol,
        Selection::Box { min, max } => {
            (0..2).all(|d| p[d] >= min[d].min(max[d]) - tol && p[d] <= max[d].max(min[d]) + tol)
        }
        Selection::Nearest(_) => false,
    }
}

/// The node of `candidates` closest to `target` (ties: the lowest number).
fn nearest(mesh: &Mesh, candidates: &[usize], target: [f64; 2]) -> Option<usize> {
    let mut best: Option<(f64, usize)> = None;
    for &i in candidates {
        let p = mesh.nodes[i];
        let d = (p[0] - target[0]).hypot(p[1] - target[1]);
        if !d.is_finite() {
            continue;
        }
        best = match best {
            Some((bd, bi)) if bd < d || (bd == d && bi < i) => Some((bd, bi)),
            _ => Some((d, i)),
        };
    }
    best.map(|(_, i)| i)
}

/// Nodes among `candidates` (global numbers) selected by `sel`, sorted and
/// unique. The tolerance is relative to the candidates' bounding box. The
/// box corners may be given in any order. `Nearest` gives one node (none
/// for no candidates).
pub fn select_nodes(mesh: &Mesh, candidates: &[usize], sel: &Selection) -> Vec<usize> {
    let mut out: Vec<usize> = match *sel {
        Selection::Nearest(target) => nearest(mesh, candidates, target).into_iter().collect(),
        _ => {
            let tol = tolerance(mesh, candidates.iter().copied());
            candidates
                .iter()
                .copied()
                .filter(|&i| matches(mesh.nodes[i], sel, tol))
                .collect()
        }
    };
    out.sort_unstable();
    out.dedup();
    out
}

/// Boundary edges among `boundary` whose two nodes are both selected by
/// `sel` (candidates: the nodes of `boundary`), in the order of `boundary`,
/// orientation kept. `Nearest` selects a single node, hence no edge.
pub fn select_edges(mesh: &Mesh, boundary: &[[usize; 2]], sel: &Selection) -> Vec<[usize; 2]> {
    if let Selection::Nearest(_) = sel {
        return Vec::new();
    }
    let tol = tolerance(mesh, boundary.iter().flatten().copied());
    boundary
        .iter()
        .copied()
        .filter(|e| e.iter().all(|&n| matches(mesh.nodes[n], sel, tol)))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::generate::{generate, Grading, MeshSpec};
    use crate::mesh::CellKind;

    fn block() -> Mesh {
        generate(&MeshSpec::Rectangle {
            origin: [-4.0, -4.0],
            size: [8.0, 4.0],
            divisions: [8, 4],
            grading: [Grading::Uniform; 2],
            kind: CellKind::Quad4,
        })
        .unwrap()
    }

    #[test]
    fn select_nodes_y_equals_bottom_row_of_rectangle() {
        let m = block();
        let all: Vec<usize> = (0..m.nodes.len()).collect();
        let sel = select_nodes(&m, &all, &Selection::YEquals(-4.0));
        assert_eq!(sel, m.node_sets["bottom"]);
        // within tolerance (1e-6 * diagonal ~ 8.9e-6) but not beyond
        let sel = select_nodes(&m, &all, &Selection::YEquals(-4.0 + 5e-6));
        assert_eq!(sel.len(), 9);
        let sel = select_nodes(&m, &all, &Selection::YEquals(-4.0 + 2e-5));
        assert!(sel.is_empty());
        let sel = select_nodes(&m, &all, &Selection::XEquals(4.0));
        assert_eq!(sel, m.node_sets["right"]);
    }

    #[test]
    fn select_nodes_box_is_closed_and_corner_order_free() {
        let m = block();
        let all: Vec<usize> = (0..m.nodes.len()).collect();
        let b = Selection::Box {
            min: [-1.0, -1.0],
            max: [1.0, 0.0],
        };
        let sel = select_nodes(&m, &all, &b);
        // x in {-1, 0, 1}, y in {-1, 0}
        assert_eq!(sel.len(), 6);
        let swapped = Selection::Box {
            min: [1.0, 0.0],
            max: [-1.0, -1.0],
        };
        assert_eq!(select_nodes(&m, &all, &swapped), sel);
    }

    #[test]
    fn select_nodes_nearest_picks_one_lowest_on_tie() {
        let m = block();
        let all: Vec<usize> = (0..m.nodes.len()).collect();
        let sel = select_nodes(&m, &all, &Selection::Nearest([0.1, -0.2]));
        assert_eq!(sel.len(), 1);
        assert_eq!(m.nodes[sel[0]], [0.0, 0.0]);
        // equidistant from (0,0) and (1,0): lowest node number wins
        let sel = select_nodes(&m, &all, &Selection::Nearest([0.5, 0.0]));
        assert_eq!(m.nodes[sel[0]], [0.0, 0.0]);
        assert!(select_nodes(&m, &[], &Selection::Nearest([0.0, 0.0])).is_empty());
    }

    #[test]
    fn select_edges_top_of_rectangle_keeps_orientation() {
        let m = block();
        let boundary = m.boundary_edges(0..m.cells.len());
        let mut sel = select_edges(&m, &boundary, &Selection::YEquals(0.0));
        let mut top = m.edge_sets["top"].clone();
        sel.sort();
        top.sort();
        assert_eq!(sel, top);
        let part = select_edges(
            &m,
            &boundary,
            &Selection::Box {
                min: [-1.0, -0.01],
                max: [1.0, 0.01],
            },
        );
        assert_eq!(part.len(), 2);
        assert!(select_edges(&m, &boundary, &Selection::Nearest([0.0, 0.0])).is_empty());
    }
}
