//! Cell geometry and shape quality: signed areas, edge-length ratios and
//! interior angles.

use super::{Cell, Mesh};

/// Signed area of a polygon given by its corner points (positive when
/// counter-clockwise; shoelace formula).
pub fn polygon_area(points: &[[f64; 2]]) -> f64 {
    let n = points.len();
    let mut twice = 0.0;
    for k in 0..n {
        let p = points[k];
        let q = points[(k + 1) % n];
        twice += (p[0] - points[0][0]) * (q[1] - points[0][1])
            - (q[0] - points[0][0]) * (p[1] - points[0][1]);
    }
    0.5 * twice
}

/// Signed area of `cell` (positive when counter-clockwise). Node numbers must
/// be in range.
pub fn cell_area(mesh: &Mesh, cell: &Cell) -> f64 {
    let pts: Vec<[f64; 2]> = cell.node_slice().iter().map(|&n| mesh.nodes[n]).collect();
    polygon_area(&pts)
}

/// Shape measures of one cell.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CellQuality {
    /// Longest edge / shortest edge (1 for an equilateral triangle or a
    /// square; infinite for a zero-length edge).
    pub aspect_ratio: f64,
    /// Smallest interior angle, degrees (60 equilateral, 90 square).
    pub min_angle: f64,
    /// Largest interior angle, degrees (>= 180 means a flat or re-entrant
    /// corner).
    pub max_angle: f64,
}

/// Shape measures of `cell`. Interior angles are measured on the
/// counter-clockwise polygon, so an inverted cell has angles above 180.
pub fn cell_quality(mesh: &Mesh, cell: &Cell) -> CellQuality {
    let n = cell.node_slice();
    let k = n.len();
    let mut longest: f64 = 0.0;
    let mut shortest = f64::INFINITY;
    let mut min_angle = f64::INFINITY;
    let mut max_angle: f64 = 0.0;
    for i in 0..k {
        let prev = mesh.nodes[n[(i + k - 1) % k]];
        let p = mesh.nodes[n[i]];
        let next = mesh.nodes[n[(i + 1) % k]];
        let e = [next[0] - p[0], next[1] - p[1]];
        let len = e[0].hypot(e[1]);
        longest = longest.max(len);
        shortest = shortest.min(len);
        // angle from (next - p) counter-clockwise to (prev - p)
        let f = [prev[0] - p[0], prev[1] - p[1]];
        let cross = e[0] * f[1] - e[1] * f[0];
        let dot = e[0] * f[0] + e[1] * f[1];
        let mut a = cross.atan2(dot).to_degrees();
        if a < 0.0 {
            a += 360.0;
        }
        min_angle = min_angle.min(a);
        max_angle = max_angle.max(a);
    }
    CellQuality {
        aspect_ratio: longest / shortest,
        min_angle,
        max_angle,
    }
}

/// Extremes of [`CellQuality`] over a mesh.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct QualitySummary {
    /// Number of cells measured.
    pub cells: usize,
    /// Smallest aspect ratio (best cell).
    pub min_aspect_ratio: f64,
    /// Largest aspect ratio (worst cell).
    pub max_aspect_ratio: f64,
    /// Cell with the largest aspect ratio.
    pub worst_aspect_cell: usize,
    /// Smallest interior angle of any cell, degrees.
    pub min_angle: f64,
    /// Largest interior angle of any cell, degrees.
    pub max_angle: f64,
}

/// Quality extremes over all cells (node numbers must be in range; see
/// [`super::validate::check`]). `None` for a mesh without cells.
pub fn summary(mesh: &Mesh) -> Option<QualitySummary> {
    let mut s: Option<QualitySummary> = None;
    for (i, c) in mesh.cells.iter().enumerate() {
        let q = cell_quality(mesh, c);
        let cur = s.get_or_insert(QualitySummary {
            cells: 0,
            min_aspect_ratio: q.aspect_ratio,
            max_aspect_ratio: q.aspect_ratio,
            worst_aspect_cell: i,
            min_angle: q.min_angle,
            max_angle: q.max_angle,
        });
        cur.cells += 1;
        cur.min_aspect_ratio = cur.min_aspect_ratio.min(q.aspect_ratio);
        if q.aspect_ratio > cur.max_aspect_ratio {
            cur.max_aspect_ratio = q.aspect_ratio;
            cur.worst_aspect_cell = i;
        }
        cur.min_angle = cur.min_angle.min(q.min_angle);
        cur.max_angle = cur.max_angle.max(q.max_angle);
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unit_square_and_equilateral_triangle_quality() {
        let mesh = Mesh::new(
            vec![
                [0.0, 0.0],
                [1.0, 0.0],
                [1.0, 1.0],
                [0.0, 1.0],
                [0.5, 3f64.sqrt() / 2.0],
            ],
            vec![Cell::quad(0, 1, 2, 3), Cell::tri(0, 1, 4)],
        );
        let q = cell_quality(&mesh, &mesh.cells[0]);
        assert!((q.aspect_ratio - 1.0).abs() < 1e-15);
        assert!((q.min_angle - 90.0).abs() < 1e-12 && (q.max_angle - 90.0).abs() < 1e-12);
        let t = cell_quality(&mesh, &mesh.cells[1]);
        assert!((t.min_angle - 60.0).abs() < 1e-9 && (t.max_angle - 60.0).abs() < 1e-9);
        assert!((cell_area(&mesh, &mesh.cells[0]) - 1.0).abs() < 1e-15);
        let s = summary(&mesh).unwrap();
        assert_eq!(s.cells, 2);
        assert!((s.min_angle - 60.0).abs() < 1e-9);
    }

    #[test]
    fn clockwise_cell_has_negative_area_and_reflex_angles() {
        let mesh = Mesh::new(
            vec![[0.0, 0.0], [2.0, 0.0], [0.0, 1.0]],
            vec![Cell::tri(0, 2, 1)],
        );
        assert_eq!(cell_area(&mesh, &mesh.cells[0]), -1.0);
        assert!(cell_quality(&mesh, &mesh.cells[0]).max_angle > 180.0);
    }
}
