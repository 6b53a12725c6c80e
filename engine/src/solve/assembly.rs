//! Element loop: internal forces and tangent stiffness of every cell,
//! scattered into the global force vector and the sparse value array.
//! Serial, in cell order: results are bit-for-bit reproducible.

use super::pattern::{Scatter, NO_SLOT};
use crate::element::recovery::{blocks_of, gather, CellBlock};
use crate::element::{quad4, tri3, ElementResponse, Section};
use crate::mesh::{CellKind, Mesh};
use crate::model::Model;

/// The element kernels of a model.
#[derive(Debug, Clone)]
pub struct Assembler {
    /// One block of cells per body, with its law and formulation.
    pub blocks: Vec<CellBlock>,
    /// Cross-section (kind, thickness).
    pub section: Section,
}

impl Assembler {
    /// Builds the kernels of `model` (materials must be valid).
    pub fn new(model: &Model) -> Result<Self, String> {
        Ok(Assembler {
            blocks: blocks_of(model)?,
            section: Section::new(&model.analysis),
        })
    }

    /// Internal forces `f_int` (2 per node, overwritten) at displacements
    /// `u`, and, if `values` is given, the tangent (the caller zeroes
    /// `values`; element entries are added).
    pub fn assemble(
        &self,
        mesh: &Mesh,
        scatter: &Scatter,
        u: &[[f64; 2]],
        f_int: &mut [f64],
        mut values: Option<&mut [f64]>,
    ) -> Result<(), String> {
        f_int.fill(0.0);
        let with_tangent = values.is_some();
        for block in &self.blocks {
            for c in block.cells.clone() {
                let cell = &mesh.cells[c];
                let slots = scatter.cell_slots(c);
                let err = |e: crate::element::ElementError| format!("cell {c}: {}", e.message);
                match cell.kind {
                    CellKind::Tri3 => {
                        let (x, ue) = gather::<3, 6>(mesh, &cell.nodes, u);
                        let r = tri3::response(&x, &ue, &self.section, &block.law, with_tangent)
                            .map_err(err)?;
                        add(&r, cell.node_slice(), slots, f_int, values.as_deref_mut());
                    }
                    CellKind::Quad4 => {
                        let (x, ue) = gather::<4, 8>(mesh, &cell.nodes, u);
                        let r = quad4::response(
                            &x,
                            &ue,
                            &self.section,
                            block.formulation,
                            &block.law,
                            with_tangent,
                        )
                        .map_err(err)?;
                        add(&r, cell.node_slice(), slots, f_int, values.as_deref_mut());
                    }
                }
            }
        }
        Ok(())
    }
}

#[inline]
fn add<const ND: usize>(
    r: &ElementResponse<ND>,
    nodes: &[usize],
    slots: &[u32],
    f_int: &mut [f64],
    values: Option<&mut [f64]>,
) {
    for (i, f) in r.force.iter().enumerate() {
        f_int[2 * nodes[i / 2] + i % 2] += f;
    }
    if let Some(values) = values {
        for (&slot, k) in slots.iter().zip(r.stiffness.as_slice()) {
            if slot != NO_SLOT {
                values[slot as usize] += k;
            }
        }
    }
}
