//! Structured meshes for tests: an `nx` x `ny` grid of quads (or triangles)
//! with optional random interior jitter.

use super::Rng;
use crate::mesh::{Cell, Mesh};

/// Node number of grid point (i, j) of an `nx` x `ny` cell grid.
pub fn grid_node(nx: usize, i: usize, j: usize) -> usize {
    j * (nx + 1) + i
}

/// A structured `nx` x `ny` grid of `[x0, x0 + w] x [y0, y0 + h]`; interior
/// nodes moved randomly by up to `jitter` times the cell size in each
/// direction (seeded by `seed`); quads, or each quad split in two
/// triangles (alternating diagonals) when `tri`. No sets.
pub fn grid(
    nx: usize,
    ny: usize,
    origin: [f64; 2],
    size: [f64; 2],
    jitter: f64,
    seed: u64,
    tri: bool,
) -> Mesh {
    let mut rng = Rng(seed);
    let (hx, hy) = (size[0] / nx as f64, size[1] / ny as f64);
    let mut nodes = Vec::new();
    for j in 0..=ny {
        for i in 0..=nx {
            let mut p = [origin[0] + i as f64 * hx, origin[1] + j as f64 * hy];
            if jitter != 0.0 && i > 0 && i < nx && j > 0 && j < ny {
                p[0] += jitter * hx * rng.sym();
                p[1] += jitter * hy * rng.sym();
            }
            nodes.push(p);
        }
    }
    let mut cells = Vec::new();
    for j in 0..ny {
        for i in 0..nx {
            let a = grid_node(nx, i, j);
            let b = grid_node(nx, i + 1, j);
            let c = grid_node(nx, i + 1, j + 1);
            let d = grid_node(nx, i, j + 1);
            if !tri {
                cells.push(Cell::quad(a, b, c, d));
            } else if (i + j) % 2 == 0 {
                cells.push(Cell::tri(a, b, c));
                cells.push(Cell::tri(a, c, d));
            } else {
                cells.push(Cell::tri(a, b, d));
                cells.push(Cell::tri(b, c, d));
            }
        }
    }
    Mesh::new(nodes, cells)
}

/// Nodes on the boundary of an `nx` x `ny` grid, in node order.
pub fn grid_boundary(nx: usize, ny: usize) -> Vec<usize> {
    let mut out = Vec::new();
    for j in 0..=ny {
        for i in 0..=nx {
            if i == 0 || j == 0 || i == nx || j == ny {
                out.push(grid_node(nx, i, j));
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn grid_counts_and_jitter_keep_the_boundary() {
        let m = grid(3, 2, [1.0, 2.0], [3.0, 2.0], 0.3, 7, true);
        assert_eq!(m.nodes.len(), 12);
        assert_eq!(m.cells.len(), 12);
        for n in grid_boundary(3, 2) {
            let p = m.nodes[n];
            assert_eq!(p[0].fract(), 0.0);
            assert_eq!(p[1].fract(), 0.0);
        }
        assert_ne!(m.nodes[grid_node(3, 1, 1)], [2.0, 3.0]);
    }
}
