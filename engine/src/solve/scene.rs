//! The seams of the dimension-generic solver: what contact and heat
//! conduction give the Newton loop, whatever the dimension.
//!
//! The Newton solver ([`super::newton::Newton`]), the driver ([`super::run`])
//! and the restart points are generic over the dimension `D`; contact and
//! the thermal coupling reach them only through the two traits here, chosen
//! per dimension by [`crate::geom::Dimension`] (`type Contact`, `type Heat`):
//!
//! - [`ContactScene`]: contact forces, tangent blocks, pattern growth,
//!   Lagrange rows, the contact loop around the Newton loops, contact
//!   history for restarts. 2D: [`ContactAssembly`] (rigid tools and
//!   node-to-segment, every method); 3D:
//!   [`super::surface_assembly::SurfaceAssembly`] (rigid surface tools and
//!   node-to-facet pairs between deformable solids: penalty, Lagrange
//!   multipliers, augmented Lagrangian);
//!   [`NoContact`] for scenes of any dimension without contact.
//! - [`HeatCoupling`]: the staggered heat step,
//!   [`crate::thermal::coupling::Coupling`] in both dimensions (one code
//!   path: conduction on every cell kind, boundary terms on facets, contact
//!   conductance against planar tools, master segments and 3D surface
//!   tools).

use super::constraints::Constraints;
use super::contact_assembly::ContactAssembly;
use super::diagnosis::PenaltyRatio;
use super::dofs::DofMap;
use super::linalg::Scatter;
use super::newton::{Converged, Failure, Newton};
use super::restart::PairHistory;
use super::Observer;
use crate::contact::rows::RowKind;
use crate::contact::NodeContact;
use crate::element::MaterialPoint;
use crate::geom::Dimension;
use crate::material::NonlinearLaw;
use crate::model::{Model, MultiplierUpdate, NewtonSettings};
use crate::thermal::solver::ThermalIncrement;
use nalgebra::Const;

