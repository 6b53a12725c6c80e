//! Contact of a solid (3D) model in the global system: the pairs of slave
//! face sets against rigid surface tools ([`crate::contact::surface`]),
//! their forces and 3x3 tangent blocks scattered into the global vectors
//! and matrix, the Lagrange rows `dg/dx = n`, and the contact loop around
//! the Newton loops of an increment (Lagrange active set, Uzawa updates of
//! the augmented Lagrangian, with the tangential shifts of friction and the
//! stick violation in its convergence test), the 3D counterpart of
//! [`super::contact_assembly`] and [`super::contact_loop`].
//!
//! Rigid tools add no unknowns and couple no nodes. Pairs between two
//! deformable solids (node-to-facet, [`crate::contact::node_to_facet`])
//! give per closed node a [`crate::contact::mortar::Coupling`] over the
//! slave and its facet's nodes: its forces and tangent are scattered, its
//! `G` is the Lagrange row, and the sparsity pattern grows when a slave
//! meets a facet it shares no cell with (the slave is then coupled to the
//! facet and the facets around it, kept for the run and for restarts).

use super::constraints::Constraints;
use super::contact_loop::{CyclingGuard, SetChange, MAX_CONTACT_ITERATIONS};
use super::diagnosis::PenaltyRatio;
use super::dofs::{Dof, DofMap};
use super::linalg::{Scatter, NO_SLOT};
use super::newton::{Converged, Failure, FailureKind, Newton};
use super::restart::PairHistory;
use super::scene::ContactScene;
use super::Observer;
use crate::contact::friction_lagrange::{self, SurfaceStatusChange};
use crate::contact::rows::{NodeRows, NodeTerm, RowKind};
use crate::contact::surface::{self, SurfacePair};
use crate::contact::{friction, friction_surface};
use crate::contact::{ContactStatus, NodeContact};
use crate::model::{ContactFormulation, ContactMethod, Model, MultiplierUpdate, NewtonSettings};
use ctc_geom::Placement;
use std::fmt::Write;

/// Gap below which an inactive Lagrange node is introduced, relative to
/// the size of the mesh (as in 2D: a node released exactly on the tool is
/// not re-introduced by round-off).
const INTRODUCE_GAP: f64 = 1e-14;

/// Contact state of a solid model and its last evaluation.
#[derive(Debug, Clone)]
pub struct SurfaceAssembly {
    /// State of each pair (slaves, areas, multipliers, active set).
    pub pairs: Vec<SurfacePair>,
    /// Evaluation of each pair at the last evaluated state.
    pub contact: Vec<Vec<NodeContact<3>>>,
    /// Lagrange constraints of the last evaluation, in dof terms.
    constraints: Constraints,
    /// Lagrange rows of the last evaluation, in node terms.
    rows: NodeRows,
    /// Direction (tool frame) of each tangential stick row, in row order.
    stick_directions: Vec<[f64; 3]>,
    /// Current nodal coordinates (scratch).
    x: Vec<[f64; 3]>,
    /// Time of the last evaluation (tool placement of the Uzawa updates).
    time: f64,
    /// Diagonal of the mesh's bounding box (introduction threshold).
    size: f64,
    /// CAD projections that failed at the last evaluation (pair, node,
    /// error): those nodes were left out of it.
    failures: Vec<(usize, usize, ctc_geom::ProjectionError)>,
    /// Node couplings added to the sparsity pattern by node-to-facet
    /// elements (sorted, kept for the rest of the run).
    couplings: Vec<(usize, usize)>,
    /// Times the sparsity pattern grew.
    pattern_growths: usize,
}

