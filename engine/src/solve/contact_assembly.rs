//! Contact in the global system: evaluation of every pair at the current
//! configuration, scatter of the contact forces and tangent blocks into the
//! global vectors and matrix, growth of the sparsity pattern when contact
//! couples nodes that share no cell, and the Lagrange constraint rows.
//!
//! The contact laws (`crate::contact`) work in node terms: a
//! [`NodeContact`] gives the force on its slave node, the forces on its
//! master nodes and the tangent over those nodes; a Lagrange law gives its
//! constraint rows as `(node, component, d g / d x)`
//! ([`crate::contact::rows::NodeRows`]). This module is the only place that
//! maps nodes to dofs for contact (through [`DofMap`] and [`Scatter`]).
//! The number of components per node is the dof map's (the length of the
//! nodal arrays), not a literal.

use super::constraints::Constraints;
use super::dofs::{Dof, DofMap};
use super::linalg::{Scatter, NO_SLOT};
use crate::contact::rows::NodeRows;
use crate::contact::{self, ContactStatus, NodeContact, PairState};
use crate::model::Model;

/// Contact state of a run and its last evaluation.
#[derive(Debug, Clone)]
pub struct ContactAssembly {
    /// Contact state of each pair (search history, multipliers, active set,
    /// friction history).
    pub pairs: Vec<PairState>,
    /// Evaluation of each pair at the last evaluated state.
    pub contact: Vec<Vec<NodeContact>>,
    /// Lagrange constraints of the last evaluation, in dof terms.
    pub constraints: Constraints,
    /// Lagrange constraint rows of the last evaluation, in node terms.
    rows: NodeRows,
    /// Current nodal coordinates (scratch).
    x: Vec<[f64; 2]>,
    /// Node couplings added to the sparsity pattern by node-to-segment
    /// contact elements (sorted, kept for the rest of the run).
    pub couplings: Vec<(usize, usize)>,
    /// Times the sparsity pattern grew.
    pub pattern_growths: usize,
    /// Free tools: the coupling rows of their angles at the last
    /// evaluation (`free_tool::assemble`).
    pub rotation_rows: Vec<contact::mortar::Coupling>,
}

impl ContactAssembly {
    /// The pairs of `model` in their reference configuration.
    pub fn new(model: &Model) -> Self {
        ContactAssembly {
            pairs: (0..model.contacts.len())
                .map(|i| PairState::new(model, i))
                .collect(),
            contact: vec![Vec::new(); model.contacts.len()],
            constraints: Constraints::default(),
            rows: NodeRows::default(),
            x: model.mesh.nodes.clone(),
            couplings: Vec::new(),
            pattern_growths: 0,
            rotation_rows: Vec::new(),
        }
    }

    /// Evaluates every pair at displacements `u` and time `t` and adds the
    /// contact forces (slave and master nodes) to `f_c` (global dofs).
    pub fn evaluate(
        &mut self,
        model: &Model,
        dofs: &DofMap,
        u: &[[f64; 2]],
        t: f64,
        f_c: &mut [f64],
    ) {
        for ((x, x0), u) in self.x.iter_mut().zip(&model.mesh.nodes).zip(u) {
            for ((xc, x0c), uc) in x.iter_mut().zip(x0).zip(u) {
                *xc = x0c + uc;
            }
        }
        let free = model.tools.iter().any(|t| t.free_rotation.is_some());
        if free {
            super::free_tool::set_angles(model, u, &mut self.pairs);
        }
        for (i, state) in self.pairs.iter_mut().enumerate() {
            let mut res = contact::evaluate_pair(model, i, &self.x, t, state);
            let free = |n: usize, c: usize| matches!(dofs.dofs[dofs.dof(n, c)], Dof::Free(_));
            // mortar: the coupling rows carry the forces (the node entries
            // repeat their sums at the slave nodes, for output)
            if state.couplings.is_some() {
                contact::node_to_segment::drop_redundant(
                    &model.contacts[i],
                    state,
                    &mut res,
                    &free,
                );
            }
            if let Some(rows) = &state.couplings {
                for c in rows {
                    for (k, &n) in c.nodes.iter().enumerate() {
                        for comp in 0..dofs.components() {
                            f_c[dofs.dof(n, comp)] += c.force[dofs.components() * k + comp];
                        }
                    }
                }
                self.contact[i] = res;
                continue;
            }
            if state.touching > 0.0
                && matches!(
                    model.contacts[i].method,
                    crate::model::ContactMethod::Lagrange { .. }
                )
            {
                // closed-gap start: touching nodes join the active set (their
                // multiplier is 0, so their force and tangent are unchanged)
                for nc in &res {
                    if let Some(k) = state.slave_index(nc.node) {
                        if nc.gap <= state.touching && !state.active[k] {
                            state.active[k] = true;
                            state.multiplier[k] = 0.0;
                        }
                    }
                }
            }
            // two-way Lagrange pairs: the rows that repeat a neighbour's
            contact::node_to_segment::drop_redundant(&model.contacts[i], state, &mut res, &free);
            for nc in &res {
                for (c, f) in nc.force.iter().enumerate() {
                    f_c[dofs.dof(nc.node, c)] += f;
                }
                if let Some(ms) = &nc.master {
                    for (&m, f) in ms.nodes.iter().zip(&ms.forces) {
                        for (c, fc) in f.iter().enumerate() {
                            f_c[dofs.dof(m, c)] += fc;
                        }
                    }
                }
            }
            self.contact[i] = res;
        }
        if free {
            super::free_tool::assemble(
                model,
                dofs,
                &self.pairs,
                &self.contact,
                &self.x,
                t,
                f_c,
                &mut self.rotation_rows,
            );
        }
    }

