//! Structured rectangle.
//!
//! Nodes row by row (`j * (nx + 1) + i`), cells row by row. Triangles cut
//! each quad along the diagonal pointing to the rectangle centre ("union
//! jack"), so the mesh is mirror-symmetric about both mid-lines when the
//! divisions are even.

use super::common::{
    add_boundary, add_node, chain, divisions, finite_point, node_budget, positive, push_quad,
};
use super::Grading;
use crate::mesh::{CellKind, Mesh, MeshError};

const NAME: &str = "rectangle";

/// Builds the rectangle `[x0, x0 + w] x [y0, y0 + h]`; see
/// [`super::MeshSpec::Rectangle`].
pub fn rectangle(
    origin: [f64; 2],
    size: [f64; 2],
    div: [usize; 2],
    grading: [Grading; 2],
    kind: CellKind,
) -> Result<Mesh, MeshError> {
    finite_point(NAME, "origin", origin)?;
    positive(NAME, "width", size[0])?;
    positive(NAME, "height", size[1])?;
    divisions(NAME, "x", div[0], 1)?;
    divisions(NAME, "y", div[1], 1)?;
    grading[0].check("rectangle x grading")?;
    grading[1].check("rectangle y grading")?;
    node_budget(
        NAME,
        (div[0].checked_add(1)).and_then(|a| div[1].checked_add(1)?.checked_mul(a)),
    )?;

    let [nx, ny] = div;
    let tx = grading[0].points(nx);
    let ty = grading[1].points(ny);
    let xs: Vec<f64> = tx.iter().map(|t| origin[0] + size[0] * t).collect();
    let ys: Vec<f64> = ty.iter().map(|t| origin[1] + size[1] * t).collect();
    let id = |i: usize, j: usize| j * (nx + 1) + i;

    let mut mesh = Mesh::default();
    for &y in &ys {
        for &x in &xs {
            mesh.nodes.push([x, y]);
        }
    }
    for j in 0..ny {
        let bottom_half = 2 * j + 1 < ny;
        for i in 0..nx {
            let left_half = 2 * i + 1 < nx;
            // Diagonal towards the centre: bottom-left -> top-right in the
            // lower-left and upper-right quadrants.
            let diagonal_ac = left_half == bottom_half;
            push_quad(
                &mut mesh.cells,
                kind,
                [id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)],
                diagonal_ac,
            );
        }
    }

    let bottom: Vec<usize> = (0..=nx).map(|i| id(i, 0)).collect();
    let right: Vec<usize> = (0..=ny).map(|j| id(nx, j)).collect();
    let top: Vec<usize> = (0..=nx).rev().map(|i| id(i, ny)).collect();
    let left: Vec<usize> = (0..=ny).rev().map(|j| id(0, j)).collect();
    add_boundary(&mut mesh, "bottom", chain(&bottom));
    add_boundary(&mut mesh, "right", chain(&right));
    add_boundary(&mut mesh, "top", chain(&top));
    add_boundary(&mut mesh, "left", chain(&left));
    add_node(&mut mesh, "corner_bl", id(0, 0));
    add_node(&mut mesh, "corner_br", id(nx, 0));
    add_node(&mut mesh, "corner_tr", id(nx, ny));
    add_node(&mut mesh, "corner_tl", id(0, ny));
    Ok(mesh)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn area(mesh: &Mesh) -> f64 {
        mesh.cells
            .iter()
            .map(|c| {
                let n = c.nodes;
                (0..n.len())
                    .map(|k| {
                        let p = mesh.nodes[n[k]];
                        let q = mesh.nodes[n[(k + 1) % n.len()]];
                        p[0] * q[1] - q[0] * p[1]
                    })
                    .sum::<f64>()
                    / 2.0
            })
            .sum()
    }

    #[test]
    fn rectangle_2x1_quad4_numbering_and_sets() {
        let m = rectangle(
            [0.0, 0.0],
            [2.0, 1.0],
            [2, 1],
            [Grading::Uniform; 2],
            CellKind::Quad4,
        )
        .unwrap();
        assert_eq!(m.nodes.len(), 6);
        assert_eq!(m.cells.len(), 2);
        assert_eq!(m.cells.nodes(0), &[0, 1, 4, 3]);
        assert_eq!(m.edge_sets["bottom"], vec![[0, 1], [1, 2]]);
        assert_eq!(m.edge_sets["right"], vec![[2, 5]]);
        assert_eq!(m.edge_sets["top"], vec![[5, 4], [4, 3]]);
        assert_eq!(m.edge_sets["left"], vec![[3, 0]]);
        assert_eq!(m.node_sets["top"], vec![3, 4, 5]);
        assert_eq!(m.node_sets["corner_tr"], vec![5]);
        assert!((area(&m) - 2.0).abs() < 1e-14);
    }

    #[test]
    fn rectangle_tri3_union_jack_is_mirror_symmetric() {
        let m = rectangle(
            [-1.0, -1.0],
            [2.0, 2.0],
            [4, 4],
            [Grading::Uniform; 2],
            CellKind::Tri3,
        )
        .unwrap();
        assert_eq!(m.cells.len(), 32);
        // every triangle has a mirror image about x = 0
        let key = |pts: Vec<[f64; 2]>| {
            let mut v: Vec<(i64, i64)> = pts
                .iter()
                .map(|p| ((p[0] * 1e6).round() as i64, (p[1] * 1e6).round() as i64))
                .collect();
            v.sort();
            v
        };
        let all: Vec<_> = m
            .cells
            .iter()
            .map(|c| key(c.nodes.iter().map(|&n| m.nodes[n]).collect()))
            .collect();
        for c in &m.cells {
            let mirrored = key(c
                .nodes
                .iter()
                .map(|&n| [-m.nodes[n][0], m.nodes[n][1]])
                .collect());
            assert!(all.contains(&mirrored));
            let flipped = key(c
                .nodes
                .iter()
                .map(|&n| [m.nodes[n][0], -m.nodes[n][1]])
                .collect());
            assert!(all.contains(&flipped));
        }
        assert!((area(&m) - 4.0).abs() < 1e-14);
    }

    #[test]
    fn rectangle_rejects_bad_input() {
        let ok = |o: [f64; 2], s: [f64; 2], d: [usize; 2]| {
            rectangle(o, s, d, [Grading::Uniform; 2], CellKind::Quad4)
        };
        assert!(ok([0.0, 0.0], [0.0, 1.0], [1, 1]).is_err());
        assert!(ok([0.0, 0.0], [1.0, -1.0], [1, 1]).is_err());
        assert!(ok([f64::NAN, 0.0], [1.0, 1.0], [1, 1]).is_err());
        assert!(ok([0.0, 0.0], [1.0, 1.0], [0, 1]).is_err());
        assert!(ok([0.0, 0.0], [1.0, 1.0], [usize::MAX, 2]).is_err());
        assert!(ok([0.0, 0.0], [1.0, 1.0], [100_000, 100_000]).is_err());
        let e = ok([0.0, 0.0], [1.0, f64::INFINITY], [1, 1]).unwrap_err();
        assert!(e.message.contains("height"), "{}", e.message);
    }
}