impl SurfaceAssembly {
    /// Introduces the inactive Lagrange nodes that penetrate, releases the
    /// active ones in tension or out of the window.
    fn update_active_sets(&mut self, model: &Model<3>) -> SetChange {
        let mut change = SetChange::default();
        let threshold = INTRODUCE_GAP * self.size;
        for (pi, cp) in model.contacts.iter().enumerate() {
            if !matches!(cp.method, ContactMethod::Lagrange { .. }) {
                continue;
            }
            let placement = cp
                .master
                .tool()
                .and_then(|k| model.surfaces.get(k))
                .map_or_else(Placement::identity, |tool| {
                    surface::placement(&tool.motion, self.time)
                });
            let state = &mut self.pairs[pi];
            let mut seen = vec![false; state.slaves.len()];
            for nc in &self.contact[pi] {
                let Some(i) = state.slave_index(nc.node) else {
                    continue;
                };
                seen[i] = true;
                if state.active[i] {
                    if state.multiplier[i] < 0.0 {
                        state.active[i] = false;
                        state.multiplier[i] = 0.0;
                        change.released.push(nc.node);
                    }
                } else if nc.gap < -threshold {
                    state.active[i] = true;
                    state.multiplier[i] = 0.0;
                    if cp.friction.is_some() {
                        friction_lagrange::reintroduce_slipping(
                            &mut state.friction,
                            i,
                            self.x[nc.node].into(),
                            nc.normal.into(),
                            &placement,
                        );
                    }
                    change.introduced.push(nc.node);
                }
            }
            for (i, s) in seen.iter().enumerate() {
                if !s && state.active[i] {
                    state.active[i] = false;
                    state.multiplier[i] = 0.0;
                    change.released.push(state.slaves[i]);
                }
            }
        }
        change
    }

    /// Uzawa update of the augmented-Lagrangian pairs of update mode
    /// `mode` whose largest violation exceeds their tolerance:
    /// `lambda* <- max(0, lambda* - alpha g)`. Whether any pair changed.
    fn uzawa_update(&mut self, model: &Model<3>, mode: MultiplierUpdate) -> bool {
        let mut updated = false;
        for (pi, cp) in model.contacts.iter().enumerate() {
            let ContactMethod::AugmentedLagrange {
                tolerance, update, ..
            } = cp.method
            else {
                continue;
            };
            // quadratic faces: the multipliers and the test at the points
            // (friction: the points' stick gaps and tangential shifts)
            let state = &mut self.pairs[pi];
            if let Some(fp) = &mut state.facets {
                let stick = if cp.friction.is_some() {
                    friction::stick_violation(&state.point_contact)
                } else {
                    0.0
                };
                if update == mode && fp.violation().max(stick) > tolerance {
                    fp.uzawa_update();
                    if cp.friction.is_some() {
                        let placement = cp
                            .master
                            .tool()
                            .and_then(|i| model.surfaces.get(i))
                            .map_or_else(Placement::identity, |tool| {
                                surface::placement(&tool.motion, self.time)
                            });
                        let points: Vec<usize> = (0..fp.rule.points.len()).collect();
                        friction_surface::uzawa_update(
                            &points,
                            &state.point_contact,
                            &placement,
                            &mut state.friction,
                        );
                    }
                    updated = true;
                }
                continue;
            }
            let list = &self.contact[pi];
            let violation = crate::contact::augmented::constraint_violation(list).max(
                if cp.friction.is_some() {
                    friction::stick_violation(list)
                } else {
                    0.0
                },
            );
            if update != mode || violation <= tolerance {
                continue;
            }
            let state = &mut self.pairs[pi];
            let mut next = vec![0.0; state.slaves.len()];
            for nc in list {
                if let Some(i) = state.slave_index(nc.node) {
                    let a = surface::alpha(&cp.method_at(nc.node), state.area[i]);
                    next[i] = (state.multiplier[i] - a * nc.gap).max(0.0);
                }
            }
            state.multiplier = next;
            if cp.friction.is_some() {
                // a deformable master (node-to-facet): shifts in the current
                // frame, stick points on the master facets
                let placement = cp
                    .master
                    .tool()
                    .and_then(|i| model.surfaces.get(i))
                    .map_or_else(Placement::identity, |tool| {
                        surface::placement(&tool.motion, self.time)
                    });
                match &state.deformable {
                    // mortar: the nodes' tangential forces (the reported
                    // traction is per reference area)
                    Some(fp) if cp.formulation == ContactFormulation::Mortar => {
                        crate::contact::mortar::friction3d::uzawa_update(
                            &state.slaves,
                            list,
                            &fp.tangential,
                            &mut state.friction,
                        );
                    }
                    _ => friction_surface::uzawa_update(
                        &state.slaves,
                        list,
                        &placement,
                        &mut state.friction,
                    ),
                }
            }
            updated = true;
        }
        updated
    }

