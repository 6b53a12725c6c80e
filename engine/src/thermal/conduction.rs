//! Heat conduction element kernels (tri3, quad4; plane and axisymmetric):
//! conductivity matrix `K_e = sum k grad(N_a) . grad(N_b) dV` and lumped
//! (row-sum) capacity `C_a = sum rho c N_a dV`, with the same integration
//! points and volume weights as the mechanical elements (`dV = w det(J) t`
//! plane, `w det(J) 2 pi r` axisymmetric: totals over the full ring).
//!
//! The capacity is lumped so that the implicit (backward Euler) transient
//! respects the discrete maximum principle on reasonable meshes.

use crate::element::{quad4, tri3, ElementError, RefPoint, Section};
use crate::mesh::{Cell, CellKind, Mesh};

/// Conductivity and lumped capacity of one cell (4 nodes at most; a
/// triangle uses the leading 3x3 block).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CellConduction {
    /// Number of nodes of the cell.
    pub nodes: usize,
    /// Conductivity matrix (row-major).
    pub conductivity: [[f64; 4]; 4],
    /// Lumped capacity per node (`rho c` times the nodal volume share).
    pub capacity: [f64; 4],
    /// Volume share of each node (`sum N_a dV`): distributes volumetric
    /// heat sources.
    pub volume: [f64; 4],
}

fn integrate<const NN: usize>(points: &[RefPoint<NN>], k: f64, rho_c: f64) -> CellConduction {
    let mut out = CellConduction {
        nodes: NN,
        conductivity: [[0.0; 4]; 4],
        capacity: [0.0; 4],
        volume: [0.0; 4],
    };
    for p in points {
        for a in 0..NN {
            for b in 0..NN {
                let g = p.dndx[a][0] * p.dndx[b][0] + p.dndx[a][1] * p.dndx[b][1];
                out.conductivity[a][b] += k * g * p.volume;
            }
            out.volume[a] += p.n[a] * p.volume;
            out.capacity[a] += rho_c * p.n[a] * p.volume;
        }
    }
    out
}

/// Conduction matrices of `cell` (reference configuration) for
/// conductivity `k` and volumetric capacity `rho_c`.
pub fn cell_conduction(
    mesh: &Mesh,
    cell: &Cell,
    section: &Section,
    k: f64,
    rho_c: f64,
) -> Result<CellConduction, ElementError> {
    let at = |i: usize| mesh.nodes[cell.nodes[i]];
    match cell.kind {
        CellKind::Tri3 => {
            let x = [at(0), at(1), at(2)];
            let pts = tri3::reference_points(&x, section)?;
            Ok(integrate(&pts, k, rho_c))
        }
        CellKind::Quad4 => {
            let x = [at(0), at(1), at(2), at(3)];
            let (pts, _) = quad4::reference_points(&x, section)?;
            Ok(integrate(&pts, k, rho_c))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
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
            for cell in &mesh.cells {
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
    fn linear_temperature_gives_the_exact_flux_on_a_rectangle() {
        // unit square, T = x: the nodal flux of K T is -k on the left
        // nodes and +k on the right ones (times thickness 2 / 2 per node)
        let mesh = Mesh::new(
            vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]],
            vec![Cell::quad(0, 1, 2, 3)],
        );
        let c = cell_conduction(
            &mesh,
            &mesh.cells[0],
            &section(AnalysisKind::PlaneStrain),
            3.0,
            0.0,
        )
        .unwrap();
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
