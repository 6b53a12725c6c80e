//! Lifecycle of the solution state: an increment attempt changes only
//! trial values (displacements, integration points, contact history);
//! [`Newton::commit`] makes them the converged state, [`Newton::rollback`]
//! returns to it (cutback), [`Newton::checkpoint`] / [`Newton::restore`]
//! write and read it as a restart point.

use super::Newton;
use crate::solve::linalg::Scatter;
use crate::solve::restart::{self, Checkpoint, PairHistory, Resume};

impl Newton<'_> {
    /// Nodal displacements of the last converged state.
    pub(crate) fn committed_displacement(&self) -> &[[f64; 2]] {
        &self.committed
    }

    /// Makes the current state the converged one.
    pub fn commit(&mut self) {
        self.flips.clear();
        self.committed.copy_from_slice(&self.u);
        self.assembler.commit();
        self.contacts.commit();
    }

    /// Returns to the last converged state.
    pub fn rollback(&mut self) {
        self.u.copy_from_slice(&self.committed);
        self.assembler.rollback();
        self.contacts.rollback();
    }

    /// The committed state as a restart checkpoint (stepping fields from
    /// the caller).
    pub(crate) fn checkpoint(&self, increment: usize, resume: Resume) -> Checkpoint {
        Checkpoint {
            fingerprint: restart::fingerprint(self.model),
            increment,
            resume,
            displacement: self.committed.clone(),
            pairs: self
                .contacts
                .pairs
                .iter()
                .map(|p| PairHistory {
                    entity: p.committed_entity.clone(),
                    multiplier: p.committed_multiplier.clone(),
                    active: p.committed_active.clone(),
                    friction: p.friction.committed_values(),
                })
                .collect(),
            points: self.assembler.points().to_vec(),
            points_time: self.assembler.committed_time(),
            couplings: self.contacts.couplings.clone(),
        }
    }

    /// Makes `cp` the committed (and current) state.
    pub(crate) fn restore(&mut self, cp: &Checkpoint) -> Result<(), String> {
        if cp.displacement.len() != self.u.len() || cp.pairs.len() != self.contacts.pairs.len() {
            return Err("the restart point does not match the model (nodes or pairs)".into());
        }
        for (s, h) in self.contacts.pairs.iter_mut().zip(&cp.pairs) {
            let n = s.committed_entity.len();
            if h.entity.len() != n || h.multiplier.len() != n || h.active.len() != n {
                return Err("the restart point does not match the model (slave nodes)".into());
            }
            s.committed_entity.clone_from(&h.entity);
            s.committed_multiplier.clone_from(&h.multiplier);
            s.committed_active.clone_from(&h.active);
            s.friction.restore_committed(&h.friction)?;
            if let Some(sp) = &mut s.surface {
                sp.restore(cp.increment);
            }
            s.rollback();
        }
        self.assembler.restore(&cp.points, cp.points_time)?;
        if !cp.couplings.is_empty() {
            self.contacts.couplings.clone_from(&cp.couplings);
            self.scatter = Scatter::with_couplings(&self.model.mesh, &self.dofs, &cp.couplings)?;
            self.values = vec![0.0; self.scatter.n_values()];
            self.linear.reset_pattern();
        }
        self.committed.copy_from_slice(&cp.displacement);
        self.u.copy_from_slice(&cp.displacement);
        Ok(())
    }
}
