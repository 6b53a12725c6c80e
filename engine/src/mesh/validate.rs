//! Mesh quality checks run before any analysis.
//!
//! [`check`] reports every problem at once, one [`MeshError`] each (long
//! lists of the same kind are cut after [`MAX_REPORTED`] entries with a
//! count of the rest).

use super::quality::cell_area;
use super::{Mesh, MeshError};
use std::collections::HashMap;

/// At most this many problems of one kind are listed individually.
pub const MAX_REPORTED: usize = 20;

/// Relative tolerance for coincident nodes: distance <= this x the diagonal
/// of the mesh bounding box.
pub const DUPLICATE_TOLERANCE: f64 = 1e-12;

/// Collects errors of one kind, keeping the first [`MAX_REPORTED`].
struct Report<'a> {
    errors: &'a mut Vec<MeshError>,
    kind: &'static str,
    count: usize,
}

impl<'a> Report<'a> {
    fn new(errors: &'a mut Vec<MeshError>, kind: &'static str) -> Self {
        Report {
            errors,
            kind,
            count: 0,
        }
    }

    fn push(&mut self, message: String) {
        self.count += 1;
        if self.count <= MAX_REPORTED {
            self.errors.push(MeshError::new(message));
        }
    }
}

impl Drop for Report<'_> {
    fn drop(&mut self) {
        if self.count > MAX_REPORTED {
            self.errors.push(MeshError::new(format!(
                "... and {} more {} (not listed)",
                self.count - MAX_REPORTED,
                self.kind
            )));
        }
    }
}

/// Checks a body's mesh: at least one cell; node numbers of cells and sets
/// in range; finite coordinates; positive cell areas (counter-clockwise) and
/// convex quadrilaterals; no coincident nodes (within
/// [`DUPLICATE_TOLERANCE`] x the bounding-box diagonal); no nodes outside
/// every cell. Returns all problems found.
pub fn check(mesh: &Mesh) -> Result<(), Vec<MeshError>> {
    let mut errors = Vec::new();
    let n = mesh.nodes.len();
    if mesh.cells.is_empty() {
        errors.push(MeshError::new("the mesh has no cells"));
    }

    {
        let mut r = Report::new(&mut errors, "non-finite coordinates");
        for (i, p) in mesh.nodes.iter().enumerate() {
            if !p[0].is_finite() || !p[1].is_finite() {
                r.push(format!(
                    "node {i} has a non-finite coordinate ({}, {})",
                    p[0], p[1]
                ));
            }
        }
    }

    let mut cell_ok = vec![true; mesh.cells.len()];
    {
        let mut r = Report::new(&mut errors, "out-of-range node numbers");
        for (c, cell) in mesh.cells.iter().enumerate() {
            for &k in cell.node_slice() {
                if k >= n {
                    r.push(format!(
                        "cell {c} refers to node {k}, but the mesh has {n} nodes"
                    ));
                    cell_ok[c] = false;
                }
            }
        }
        for (name, set) in &mesh.node_sets {
            if let Some(&k) = set.iter().find(|&&k| k >= n) {
                r.push(format!(
                    "node set '{name}' refers to node {k}, but the mesh has {n} nodes"
                ));
            }
        }
        for (name, set) in &mesh.edge_sets {
            if let Some(e) = set.iter().find(|e| e[0] >= n || e[1] >= n) {
                r.push(format!(
                    "edge set '{name}' refers to edge ({}, {}), but the mesh has {n} nodes",
                    e[0], e[1]
                ));
            }
        }
    }

    check_areas(mesh, &cell_ok, &mut errors);
    check_duplicates(mesh, &mut errors);

    {
        let mut used = vec![false; n];
        for cell in &mesh.cells {
            for &k in cell.node_slice() {
                if k < n {
                    used[k] = true;
                }
            }
        }
        let mut r = Report::new(&mut errors, "unused nodes");
        for (i, _) in used.iter().enumerate().filter(|(_, u)| !**u) {
            let p = mesh.nodes[i];
            r.push(format!(
                "node {i} at ({}, {}) belongs to no cell",
                p[0], p[1]
            ));
        }
    }

    if errors.is_empty() {
        Ok(())
    } else {
        Err(errors)
    }
}