    /// Adds the 3x3 blocks of the closed nodes of `res` (a rigid tool's
    /// pair) to `values`.
    fn add_node_blocks(&self, res: &[NodeContact<3>], scatter: &Scatter, values: &mut [f64]) {
        for nc in res {
            if nc.status != ContactStatus::Closed {
                continue;
            }
            let slots = scatter.node_slots(nc.node);
            for b in 0..3 {
                for a in 0..3 {
                    let s = slots[a + 3 * b];
                    if s != NO_SLOT {
                        values[s as usize] += nc.stiffness[a][b];
                    }
                }
            }
        }
    }

    /// The active sets, then the stick/slip statuses (cycling guard).
    fn active_key(&self) -> Vec<bool> {
        self.pairs
            .iter()
            .flat_map(|p| p.active.iter().copied())
            .chain(friction_lagrange::status_key(
                self.pairs.iter().map(|p| &p.friction),
            ))
            .collect()
    }

    /// Stick/slip status loop of the Lagrange pairs with friction
    /// ([`friction_lagrange::update_surface_status`]).
    fn update_friction_status(&mut self, model: &Model<3>) -> SurfaceStatusChange {
        let placement: Vec<_> = model
            .contacts
            .iter()
            .map(|cp| {
                cp.master
                    .tool()
                    .and_then(|i| model.surfaces.get(i))
                    .map(|tool| surface::placement(&tool.motion, self.time))
            })
            .collect();
        friction_lagrange::update_surface_status(
            model,
            &mut self.pairs,
            &self.contact,
            &placement,
            INTRODUCE_GAP * self.size,
        )
    }
}

impl ContactScene<3> for SurfaceAssembly {
    fn new(model: &Model<3>) -> Self {
        let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
        for p in &model.mesh.nodes {
            for c in 0..3 {
                lo[c] = lo[c].min(p[c]);
                hi[c] = hi[c].max(p[c]);
            }
        }
        let size = (0..3).map(|c| (hi[c] - lo[c]).powi(2)).sum::<f64>().sqrt();
        SurfaceAssembly {
            pairs: (0..model.contacts.len())
                .map(|i| SurfacePair::new(model, i))
                .collect(),
            contact: vec![Vec::new(); model.contacts.len()],
            constraints: Constraints::default(),
            rows: NodeRows::default(),
            stick_directions: Vec::new(),
            x: model.mesh.nodes.clone(),
            time: 0.0,
            size: if size.is_finite() && size > 0.0 {
                size
            } else {
                1.0
            },
            failures: Vec::new(),
            couplings: Vec::new(),
            pattern_growths: 0,
        }
    }

    fn evaluate(
        &mut self,
        model: &Model<3>,
        dofs: &DofMap<3>,
        u: &[[f64; 3]],
        t: f64,
        f_c: &mut [f64],
    ) {
        for ((x, x0), u) in self.x.iter_mut().zip(&model.mesh.nodes).zip(u) {
            for c in 0..3 {
                x[c] = x0[c] + u[c];
            }
        }
        self.failures.clear();
        self.time = t;
        for (i, state) in self.pairs.iter_mut().enumerate() {
            let (mut res, failed) = surface::evaluate_pair(model, i, &self.x, t, state);
            // two-way Lagrange pairs: the rows that repeat a neighbour's
            let free = |n: usize, c: usize| matches!(dofs.dofs[dofs.dof(n, c)], Dof::Free(_));
            crate::contact::node_to_facet::drop_redundant(
                &model.contacts[i],
                state,
                &mut res,
                &free,
            );
            self.failures
                .extend(failed.into_iter().map(|(n, e)| (i, n, e)));
            match &state.deformable {
                // node-to-facet: the couplings carry slave and master forces
                Some(fp) => {
                    for c in &fp.couplings {
                        for (k, &n) in c.nodes.iter().enumerate() {
                            for comp in 0..3 {
                                f_c[dofs.dof(n, comp)] += c.force[3 * k + comp];
                            }
                        }
                    }
                }
                // quadratic faces: the face rows carry the forces
                None if state.facets.is_some() => {
                    for c in &state.couplings {
                        for (k, &n) in c.nodes.iter().enumerate() {
                            for comp in 0..3 {
                                f_c[dofs.dof(n, comp)] += c.force[3 * k + comp];
                            }
                        }
                    }
                }
                None => {
                    for nc in &res {
                        for (c, f) in nc.force.iter().enumerate() {
                            f_c[dofs.dof(nc.node, c)] += f;
                        }
                    }
                }
            }
            self.contact[i] = res;
        }
    }

