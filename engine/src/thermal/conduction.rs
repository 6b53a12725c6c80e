//! Heat conduction element kernels (every cell kind through its reference
//! cell and quadrature: tri3/quad4/tri6/quad8/quad9 plane and
//! axisymmetric, tet4/hex8/tet10/hex20/hex27 solid):
//! conductivity matrix `K_e = sum k grad(N_a) . grad(N_b) dV` and lumped
//! (row-sum) capacity `C_a = sum rho c N_a dV`, with the same integration
//! points and volume weights as the mechanical elements (`dV = w det(J) t`
//! plane, `w det(J) 2 pi r` axisymmetric: totals over the full ring).
//!
//! The capacity is lumped so that the implicit (backward Euler) transient
//! respects the discrete maximum principle on reasonable meshes.

use crate::element::{kernel_of, ElementError, Section};
use crate::geom::Dimension;
use crate::mesh::Mesh;
use nalgebra::Const;

/// Conductivity and lumped capacity of one cell.
#[derive(Debug, Clone, PartialEq)]
pub struct CellConduction {
    /// Number of nodes of the cell.
    pub nodes: usize,
    /// Conductivity matrix, `conductivity[a][b]`.
    pub conductivity: Vec<Vec<f64>>,
    /// Lumped capacity per node (`rho c` times the nodal volume share).
    pub capacity: Vec<f64>,
    /// Volume share of each node (`sum N_a dV`): distributes volumetric
    /// heat sources.
    pub volume: Vec<f64>,
}

/// Conduction matrices of cell `c` (reference configuration) for
/// conductivity `k` and volumetric capacity `rho_c`.
pub fn cell_conduction<const D: usize>(
    mesh: &Mesh<D>,
    c: usize,
    section: &Section,
    k: f64,
    rho_c: f64,
) -> Result<CellConduction, ElementError>
where
    Const<D>: Dimension<D>,
{
    let kernel = kernel_of::<D>(mesh.cells.kind(c))?;
    let points = kernel.shape_points(&mesh.cell_points(c), section)?;
    let nn = kernel.node_count();
    let mut out = CellConduction {
        nodes: nn,
        conductivity: vec![vec![0.0; nn]; nn],
        capacity: vec![0.0; nn],
        volume: vec![0.0; nn],
    };
    for p in &points {
        for a in 0..nn {
            for b in 0..nn {
                let g: f64 = (0..D).map(|k| p.dndx[a][k] * p.dndx[b][k]).sum();
                out.conductivity[a][b] += k * g * p.volume;
            }
            out.volume[a] += p.n[a] * p.volume;
            out.capacity[a] += rho_c * p.n[a] * p.volume;
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::Cell;
    use crate::model::AnalysisKind;

    fn section(kind: AnalysisKind) -> Section {
        Section {
            kind,
            thickness: 2.0,
        }
    }

    #[test]
    fn conduction_matrix_is_symmetric_with_zero_row_sums_and_exact_volume() {
        let mesh = Mesh::new(
            vec![[1.0, 0.0], [3.0, 0.5], [2.5, 2.0], [1.2, 1.5]],
            vec![Cell::quad(0, 1, 2, 3), Cell::tri(0, 1, 2)],
        );
        for kind in [AnalysisKind::PlaneStrain, AnalysisKind::Axisymmetric] {
            for cell in 0..mesh.cells.len() {
                let c = cell_conduction(&mesh, cell, &section(kind), 3.0, 5.0).unwrap();
                let n = c.nodes;
                for a in 0..n {
                    let row: f64 = c.conductivity[a][..n].iter().sum();
                    assert!(row.abs() < 1e-12, "{row}");
                    for b in 0..n {
                        assert!((c.conductivity[a][b] - c.conductivity[b][a]).abs() < 1e-12);
                    }
                }
                let v: f64 = c.volume[..n].iter().sum();
                let cap: f64 = c.capacity[..n].iter().sum();
                assert!((cap - 5.0 * v).abs() < 1e-12 * v);
            }
        }
    }

    #[test]
    fn solid_cells_are_symmetric_with_zero_row_sums_exact_volume_and_flux() {
        // a distorted hex8 and a tet4; T = 2x - y + 3z gives K T = 0 on the
        // sums and the exact flux k grad T . (sum of the nodal gradients)
        let x = [
            [0.0, 0.0, 0.0],
            [1.2, 0.1, 0.0],
            [1.1, 1.0, 0.1],
            [-0.1, 0.9, 0.0],
            [0.1, 0.0, 1.0],
            [1.0, 0.0, 1.1],
            [1.0, 1.1, 0.9],
            [0.0, 1.0, 1.0],
        ];
        let mesh = Mesh::<3>::new(
            x.to_vec(),
            vec![Cell::hex([0, 1, 2, 3, 4, 5, 6, 7]), Cell::tet([0, 1, 3, 4])],
        );
        let s = section(AnalysisKind::Solid);
        for (cell, tet) in [(0, false), (1, true)] {
            let c = cell_conduction(&mesh, cell, &s, 3.0, 5.0).unwrap();
            let n = c.nodes;
            for a in 0..n {
                let row: f64 = c.conductivity[a][..n].iter().sum();
                assert!(row.abs() < 1e-12, "{row}");
                for b in 0..n {
                    assert!((c.conductivity[a][b] - c.conductivity[b][a]).abs() < 1e-12);
                }
            }
            let v: f64 = c.volume.iter().sum();
            let cap: f64 = c.capacity.iter().sum();
            assert!((cap - 5.0 * v).abs() < 1e-12 * v);
            if tet {
                // tet (0, 1, 3, 4): det [x1 - x0, x3 - x0, x4 - x0] / 6
                let det = 1.2 * 0.9 - 0.1 * -0.1;
                assert!((v - det / 6.0).abs() < 1e-14, "{v}");
            }
            // a linear field: the nodal heat K T sums to zero (no source)
            let nodes = mesh.cells.nodes(cell);
            let t: Vec<f64> = nodes
                .iter()
                .map(|&i| 2.0 * x[i][0] - x[i][1] + 3.0 * x[i][2])
                .collect();
            let total: f64 = (0..n)
                .map(|a| (0..n).map(|b| c.conductivity[a][b] * t[b]).sum::<f64>())
                .sum();
            assert!(total.abs() < 1e-12, "{total}");
        }
    }

    #[test]
    fn linear_temperature_gives_the_exact_flux_on_a_rectangle() {
        // unit square, T = x: the nodal flux of K T is -k on the left
        // nodes and +k on the right ones (times thickness 2 / 2 per node)
        let mesh = Mesh::new(
            vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]],
            vec![Cell::quad(0, 1, 2, 3)],
        );
        let c = cell_conduction(&mesh, 0, &section(AnalysisKind::PlaneStrain), 3.0, 0.0).unwrap();
        let t = [0.0, 1.0, 1.0, 0.0];
        let f: Vec<f64> = (0..4)
            .map(|a| (0..4).map(|b| c.conductivity[a][b] * t[b]).sum())
            .collect();
        for (a, fa) in f.iter().enumerate() {
            let expect = if t[a] == 0.0 { -3.0 } else { 3.0 };
            assert!((fa - expect).abs() < 1e-12, "{f:?}");
        }
    }
}