/// Contact as the solver sees it, in dimension `D`.
pub trait ContactScene<const D: usize>: Sized + Clone + std::fmt::Debug {
    /// The pairs of `model` in their reference configuration.
    fn new(model: &Model<D>) -> Self;
    /// Evaluates every pair at displacements `u` and time `t`; adds the
    /// contact forces to `f_c` (global dofs).
    fn evaluate(
        &mut self,
        model: &Model<D>,
        dofs: &DofMap<D>,
        u: &[[f64; D]],
        t: f64,
        f_c: &mut [f64],
    );
    /// The new scatter map when the last evaluation couples nodes missing
    /// from the pattern of `scatter`.
    fn grow_pattern(
        &mut self,
        model: &Model<D>,
        dofs: &DofMap<D>,
        scatter: &Scatter,
    ) -> Result<Option<Scatter>, String>;
    /// Adds the contact tangent of the last evaluation to `values`.
    fn add_tangent(&self, scatter: &Scatter, dofs: &DofMap<D>, values: &mut [f64]);
    /// Builds the Lagrange constraints of the last evaluation.
    fn build_constraints(&mut self, model: &Model<D>, dofs: &DofMap<D>);
    /// The Lagrange constraints of the last evaluation, in dof terms.
    fn constraints(&self) -> &Constraints;
    /// Adds the multiplier corrections of a saddle-point solve (one per
    /// constraint row) to the multipliers they belong to.
    fn apply_multiplier_corrections(&mut self, dlambda: &[f64]);
    /// Augmented Lagrangian with `update = newton`: updates the
    /// multipliers inside the Newton loop; whether any changed.
    fn newton_multiplier_update(&mut self, model: &Model<D>) -> bool;
    /// Mortar with Lagrange multipliers: the semi-smooth Newton update of
    /// the active sets at the current iterate
    /// ([`crate::contact::semismooth`]); whether any node switched.
    fn semismooth_update(&mut self, model: &Model<D>) -> bool;
    /// Contact evaluation of each pair at the last evaluated state (empty
    /// without contact).
    fn contact(&self) -> &[Vec<NodeContact<D>>];
    /// The same, to amend at a commit (the time scheme's friction work,
    /// [`super::dynamics::Dynamics::friction_work`]).
    fn contact_mut(&mut self) -> &mut [Vec<NodeContact<D>>];
    /// Closed contact nodes at the last evaluation.
    fn active_contacts(&self) -> usize;
    /// Largest penetration at the last evaluation.
    fn max_penetration(&self) -> f64;
    /// Commits the contact history of a converged increment.
    fn commit(&mut self);
    /// Restores the contact history of the last converged increment.
    fn rollback(&mut self);
    /// Times the sparsity pattern grew.
    fn pattern_growths(&self) -> usize;
    /// The largest penalty / element stiffness ratio (diagnosis).
    fn penalty_ratio(
        &self,
        model: &Model<D>,
        scatter: &Scatter,
        values: &[f64],
    ) -> Option<PenaltyRatio>;
    /// Smallest fraction of the increment at which a node of a pair with
    /// `cut_at_impact` first touched its master.
    fn impact_fraction(&self, model: &Model<D>) -> Option<f64>;
    /// Warnings for slave nodes that moved farther than the search window
    /// in the increment from `(u0, t0)` to `(u1, t1)`.
    fn increment_warnings(
        &self,
        model: &Model<D>,
        before: (&[[f64; D]], f64),
        after: (&[[f64; D]], f64),
        increment: usize,
    ) -> Vec<String>;
    /// Friction work of the last evaluation, per pair.
    fn friction_work(&self) -> Vec<f64>;
    /// Search and projection figures of the pairs against surface tools
    /// over the run so far (3D; empty otherwise).
    fn search_figures(&self, _model: &Model<D>) -> Vec<crate::contact::surface::SearchFigures> {
        Vec::new()
    }
    /// Committed contact history per pair and the pattern couplings (for a
    /// restart point).
    fn history(&self) -> (Vec<PairHistory>, Vec<(usize, usize)>);
    /// Restores the committed history of a restart point written after
    /// increment `increment`, whose committed nodal coordinates are
    /// `positions`.
    fn restore(
        &mut self,
        pairs: &[PairHistory],
        increment: usize,
        positions: &[[f64; D]],
    ) -> Result<(), String>;
    /// Sets the pattern couplings of a restart point.
    fn set_couplings(&mut self, couplings: &[(usize, usize)]);
    /// The contact CSV of pair `pair` (`crate::output::contact_csv`).
    fn contact_csv(
        model: &Model<D>,
        pair: usize,
        displacement: &[[f64; D]],
        contact: &[NodeContact<D>],
    ) -> String;
    /// Turns the closed-gap start (slave nodes touching their master count
    /// as closed) on or off; planar pairs only (`PairState::touching`).
    fn set_touching(&mut self, _model: &Model<D>, _on: bool) {}
    /// A Newton loop starts: the penalty cycling guard forgets what it
    /// held (3D node-to-facet pairs,
    /// `crate::contact::node_to_facet::DeformablePair::guard_cycle`);
    /// `quasi_static`: the step has no inertia (the hold keeps frictional
    /// node-to-facet nodes too,
    /// `crate::contact::node_to_facet::DeformablePair::hold_friction`).
    fn guard_start(&mut self, _quasi_static: bool) {}
    /// After an accepted Newton iterate: the penalty cycling guard holds
    /// the nodes whose statuses cycle; whether it held new ones (the
    /// tangent at hand is then stale).
    fn guard_cycle(&mut self, _model: &Model<D>) -> bool {
        false
    }
    /// At a converged iterate: whether the nodes the guard froze agree
    /// with the contact law there (if not, they are released and the
    /// Newton loop goes on).
    fn guard_consistent(&mut self) -> bool {
        true
    }
    /// One increment attempt: the Newton loops of `newton` inside the
    /// contact loop (Lagrange active set, Uzawa updates).
    fn attempt(
        newton: &mut Newton<'_, D>,
        settings: &NewtonSettings,
        t: f64,
        step: usize,
        increment: usize,
        observer: &mut dyn Observer<D>,
    ) -> Result<Converged, Failure>
    where
        Const<D>: Dimension<D>;
}

impl ContactScene<2> for ContactAssembly {
    fn new(model: &Model) -> Self {
        ContactAssembly::new(model)
    }