    fn grow_pattern(
        &mut self,
        model: &Model<3>,
        dofs: &DofMap<3>,
        scatter: &Scatter,
    ) -> Result<Option<Scatter>, String> {
        let couplings = &self.couplings;
        let missing = self
            .pairs
            .iter()
            .filter_map(|p| p.deformable.as_ref())
            .flat_map(|f| &f.couplings)
            .any(|c| {
                c.nodes.iter().any(|&a| {
                    c.nodes
                        .iter()
                        .any(|&b| !scatter.contact_coupled(dofs, couplings, a, b))
                })
            });
        if !missing {
            return Ok(None);
        }
        let mut near = Vec::new();
        for (state, res) in self.pairs.iter().zip(&self.contact) {
            let Some(fp) = &state.deformable else {
                continue;
            };
            // every node pair of a row (a mortar row spans the slave
            // facets around its node and the master facets they overlap)
            for c in &fp.couplings {
                for (k, &a) in c.nodes.iter().enumerate() {
                    for &b in &c.nodes[k + 1..] {
                        self.couplings.push((a.min(b), a.max(b)));
                    }
                }
            }
            for nc in res.iter().filter(|nc| nc.status == ContactStatus::Closed) {
                let Some(i) = state.slave_index(nc.node) else {
                    continue;
                };
                near.clear();
                fp.neighbourhood(i, nc.entity, &mut near);
                for &m in &near {
                    if m != nc.node {
                        self.couplings.push((nc.node.min(m), nc.node.max(m)));
                    }
                }
            }
        }
        self.couplings.sort_unstable();
        self.couplings.dedup();
        // the discrete elements' and free tools' couplings too (as the 2D
        // scene and a restart build it): a pattern of the contact couplings
        // alone dropped a spring link's off-diagonal tangent terms from the
        // first growth on, and Newton converged linearly (the 3D tube of
        // the dynamic buckling: 14 iterations per increment after a cutback
        // sequence, 3-4 after a restart from the same state)
        let grown = super::discrete::scatter_for(model, dofs, &self.couplings, scatter.share())?;
        self.pattern_growths += 1;
        Ok(Some(grown))
    }

    fn add_tangent(&self, scatter: &Scatter, dofs: &DofMap<3>, values: &mut [f64]) {
        for (state, res) in self.pairs.iter().zip(&self.contact) {
            if let Some(fp) = &state.deformable {
                for c in &fp.couplings {
                    super::contact_assembly::add_coupling(c, scatter, dofs, values);
                }
                continue;
            }
            if state.facets.is_some() {
                // quadratic faces: the face rows
                for c in &state.couplings {
                    super::contact_assembly::add_coupling(c, scatter, dofs, values);
                }
                continue;
            }
            self.add_node_blocks(res, scatter, values);
        }
    }
    fn build_constraints(&mut self, model: &Model<3>, dofs: &DofMap<3>) {
        self.rows.clear();
        for (pi, cp) in model.contacts.iter().enumerate() {
            if !matches!(cp.method, ContactMethod::Lagrange { .. }) {
                continue;
            }
            for nc in &self.contact[pi] {
                let Some(i) = self.pairs[pi].slave_index(nc.node) else {
                    continue;
                };
                if !self.pairs[pi].active[i] {
                    continue;
                }
                // quadratic faces: the node's weighted gap over its faces'
                // nodes
                if let Some(fp) = &self.pairs[pi].facets {
                    if let Some(row) = fp.row(nc.node) {
                        self.rows.push(
                            RowKind::Normal,
                            (pi, i),
                            row.gap,
                            row.terms.iter().copied(),
                        );
                    }
                    continue;
                }
                // node-to-facet: the row G over the slave and the facet nodes
                if let Some(fp) = &self.pairs[pi].deformable {
                    if let Ok(k) = fp.couplings.binary_search_by_key(&nc.node, |c| c.slave) {
                        crate::contact::lagrange::push_coupling(
                            &mut self.rows,
                            (pi, i),
                            nc.gap,
                            &fp.couplings[k],
                            3,
                        );
                    }
                    continue;
                }
                self.rows.push(
                    RowKind::Normal,
                    (pi, i),
                    nc.gap,
                    (0..3).map(|c| NodeTerm {
                        node: nc.node,
                        component: c,
                        coefficient: nc.normal[c],
                    }),
                );
            }
        }
        self.stick_directions.clear();
        friction_lagrange::surface_stick_rows(
            model,
            &self.pairs,
            &self.contact,
            &mut self.rows,
            &mut self.stick_directions,
        );
        self.constraints.build(&self.rows, dofs);
    }

