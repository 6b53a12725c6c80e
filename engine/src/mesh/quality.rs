//! Cell geometry and shape quality: signed areas and volumes, edge-length
//! ratios and interior angles (of the cell in 2D, of its faces in 3D).

use super::{CellRef, Mesh};

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

/// Signed area of a planar `cell` (positive when counter-clockwise). Node
/// numbers must be in range.
pub fn cell_area(mesh: &Mesh<2>, cell: CellRef<'_>) -> f64 {
    let pts: Vec<[f64; 2]> = cell.nodes.iter().map(|&n| mesh.nodes[n]).collect();
    polygon_area(&pts)
}

/// Signed measure of `cell`: its area (2D, positive when counter-clockwise)
/// or its volume (3D, positive when the node order is gmsh's). Node
/// numbers must be in range.
pub fn cell_measure<const D: usize>(mesh: &Mesh<D>, cell: CellRef<'_>) -> f64 {
    if D == 2 {
        let pts: Vec<[f64; 2]> = cell
            .nodes
            .iter()
            .map(|&n| [mesh.nodes[n][0], mesh.nodes[n][1]])
            .collect();
        return polygon_area(&pts);
    }
    let pts: Vec<&[f64]> = cell.nodes.iter().map(|&n| &mesh.nodes[n][..]).collect();
    crate::element::reference::corner_jacobians(cell.kind, &pts).map_or(f64::NAN, |(_, v)| v)
}

/// Shape measures of one cell.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CellQuality {
    /// Longest edge / shortest edge (1 for an equilateral triangle, a
    /// square or a cube; infinite for a zero-length edge).
    pub aspect_ratio: f64,
    /// Smallest interior angle, degrees (60 equilateral, 90 square), of the
    /// cell (2D) or of its faces (3D).
    pub min_angle: f64,
    /// Largest interior angle, degrees (>= 180 means a flat or re-entrant
    /// corner).
    pub max_angle: f64,
}

/// Interior angles and edge lengths of the polygon `p` (planar, or a face
/// in space measured in its own plane, counter-clockwise seen from
/// `normal`).
fn polygon_measures(p: &[[f64; 3]], normal: [f64; 3], q: &mut CellQuality, edges: &mut (f64, f64)) {
    let k = p.len();
    let sub = |a: [f64; 3], b: [f64; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
    let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    for i in 0..k {
        let (prev, c, next) = (p[(i + k - 1) % k], p[i], p[(i + 1) % k]);
        let e = sub(next, c);
        let f = sub(prev, c);
        let len = dot(e, e).sqrt();
        edges.0 = edges.0.max(len);
        edges.1 = edges.1.min(len);
        // angle from (next - c) counter-clockwise (about `normal`) to (prev - c)
        let cross = [
            e[1] * f[2] - e[2] * f[1],
            e[2] * f[0] - e[0] * f[2],
            e[0] * f[1] - e[1] * f[0],
        ];
        let mut a = dot(cross, normal).atan2(dot(e, f)).to_degrees();
        if a < 0.0 {
            a += 360.0;
        }
        q.min_angle = q.min_angle.min(a);
        q.max_angle = q.max_angle.max(a);
    }
}

/// Shape measures of `cell`. Interior angles are measured on the
/// counter-clockwise polygon (2D) or on each face seen from outside (3D),
/// so an inverted cell has angles above 180.
pub fn cell_quality<const D: usize>(mesh: &Mesh<D>, cell: CellRef<'_>) -> CellQuality {
    let at = |n: usize| -> [f64; 3] {
        std::array::from_fn(|k| if k < D { mesh.nodes[n][k] } else { 0.0 })
    };
    let mut q = CellQuality {
        aspect_ratio: 0.0,
        min_angle: f64::INFINITY,
        max_angle: 0.0,
    };
    let mut edges = (0.0f64, f64::INFINITY);
    if D == 2 {
        let p: Vec<[f64; 3]> = cell.nodes.iter().map(|&n| at(n)).collect();
        polygon_measures(&p, [0.0, 0.0, 1.0], &mut q, &mut edges);
    } else {
        for face in cell.kind.faces() {
            let p: Vec<[f64; 3]> = face.iter().map(|&a| at(cell.nodes[a])).collect();
            // outward normal of the face (Newell's method)
            let mut n = [0.0; 3];
            for i in 0..p.len() {
                let (a, b) = (p[i], p[(i + 1) % p.len()]);
                n[0] += (a[1] - b[1]) * (a[2] + b[2]);
                n[1] += (a[2] - b[2]) * (a[0] + b[0]);
                n[2] += (a[0] - b[0]) * (a[1] + b[1]);
            }
            polygon_measures(&p, n, &mut q, &mut edges);
        }
    }
    q.aspect_ratio = edges.0 / edges.1;
    q
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
pub fn summary<const D: usize>(mesh: &Mesh<D>) -> Option<QualitySummary> {
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
    use crate::mesh::Cell;

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
        let q = cell_quality(&mesh, mesh.cells.get(0));
        assert!((q.aspect_ratio - 1.0).abs() < 1e-15);
        assert!((q.min_angle - 90.0).abs() < 1e-12 && (q.max_angle - 90.0).abs() < 1e-12);
        let t = cell_quality(&mesh, mesh.cells.get(1));
        assert!((t.min_angle - 60.0).abs() < 1e-9 && (t.max_angle - 60.0).abs() < 1e-9);
        assert!((cell_area(&mesh, mesh.cells.get(0)) - 1.0).abs() < 1e-15);
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
        assert_eq!(cell_area(&mesh, mesh.cells.get(0)), -1.0);
        assert!(cell_quality(&mesh, mesh.cells.get(0)).max_angle > 180.0);
    }

    #[test]
    fn unit_cube_and_corner_tetrahedron_volume_and_quality() {
        let cube: Vec<[f64; 3]> = vec![
            [0.0, 0.0, 0.0],
            [2.0, 0.0, 0.0],
            [2.0, 2.0, 0.0],
            [0.0, 2.0, 0.0],
            [0.0, 0.0, 2.0],
            [2.0, 0.0, 2.0],
            [2.0, 2.0, 2.0],
            [0.0, 2.0, 2.0],
        ];
        let mesh = Mesh::new(
            cube,
            vec![Cell::hex([0, 1, 2, 3, 4, 5, 6, 7]), Cell::tet([0, 1, 3, 4])],
        );
        assert!((cell_measure(&mesh, mesh.cells.get(0)) - 8.0).abs() < 1e-14);
        assert!((cell_measure(&mesh, mesh.cells.get(1)) - 8.0 / 6.0).abs() < 1e-14);
        let q = cell_quality(&mesh, mesh.cells.get(0));
        assert!((q.aspect_ratio - 1.0).abs() < 1e-15);
        assert!((q.min_angle - 90.0).abs() < 1e-12 && (q.max_angle - 90.0).abs() < 1e-12);
        // every face of the cube is seen counter-clockwise from outside
        let t = cell_quality(&mesh, mesh.cells.get(1));
        assert!(t.max_angle <= 90.0 + 1e-12, "{t:?}");
        assert!((t.aspect_ratio - 2f64.sqrt()).abs() < 1e-14);
    }
}