    fn evaluate(&mut self, model: &Model, dofs: &DofMap, u: &[[f64; 2]], t: f64, f_c: &mut [f64]) {
        ContactAssembly::evaluate(self, model, dofs, u, t, f_c);
    }

    fn set_touching(&mut self, model: &Model, on: bool) {
        ContactAssembly::set_touching(self, model, on);
    }

    fn grow_pattern(
        &mut self,
        model: &Model,
        dofs: &DofMap,
        scatter: &Scatter,
    ) -> Result<Option<Scatter>, String> {
        ContactAssembly::grow_pattern(self, model, dofs, scatter)
    }

    fn add_tangent(&self, scatter: &Scatter, dofs: &DofMap, values: &mut [f64]) {
        ContactAssembly::add_tangent(self, scatter, dofs, values);
    }

    fn build_constraints(&mut self, model: &Model, dofs: &DofMap) {
        ContactAssembly::build_constraints(self, model, dofs);
    }

    fn constraints(&self) -> &Constraints {
        &self.constraints
    }

    fn apply_multiplier_corrections(&mut self, dlambda: &[f64]) {
        let pairs = &mut self.pairs;
        for ((&(p, i), kind), dl) in self
            .constraints
            .owner
            .iter()
            .zip(&self.constraints.kind)
            .zip(dlambda)
        {
            match kind {
                RowKind::Stick => pairs[p].friction.multiplier[i] += dl,
                RowKind::Normal => pairs[p].multiplier[i] += dl,
            }
        }
    }

    fn newton_multiplier_update(&mut self, model: &Model) -> bool {
        crate::contact::augmented::uzawa_update(
            model,
            &mut self.pairs,
            &self.contact,
            MultiplierUpdate::Newton,
        )
    }

    fn semismooth_update(&mut self, model: &Model) -> bool {
        let threshold = super::contact_loop::introduce_threshold(model);
        let ring = crate::contact::mortar::weight(model);
        let mut switched = false;
        for (pi, cp) in model.contacts.iter().enumerate() {
            if !crate::contact::semismooth::applies(cp) {
                continue;
            }
            let young = crate::contact::semismooth::young(model, cp);
            let state = &mut self.pairs[pi];
            let slaves = &state.slaves;
            let c = |i: usize| {
                let w = match ring {
                    crate::contact::mortar::integrals::Weight::Thickness(t) => t,
                    crate::contact::mortar::integrals::Weight::Axisymmetric => {
                        2.0 * std::f64::consts::PI * model.mesh.nodes[slaves[i]][0].abs()
                    }
                };
                young * w
            };
            let redundant = &state.redundant;
            let keep = |i: usize| redundant.get(i).copied().unwrap_or(false);
            let s = crate::contact::semismooth::update(
                slaves,
                &mut state.active,
                &mut state.multiplier,
                &mut state.switches,
                &self.contact[pi],
                c,
                keep,
                threshold,
            );
            crate::contact::semismooth::log(&cp.name, &s);
            switched |= !s.is_empty();
        }
        switched
    }

    fn contact(&self) -> &[Vec<NodeContact>] {
        &self.contact
    }

    fn contact_mut(&mut self) -> &mut [Vec<NodeContact>] {
        &mut self.contact
    }

    fn active_contacts(&self) -> usize {
        ContactAssembly::active_contacts(self)
    }

    fn max_penetration(&self) -> f64 {
        ContactAssembly::max_penetration(self)
    }

    fn commit(&mut self) {
        ContactAssembly::commit(self);
    }

    fn rollback(&mut self) {
        ContactAssembly::rollback(self);
    }

    fn pattern_growths(&self) -> usize {
        self.pattern_growths
    }

    fn penalty_ratio(
        &self,
        model: &Model,
        scatter: &Scatter,
        values: &[f64],
    ) -> Option<PenaltyRatio> {
        super::diagnosis::penalty_ratio(model, self, scatter, values)
    }

    fn impact_fraction(&self, model: &Model) -> Option<f64> {
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
        model: &Model,
        before: (&[[f64; 2]], f64),
        after: (&[[f64; 2]], f64),
        increment: usize,
    ) -> Vec<String> {
        super::jumps::increment_warnings(model, &self.pairs, before, after, increment)
    }