    fn constraints(&self) -> &Constraints {
        &self.constraints
    }

    fn apply_multiplier_corrections(&mut self, dlambda: &[f64]) {
        let mut directions = self.stick_directions.iter();
        for ((&(p, i), kind), dl) in self
            .constraints
            .owner
            .iter()
            .zip(&self.constraints.kind)
            .zip(dlambda)
        {
            match kind {
                RowKind::Normal => self.pairs[p].multiplier[i] += dl,
                RowKind::Stick => {
                    if let Some(t) = directions.next() {
                        let m = &mut self.pairs[p].friction.shift[i];
                        for c in 0..3 {
                            m[c] += t[c] * dl;
                        }
                    }
                }
            }
        }
    }

    fn newton_multiplier_update(&mut self, model: &Model<3>) -> bool {
        self.uzawa_update(model, MultiplierUpdate::Newton)
    }

    fn semismooth_update(&mut self, model: &Model<3>) -> bool {
        let threshold = INTRODUCE_GAP * self.size;
        let mut switched = false;
        for (pi, cp) in model.contacts.iter().enumerate() {
            if !crate::contact::semismooth::applies(cp) {
                continue;
            }
            let young = crate::contact::semismooth::young(model, cp);
            let state = &mut self.pairs[pi];
            let area = &state.area;
            let c = |i: usize| young * area.get(i).copied().unwrap_or(0.0).sqrt();
            let redundant = &state.redundant;
            let keep = |i: usize| redundant.get(i).copied().unwrap_or(false);
            let s = crate::contact::semismooth::update(
                &state.slaves,
                &mut state.active,
                &mut state.multiplier,
                &mut state.switches,
                &self.contact[pi],
                c,
                keep,
                threshold,
            );
            crate::contact::semismooth::log(&cp.name, &s);
            // Lagrange friction against a tool: a node introduced again in
            // the increment comes back slipping (as in the active-set loop)
            if cp.friction.is_some() && !s.introduced.is_empty() {
                let placement = cp
                    .master
                    .tool()
                    .and_then(|k| model.surfaces.get(k))
                    .map_or_else(Placement::identity, |tool| {
                        surface::placement(&tool.motion, self.time)
                    });
                for nc in &self.contact[pi] {
                    if s.introduced.binary_search(&nc.node).is_err() {
                        continue;
                    }
                    if let Some(i) = state.slave_index(nc.node) {
                        friction_lagrange::reintroduce_slipping(
                            &mut state.friction,
                            i,
                            self.x[nc.node].into(),
                            nc.normal.into(),
                            &placement,
                        );
                    }
                }
            }
            switched |= !s.is_empty();
        }
        switched
    }

    fn contact(&self) -> &[Vec<NodeContact<3>>] {
        &self.contact
    }

    fn contact_mut(&mut self) -> &mut [Vec<NodeContact<3>>] {
        &mut self.contact
    }

    fn active_contacts(&self) -> usize {
        self.contact
            .iter()
            .flatten()
            .filter(|c| c.status == ContactStatus::Closed)
            .count()
    }

    fn max_penetration(&self) -> f64 {
        self.contact
            .iter()
            .flatten()
            .map(|c| -c.gap)
            .fold(0.0, f64::max)
    }

    fn commit(&mut self) {
        for p in &mut self.pairs {
            p.commit();
        }
    }

    fn guard_start(&mut self, quasi_static: bool) {
        for fp in self.pairs.iter_mut().filter_map(|p| p.deformable.as_mut()) {
            fp.hold_friction = quasi_static;
            fp.guard_start();
        }
    }

    fn guard_cycle(&mut self, model: &Model<3>) -> bool {
        let mut held = 0;
        // 3D mortar and node-to-facet: the nodes closed at this iterate
        // (the hold of the next, `mortar::HOLD_BAND`)
        for fp in self.pairs.iter_mut().filter_map(|p| p.deformable.as_mut()) {
            fp.accept_iterate();
        }
        for ((state, cp), res) in self
            .pairs
            .iter_mut()
            .zip(&model.contacts)
            .zip(&self.contact)
        {
            // node-to-facet penalty pairs (mortar is evaluated elsewhere)
            if !matches!(cp.method, ContactMethod::Penalty { .. })
                || cp.formulation == ContactFormulation::Mortar
            {
                continue;
            }
            if let Some(fp) = state.deformable.as_mut() {
                let n = fp.guard_cycle(&state.slaves, res);
                if n > 0 && crate::contact::log::debug_enabled() {
                    eprintln!(
                        "[ctc ntf] pair '{}': cycling guard holds {n} more nodes",
                        cp.name
                    );
                }
                held += n;
            }
        }
        held > 0
    }