    /// Turns the closed-gap start on (the first iteration of the analysis)
    /// or off: the touching tolerance of every frictionless pair that
    /// involves a body held only by contact (slave or master,
    /// [`crate::solve::check::held_only_by_contact`]; the other pairs are
    /// left as they are) is [`contact::penalty::TOUCH_FRACTION`] of its
    /// smallest slave edge.
    pub fn set_touching(&mut self, model: &Model, on: bool) {
        let held = if on {
            crate::solve::check::held_only_by_contact(model)
        } else {
            Vec::new()
        };
        let held = |b: usize| held.get(b).copied().unwrap_or(false);
        for (i, state) in self.pairs.iter_mut().enumerate() {
            state.touching = 0.0;
            let Some(cp) = model.contacts.get(i).filter(|_| on) else {
                continue;
            };
            let master_held = match &cp.master {
                crate::model::ContactMaster::Surface { body, .. } => held(*body),
                crate::model::ContactMaster::Tool(_) => false,
            };
            // frictional pairs keep their first-impact stick points: only
            // `stabilize` helps them
            if !(held(cp.body) || master_held) || cp.friction.is_some() {
                continue;
            }
            let nodes = &model.mesh.nodes;
            let h = cp
                .edges
                .iter()
                .filter_map(|&[a, b]| {
                    let (pa, pb) = (nodes.get(a)?, nodes.get(b)?);
                    Some((pb[0] - pa[0]).hypot(pb[1] - pa[1]))
                })
                .filter(|l| *l > 0.0)
                .fold(f64::INFINITY, f64::min);
            if h.is_finite() {
                state.touching = contact::penalty::TOUCH_FRACTION * h;
            }
        }
    }

    /// Adds the contact tangent blocks of the last evaluation to the matrix
    /// `values` (slots of `scatter`); entries missing from the pattern are
    /// skipped (grow the pattern first, [`ContactAssembly::grow_pattern`]).
    pub fn add_tangent(&self, scatter: &Scatter, dofs: &DofMap, values: &mut [f64]) {
        let nc_dim = dofs.components();
        for c in &self.rotation_rows {
            add_coupling(c, scatter, dofs, values);
        }
        for (res, state) in self.contact.iter().zip(&self.pairs) {
            if let Some(rows) = &state.couplings {
                for c in rows {
                    add_coupling(c, scatter, dofs, values);
                }
                continue;
            }
            for nc in res {
                match &nc.master {
                    None => {
                        let slots = scatter.node_slots(nc.node);
                        for b in 0..nc_dim {
                            for a in 0..nc_dim {
                                let s = slots[a + nc_dim * b];
                                if s != NO_SLOT {
                                    values[s as usize] += nc.stiffness[a][b];
                                }
                            }
                        }
                    }
                    Some(ms) => {
                        let nodes = [nc.node, ms.nodes[0], ms.nodes[1]];
                        for (bj, &nb) in nodes.iter().enumerate() {
                            for (bi, &na) in nodes.iter().enumerate() {
                                if !scatter.adds_rows_of(na) {
                                    continue;
                                }
                                let Some(slots) = scatter.pair_slots(dofs, na, nb) else {
                                    continue;
                                };
                                for b in 0..nc_dim {
                                    for a in 0..nc_dim {
                                        let s = slots[a + nc_dim * b];
                                        if s != NO_SLOT {
                                            values[s as usize] +=
                                                ms.tangent[nc_dim * bi + a][nc_dim * bj + b];
                                        }
                                    }
                                }
                            }
                        }
                    }
                }
            }
        }
    }