/// Signed areas and, for quadrilaterals, the corner Jacobians (a
/// non-convex quad has a negative Jacobian at its re-entrant corner even
/// when its area is positive).
fn check_areas(mesh: &Mesh, cell_ok: &[bool], errors: &mut Vec<MeshError>) {
    let mut r = Report::new(errors, "inverted or degenerate cells");
    for (c, cell) in mesh.cells.iter().enumerate() {
        if !cell_ok[c] {
            continue;
        }
        let nodes = cell.node_slice();
        let pts: Vec<[f64; 2]> = nodes.iter().map(|&k| mesh.nodes[k]).collect();
        if pts.iter().flatten().any(|v| !v.is_finite()) {
            continue;
        }
        let longest = (0..pts.len())
            .map(|i| {
                let (p, q) = (pts[i], pts[(i + 1) % pts.len()]);
                (q[0] - p[0]).hypot(q[1] - p[1])
            })
            .fold(0.0, f64::max);
        let area = cell_area(mesh, cell);
        let tiny = 1e-12 * longest * longest;
        let kind = match cell.kind {
            super::CellKind::Tri3 => "tri3",
            super::CellKind::Quad4 => "quad4",
        };
        let list = nodes
            .iter()
            .map(|k| k.to_string())
            .collect::<Vec<_>>()
            .join(" ");
        if area.abs() <= tiny {
            r.push(format!(
                "cell {c} ({kind}, nodes {list}) has zero area ({area:e}): degenerate"
            ));
        } else if area < 0.0 {
            r.push(format!(
                "cell {c} ({kind}, nodes {list}) has negative area {area:e}: inverted (clockwise)"
            ));
        } else if pts.len() == 4 {
            for i in 0..4 {
                let (prev, p, next) = (pts[(i + 3) % 4], pts[i], pts[(i + 1) % 4]);
                let cross =
                    (next[0] - p[0]) * (prev[1] - p[1]) - (next[1] - p[1]) * (prev[0] - p[0]);
                if cross <= tiny {
                    r.push(format!(
                        "cell {c} (quad4, nodes {list}) is not convex at node {}: its Jacobian is not positive there",
                        nodes[i]
                    ));
                    break;
                }
            }
        }
    }
}