    fn guard_consistent(&mut self) -> bool {
        let mut ok = true;
        for (state, res) in self.pairs.iter_mut().zip(&self.contact) {
            if let Some(fp) = state.deformable.as_mut() {
                ok &= fp.guard_consistent(&state.slaves, res);
            }
        }
        ok
    }

    fn rollback(&mut self) {
        for p in &mut self.pairs {
            p.rollback();
        }
    }

    fn pattern_growths(&self) -> usize {
        self.pattern_growths
    }

    fn penalty_ratio(&self, _: &Model<3>, _: &Scatter, _: &[f64]) -> Option<PenaltyRatio> {
        None
    }

    fn impact_fraction(&self, model: &Model<3>) -> Option<f64> {
        model
            .contacts
            .iter()
            .zip(&self.pairs)
            .filter(|(c, _)| c.friction.is_some_and(|f| f.cut_at_impact))
            .filter_map(|(_, p)| p.friction.impact)
            .reduce(f64::min)
    }

    fn increment_warnings(
        &self,
        model: &Model<3>,
        before: (&[[f64; 3]], f64),
        after: (&[[f64; 3]], f64),
        increment: usize,
    ) -> Vec<String> {
        // a slave node that moved farther than the window relative to the
        // tool in one increment may have passed through a thin tool
        let mut out: Vec<String> = self
            .failures
            .iter()
            .map(|(p, n, e)| {
                format!(
                    "increment {increment}: slave node {n} of pair `{}`: {e}; the node was left \
                     out of the contact evaluation (check the CAD faces near it)",
                    model.contacts[*p].name
                )
            })
            .collect();
        // node-to-facet pairs: the deck's slave nodes against the master
        // faces (the rule of `contact::jump` in 3D)
        let place = |u: &[[f64; 3]]| -> Vec<[f64; 3]> {
            model
                .mesh
                .nodes
                .iter()
                .zip(u)
                .map(|(x, d)| std::array::from_fn(|c| x[c] + d[c]))
                .collect()
        };
        let deformable = model
            .contacts
            .iter()
            .any(|c| matches!(c.master, crate::model::ContactMaster::Surface { .. }));
        let (x0, x1) = if deformable {
            (place(before.0), place(after.0))
        } else {
            (Vec::new(), Vec::new())
        };
        for (pi, cp) in model.contacts.iter().enumerate() {
            let crate::model::ContactMaster::Surface { faces, .. } = &cp.master else {
                continue;
            };

            let mut master = crate::contact::node_to_facet::FacetSurface::new(faces);
            let prof = self.pairs[pi].prof;
            let jumps =
                crate::contact::node_to_facet::jumps(&mut master, &cp.nodes, prof, &x0, &x1);
            out.extend(crate::contact::jump::warning(
                &cp.name, increment, after.1, prof, &jumps,
            ));
        }
        for (pi, cp) in model.contacts.iter().enumerate() {
            let Some(tool) = cp.master.tool().and_then(|i| model.surfaces.get(i)) else {
                continue;
            };
            let (p0, p1) = (
                surface::placement(&tool.motion, before.1),
                surface::placement(&tool.motion, after.1),
            );
            let prof = self.pairs[pi].prof;
            let worst = cp
                .nodes
                .iter()
                .map(|&n| {
                    let x0 = model.mesh.nodes[n];
                    let at = |u: &[f64; 3], p: &ctc_geom::Placement| {
                        p.to_reference(&ctc_geom::Vec3::from_fn(|k, _| x0[k] + u[k]))
                    };
                    ((at(&after.0[n], &p1) - at(&before.0[n], &p0)).norm(), n)
                })
                .fold((0.0, usize::MAX), |a, b| if b.0 > a.0 { b } else { a });
            if prof > 0.0 && worst.0 > prof {
                out.push(format!(
                    "increment {increment}: slave node {} of pair `{}` moved {:.3e} relative to \
                     the tool, more than the search window prof = {:.3e}; reduce the time step \
                     if the node may have crossed the tool",
                    worst.1, cp.name, worst.0, prof
                ));
            }
        }
        out
    }

