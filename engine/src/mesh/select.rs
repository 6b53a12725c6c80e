//! Geometric selections of nodes, boundary edges (2D) and boundary faces
//! (3D), in any dimension `D`.
//!
//! Coordinates are compared with a tolerance of [`RELATIVE_TOLERANCE`] times
//! the diagonal of the bounding box of the candidate nodes, so `x = 0`
//! selects nodes at `x = 1e-17` on a body of size 1 but not at `x = 1e-3`.

use super::{Facet, Mesh};

/// A geometric selection in dimension `D`, evaluated on reference
/// coordinates with a tolerance relative to the body size. `Selection`
/// without a parameter is the planar one.
#[derive(Debug, Clone, PartialEq)]
pub enum Selection<const D: usize = 2> {
    /// Nodes with x = value (within tolerance).
    XEquals(f64),
    /// Nodes with y = value (within tolerance).
    YEquals(f64),
    /// Nodes with z = value (within tolerance); selects nothing in 2D.
    ZEquals(f64),
    /// Nodes inside the closed box [min, max].
    Box {
        /// Lower corner.
        min: [f64; D],
        /// Upper corner.
        max: [f64; D],
    },
    /// The single node closest to the point.
    Nearest([f64; D]),
}

impl<const D: usize> Selection<D> {
    /// The coordinate axis (0 = x, 1 = y, 2 = z) and value of a plane
    /// selection `x = ..`, `y = ..`, `z = ..`.
    pub fn plane(&self) -> Option<(usize, f64)> {
        match *self {
            Selection::XEquals(v) => Some((0, v)),
            Selection::YEquals(v) => Some((1, v)),
            Selection::ZEquals(v) => Some((2, v)),
            Selection::Box { .. } | Selection::Nearest(_) => None,
        }
    }
}

/// Tolerance of the coordinate comparisons, relative to the diagonal of the
/// candidates' bounding box.
pub const RELATIVE_TOLERANCE: f64 = 1e-6;

/// The bounding box `(lo, hi)` of the finite points among `nodes` (`None`
/// when there is none).
pub fn bounds<const D: usize>(
    mesh: &Mesh<D>,
    nodes: impl Iterator<Item = usize>,
) -> Option<([f64; D], [f64; D])> {
    let mut lo = [f64::INFINITY; D];
    let mut hi = [f64::NEG_INFINITY; D];
    let mut any = false;
    for i in nodes {
        let p = mesh.nodes[i];
        if p.iter().all(|v| v.is_finite()) {
            any = true;
            for d in 0..D {
                lo[d] = lo[d].min(p[d]);
                hi[d] = hi[d].max(p[d]);
            }
        }
    }
    any.then_some((lo, hi))
}

/// Absolute tolerance for `nodes`: [`RELATIVE_TOLERANCE`] x the diagonal of
/// their bounding box (0 for fewer than two distinct points; non-finite
/// coordinates are ignored).
pub fn tolerance<const D: usize>(mesh: &Mesh<D>, nodes: impl Iterator<Item = usize>) -> f64 {
    match bounds(mesh, nodes) {
        None => 0.0,
        Some((lo, hi)) => {
            let d2: f64 = (0..D).map(|d| (hi[d] - lo[d]).powi(2)).sum();
            RELATIVE_TOLERANCE * d2.sqrt()
        }
    }
}

/// Whether the point `p` is selected by `sel` with absolute tolerance `tol`
/// (`Nearest` is not a per-point test: always false here).
fn matches<const D: usize>(p: &[f64; D], sel: &Selection<D>, tol: f64) -> bool {
    match sel {
        Selection::XEquals(_) | Selection::YEquals(_) | Selection::ZEquals(_) => {
            let (axis, v) = sel.plane().expect("a plane selection");
            axis < D && (p[axis] - v).abs() <= tol
        }
        Selection::Box { min, max } => {
            (0..D).all(|d| p[d] >= min[d].min(max[d]) - tol && p[d] <= max[d].max(min[d]) + tol)
        }
        Selection::Nearest(_) => false,
    }
}