    fn friction_work(&self) -> Vec<f64> {
        self.contact
            .iter()
            .map(|l| crate::contact::friction::pair_dissipation(l))
            .collect()
    }

    fn history(&self) -> (Vec<PairHistory>, Vec<(usize, usize)>) {
        let pairs = self
            .pairs
            .iter()
            .map(|p| PairHistory {
                entity: p.committed_entity.clone(),
                // face-integrated pairs: the points' multipliers follow
                multiplier: p
                    .committed_multiplier
                    .iter()
                    .chain(p.facets.iter().flat_map(|f| &f.committed))
                    .copied()
                    .collect(),
                active: p.committed_active.clone(),
                friction: p.friction.committed_values(),
                beside: Vec::new(),
            })
            .collect();
        (pairs, self.couplings.clone())
    }

    fn restore(
        &mut self,
        pairs: &[PairHistory],
        increment: usize,
        positions: &[[f64; 2]],
    ) -> Result<(), String> {
        if pairs.len() != self.pairs.len() {
            return Err("the restart point does not match the model (nodes or pairs)".into());
        }
        for (s, h) in self.pairs.iter_mut().zip(pairs) {
            let n = s.committed_entity.len();
            let points = s.facets.as_ref().map_or(0, |f| f.committed.len());
            if h.entity.len() != n || h.multiplier.len() != n + points || h.active.len() != n {
                return Err("the restart point does not match the model (slave nodes)".into());
            }
            s.committed_entity.clone_from(&h.entity);
            s.committed_multiplier = h.multiplier[..n].to_vec();
            if let Some(fp) = &mut s.facets {
                fp.restore(&h.multiplier[n..])?;
            }
            s.committed_active.clone_from(&h.active);
            s.friction.restore_committed(&h.friction)?;
            if let Some(sp) = &mut s.surface {
                sp.restore(increment, positions);
            }
            s.rollback();
        }
        Ok(())
    }

    fn set_couplings(&mut self, couplings: &[(usize, usize)]) {
        self.couplings = couplings.to_vec();
    }

    fn contact_csv(
        model: &Model,
        pair: usize,
        displacement: &[[f64; 2]],
        contact: &[NodeContact],
    ) -> String {
        crate::output::contact_csv::contact_csv(model, pair, displacement, contact)
    }

    fn attempt(
        newton: &mut Newton<'_, 2>,
        settings: &NewtonSettings,
        t: f64,
        step: usize,
        increment: usize,
        observer: &mut dyn Observer<2>,
    ) -> Result<Converged, Failure> {
        super::contact_loop::attempt(newton, settings, t, step, increment, observer)
    }
}

/// No contact at all (a scene without pairs, in any dimension).
#[derive(Debug, Clone, Default)]
pub struct NoContact {
    constraints: Constraints,
}

impl<const D: usize> ContactScene<D> for NoContact {
    fn new(_: &Model<D>) -> Self {
        NoContact::default()
    }

    fn evaluate(&mut self, _: &Model<D>, _: &DofMap<D>, _: &[[f64; D]], _: f64, _: &mut [f64]) {}

    fn grow_pattern(
        &mut self,
        _: &Model<D>,
        _: &DofMap<D>,
        _: &Scatter,
    ) -> Result<Option<Scatter>, String> {
        Ok(None)
    }

    fn add_tangent(&self, _: &Scatter, _: &DofMap<D>, _: &mut [f64]) {}

    fn build_constraints(&mut self, _: &Model<D>, _: &DofMap<D>) {}

    fn constraints(&self) -> &Constraints {
        &self.constraints
    }

    fn apply_multiplier_corrections(&mut self, _: &[f64]) {}

    fn newton_multiplier_update(&mut self, _: &Model<D>) -> bool {
        false
    }

    fn semismooth_update(&mut self, _: &Model<D>) -> bool {
        false
    }

    fn contact(&self) -> &[Vec<NodeContact<D>>] {
        &[]
    }

    fn contact_mut(&mut self) -> &mut [Vec<NodeContact<D>>] {
        &mut []
    }

    fn active_contacts(&self) -> usize {
        0
    }

    fn max_penetration(&self) -> f64 {
        0.0
    }

    fn commit(&mut self) {}

    fn rollback(&mut self) {}

    fn pattern_growths(&self) -> usize {
        0
    }

