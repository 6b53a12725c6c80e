//! Helpers shared by the generators: input checks, exact polar points,
//! quad splitting and named boundary sets.

use crate::mesh::{Cell, CellKind, Cells, Mesh, MeshError};

/// Largest number of nodes a generator accepts: a 2D body beyond this is
/// almost certainly a typo in the divisions, and would exhaust memory.
pub const MAX_NODES: usize = 10_000_000;

/// Error unless `value` is finite and > 0.
pub fn positive(generator: &str, what: &str, value: f64) -> Result<(), MeshError> {
    if value.is_finite() && value > 0.0 {
        Ok(())
    } else {
        Err(MeshError::new(format!(
            "{generator}: {what} must be a positive number, got {value}"
        )))
    }
}

/// Error unless both coordinates of `p` are finite.
pub fn finite_point(generator: &str, what: &str, p: [f64; 2]) -> Result<(), MeshError> {
    if p.iter().all(|v| v.is_finite()) {
        Ok(())
    } else {
        Err(MeshError::new(format!(
            "{generator}: {what} ({}, {}) must be finite",
            p[0], p[1]
        )))
    }
}

/// Error unless `n >= min`.
pub fn divisions(generator: &str, what: &str, n: usize, min: usize) -> Result<(), MeshError> {
    if n >= min {
        Ok(())
    } else {
        Err(MeshError::new(format!(
            "{generator}: {what} divisions must be at least {min}, got {n}"
        )))
    }
}

/// Error when `count` (computed with overflow checks, `None` = overflow)
/// exceeds [`MAX_NODES`].
pub fn node_budget(generator: &str, count: Option<usize>) -> Result<(), MeshError> {
    match count {
        Some(n) if n <= MAX_NODES => Ok(()),
        _ => Err(MeshError::new(format!(
            "{generator}: the divisions ask for more than {MAX_NODES} nodes; check them"
        ))),
    }
}

/// `(cos, sin)` of an angle in degrees, exact for multiples of 90 degrees
/// (so nodes on the axes land exactly on them).
pub fn cos_sin_deg(deg: f64) -> (f64, f64) {
    let quarter = deg / 90.0;
    if quarter == quarter.round() && quarter.abs() < 1e15 {
        match (quarter as i64).rem_euclid(4) {
            0 => (1.0, 0.0),
            1 => (0.0, 1.0),
            2 => (-1.0, 0.0),
            _ => (0.0, -1.0),
        }
    } else {
        let (s, c) = deg.to_radians().sin_cos();
        (c, s)
    }
}

/// The point at radius `r` and angle `deg` (degrees) around `center`.
pub fn polar_point(center: [f64; 2], r: f64, deg: f64) -> [f64; 2] {
    let (c, s) = cos_sin_deg(deg);
    [center[0] + r * c, center[1] + r * s]
}

/// Appends the counter-clockwise quad `a b c d` as one `Quad4` or as two
/// `Tri3` cut along the diagonal `a-c` (`diagonal_ac`) or `b-d`.
/// (Planar generators produce `Tri3` or `Quad4`; any other kind is a
/// programming error.)
pub fn push_quad(cells: &mut Cells, kind: CellKind, n: [usize; 4], diagonal_ac: bool) {
    let [a, b, c, d] = n;
    match kind {
        CellKind::Tri3 if diagonal_ac => {
            cells.push(Cell::tri(a, b, c));
            cells.push(Cell::tri(a, c, d));
        }
        CellKind::Tri3 => {
            cells.push(Cell::tri(a, b, d));
            cells.push(Cell::tri(b, c, d));
        }
        _ => cells.push(Cell::quad(a, b, c, d)),
    }
}

/// Adds the edge set `name` (edges as given, body on their left) and the node
/// set of the same name (the sorted nodes of those edges).
pub fn add_boundary(mesh: &mut Mesh, name: &str, edges: Vec<[usize; 2]>) {
    let mut nodes: Vec<usize> = edges.iter().flatten().copied().collect();
    nodes.sort_unstable();
    nodes.dedup();
    mesh.node_sets.insert(name.to_string(), nodes);
    mesh.edge_sets.insert(name.to_string(), edges);
}

/// Edges joining consecutive nodes of `walk`.
pub fn chain(walk: &[usize]) -> Vec<[usize; 2]> {
    walk.windows(2).map(|w| [w[0], w[1]]).collect()
}

/// Adds the one-node set `name`.
pub fn add_node(mesh: &mut Mesh, name: &str, node: usize) {
    mesh.node_sets.insert(name.to_string(), vec![node]);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cos_sin_exact_on_axes() {
        assert_eq!(cos_sin_deg(180.0), (-1.0, 0.0));
        assert_eq!(cos_sin_deg(-90.0), (0.0, -1.0));
        assert_eq!(cos_sin_deg(360.0), (1.0, 0.0));
        assert_eq!(cos_sin_deg(450.0), (0.0, 1.0));
        let (c, s) = cos_sin_deg(30.0);
        assert!((c - 3f64.sqrt() / 2.0).abs() < 1e-15 && (s - 0.5).abs() < 1e-15);
    }

    #[test]
    fn push_quad_splits_counter_clockwise() {
        let mut cells = Cells::new();
        push_quad(&mut cells, CellKind::Tri3, [0, 1, 2, 3], true);
        push_quad(&mut cells, CellKind::Tri3, [0, 1, 2, 3], false);
        let want: Cells = [
            Cell::tri(0, 1, 2),
            Cell::tri(0, 2, 3),
            Cell::tri(0, 1, 3),
            Cell::tri(1, 2, 3),
        ]
        .into_iter()
        .collect();
        assert_eq!(cells, want);
    }
}