/// The node of `candidates` closest to `target` (ties: the lowest number).
fn nearest<const D: usize>(
    mesh: &Mesh<D>,
    candidates: &[usize],
    target: [f64; D],
) -> Option<usize> {
    let mut best: Option<(f64, usize)> = None;
    for &i in candidates {
        let p = mesh.nodes[i];
        let d: f64 = (0..D)
            .map(|k| (p[k] - target[k]).powi(2))
            .sum::<f64>()
            .sqrt();
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
pub fn select_nodes<const D: usize>(
    mesh: &Mesh<D>,
    candidates: &[usize],
    sel: &Selection<D>,
) -> Vec<usize> {
    let mut out: Vec<usize> = match *sel {
        Selection::Nearest(target) => nearest(mesh, candidates, target).into_iter().collect(),
        _ => {
            let tol = tolerance(mesh, candidates.iter().copied());
            candidates
                .iter()
                .copied()
                .filter(|&i| matches(&mesh.nodes[i], sel, tol))
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
        .filter(|e| e.iter().all(|&n| matches(&mesh.nodes[n], sel, tol)))
        .collect()
}

/// Boundary facets (faces of a solid, edges of a planar mesh) among
/// `boundary` whose nodes are all selected by `sel` (candidates: the nodes
/// of `boundary`), in the order of `boundary`, node order kept. `Nearest`
/// selects a single node, hence no facet.
pub fn select_facets<const D: usize>(
    mesh: &Mesh<D>,
    boundary: &[Facet],
    sel: &Selection<D>,
) -> Vec<Facet> {
    if let Selection::Nearest(_) = sel {
        return Vec::new();
    }
    let tol = tolerance(
        mesh,
        boundary.iter().flat_map(|f| f.nodes().iter().copied()),
    );
    boundary
        .iter()
        .filter(|f| f.nodes().iter().all(|&n| matches(&mesh.nodes[n], sel, tol)))
        .copied()
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

    fn brick(kind: CellKind) -> Mesh<3> {
        // [0, 2] x [0, 1] x [0, 1], 4 x 2 x 2 divisions
        crate::mesh::generate::solid::brick(
            [0.0, 0.0, 0.0],
            [2.0, 1.0, 1.0],
            [4, 2, 2],
            [Grading::Uniform; 3],
            kind,
        )
        .unwrap()
    }

    #[test]
    fn select_nodes_z_equals_in_3d_is_relative_to_the_body_diagonal() {
        let m = brick(CellKind::Hex8);
        let all: Vec<usize> = (0..m.nodes.len()).collect();
        let top = select_nodes(&m, &all, &Selection::ZEquals(1.0));
        assert_eq!(top, m.node_sets["zmax"]);
        assert_eq!(top.len(), 5 * 3);
        // diagonal sqrt(6) ~ 2.449: tolerance ~ 2.449e-6
        assert_eq!(
            select_nodes(&m, &all, &Selection::ZEquals(1.0 + 2.4e-6)),
            top
        );
        assert!(select_nodes(&m, &all, &Selection::ZEquals(1.0 + 2.5e-6)).is_empty());
        // an interior plane has nodes
        assert_eq!(select_nodes(&m, &all, &Selection::ZEquals(0.5)).len(), 15);
        // z in a planar mesh selects nothing (the deck refuses it first)
        let flat = block();
        let all2: Vec<usize> = (0..flat.nodes.len()).collect();
        assert!(select_nodes(&flat, &all2, &Selection::ZEquals(0.0)).is_empty());
    }

    #[test]
    fn select_nodes_box_and_nearest_in_3d() {
        let m = brick(CellKind::Tet4);
        let all: Vec<usize> = (0..m.nodes.len()).collect();
        let b = Selection::Box {
            min: [1.5, 1.0, 1.0],
            max: [0.5, 0.0, 0.6],
        };
        // x in {0.5, 1, 1.5}, y in {0, 0.5, 1}, z = 1
        let sel = select_nodes(&m, &all, &b);
        assert_eq!(sel.len(), 9);
        assert!(sel.iter().all(|&n| m.nodes[n][2] == 1.0));
        let near = select_nodes(&m, &all, &Selection::Nearest([1.9, 0.1, 0.6]));
        assert_eq!(near.len(), 1);
        assert_eq!(m.nodes[near[0]], [2.0, 0.0, 0.5]);
    }

    #[test]
    fn select_facets_z_equals_matches_the_generator_face_sets() {
        for kind in [CellKind::Hex8, CellKind::Tet4] {
            let m = brick(kind);
            let boundary = m.boundary_facets(0..m.cells.len());
            for (axis, value, set) in [(2, 1.0, "zmax"), (0, 0.0, "xmin"), (1, 1.0, "ymax")] {
                let sel = match axis {
                    0 => Selection::XEquals(value),
                    1 => Selection::YEquals(value),
                    _ => Selection::ZEquals(value),
                };
                let mut got = select_facets(&m, &boundary, &sel);
                let mut want = m.face_sets[set].clone();
                got.sort();
                want.sort();
                assert_eq!(got, want, "{kind:?} {set}");
            }
            // an interior plane has nodes but no boundary face
            assert!(select_facets(&m, &boundary, &Selection::ZEquals(0.5)).is_empty());
            // half of the top face: x in [0, 1]
            let half = Selection::Box {
                min: [0.0, 0.0, 1.0],
                max: [1.0, 1.0, 1.0],
            };
            let per = if kind == CellKind::Hex8 { 1 } else { 2 };
            assert_eq!(select_facets(&m, &boundary, &half).len(), 2 * 2 * per);
            assert!(select_facets(&m, &boundary, &Selection::Nearest([0.0; 3])).is_empty());
        }
    }
}