/// Coincident nodes through a hash grid with cells of the tolerance size:
/// each node is compared with the nodes of its own and the 8 neighbouring
/// grid cells only.
fn check_duplicates(mesh: &Mesh, errors: &mut Vec<MeshError>) {
    let finite: Vec<usize> = (0..mesh.nodes.len())
        .filter(|&i| mesh.nodes[i].iter().all(|v| v.is_finite()))
        .collect();
    if finite.len() < 2 {
        return;
    }
    let mut lo = [f64::INFINITY; 2];
    let mut hi = [f64::NEG_INFINITY; 2];
    for &i in &finite {
        for d in 0..2 {
            lo[d] = lo[d].min(mesh.nodes[i][d]);
            hi[d] = hi[d].max(mesh.nodes[i][d]);
        }
    }
    let diagonal = (hi[0] - lo[0]).hypot(hi[1] - lo[1]);
    let tol = DUPLICATE_TOLERANCE * diagonal;
    let mut r = Report::new(errors, "coincident node pairs");
    if tol == 0.0 || !tol.is_finite() {
        // every finite node is at the same point (or the box overflows)
        if tol == 0.0 {
            for &j in &finite[1..] {
                r.push(format!(
                    "nodes {} and {j} coincide at ({}, {})",
                    finite[0], mesh.nodes[j][0], mesh.nodes[j][1]
                ));
            }
        }
        return;
    }
    let key = |p: [f64; 2]| -> (i64, i64) {
        (
            ((p[0] - lo[0]) / tol).floor() as i64,
            ((p[1] - lo[1]) / tol).floor() as i64,
        )
    };
    let mut grid: HashMap<(i64, i64), Vec<usize>> = HashMap::new();
    for &i in &finite {
        let p = mesh.nodes[i];
        let (kx, ky) = key(p);
        let mut first: Option<usize> = None;
        for dx in -1..=1 {
            for dy in -1..=1 {
                if let Some(list) = grid.get(&(kx.saturating_add(dx), ky.saturating_add(dy))) {
                    for &j in list {
                        let q = mesh.nodes[j];
                        if (p[0] - q[0]).hypot(p[1] - q[1]) <= tol {
                            first = Some(first.map_or(j, |f: usize| f.min(j)));
                        }
                    }
                }
            }
        }
        if let Some(j) = first {
            r.push(format!(
                "nodes {j} and {i} coincide at ({}, {}) (distance <= {tol:e})",
                p[0], p[1]
            ));
        }
        grid.entry((kx, ky)).or_default().push(i);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::Cell;

    fn square() -> Mesh {
        Mesh::new(
            vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]],
            vec![Cell::quad(0, 1, 2, 3)],
        )
    }

    #[test]
    fn valid_unit_square_passes() {
        assert_eq!(check(&square()), Ok(()));
    }

    #[test]
    fn inverted_degenerate_and_nonconvex_cells_reported() {
        let mut m = square();
        m.nodes.extend([[2.0, 0.0], [3.0, 0.0], [0.4, 0.2]]);
        m.cells.push(Cell::tri(1, 2, 4)); // clockwise
        m.cells.push(Cell::tri(1, 4, 5)); // collinear
        m.cells.push(Cell::quad(0, 1, 2, 6)); // positive area, re-entrant at node 6
        let errs = check(&m).unwrap_err();
        let text: Vec<String> = errs.iter().map(|e| e.message.clone()).collect();
        assert!(
            text.iter()
                .any(|t| t.contains("cell 1") && t.contains("inverted")),
            "{text:?}"
        );
        assert!(
            text.iter()
                .any(|t| t.contains("cell 2") && t.contains("degenerate")),
            "{text:?}"
        );
        assert!(
            text.iter()
                .any(|t| t.contains("cell 3") && t.contains("not convex")),
            "{text:?}"
        );
    }

    #[test]
    fn out_of_range_duplicate_unused_and_nan_reported_together() {
        let mut m = square();
        m.nodes.push([1.0, 1.0 + 1e-15]); // 4: duplicate of 2, unused
        m.nodes.push([f64::NAN, 0.0]); // 5: non-finite, unused
        m.cells.push(Cell::tri(0, 2, 9));
        m.node_sets.insert("s".into(), vec![0, 7]);
        let errs = check(&m).unwrap_err();
        let text: Vec<String> = errs.iter().map(|e| e.message.clone()).collect();
        assert!(text.iter().any(|t| t.contains("node 9")), "{text:?}");
        assert!(text.iter().any(|t| t.contains("node set 's'")), "{text:?}");
        assert!(
            text.iter().any(|t| t.contains("nodes 2 and 4 coincide")),
            "{text:?}"
        );
        assert!(
            text.iter()
                .any(|t| t.contains("node 4") && t.contains("no cell")),
            "{text:?}"
        );
        assert!(
            text.iter()
                .any(|t| t.contains("node 5") && t.contains("non-finite")),
            "{text:?}"
        );
    }

    #[test]
    fn duplicate_search_scales_linearly_on_a_large_grid() {
        // 300 x 300 grid: an O(n^2) search would take ~4e9 distance checks
        let k = 300;
        let mut m = Mesh::default();
        for j in 0..=k {
            for i in 0..=k {
                m.nodes.push([i as f64, j as f64]);
            }
        }
        for j in 0..k {
            for i in 0..k {
                let a = j * (k + 1) + i;
                m.cells.push(Cell::quad(a, a + 1, a + k + 2, a + k + 1));
            }
        }
        let t = std::time::Instant::now();
        assert_eq!(check(&m), Ok(()));
        assert!(t.elapsed().as_secs_f64() < 5.0);
        m.nodes.push([150.0, 150.0]);
        let errs = check(&m).unwrap_err();
        assert!(errs[0].message.contains("coincide"), "{:?}", errs[0]);
    }

    #[test]
    fn long_lists_are_cut() {
        let mut m = square();
        for i in 0..30 {
            m.nodes.push([5.0 + i as f64, 5.0]);
        }
        let errs = check(&m).unwrap_err();
        assert_eq!(errs.len(), MAX_REPORTED + 1);
        assert!(errs
            .last()
            .unwrap()
            .message
            .contains("10 more unused nodes"));
    }

    #[test]
    fn empty_mesh_reported() {
        let errs = check(&Mesh::default()).unwrap_err();
        assert!(errs[0].message.contains("no cells"));
    }
}
