//! Mesh quality checks run before any analysis.
//!
//! [`check`] reports every problem at once, one [`MeshError`] each (long
//! lists of the same kind are cut after [`MAX_REPORTED`] entries with a
//! count of the rest).

use super::quality::polygon_area;
use super::{Mesh, MeshError};
use rustc_hash::FxHashMap;

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

/// `(x, y[, z])` of a point, for messages.
fn coords<const D: usize>(p: &[f64; D]) -> String {
    let c: Vec<String> = p.iter().map(|v| v.to_string()).collect();
    format!("({})", c.join(", "))
}

/// Checks a body's mesh: at least one cell; node numbers of cells and sets
/// in range; finite coordinates; positive cell areas (counter-clockwise)
/// and convex quadrilaterals in 2D, positive volumes and positive corner
/// Jacobians in 3D; no coincident nodes (within [`DUPLICATE_TOLERANCE`] x
/// the bounding-box diagonal); no nodes outside every cell. Returns all
/// problems found.
pub fn check<const D: usize>(mesh: &Mesh<D>) -> Result<(), Vec<MeshError>> {
    let mut errors = Vec::new();
    let n = mesh.nodes.len();
    if mesh.cells.is_empty() {
        errors.push(MeshError::new("the mesh has no cells"));
    }

    {
        let mut r = Report::new(&mut errors, "non-finite coordinates");
        for (i, p) in mesh.nodes.iter().enumerate() {
            if !p.iter().all(|v| v.is_finite()) {
                r.push(format!(
                    "node {i} has a non-finite coordinate {}",
                    coords(p)
                ));
            }
        }
    }

    let mut cell_ok = vec![true; mesh.cells.len()];
    {
        let mut r = Report::new(&mut errors, "out-of-range node numbers");
        for (c, cell) in mesh.cells.iter().enumerate() {
            if cell.kind.dimension() != D {
                r.push(format!(
                    "cell {c} is a {} cell in a {D}D mesh",
                    cell.kind.name()
                ));
                cell_ok[c] = false;
                continue;
            }
            for &k in cell.nodes {
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
        for (name, set) in &mesh.face_sets {
            if let Some(f) = set.iter().find(|f| f.nodes().iter().any(|&k| k >= n)) {
                r.push(format!(
                    "face set '{name}' refers to face {:?}, but the mesh has {n} nodes",
                    f.nodes()
                ));
            }
        }
    }

    if D == 2 {
        check_areas(mesh, &cell_ok, &mut errors);
    } else {
        check_volumes(mesh, &cell_ok, &mut errors);
    }
    check_duplicates(mesh, &mut errors);

    {
        let mut used = vec![false; n];
        for &k in mesh.cells.all_nodes() {
            if k < n {
                used[k] = true;
            }
        }
        let mut r = Report::new(&mut errors, "unused nodes");
        for (i, _) in used.iter().enumerate().filter(|(_, u)| !**u) {
            r.push(format!(
                "node {i} at {} belongs to no cell",
                coords(&mesh.nodes[i])
            ));
        }
    }

    if errors.is_empty() {
        Ok(())
    } else {
        Err(errors)
    }
}

fn node_list(nodes: &[usize]) -> String {
    nodes
        .iter()
        .map(|k| k.to_string())
        .collect::<Vec<_>>()
        .join(" ")
}

/// Signed areas and, for quadrilaterals, the corner Jacobians (a
/// non-convex quad has a negative Jacobian at its re-entrant corner even
/// when its area is positive).
fn check_areas<const D: usize>(mesh: &Mesh<D>, cell_ok: &[bool], errors: &mut Vec<MeshError>) {
    let mut r = Report::new(errors, "inverted or degenerate cells");
    for (c, cell) in mesh.cells.iter().enumerate() {
        if !cell_ok[c] {
            continue;
        }
        let nodes = cell.nodes;
        // the corners of the largest planar cell (quad9) without an
        // allocation per cell
        let mut corners = [[0.0; 2]; 9];
        let pts = &mut corners[..nodes.len().min(9)];
        for (p, &k) in pts.iter_mut().zip(nodes) {
            *p = [mesh.nodes[k][0], mesh.nodes[k][1]];
        }
        let pts: &[[f64; 2]] = pts;
        if pts.iter().flatten().any(|v| !v.is_finite()) {
            continue;
        }
        let longest = (0..pts.len())
            .map(|i| {
                let (p, q) = (pts[i], pts[(i + 1) % pts.len()]);
                (q[0] - p[0]).hypot(q[1] - p[1])
            })
            .fold(0.0, f64::max);
        let area = polygon_area(pts);
        let tiny = 1e-12 * longest * longest;
        let kind = cell.kind.name();
        // formatted only for a reported cell
        let list = || node_list(nodes);
        if area.abs() <= tiny {
            r.push(format!(
                "cell {c} ({kind}, nodes {}) has zero area ({area:e}): degenerate",
                list()
            ));
        } else if area < 0.0 {
            r.push(format!(
                "cell {c} ({kind}, nodes {}) has negative area {area:e}: inverted (clockwise)",
                list()
            ));
        } else if pts.len() == 4 {
            for i in 0..4 {
                let (prev, p, next) = (pts[(i + 3) % 4], pts[i], pts[(i + 1) % 4]);
                let cross =
                    (next[0] - p[0]) * (prev[1] - p[1]) - (next[1] - p[1]) * (prev[0] - p[0]);
                if cross <= tiny {
                    r.push(format!(
                        "cell {c} (quad4, nodes {}) is not convex at node {}: its Jacobian is not positive there",
                        list(),
                        nodes[i]
                    ));
                    break;
                }
            }
        }
    }
}

/// Signed volumes and the Jacobian at every corner of solid cells (an
/// inverted or twisted hexahedron has a non-positive Jacobian at some
/// corner even when its volume is positive).
fn check_volumes<const D: usize>(mesh: &Mesh<D>, cell_ok: &[bool], errors: &mut Vec<MeshError>) {
    let mut r = Report::new(errors, "inverted or degenerate cells");
    for (c, cell) in mesh.cells.iter().enumerate() {
        if !cell_ok[c] {
            continue;
        }
        let pts: Vec<&[f64]> = cell.nodes.iter().map(|&k| &mesh.nodes[k][..]).collect();
        if pts.iter().any(|p| p.iter().any(|v| !v.is_finite())) {
            continue;
        }
        let Some((corners, volume)) = crate::element::reference::corner_jacobians(cell.kind, &pts)
        else {
            continue;
        };
        let mut longest: f64 = 0.0;
        for face in cell.kind.faces() {
            for i in 0..face.len() {
                let (p, q) = (pts[face[i]], pts[face[(i + 1) % face.len()]]);
                let l = (0..D).map(|k| (q[k] - p[k]).powi(2)).sum::<f64>().sqrt();
                longest = longest.max(l);
            }
        }
        let tiny = 1e-12 * longest.powi(3);
        let kind = cell.kind.name();
        // formatted only for a reported cell
        let list = || node_list(cell.nodes);
        if volume.abs() <= tiny {
            r.push(format!(
                "cell {c} ({kind}, nodes {}) has zero volume ({volume:e}): degenerate",
                list()
            ));
        } else if volume < 0.0 {
            r.push(format!(
                "cell {c} ({kind}, nodes {}) has negative volume {volume:e}: inverted (the \
                 node order must follow gmsh's)",
                list()
            ));
        } else if let Some(i) = corners.iter().position(|&j| j <= tiny) {
            if let Some(node) = cell.nodes.get(i) {
                r.push(format!(
                    "cell {c} ({kind}, nodes {}) is inverted or twisted at node {node}: its \
                     Jacobian is not positive there",
                    list()
                ));
            } else {
                r.push(format!(
                    "cell {c} ({kind}, nodes {}) is inverted or twisted at its integration \
                     point {}: its Jacobian is not positive there (a midside node too far off \
                     the middle of its edge?)",
                    list(),
                    i - cell.nodes.len()
                ));
            }
        }
    }
}

/// Coincident nodes through a hash grid with cells of the tolerance size:
/// each node is compared with the nodes of its own and the `3^D - 1`
/// neighbouring grid cells only.
fn check_duplicates<const D: usize>(mesh: &Mesh<D>, errors: &mut Vec<MeshError>) {
    let finite: Vec<usize> = (0..mesh.nodes.len())
        .filter(|&i| mesh.nodes[i].iter().all(|v| v.is_finite()))
        .collect();
    if finite.len() < 2 {
        return;
    }
    let mut lo = [f64::INFINITY; D];
    let mut hi = [f64::NEG_INFINITY; D];
    for &i in &finite {
        for d in 0..D {
            lo[d] = lo[d].min(mesh.nodes[i][d]);
            hi[d] = hi[d].max(mesh.nodes[i][d]);
        }
    }
    let dist = |p: &[f64; D], q: &[f64; D]| -> f64 {
        if D == 2 {
            (p[0] - q[0]).hypot(p[1] - q[1])
        } else {
            (0..D).map(|k| (p[k] - q[k]).powi(2)).sum::<f64>().sqrt()
        }
    };
    let diagonal = dist(&hi, &lo);
    let tol = DUPLICATE_TOLERANCE * diagonal;
    let mut r = Report::new(errors, "coincident node pairs");
    if tol == 0.0 || !tol.is_finite() {
        // every finite node is at the same point (or the box overflows)
        if tol == 0.0 {
            for &j in &finite[1..] {
                r.push(format!(
                    "nodes {} and {j} coincide at {}",
                    finite[0],
                    coords(&mesh.nodes[j])
                ));
            }
        }
        return;
    }
    let key = |p: &[f64; D]| -> [i64; D] {
        std::array::from_fn(|k| ((p[k] - lo[k]) / tol).floor() as i64)
    };
    let neighbours = 3usize.pow(D as u32);
    // lookups only (no iteration): the Fx hash cannot change the report;
    // each grid cell's nodes are a list threaded through `next` (no
    // allocation per cell; the order within a list does not matter, the
    // smallest coincident node is reported)
    const END: usize = usize::MAX;
    let mut grid: FxHashMap<[i64; D], usize> = FxHashMap::default();
    grid.reserve(finite.len());
    let mut next = vec![END; mesh.nodes.len()];
    for &i in &finite {
        let p = &mesh.nodes[i];
        let k = key(p);
        let mut first: Option<usize> = None;
        for m in 0..neighbours {
            let mut cell = k;
            let mut code = m;
            for c in cell.iter_mut() {
                *c = c.saturating_add((code % 3) as i64 - 1);
                code /= 3;
            }
            let mut j = grid.get(&cell).copied().unwrap_or(END);
            while j != END {
                if dist(p, &mesh.nodes[j]) <= tol {
                    first = Some(first.map_or(j, |f: usize| f.min(j)));
                }
                j = next[j];
            }
        }
        if let Some(j) = first {
            r.push(format!(
                "nodes {j} and {i} coincide at {} (distance <= {tol:e})",
                coords(p)
            ));
        }
        let head = grid.entry(k).or_insert(END);
        next[i] = *head;
        *head = i;
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
    fn solid_cells_inverted_twisted_degenerate_and_duplicates_reported() {
        let cube: Vec<[f64; 3]> = vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0],
            [1.0, 0.0, 1.0],
            [1.0, 1.0, 1.0],
            [0.0, 1.0, 1.0],
        ];
        let ok = Mesh::new(cube.clone(), vec![Cell::hex([0, 1, 2, 3, 4, 5, 6, 7])]);
        assert_eq!(check(&ok), Ok(()));
        let mut m = Mesh::new(cube, vec![Cell::hex([0, 1, 2, 3, 4, 5, 6, 7])]);
        m.cells.push(Cell::tet([0, 2, 1, 4])); // inverted
        m.cells.push(Cell::tet([0, 1, 2, 3])); // flat
        m.nodes.push([0.2, 0.2, 0.2]); // 8: node 6 pushed through the cube
        m.cells.push(Cell::hex([0, 1, 2, 3, 4, 5, 8, 7])); // positive volume, inverted corner
        m.nodes.push([1.0, 1.0, 1.0 + 1e-15]); // 9: duplicate of 6
        let text: Vec<String> = check(&m)
            .unwrap_err()
            .iter()
            .map(|e| e.message.clone())
            .collect();
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
                .any(|t| t.contains("cell 3") && t.contains("twisted")),
            "{text:?}"
        );
        assert!(
            text.iter().any(|t| t.contains("nodes 6 and 9 coincide")),
            "{text:?}"
        );
        let planar_in_3d = Mesh::<3>::new(vec![[0.0; 3]; 3], vec![Cell::tri(0, 1, 2)]);
        let text = check(&planar_in_3d).unwrap_err();
        assert!(
            text[0].message.contains("tri3 cell in a 3D mesh"),
            "{text:?}"
        );
    }

    #[test]
    fn empty_mesh_reported() {
        let errs = check(&Mesh::<2>::default()).unwrap_err();
        assert!(errs[0].message.contains("no cells"));
    }
}