    /// Grows the sparsity pattern when a node-to-segment element of the
    /// last evaluation couples nodes that share no cell and are not coupled
    /// yet: the slave is coupled to the whole neighbourhood of its segment
    /// (see [`contact::node_to_segment::neighbourhood`]) so that the pattern
    /// grows rarely; added couplings stay for the rest of the run. Returns
    /// the new scatter map when the pattern grew (the caller resizes the
    /// value array and resets the linear system's symbolic analysis).
    pub fn grow_pattern(
        &mut self,
        model: &Model,
        dofs: &DofMap,
        scatter: &Scatter,
    ) -> Result<Option<Scatter>, String> {
        let couplings = &self.couplings;
        let coupled = |a: usize, b: usize| scatter.contact_coupled(dofs, couplings, a, b);
        // the master segment's own pair too: under a distributed assembly
        // its cell may be another rank's (alone it is always in the pattern)
        let missing = self.contact.iter().flatten().any(|nc| {
            nc.master.as_ref().is_some_and(|ms| {
                !coupled(ms.nodes[0], ms.nodes[1]) || ms.nodes.iter().any(|&m| !coupled(nc.node, m))
            })
        });
        let rows = || {
            self.pairs
                .iter()
                .filter_map(|s| s.couplings.as_ref())
                .flatten()
        };
        let missing_rows = rows().any(|c| {
            c.nodes
                .iter()
                .any(|&a| c.nodes.iter().any(|&b| !coupled(a, b)))
        });
        if !missing && !missing_rows {
            return Ok(None);
        }
        let mut extra = Vec::new();
        for c in rows() {
            for &a in &c.nodes {
                for &b in &c.nodes {
                    if a < b {
                        extra.push((a, b));
                    }
                }
            }
        }
        self.couplings.extend(extra);
        let split = scatter.share().is_some_and(|s| s.split());
        let mut near = Vec::new();
        for (p, res) in self.contact.iter().enumerate() {
            for nc in res {
                let Some(ms) = &nc.master else {
                    continue;
                };
                near.clear();
                near.extend(ms.nodes);
                contact::node_to_segment::neighbourhood(
                    &self.pairs[p],
                    nc.node,
                    nc.entity,
                    &mut near,
                );
                for &m in &near {
                    if m != nc.node {
                        self.couplings.push((nc.node.min(m), nc.node.max(m)));
                    }
                }
                if split {
                    // the pairs of the master nodes around it as well (the
                    // test above asks for the list, not the rank's cells)
                    for (k, &a) in near.iter().enumerate() {
                        for &b in &near[k + 1..] {
                            if a != b {
                                self.couplings.push((a.min(b), a.max(b)));
                            }
                        }
                    }
                }
            }
        }
        self.couplings.sort_unstable();
        self.couplings.dedup();
        let grown = super::discrete::scatter_for(model, dofs, &self.couplings, scatter.share())?;
        self.pattern_growths += 1;
        Ok(Some(grown))
    }

    /// Builds the Lagrange constraints of the last evaluation: normal rows
    /// of the active nodes, then stick rows of Lagrange friction.
    pub fn build_constraints(&mut self, model: &Model, dofs: &DofMap) {
        self.rows.clear();
        contact::lagrange::normal_rows(model, &self.pairs, &self.contact, &mut self.rows);
        contact::friction_lagrange::stick_rows(model, &self.contact, &mut self.rows);
        self.constraints.build(&self.rows, dofs);
    }

    /// Closed contact nodes at the last evaluation.
    pub fn active_contacts(&self) -> usize {
        self.contact
            .iter()
            .flatten()
            .filter(|c| c.status == ContactStatus::Closed)
            .count()
    }

    /// Largest penetration over all pairs at the last evaluation.
    pub fn max_penetration(&self) -> f64 {
        self.contact
            .iter()
            .map(|c| contact::augmented::max_penetration(c))
            .fold(0.0, f64::max)
    }

    /// Commits the contact history of a converged increment.
    pub fn commit(&mut self) {
        for p in &mut self.pairs {
            p.commit();
        }
    }

    /// Restores the contact history of the last converged increment.
    pub fn rollback(&mut self) {
        for p in &mut self.pairs {
            p.rollback();
        }
    }
}

/// Adds the tangent of one coupling row (any number of nodes, the dof
/// map's components per node; mortar and smoothed node-to-segment in 2D,
/// node-to-facet and the face rows of quadratic faces against surface tools
/// in 3D).
pub(crate) fn add_coupling<const D: usize>(
    c: &contact::mortar::Coupling,
    scatter: &Scatter,
    dofs: &DofMap<D>,
    values: &mut [f64],
) {
    let dim = dofs.components();
    let nd = dim * c.nodes.len();
    for (bj, &nb) in c.nodes.iter().enumerate() {
        for (bi, &na) in c.nodes.iter().enumerate() {
            if !scatter.adds_rows_of(na) {
                continue;
            }
            let Some(slots) = scatter.pair_slots(dofs, na, nb) else {
                continue;
            };
            for b in 0..dim {
                for a in 0..dim {
                    let s = slots[a + dim * b];
                    if s != NO_SLOT {
                        values[s as usize] += c.tangent[(dim * bi + a) * nd + dim * bj + b];
                    }
                }
            }
        }
    }
}