    fn penalty_ratio(&self, _: &Model<D>, _: &Scatter, _: &[f64]) -> Option<PenaltyRatio> {
        None
    }

    fn impact_fraction(&self, _: &Model<D>) -> Option<f64> {
        None
    }

    fn increment_warnings(
        &self,
        _: &Model<D>,
        _: (&[[f64; D]], f64),
        _: (&[[f64; D]], f64),
        _: usize,
    ) -> Vec<String> {
        Vec::new()
    }

    fn friction_work(&self) -> Vec<f64> {
        Vec::new()
    }

    fn history(&self) -> (Vec<PairHistory>, Vec<(usize, usize)>) {
        (Vec::new(), Vec::new())
    }

    fn restore(&mut self, pairs: &[PairHistory], _: usize, _: &[[f64; D]]) -> Result<(), String> {
        if pairs.is_empty() {
            Ok(())
        } else {
            Err("the restart point does not match the model (contact pairs)".into())
        }
    }

    fn set_couplings(&mut self, _: &[(usize, usize)]) {}

    fn contact_csv(_: &Model<D>, _: usize, _: &[[f64; D]], _: &[NodeContact<D>]) -> String {
        String::new()
    }

    fn attempt(
        newton: &mut Newton<'_, D>,
        settings: &NewtonSettings,
        t: f64,
        step: usize,
        increment: usize,
        observer: &mut dyn Observer<D>,
    ) -> Result<Converged, Failure>
    where
        Const<D>: Dimension<D>,
    {
        newton.newton_loop(settings, t, step, increment, observer)
    }
}

/// The thermal side of a coupled run, as the driver sees it.
pub trait HeatCoupling<const D: usize>: Sized {
    /// The coupling of `model`, `None` when the scene has no thermal part.
    fn new(model: &Model<D>) -> Result<Option<Self>, String>;
    /// Temperature unknowns.
    fn free_dofs(&self) -> usize;
    /// Thermal strain of every cell at the committed temperatures.
    fn thermal_strains(&self, model: &Model<D>) -> Vec<f64>;
    /// Law of each cell at its committed temperature (empty when no
    /// material is temperature dependent).
    fn cell_laws(&self, model: &Model<D>) -> Result<Vec<Option<NonlinearLaw>>, String>;
    /// Heat step of the increment ending at `t` on the converged state,
    /// then commits the temperatures.
    fn heat_step(
        &mut self,
        model: &Model<D>,
        t: f64,
        dt: f64,
        contact: &[Vec<NodeContact<D>>],
        before: &[Vec<MaterialPoint>],
        after: &[Vec<MaterialPoint>],
    ) -> Result<(), String>;
    /// Nodal temperatures.
    fn temperature(&self) -> &[f64];
    /// The last heat step.
    fn last(&self) -> &ThermalIncrement;
}

impl<const D: usize> HeatCoupling<D> for crate::thermal::coupling::Coupling
where
    Const<D>: Dimension<D>,
{
    fn new(model: &Model<D>) -> Result<Option<Self>, String> {
        crate::thermal::coupling::Coupling::new(model)
    }

    fn free_dofs(&self) -> usize {
        self.solver.free_dofs()
    }

    fn thermal_strains(&self, model: &Model<D>) -> Vec<f64> {
        crate::thermal::coupling::Coupling::thermal_strains(self, model)
    }

    fn cell_laws(&self, model: &Model<D>) -> Result<Vec<Option<NonlinearLaw>>, String> {
        crate::thermal::coupling::Coupling::cell_laws(self, model)
    }

    fn heat_step(
        &mut self,
        model: &Model<D>,
        t: f64,
        dt: f64,
        contact: &[Vec<NodeContact<D>>],
        before: &[Vec<MaterialPoint>],
        after: &[Vec<MaterialPoint>],
    ) -> Result<(), String> {
        crate::thermal::coupling::Coupling::heat_step(self, model, t, dt, contact, before, after)
            .map_err(|e| format!("heat conduction at t = {t}: {e}"))?;
        self.solver.commit();
        Ok(())
    }

    fn temperature(&self) -> &[f64] {
        &self.solver.temperature
    }

    fn last(&self) -> &ThermalIncrement {
        &self.solver.last
    }
}
