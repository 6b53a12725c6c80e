//! Lifecycle of the solution state: an increment attempt changes only
//! trial values (displacements, integration points, contact history);
//! [`Newton::commit`] makes them the converged state, [`Newton::rollback`]
//! returns to it (cutback), [`Newton::checkpoint`] / [`Newton::restore`]
//! write and read it as a restart point.

use super::Newton;
use crate::geom::Dimension;
use crate::solve::restart::{self, Checkpoint, Resume};
use crate::solve::scene::ContactScene;
use nalgebra::Const;

impl<const D: usize> Newton<'_, D>
where
    Const<D>: Dimension<D>,
{
    /// Nodal displacements of the last converged state.
    pub(crate) fn committed_displacement(&self) -> &[[f64; D]] {
        &self.committed
    }

    /// Makes the current state the converged one.
    pub fn commit(&mut self) {
        self.flips.clear();
        self.touch_start = false;
        self.any_committed = true;
        self.stabilization.commit(
            &self.dofs.free,
            self.u.as_flattened(),
            self.committed.as_flattened(),
            &self.f_int,
        );
        if self.dynamics.is_some() {
            let (ext, prescribed) = self.audit_forces();
            let penalty = crate::solve::dynamics::penalty_energy(self.contacts.contact());
            if let Some(dy) = self.dynamics.as_mut() {
                dy.commit(
                    self.model,
                    self.u.as_flattened(),
                    self.committed.as_flattened(),
                    &self.r_static,
                    [&self.f_int, &ext, &self.f_c, &self.damping],
                    &prescribed,
                );
                dy.energy.penalty = penalty;
                // the friction work by the rule of the other work integrals
                dy.friction_work(self.contacts.contact_mut());
            }
        }
        // the increment's start: the end of the last one recorded (exact
        // grid times), else the assembler's accumulated time
        let t0 = self
            .history
            .last
            .as_ref()
            .map_or(self.assembler.committed_time(), |h| h.times.1);
        let (step, t1) = self.attempt;
        self.history.record(step, t0, t1, &self.committed);
        self.fresh = true;
        self.committed.copy_from_slice(&self.u);
        self.rechart_rotations();
        self.assembler.commit();
        // distributed assembly: every rank receives the other ranks' points
        let linear = &self.linear;
        self.assembler
            .exchange_points(|v: &mut [f64]| linear.sum_over_ranks(v));
        self.contacts.commit();
    }

    /// The external forces of the energy audit at the end of the attempt
    /// and the prescribed dofs: the loads, follower loads and the
    /// reactions at the end of the increment (the static part here, `M
    /// a1` added by [`crate::solve::dynamics::Dynamics::audit`]; not the
    /// generalized-alpha weighted reactions of the residual, whose
    /// `alpha_f r(u0)` share would count the drive's work `1 / (1 -
    /// alpha_f)` times).
    fn audit_forces(&self) -> (Vec<f64>, Vec<usize>) {
        let mut ext = self.f_ext.clone();
        for (e, f) in ext.iter_mut().zip(&self.f_follow) {
            *e += f;
        }
        let prescribed: Vec<usize> = self.dofs.prescribed.iter().map(|p| p.dof).collect();
        for &g in &prescribed {
            ext[g] += self.r_static[g];
        }
        (ext, prescribed)
    }

    /// The energy the last converged attempt of a dynamic increment would
    /// create if committed ([`crate::solve::dynamics::Energy::created_since`]:
    /// the growth of the kinetic energy, internal and damping work and
    /// stored penalty energy beyond the work of the loads and supports),
    /// the scale it is weighed against (the largest energy of the run,
    /// this attempt's included) and where (words: the node whose contact
    /// forces did the most work in the attempt, its gap at the end). `None`:
    /// a quasi-static increment, or one without a contact force at its
    /// start or end: the control weighs what contact creates, and the
    /// scheme's own numerical dissipation of an increment takes either
    /// sign (the planar blade loss's spin-up from rest: +2.9e-4, -1.5e-4,
    /// +7.7e-4 mJ in successive increments; at `energy_tol = 1e-4` it
    /// redid 597 of 1098 increments before this rule).
    pub fn energy_created(&self) -> Option<(f64, f64, String)> {
        let dy = self.dynamics.as_ref()?;
        dy.active()?;
        // no contact force at either end of the increment: nothing for
        // the control to weigh (the scheme's own numerical dissipation of
        // an increment takes either sign)
        let f0 = dy.contact_force0();
        if self.f_c.iter().chain(f0).all(|&f| f == 0.0) {
            return None;
        }
        let (ext, prescribed) = self.audit_forces();
        let u = self.u.as_flattened();
        let u0 = self.committed.as_flattened();
        let mut audit = dy.audit(
            self.model,
            u,
            u0,
            [&self.f_int, &ext, &self.f_c, &self.damping],
            &prescribed,
        );
        audit.energy.penalty = crate::solve::dynamics::penalty_energy(self.contacts.contact());
        let created = audit.energy.created_since(&dy.energy);
        let scale = audit.energy.scale.max(audit.energy.penalty);
        // the node whose contact forces did the most work in the attempt
        let mut best = (0.0, usize::MAX);
        for n in 0..u.len() / D {
            let w: f64 = (n * D..n * D + D)
                .map(|g| 0.5 * (self.f_c[g] + f0[g]) * (u[g] - u0[g]))
                .sum();
            if w > best.0 {
                best = (w, n);
            }
        }
        let at = if best.1 == usize::MAX {
            "no node's contact forces did positive work".to_string()
        } else {
            let n = best.1;
            let gap = self
                .contacts
                .contact()
                .iter()
                .enumerate()
                .flat_map(|(p, l)| l.iter().map(move |c| (p, c)))
                .filter(|(_, c)| c.node == n)
                .map(|(p, c)| format!(" (pair {p}: gap {:.3e})", c.gap))
                .next()
                .unwrap_or_default();
            format!("node {n}'s contact forces did {:.3e} of work{gap}", best.0)
        };
        if crate::contact::log::debug_enabled() {
            eprintln!(
                "energy control: t = {:.6e}: created {created:.4e} (contact work {:.4e}, \
                 penalty energy {:.4e} -> {:.4e}, balance {:.4e} -> {:.4e}), scale {scale:.4e}; {at}",
                self.attempt.1,
                audit.energy.contact - dy.energy.contact,
                dy.energy.penalty,
                audit.energy.penalty,
                dy.energy.balance,
                audit.energy.balance,
            );
        }
        Some((created, scale, at))
    }

    /// Free 3D rigid bodies whose rotation vector ended the increment past
    /// `pi`: the committed state carried over to the equivalent rotation
    /// vector `psi (1 - 2 pi / |psi|)` ([`crate::solve::rotation_chart`]),
    /// so a body turns any number of times away from the singular `|psi| =
    /// 2 pi`. Bodies with a prescribed rotation component are left alone.
    fn rechart_rotations(&mut self) {
        use crate::solve::dofs::Dof;
        use crate::solve::rotation_chart::{complement, equivalent, Chart};
        if D != 3 {
            return;
        }
        for (_, spin) in crate::solve::rigid_body::bodies(self.model) {
            let dofs: [usize; 3] = std::array::from_fn(|c| self.dofs.dof(spin, c));
            if dofs
                .iter()
                .any(|&g| !matches!(self.dofs.dofs[g], Dof::Free(_)))
            {
                continue;
            }
            let psi: [f64; 3] = std::array::from_fn(|c| self.u[spin][c]);
            let Some(new) = equivalent(psi) else {
                continue;
            };
            // regular: |psi| just past pi after a converged increment
            let Some(chart) = Chart::new(psi, new) else {
                continue;
            };
            self.u[spin][..3].copy_from_slice(&new);
            self.committed[spin][..3].copy_from_slice(&new);
            if let Some(h) = self.history.last.as_mut() {
                let start: [f64; 3] = std::array::from_fn(|c| h.start[spin][c]);
                let start = complement(start);
                h.start[spin][..3].copy_from_slice(&start);
            }
            if let Some(dy) = self.dynamics.as_mut() {
                dy.rechart(dofs, &chart);
            }
            self.stabilization.rechart(dofs, &chart);
        }
    }

    /// Returns to the last converged state.
    pub fn rollback(&mut self) {
        self.u.copy_from_slice(&self.committed);
        self.touch_start = !self.any_committed;
        self.fresh = true;
        self.assembler.rollback();
        self.contacts.rollback();
    }

    /// The committed state as a restart checkpoint (stepping fields from
    /// the caller).
    pub(crate) fn checkpoint(&self, increment: usize, resume: Resume) -> Checkpoint<D> {
        let (pairs, couplings) = self.contacts.history();
        Checkpoint {
            fingerprint: *self
                .fingerprint
                .get_or_init(|| restart::fingerprint(self.model)),
            increment,
            resume,
            displacement: self.committed.clone(),
            pairs,
            // a split share: gathered on the first rank, which writes the
            // restart file (collective: every rank builds the checkpoint)
            points: self
                .assembler
                .gathered_points(|local| self.linear.gather_on_first(local)),
            points_time: self.assembler.committed_time(),
            couplings,
            dynamics: self.dynamics.as_ref().map(|d| d.saved()),
            predictor: self.history.last.clone(),
        }
    }

    /// Makes `cp` the committed (and current) state.
    pub(crate) fn restore(&mut self, cp: &Checkpoint<D>) -> Result<(), String> {
        if cp.displacement.len() != self.u.len() {
            return Err("the restart point does not match the model (nodes or pairs)".into());
        }
        if let Some(dy) = self.dynamics.as_mut() {
            match &cp.dynamics {
                Some(s) => dy.restore(s)?,
                None if cp.increment > 0 => {
                    return Err("the restart point holds no velocities or accelerations (a \
                                file of the previous format): run from the start"
                        .into())
                }
                None => {}
            }
        }
        let positions: Vec<[f64; D]> = self
            .model
            .mesh
            .nodes
            .iter()
            .zip(&cp.displacement)
            .map(|(x, u)| std::array::from_fn(|c| x[c] + u[c]))
            .collect();
        self.contacts.restore(&cp.pairs, cp.increment, &positions)?;
        self.assembler.restore(&cp.points, cp.points_time)?;
        if !cp.couplings.is_empty() {
            self.contacts.set_couplings(&cp.couplings);
            self.scatter = super::super::discrete::scatter_for(
                self.model,
                &self.dofs,
                &cp.couplings,
                self.scatter.share(),
            )?;
            self.values = vec![0.0; self.scatter.n_values()];
            self.linear.reset_pattern();
        }
        self.committed.copy_from_slice(&cp.displacement);
        self.u.copy_from_slice(&cp.displacement);
        self.any_committed = cp.increment > 0;
        self.touch_start = !self.any_committed;
        self.history.last = cp.predictor.clone();
        self.fresh = true;
        Ok(())
    }
}