    fn search_figures(&self, model: &Model<3>) -> Vec<surface::SearchFigures> {
        model
            .contacts
            .iter()
            .zip(&self.pairs)
            .map(|(cp, p)| {
                let tool = cp
                    .master
                    .tool()
                    .and_then(|i| model.surfaces.get(i))
                    .map_or("", |t| t.name.as_str());
                p.figures(&cp.name, tool)
            })
            .collect()
    }

    fn friction_work(&self) -> Vec<f64> {
        self.contact
            .iter()
            .map(|l| friction::pair_dissipation(l))
            .collect()
    }

    fn history(&self) -> (Vec<PairHistory>, Vec<(usize, usize)>) {
        let pairs = self
            .pairs
            .iter()
            .map(|p| {
                let (multiplier, active) = p.committed();
                PairHistory {
                    // node-to-facet: the search memory (the seam rule
                    // depends on it)
                    entity: p
                        .deformable
                        .as_ref()
                        .map_or_else(|| vec![None; p.slaves.len()], |f| f.memory().to_vec()),
                    // face-integrated pairs: the points' multipliers follow
                    multiplier: multiplier
                        .iter()
                        .chain(p.facets.iter().flat_map(|f| &f.committed))
                        .copied()
                        .collect(),
                    active: active.to_vec(),
                    friction: p.friction.committed_values(),
                    // node-to-facet penalty: the nodes beside the master
                    beside: p
                        .deformable
                        .as_ref()
                        .map_or_else(Vec::new, |f| f.committed_beside().to_vec()),
                }
            })
            .collect();
        (pairs, self.couplings.clone())
    }

    fn restore(
        &mut self,
        pairs: &[PairHistory],
        increment: usize,
        positions: &[[f64; 3]],
    ) -> Result<(), String> {
        if pairs.len() != self.pairs.len() {
            return Err("the restart point does not match the model (contact pairs)".into());
        }
        for (s, h) in self.pairs.iter_mut().zip(pairs) {
            let n = s.slaves.len();
            let points = s.facets.as_ref().map_or(0, |f| f.committed.len());
            if h.multiplier.len() != n + points || h.active.len() != n {
                return Err("the restart point does not match the model (slave nodes)".into());
            }
            if let Some(fp) = &mut s.facets {
                fp.restore(&h.multiplier[n..])?;
            }
            // restart points written before 3D friction carry no friction
            // state: start from none
            if !h.friction.is_empty() {
                s.friction.restore_committed(&h.friction)?;
            }
            if let Some(f) = &mut s.deformable {
                if h.entity.len() != n || !(h.beside.is_empty() || h.beside.len() == n) {
                    return Err("the restart point does not match the model (slave nodes)".into());
                }
                f.restore(increment, &h.entity, positions, &h.beside);
            }
            s.restore(&h.multiplier[..n], &h.active);
        }
        Ok(())
    }

    fn set_couplings(&mut self, couplings: &[(usize, usize)]) {
        self.couplings = couplings.to_vec();
    }

    /// The closed-gap start of the node-to-facet pairs that involve a body
    /// held only by contact (slave or master; frictionless: all of them in
    /// 3D): [`crate::contact::penalty::TOUCH_FRACTION`] of the pair's
    /// smallest slave facet edge, as in 2D.
    fn set_touching(&mut self, model: &Model<3>, on: bool) {
        let held = if on {
            super::check::held_only_by_contact(model)
        } else {
            Vec::new()
        };
        let held = |b: usize| held.get(b).copied().unwrap_or(false);
        for (cp, state) in model.contacts.iter().zip(&mut self.pairs) {
            state.touching = 0.0;
            let crate::model::ContactMaster::Surface { body, .. } = &cp.master else {
                continue;
            };
            if !on || !(held(cp.body) || held(*body)) || cp.friction.is_some() {
                continue;
            }
            let nodes = &model.mesh.nodes;
            let h = cp
                .faces
                .iter()
                .flat_map(|f| {
                    let n = f.nodes();
                    (0..n.len()).map(move |k| (n[k], n[(k + 1) % n.len()]))
                })
                .filter_map(|(a, b)| {
                    let (pa, pb) = (nodes.get(a)?, nodes.get(b)?);
                    Some((0..3).map(|c| (pb[c] - pa[c]).powi(2)).sum::<f64>().sqrt())
                })
                .filter(|l| *l > 0.0)
                .fold(f64::INFINITY, f64::min);
            if h.is_finite() {
                state.touching = crate::contact::penalty::TOUCH_FRACTION * h;
            }
        }
    }

    fn contact_csv(
        model: &Model<3>,
        pair: usize,
        displacement: &[[f64; 3]],
        contact: &[NodeContact<3>],
    ) -> String {
        use crate::output::encode::Shortest as N;
        let cp = &model.contacts[pair];
        let friction = cp.friction.is_some();
        let mut s = String::from("node,x,y,z,gap,pressure,status,force_x,force_y,force_z");
        s.push_str(if friction {
            ",tangential_x,tangential_y,tangential_z,slip,friction_status,dissipation\n"
        } else {
            "\n"
        });
        // both surfaces' nodes when both act as slaves (double passes), as
        // in 2D: a double pass's second side carries the contact in every
        // other increment
        for n in crate::contact::node_to_facet::slave_nodes(model, pair) {
            let x0 = model.mesh.nodes[n];
            let u = displacement[n];
            let _ = write!(
                s,
                "{n},{},{},{}",
                N(x0[0] + u[0]),
                N(x0[1] + u[1]),
                N(x0[2] + u[2])
            );
            match contact.iter().find(|c| c.node == n) {
                Some(c) => {
                    let _ = write!(
                        s,
                        ",{},{},{},{},{},{}",
                        N(c.gap),
                        N(c.pressure),
                        u8::from(c.status == ContactStatus::Closed),
                        N(c.force[0]),
                        N(c.force[1]),
                        N(c.force[2])
                    );
                    if friction {
                        let f = &c.friction;
                        let _ = write!(
                            s,
                            ",{},{},{},{},{},{}",
                            N(f.traction[0]),
                            N(f.traction[1]),
                            N(f.traction[2]),
                            N(f.slip),
                            friction::status_code(f.status),
                            N(f.dissipation)
                        );
                    }
                    s.push('\n');
                }
                None => {
                    s.push_str(",,0,0,0,0,0");
                    s.push_str(if friction { ",0,0,0,0,0,0\n" } else { "\n" });
                }
            }
        }
        s
    }

    fn attempt(
        newton: &mut Newton<'_, 3>,
        settings: &NewtonSettings,
        t: f64,
        step: usize,
        increment: usize,
        observer: &mut dyn Observer<3>,
    ) -> Result<Converged, Failure> {
        let mut residuals: Vec<f64> = Vec::new();
        let mut iterations = 0;
        let mut updates = 0;
        let mut guard = CyclingGuard::new(newton.contacts.active_key());
        for _ in 0..MAX_CONTACT_ITERATIONS {
            let conv = newton
                .newton_loop(settings, t, step, increment, observer)
                .map_err(|mut f| {
                    let mut r = residuals.clone();
                    r.append(&mut f.residuals);
                    f.residuals = r;
                    f
                })?;
            iterations += conv.iterations;
            updates += conv.contact_iterations;
            residuals.extend_from_slice(&conv.residuals);
            let model = newton.model;
            // the contact and friction loops in one pass: the stick/slip
            // statuses of the nodes that stay closed are decided on the same
            // solution as the active set (see `friction_lagrange`)
            let mut change = newton.contacts.update_active_sets(model);
            change
                .introduced
                .extend(newton.contacts.update_friction_status(model).switched);
            if !change.is_empty() {
                updates += 1;
                if let Err(detail) = guard.visit(newton.contacts.active_key(), &change) {
                    return Err(Failure {
                        kind: FailureKind::ActiveSetCycling,
                        residuals,
                        detail,
                    });
                }
                continue;
            }
            if newton
                .contacts
                .uzawa_update(model, MultiplierUpdate::Converged)
            {
                updates += 1;
                continue;
            }
            return Ok(Converged {
                iterations,
                residuals,
                active_contacts: conv.active_contacts,
                contact_iterations: updates,
                max_penetration: conv.max_penetration,
            });
        }
        Err(Failure {
            kind: FailureKind::MaxIterations,
            residuals,
            detail: format!(
                "the contact iterations (active set / Uzawa updates) did not settle in \
                 {MAX_CONTACT_ITERATIONS} Newton loops"
            ),
        })
    }
}
