//! Newton-Raphson iterations of one increment (seed flowchart):
//! contact search and forces -> internal forces -> residual
//! `r = f_int - f_ext - f_follower - f_contact` on the free dofs -> tangent
//! `K = K_int + K_contact` -> solve -> update, with a line search, NaN/inf
//! and divergence detection.
//!
//! Predictor: the first iteration starts from the last converged state and
//! applies the whole increment of prescribed displacements `dp` through the
//! tangent, `K_ff du = -(r_f + K_fp dp)`, so a linear problem is solved
//! exactly by one iteration. A linear elastic increment takes one
//! factorization, one solve plus one back-substitution (the estimate of the
//! next correction, [`convergence`]), and two residual evaluations.
//!
//! One concept per file:
//! - this file: the loop ([`Newton::newton_loop`]), the evaluation of the
//!   residual and tangent, the linear solves;
//! - [`convergence`]: the convergence and divergence tests;
//! - [`line_search`]: the energy test and backtracking;
//! - [`failure`]: the typed failure taxonomy;
//! - [`state`]: commit / rollback / restart of the solution state.
//!
//! Contact enters through [`ContactAssembly`] (forces, tangent blocks,
//! pattern growth, Lagrange rows); the contact loop around the Newton loops
//! (active set, Uzawa, friction statuses) is `solve::contact_loop`, which
//! drives this solver through [`NewtonLoop`].

pub mod convergence;
pub mod failure;
pub mod line_search;
pub mod predictor;
mod start;
pub mod state;

#[cfg(test)]
mod bulk_tests;
#[cfg(test)]
mod condensed_tests;

pub use convergence::Converged;
pub use failure::{Failure, FailureKind};

use super::assembly::Assembler;
use super::contact_loop::NewtonLoop;
use super::dofs::{Dof, DofMap};
use super::linalg::condensed::CondensedSolver;
use super::linalg::direct::LinearSolver;
use super::linalg::saddle::SaddleSolver;
use super::linalg::{FactorStats, LinearError, LinearSystem, SaddlePointSystem, Scatter, ZeroMode};
use super::loads::external_forces;
use super::memory::thread_cpu_seconds;
use super::scene::ContactScene;
use super::{IterationInfo, Observer, Timings};
use crate::contact::{NodeContact, PairState};
use crate::geom::Dimension;
use crate::model::{ContactMethod, LagrangeFormulation, Model, MultiplierUpdate, NewtonSettings};
use convergence::{norm, Criteria, DivergenceMonitor, Eval, TINY};
use nalgebra::Const;
use std::time::Instant;

/// Halvings of a Newton step that inverts an element before the increment
/// is given up (and cut back): down to 1/1024 of the step.
pub const VALID_HALVINGS: i32 = 10;

/// The contact scene of dimension `D` ([`Dimension::Contact`]).
pub type ContactOf<const D: usize> = <Const<D> as Dimension<D>>::Contact;

/// The Newton solver of a model of dimension `D`: numbering, pattern,
/// factorization and the evolving state.
pub struct Newton<'m, const D: usize = 2>
where
    Const<D>: Dimension<D>,
{
    pub(super) model: &'m Model<D>,
    /// Dof numbering.
    pub dofs: DofMap<D>,
    scatter: Scatter,
    assembler: Assembler<D>,
    /// The tangent system (faer direct by default).
    linear: Box<dyn LinearSystem + 'm>,
    /// Current nodal displacements.
    pub u: Vec<[f64; D]>,
    committed: Vec<[f64; D]>,
    /// Contact pairs: state, last evaluation, Lagrange constraints, pattern
    /// couplings (`crate::solve::scene`).
    pub(super) contacts: ContactOf<D>,
    /// Saddle-point solver (models with a Lagrange-multiplier pair).
    saddle: Option<Box<dyn SaddlePointSystem>>,
    /// Multiplier corrections of the last saddle-point solve.
    dlambda: Vec<f64>,
    /// Order and stored entries of the largest saddle-point (or condensed)
    /// matrix factorized.
    saddle_largest: (usize, usize),
    /// Augmented-Lagrangian updates made inside the current Newton loop.
    inner_updates: usize,
    values: Vec<f64>,
    f_int: Vec<f64>,
    f_ext: Vec<f64>,
    f_c: Vec<f64>,
    /// Forces of the follower pressures at the current state (zero when
    /// the model has none).
    f_follow: Vec<f64>,
    /// Whether the model has a follower pressure.
    follower: bool,
    r_free: Vec<f64>,
    reactions: Vec<f64>,
    target: Vec<f64>,
    dp: Vec<f64>,
    rhs: Vec<f64>,
    /// Right-hand side of the current iteration before the solve
    /// (`-r` at the start of the step), for the line-search energy test.
    rhs0: Vec<f64>,
    base: Vec<f64>,
    /// Wall time per phase.
    pub timings: Timings,
    /// Newton iterations done, all attempts included.
    pub iterations: usize,
    /// Starts moved by the predictor's edge rule ([`predictor::edge_moves`])
    /// or first-touch rule ([`predictor::first_touch_moves`]) whose first
    /// step the line search shortened, retaken from the unmoved start (all
    /// attempts included).
    pub predictor_retakes: usize,
    /// Contact status flips in the failed attempts since the last
    /// converged increment (diagnosis).
    pub flips: super::diagnosis::FlipTracker,
    /// Round-off floor of the residual at the last tangent evaluation
    /// (absolute, see [`convergence`]).
    floor: f64,
    /// The last evaluation of the residual.
    last_eval: Option<Eval>,
    /// Free dofs of contact nodes (their gaps are computed from the
    /// coordinates: see [`Newton::round_off_floor`]).
    contact_dof: Vec<bool>,
    /// The first zero-energy mode of a tangent met in the current Newton
    /// loop, and whether the last factorized tangent had one.
    zero_mode: (Option<ZeroMode>, bool),
    /// Diagonal of the mesh's bounding box (round-off floor).
    model_size: f64,
    /// The next evaluation starts with the touching contact nodes closed
    /// (closed-gap start, `PairState::touching`): the first iteration of
    /// each attempt of the first increment of the analysis (reset by
    /// [`Newton::rollback`] until an increment converged).
    touch_start: bool,
    /// Whether an increment converged (or the run restarted after one).
    any_committed: bool,
    /// Closed nodes per contact pair at the first evaluation of the
    /// analysis (touching start included; `None`: not evaluated yet).
    start_closed: Option<Vec<usize>>,
    /// Vanishing stabilization of the bodies held only by contact
    /// (`newton { stabilize }`, [`super::stabilize`]).
    pub stabilization: super::stabilize::Stabilization,
    /// Mass, velocities, accelerations and energies (models with a
    /// dynamic step, [`super::dynamics`]).
    pub(super) dynamics: Option<super::dynamics::Dynamics>,
    /// Inertia part of the residual of the last evaluation, per dof.
    inertia: Vec<f64>,
    /// `f_int - f_ext - f_follow - f_c + C v` of the last evaluation, per dof.
    r_static: Vec<f64>,
    /// Rayleigh damping force `C v` of the last evaluation, per dof.
    damping: Vec<f64>,
    /// Factor of each load of the model (pressure controllers; 1
    /// otherwise).
    load_scale: Vec<f64>,
    /// This rank's cells and nodes under a distributed assembly
    /// ([`super::share`]): partial internal forces and tangent, the forces
    /// summed over the ranks by the linear system.
    share: Option<std::sync::Arc<super::share::AssemblyShare>>,
    /// The follower facets this rank evaluates, under a distributed
    /// assembly split over ranks with a follower pressure
    /// ([`super::follower::FollowerShare`]).
    follower_share: Option<super::follower::FollowerShare>,
    /// The converged history the increment predictor extrapolates
    /// ([`predictor`]).
    pub(super) history: predictor::History<D>,
    /// The next Newton loop is the first of an increment attempt (set by
    /// commit, rollback and restore): the predictor may start it.
    fresh: bool,
    /// Step and end time of the current attempt (recorded into the history
    /// at commit).
    attempt: (usize, f64),
    /// The model's restart fingerprint ([`super::restart::fingerprint`]),
    /// computed at the first checkpoint (it formats the whole model).
    fingerprint: std::sync::OnceLock<u64>,
}

impl<const D: usize> std::fmt::Debug for Newton<'_, D>
where
    Const<D>: Dimension<D>,
{
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Newton")
            .field("free_dofs", &self.dofs.n_free())
            .field("nnz", &self.scatter.pattern.nnz())
            .finish()
    }
}

impl<'m, const D: usize> Newton<'m, D>
where
    Const<D>: Dimension<D>,
{
    /// Numbers the dofs, builds the sparse pattern and checks every element
    /// of the (checked) `model` in its reference configuration; the tangent
    /// is solved by the default direct solver.
    pub fn new(model: &'m Model<D>) -> Result<Self, String> {
        Self::with_linear_system(model, Box::new(LinearSolver::new()))
    }

    /// Like [`Newton::new`] with the tangent solved by `linear`.
    pub fn with_linear_system(
        model: &'m Model<D>,
        linear: Box<dyn LinearSystem + 'm>,
    ) -> Result<Self, String> {
        let nn = model.mesh.nodes.len();
        let dofs = DofMap::new(model);
        // a distributed assembly (`super::share`): this rank's cells only
        let share = linear.share();
        crate::solve::memory::trace("newton: dof map");
        let scatter = super::discrete::scatter_for(model, &dofs, &[], share.as_ref())?;
        crate::solve::memory::trace("newton: scatter (pattern)");
        let assembler = Assembler::with_share(model, share.clone())?;
        crate::solve::memory::trace("newton: assembler (element k)");
        let n_free = dofs.n_free();
        let n_presc = dofs.prescribed.len();
        let n_dofs = dofs.dofs.len();
        let mut newton = Newton {
            model,
            values: vec![0.0; scatter.n_values()],
            scatter,
            assembler,
            linear,
            u: vec![[0.0; D]; nn],
            committed: vec![[0.0; D]; nn],
            contacts: ContactOf::<D>::new(model),
            saddle: model.contacts.iter().find_map(|c| match c.method {
                ContactMethod::Lagrange {
                    formulation: LagrangeFormulation::Condensed,
                } => Some(Box::new(CondensedSolver::new()) as Box<dyn SaddlePointSystem>),
                ContactMethod::Lagrange { formulation } => {
                    Some(Box::new(SaddleSolver::new(formulation)) as Box<dyn SaddlePointSystem>)
                }
                _ => None,
            }),
            dlambda: Vec::new(),
            saddle_largest: (0, 0),
            inner_updates: 0,
            f_int: vec![0.0; n_dofs],
            f_ext: vec![0.0; n_dofs],
            f_c: vec![0.0; n_dofs],
            f_follow: vec![0.0; n_dofs],
            follower: super::follower::has_follower(model) || super::rigid_body::has_moments(model),
            r_free: vec![0.0; n_free],
            reactions: vec![0.0; n_presc],
            target: vec![0.0; n_presc],
            dp: vec![0.0; n_presc],
            rhs: vec![0.0; n_free],
            rhs0: vec![0.0; n_free],
            base: vec![0.0; n_free],
            dofs,
            timings: Timings::default(),
            iterations: 0,
            predictor_retakes: 0,
            flips: Default::default(),
            floor: 0.0,
            last_eval: None,
            contact_dof: Vec::new(),
            zero_mode: (None, false),
            model_size: 0.0,
            stabilization: Default::default(),
            touch_start: true,
            any_committed: false,
            start_closed: None,
            dynamics: model
                .steps
                .iter()
                .any(|s| s.dynamic.is_some())
                .then(|| super::dynamics::Dynamics::new(model)),
            inertia: vec![0.0; n_dofs],
            r_static: vec![0.0; n_dofs],
            damping: vec![0.0; n_dofs],
            load_scale: vec![1.0; model.loads.len()],
            follower_share: share
                .as_ref()
                .filter(|s| s.split() && super::follower::has_follower(model))
                .map(|s| super::follower::FollowerShare::new(model, s)),
            share,
            history: predictor::History::default(),
            fresh: true,
            attempt: (0, 0.0),
            fingerprint: std::sync::OnceLock::new(),
        };
        let (mut lo, mut hi) = ([f64::INFINITY; D], [f64::NEG_INFINITY; D]);
        for p in &model.mesh.nodes {
            for c in 0..D {
                lo[c] = lo[c].min(p[c]);
                hi[c] = hi[c].max(p[c]);
            }
        }
        let size = (0..D).map(|c| (hi[c] - lo[c]).powi(2)).sum::<f64>().sqrt();
        newton.model_size = if size.is_finite() { size } else { 0.0 };
        let mut contact_node = vec![false; nn];
        for c in &model.contacts {
            let master = match &c.master {
                crate::model::ContactMaster::Surface { nodes, .. } => &nodes[..],
                crate::model::ContactMaster::Tool(_) => &[],
            };
            for &n in c.nodes.iter().chain(master) {
                contact_node[n] = true;
            }
        }
        let nc = newton.dofs.components();
        newton.contact_dof = newton
            .dofs
            .free
            .iter()
            .map(|&g| contact_node[g / nc])
            .collect();
        // bodies with a constant stiffness: between tangents only the
        // contact surfaces' rows and columns change (a hint to the linear
        // system: `linalg::schur`)
        if !model.contacts.is_empty() && !newton.assembler.has_points() {
            let candidates: Vec<usize> = (0..n_free).filter(|&i| newton.contact_dof[i]).collect();
            newton.linear.set_candidates(&candidates);
        }
        // element check in the reference configuration (inverted, off-axis cells)
        let mut f = std::mem::take(&mut newton.f_int);
        let r = newton
            .assembler
            .assemble(&model.mesh, &newton.scatter, &newton.u, &mut f, None);
        newton.f_int = f;
        r?;
        // the stabilization's stiffness scale: the element tangent's
        // diagonal in the reference configuration
        let mut diag = Vec::new();
        if model.steps.iter().any(|s| s.newton.stabilize.is_some()) {
            let mut f = vec![0.0; n_dofs];
            let mut values = vec![0.0; newton.scatter.n_values()];
            newton.assembler.assemble(
                &model.mesh,
                &newton.scatter,
                &newton.u,
                &mut f,
                Some(&mut values),
            )?;
            let p = &newton.scatter.pattern;
            diag = (0..p.n)
                .map(|j| p.find(j, j).map_or(0.0, |k| values[k]))
                .collect();
        }
        crate::solve::memory::trace("newton: vectors, first f_int");
        newton.stabilization = super::stabilize::Stabilization::new(model, &newton.dofs, |j| {
            diag.get(j).copied().unwrap_or(0.0)
        });
        Ok(newton)
    }

    /// Velocities, accelerations and energies (models with a dynamic step).
    pub fn dynamics(&self) -> Option<&super::dynamics::Dynamics> {
        self.dynamics.as_ref()
    }

    /// The local error estimate of the last attempt of a dynamic increment
    /// ([`super::dynamics::Dynamics::local_error`]).
    pub fn local_error(&self) -> Option<f64> {
        self.dynamics.as_ref()?.local_error(
            self.model,
            self.u.as_flattened(),
            self.committed.as_flattened(),
        )
    }

    /// The largest rotation of a cell over the last attempt (from the
    /// committed state), in radians, and the global cell
    /// ([`super::cell_rotation::largest`]).
    pub fn cell_rotation(&self) -> Option<(f64, usize)> {
        super::cell_rotation::largest(
            self.model,
            self.u.as_flattened(),
            self.committed.as_flattened(),
        )
    }

    /// Sets the integrator of the increment ending at `t` of step `step`;
    /// at the first dynamic increment, builds the mass and the initial
    /// acceleration `M a_0 = f_ext - f_int + f_c` of the committed state.
    fn begin_dynamics(&mut self, t: f64, step: usize) -> Result<(), Failure> {
        let model = self.model;
        let Some(mut dy) = self.dynamics.take() else {
            return Ok(());
        };
        let s = model.steps.get(step);
        let t0 = self.assembler.committed_time();
        let mut out = Ok(());
        if let Some(d) = s.and_then(|s| s.dynamic) {
            let assembler = &self.assembler;
            out = dy
                .build_mass(model, &d)
                .and_then(|()| {
                    dy.build_damping(model, &d, || assembler.reference_stiffness(&model.mesh))
                })
                .map_err(|e| Failure::new(FailureKind::Element, e));
            if out.is_ok() && !dy.started {
                external_forces(model, t0, &mut self.f_ext);
                out = self.evaluate(t0, false).map(|_| ());
                // the massless dofs' static condensation (`start.rs`)
                let r0 = match out {
                    Ok(()) => self.consistent_start(&dy, t0),
                    Err(e) => Err(e),
                };
                out = r0.as_ref().map(|_| ()).map_err(Clone::clone);
                if let Ok(start) = r0 {
                    let r0 = &start.residual;
                    dy.start(model, &self.dofs, r0);
                    // the condensation's forces `K du` start the work
                    // integrals (the audit's forces are those of the
                    // scheme's committed residual): the contact's share
                    // and the internal forces' rest
                    let internal: Vec<f64> = (0..r0.len())
                        .map(|g| r0[g] - self.r_static[g] + start.contact[g])
                        .collect();
                    if !self.any_committed {
                        // the work integrals start from the forces of the
                        // initial state (a load present at t0, e.g.
                        // gravity, works from the first increment on)
                        let mut ext = self.f_ext.clone();
                        for (e, f) in ext.iter_mut().zip(&self.f_follow) {
                            *e += f;
                        }
                        for (p, r) in self.dofs.prescribed.iter().zip(&self.reactions) {
                            ext[p.dof] += r;
                        }
                        dy.start_forces([&self.f_int, &ext, &self.f_c]);
                    }
                    dy.add_start_forces(&internal, &start.contact);
                }
            }
        }
        dy.begin_increment(s, t - t0);
        self.dynamics = Some(dy);
        out
    }

    /// Closed nodes per contact pair at the first evaluation of the
    /// analysis (the touching start included); empty before it.
    pub fn start_closed(&self) -> &[usize] {
        self.start_closed.as_deref().unwrap_or(&[])
    }

    /// Tangents whose element part was a copy of the assembled bulk
    /// (linear models, [`super::bulk_tangent`]), and bulk assemblies.
    pub fn bulk_counts(&self) -> (usize, usize) {
        self.assembler.bulk_counts()
    }

    /// Turns the assembled bulk tangent of linear models off (`false`:
    /// the element loop assembles every tangent) or on (the default).
    pub fn set_bulk_tangent(&mut self, enabled: bool) {
        self.assembler.set_bulk_tangent(enabled);
    }

    /// Counters of the tangent's factorizations.
    pub fn factor_stats(&self) -> FactorStats {
        self.linear.stats()
    }

    /// Counters of a distributed linear solver (`None`: the serial one).
    /// Collective under MPI (see [`LinearSystem::distributed`]).
    pub fn distributed_stats(&self) -> Option<super::linalg::DistributedStats> {
        self.linear.distributed(&self.timings)
    }

    /// Saddle-point factorizations (symbolic, numeric) of the Lagrange
    /// multiplier systems; the symbolic one is recomputed only when the
    /// active set changes.
    pub fn saddle_factorizations(&self) -> (usize, usize) {
        self.saddle.as_ref().map_or((0, 0), |s| s.counts())
    }

    /// The largest Lagrange-multiplier system factorized: its order (the
    /// saddle point's `n + m`, or `n` condensed) and stored entries.
    pub fn saddle_largest_system(&self) -> (usize, usize) {
        self.saddle_largest
    }

    /// `|A - A^T|_F / |A|_F` of the last condensed matrix (`None`: the
    /// saddle point, or nothing factorized).
    pub fn saddle_asymmetry(&self) -> Option<f64> {
        self.saddle.as_ref().and_then(|s| s.asymmetry())
    }

    /// Number of nonzeros of the free-free matrix (both triangles).
    pub fn nnz(&self) -> usize {
        self.scatter.pattern.nnz()
    }

    /// Times the sparsity pattern grew (node-to-segment couplings).
    pub fn pattern_growths(&self) -> usize {
        self.contacts.pattern_growths()
    }

    /// Reaction forces per node at the last evaluated state (zero except at
    /// prescribed dofs).
    pub fn reaction_field(&self) -> Vec<[f64; D]> {
        let nc = self.dofs.components();
        let mut out = vec![[0.0; D]; self.u.len()];
        for (p, r) in self.dofs.prescribed.iter().zip(&self.reactions) {
            out[p.dof / nc][p.dof % nc] = *r;
        }
        out
    }

    /// Committed integration points per global cell (bodies with nonlinear
    /// laws; empty for small-strain linear elastic cells).
    pub fn material_points(&self) -> &[Vec<crate::element::MaterialPoint>] {
        self.assembler.points()
    }

    /// Factor of each load of the model (a pressure controller's; 1
    /// otherwise).
    pub fn load_scales(&self) -> &[f64] {
        &self.load_scale
    }

    /// Sets the factor of load `i` for the next increments.
    pub fn set_load_scale(&mut self, i: usize, scale: f64) {
        if let Some(s) = self.load_scale.get_mut(i) {
            *s = scale;
        }
    }

    /// Isotropic thermal strain of each cell the next solves use (empty
    /// without heat).
    pub fn thermal_strains(&self) -> &[f64] {
        self.assembler.thermal_strains()
    }

    /// Sets the thermal strains (and temperature-dependent laws) of the
    /// cells for the next increments (`crate::thermal::coupling`).
    pub fn set_thermal_state(
        &mut self,
        strain: Vec<f64>,
        laws: Vec<Option<crate::material::NonlinearLaw>>,
    ) -> Result<(), String> {
        self.assembler
            .set_thermal_state(&self.model.mesh, strain, laws)
    }

    /// Contact evaluation of each pair at the last evaluated state.
    pub fn contact(&self) -> &[Vec<NodeContact<D>>] {
        self.contacts.contact()
    }

    /// The contact scene (state of every pair, last evaluation).
    pub fn contacts(&self) -> &ContactOf<D> {
        &self.contacts
    }

    /// Closed contact nodes at the last evaluated state.
    /// Abandons an increment's first iteration (reported to `observer`:
    /// it counts) and starts again from the last converged state with the
    /// prescribed increment `plain_dp` (the current one when `None`):
    /// returns the norm of the increment now prescribed.
    fn abandon_first_step(
        &mut self,
        info: &IterationInfo,
        plain_dp: Option<&[f64]>,
        observer: &mut dyn Observer<D>,
    ) -> f64 {
        observer.iteration(info);
        self.u.copy_from_slice(&self.committed);
        if let Some(dp) = plain_dp {
            self.dp.copy_from_slice(dp);
        }
        norm(&self.dp)
    }

    pub fn active_contacts(&self) -> usize {
        self.contacts.active_contacts()
    }

    /// The largest ratio of a penalty coefficient to the element stiffness
    /// at its node (see [`super::diagnosis::penalty_ratio`]).
    pub fn penalty_ratio(&self) -> Option<super::diagnosis::PenaltyRatio> {
        self.contacts
            .penalty_ratio(self.model, &self.scatter, &self.values)
    }

    /// Smallest fraction of the increment at which a node of a pair with
    /// `cut_at_impact` first touched its master, at the last evaluation
    /// (`None`: no such impact).
    pub fn impact_fraction(&self) -> Option<f64> {
        self.contacts.impact_fraction(self.model)
    }

    /// The round-off floor of the relative residual at the last evaluation
    /// (`FLOOR_FACTOR eps || |K| |x| ||` over the force scale), and whether
    /// the residual was at it.
    pub fn residual_floor(&self) -> (f64, bool) {
        self.last_eval
            .map_or((0.0, false), |e| (e.rel_floor(), e.at_floor()))
    }

    /// `FLOOR_FACTOR eps || |K| |x| ||` with the current tangent values,
    /// `x` the coordinates `X + u` at contact nodes (a gap is a difference
    /// of coordinates) and the displacements `u` elsewhere (an element
    /// force is a function of the displacement gradient). A displacement
    /// counts at most as the committed one plus the size of the model: an
    /// iterate running away along a zero-energy mode (a block pulled above
    /// its friction limit) must not raise the floor to its own size.
    fn round_off_floor(&self) -> f64 {
        let nc = self.dofs.components();
        let u = self.u.as_flattened();
        let committed = self.committed.as_flattened();
        let nodes = &self.model.mesh.nodes;
        let p = &self.scatter.pattern;
        let mut y = vec![0.0; p.n];
        for (j, &g) in self.dofs.free.iter().enumerate() {
            let d = u[g].abs().min(committed[g].abs() + self.model_size);
            let x = if self.contact_dof[j] {
                nodes[g / nc][g % nc].abs() + d
            } else {
                d
            };
            if x == 0.0 {
                continue;
            }
            for k in p.col_ptr[j]..p.col_ptr[j + 1] {
                y[p.row_idx[k]] += self.values[k].abs() * x;
            }
        }
        if self.share.as_ref().is_some_and(|s| s.split()) {
            // each rank holds the terms of its cells
            self.linear.sum_over_ranks(&mut y);
        }
        // the element thermal forces `eps_th f_unit` carry their own
        // round-off (a fully held heated body has `u = 0` and no other)
        convergence::FLOOR_FACTOR * f64::EPSILON * (norm(&y) + self.assembler.thermal_scale())
    }

    /// Largest penetration over all pairs at the last evaluation.
    pub fn max_penetration(&self) -> f64 {
        self.contacts.max_penetration()
    }

    /// Contact, internal forces and residual at the current `u` and time
    /// `t`; the tangent too if `with_tangent`. A linear model (the
    /// assembler's [`super::bulk_tangent::BulkTangent`]) puts the element
    /// part first, a copy of the bulk (the element loop's bits), and adds
    /// the contact and follower tangents to it; other models add the
    /// contact and follower tangents into zeroed values and the element
    /// loop after them. The springs, stabilization and inertia come last.
    fn evaluate(&mut self, t: f64, with_tangent: bool) -> Result<Eval, Failure> {
        let model = self.model;
        let element_first = self.assembler.bulk_applies();
        let cpu0 = thread_cpu_seconds();
        let start = Instant::now();
        if with_tangent && !element_first {
            self.values.fill(0.0);
        }
        self.f_c.fill(0.0);
        if !model.contacts.is_empty() {
            self.contacts
                .evaluate(model, &self.dofs, &self.u, t, &mut self.f_c);
            if with_tangent {
                let grown = self
                    .contacts
                    .grow_pattern(model, &self.dofs, &self.scatter)
                    .map_err(|detail| Failure::new(FailureKind::Singular, detail))?;
                if let Some(scatter) = grown {
                    self.scatter = scatter;
                    self.values = vec![0.0; self.scatter.n_values()];
                    self.linear.reset_pattern();
                }
                if !element_first {
                    self.contacts
                        .add_tangent(&self.scatter, &self.dofs, &mut self.values);
                }
            }
            if self.saddle.is_some() {
                self.contacts.build_constraints(model, &self.dofs);
            }
        }
        if !element_first {
            self.follower_forces(t, with_tangent);
        }
        let mid = Instant::now();
        let cpu1 = thread_cpu_seconds();
        self.timings.contact += (mid - start).as_secs_f64();
        self.timings.cpu[1] += cpu1 - cpu0;
        let mut assembled = if with_tangent && element_first {
            self.assembler.assemble_tangent(
                &model.mesh,
                &self.scatter,
                &self.u,
                &mut self.f_int,
                &mut self.values,
            )
        } else {
            let values = with_tangent.then_some(&mut self.values[..]);
            self.assembler
                .assemble(&model.mesh, &self.scatter, &self.u, &mut self.f_int, values)
        };
        self.timings.cells_assembled = self.assembler.assembled_cells();
        if self.share.as_ref().is_some_and(|s| s.split()) {
            // every rank fails together (an element another rank met), and
            // the residual is the sum of the ranks' internal forces
            let failed = self.linear.any_rank(assembled.is_err());
            if failed && assembled.is_ok() {
                assembled = Err("an element failed on another MPI rank".into());
            }
            if !failed {
                self.linear.sum_over_ranks(&mut self.f_int);
            }
        }
        let end = Instant::now();
        let cpu2 = thread_cpu_seconds();
        self.timings.assembly += (end - mid).as_secs_f64();
        self.timings.cpu[0] += cpu2 - cpu1;
        assembled.map_err(|detail| Failure::new(FailureKind::Element, detail))?;
        if element_first {
            // the contact and follower tangents, added to the element part
            if with_tangent && !model.contacts.is_empty() {
                self.contacts
                    .add_tangent(&self.scatter, &self.dofs, &mut self.values);
            }
            self.follower_forces(t, with_tangent);
            self.timings.contact += end.elapsed().as_secs_f64();
            self.timings.cpu[1] += thread_cpu_seconds() - cpu2;
        }
        let residual_start = Instant::now();
        // springs to the ground and between nodes: internal forces (their
        // energy is part of the internal work)
        if super::discrete::any(model, |k, _| k) {
            super::discrete::times(model, self.u.as_flattened(), &mut self.f_int, t, |k, _| k);
            if with_tangent {
                super::discrete::add_tangent(
                    model,
                    &self.dofs,
                    &self.scatter,
                    &mut self.values,
                    t,
                    |k, _| k,
                );
            }
        }
        // rigid bodies: the ties of their nodes to the pilot's motion
        super::rigid_body::add_forces(model, self.u.as_flattened(), &mut self.f_int);
        if with_tangent {
            super::rigid_body::add_tangent(
                model,
                self.u.as_flattened(),
                &self.dofs,
                &self.scatter,
                &mut self.values,
            );
        }
        if with_tangent {
            self.stabilization
                .add_springs(&self.scatter.pattern, &mut self.values);
        }
        let inertia_scale = match &self.dynamics {
            Some(dy) => {
                if with_tangent {
                    dy.add_tangent(model, &self.dofs, &self.scatter, &mut self.values);
                }
                let (u, u0) = (self.u.as_flattened(), self.committed.as_flattened());
                let damping = dy.damping_force(model, u, u0, &mut self.damping);
                dy.inertia(model, u, u0, &mut self.inertia).max(damping)
            }
            None => {
                self.inertia.fill(0.0);
                self.damping.fill(0.0);
                0.0
            }
        };
        let (mut r2, mut load2, mut react2, mut fint2) = (0.0, 0.0, 0.0, 0.0);
        for (g, role) in self.dofs.dofs.iter().enumerate() {
            let rs =
                self.f_int[g] - self.f_ext[g] - self.f_follow[g] - self.f_c[g] + self.damping[g];
            self.r_static[g] = rs;
            let r = rs + self.inertia[g];
            match *role {
                Dof::Free(i) => {
                    self.r_free[i] = r;
                    r2 += r * r;
                }
                Dof::Prescribed(p) => {
                    self.reactions[p] = r;
                    react2 += r * r;
                }
                Dof::Inactive => continue,
            }
            let l = self.f_ext[g] + self.f_follow[g] + self.f_c[g];
            load2 += l * l;
            fint2 += self.f_int[g] * self.f_int[g];
        }
        if self.stabilization.factor > 0.0 {
            // r_f += c(t) d_b (u - u_committed) on the stabilized dofs
            self.stabilization.add_forces(
                &self.dofs.free,
                self.u.as_flattened(),
                self.committed.as_flattened(),
                &mut self.r_free,
            );
            r2 = self.r_free.iter().map(|r| r * r).sum();
        }
        let abs = r2.sqrt();
        let denom = (load2.sqrt() + react2.sqrt())
            .max(fint2.sqrt())
            .max(self.assembler.thermal_scale())
            .max(inertia_scale)
            .max(TINY);
        if with_tangent {
            self.floor = self.round_off_floor();
        }
        let ev = Eval {
            abs,
            rel: abs / denom,
            floor: self.floor,
            scale: denom,
        };
        self.last_eval = Some(ev);
        self.timings.residual += residual_start.elapsed().as_secs_f64();
        Ok(ev)
    }

    /// The follower pressures' forces and the 3D rigid bodies' moments at
    /// the current state into `f_follow` (overwritten) and,
    /// `with_tangent`, their load stiffness added to the tangent; nothing
    /// without either.
    fn follower_forces(&mut self, t: f64, with_tangent: bool) {
        if !self.follower {
            return;
        }
        self.f_follow.fill(0.0);
        let tangent = if with_tangent {
            Some((&self.scatter, &self.dofs, &mut self.values[..]))
        } else {
            None
        };
        super::follower::add_follower_forces(
            self.model,
            t,
            &self.load_scale,
            &self.u,
            &mut self.f_follow,
            tangent,
            self.follower_share.as_ref(),
        );
        if let Some(fs) = &self.follower_share {
            // each rank evaluated the facets of its cells
            fs.sum(&mut self.f_follow, |v| self.linear.sum_over_ranks(v));
        }
        // the rigid bodies' moments, whole on every rank (after the sum: a
        // model with a rigid body is assembled replicated)
        let tangent = if with_tangent {
            Some((&self.scatter, &self.dofs, &mut self.values[..]))
        } else {
            None
        };
        super::rigid_body::add_moments(self.model, t, &self.u, &mut self.f_follow, tangent);
    }

    /// `out += K_fp dp` (the prescribed increment's forces on the free
    /// dofs); under a distributed assembly each rank holds the `K_fp`
    /// entries of its cells, so the partial products are summed over the
    /// ranks (the same bits on every rank).
    fn add_kfp_dp(&self, out: &mut [f64]) {
        if self.share.as_ref().is_some_and(|s| s.split()) {
            let mut kfp = vec![0.0; out.len()];
            self.scatter
                .add_fp_product(&self.values, &self.dp, &mut kfp);
            self.linear.sum_over_ranks(&mut kfp);
            for (r, k) in out.iter_mut().zip(&kfp) {
                *r += k;
            }
        } else {
            self.scatter.add_fp_product(&self.values, &self.dp, out);
        }
    }

    /// The increment predictor ([`predictor`]), called with the plain start
    /// evaluated (the converged state, tangent included): moves the free
    /// dofs to the extrapolation by `ratio` of the last converged
    /// increment and the prescribed dofs to their targets; with a
    /// rigid-tool pair, the nodes the extrapolation closes but the contact
    /// edge does not reach are moved back out of the tool
    /// ([`predictor::edge_moves`], against the gaps of the converged state
    /// `t_n`); evaluates there, and keeps that start when its residual
    /// `||r_f||` is smaller
    /// than the plain start's `||r_f + K_fp dp||`; otherwise (or when the
    /// predicted state inverts an element, or fails otherwise) the plain
    /// start is evaluated again. Returns whether the predicted start is
    /// kept (then `dp = 0`: the prescribed increment is in the state).
    fn predict(&mut self, t: f64, ratio: f64, edge: bool) -> Result<(bool, bool), Failure> {
        let Some(last) = self.history.last.as_ref() else {
            return Ok((false, false));
        };
        let t_n = last.times.1;
        let mut plain = self.r_free.clone();
        // summed over the ranks: every rank must take the same decision
        // below (an evaluation is collective)
        self.add_kfp_dp(&mut plain);
        let plain_norm = norm(&plain);
        // the converged gaps of the rigid-tool pairs' nodes (the committed
        // state against the tool at t_n)
        let model = self.model;
        let converged_gaps = if model.contacts.iter().any(|c| c.master.tool().is_some()) {
            self.contacts
                .evaluate(model, &self.dofs, &self.u, t_n, &mut self.f_c);
            Some(predictor::gaps(model, self.contacts.contact()))
        } else {
            None
        };
        {
            let u = self.u.as_flattened_mut();
            predictor::extrapolate(u, last.start.as_flattened(), &self.dofs.free, ratio);
            for (p, v) in self.dofs.prescribed.iter().zip(&self.target) {
                u[p.dof] = *v;
            }
        }
        // the contact edge's advance: the nodes the extrapolation closes
        // that the edge does not reach are moved back out of the tool (a
        // predicted state that fails to evaluate is left to the test below)
        let mut moved = false;
        if let Some(g_n) = converged_gaps.filter(|_| edge && self.evaluate(t, false).is_ok()) {
            let moves = predictor::edge_moves(model, self.contacts.contact(), &g_n, ratio);
            moved = !moves.is_empty();
            for (node, d) in moves {
                for (c, v) in d.iter().enumerate() {
                    let g = self.dofs.dof(node, c);
                    if matches!(self.dofs.dofs[g], Dof::Free(_)) {
                        self.u[node][c] += v;
                    }
                }
            }
        }
        let predicted = self.evaluate(t, true);
        if matches!(predicted, Ok(ev) if ev.abs.is_finite() && ev.abs < plain_norm) {
            self.dp.fill(0.0);
            return Ok((true, moved));
        }
        self.u.copy_from_slice(&self.committed);
        self.evaluate(t, true)?;
        Ok((false, false))
    }

    /// The first-touch rule of the predictor ([`predictor::first_touch_moves`]),
    /// called with the plain start of the analysis' first increment
    /// evaluated (the undeformed state against the tool at `t`): the
    /// closed nodes of a first touch that penetrate less than half the
    /// deepest are moved out of the tool, and that start is evaluated and
    /// kept when its `||r_f + K_fp dp||` is below the plain start's;
    /// otherwise the plain start is evaluated again. `t_n`: the time of
    /// the converged state. Returns whether the moved start is kept (the
    /// prescribed increment `dp` still to apply, as from the plain start).
    fn first_touch(&mut self, t: f64, t_n: f64) -> Result<bool, Failure> {
        let model = self.model;
        // the cheap test first: a pair the rule would act on without the
        // gaps at t_n (a pair that touched at t_n is left alone below)
        let at_t: Vec<Vec<NodeContact<D>>> = self.contacts.contact().to_vec();
        let none = vec![Vec::new(); at_t.len()];
        if predictor::first_touch_moves(model, &at_t, &none).is_empty() {
            return Ok(false);
        }
        let mut plain = self.r_free.clone();
        self.add_kfp_dp(&mut plain);
        let plain_norm = norm(&plain);
        self.contacts
            .evaluate(model, &self.dofs, &self.u, t_n, &mut self.f_c);
        let g_n = predictor::gaps(model, self.contacts.contact());
        let moves = predictor::first_touch_moves(model, &at_t, &g_n);
        for &(node, d) in &moves {
            for (c, v) in d.iter().enumerate() {
                let g = self.dofs.dof(node, c);
                if matches!(self.dofs.dofs[g], Dof::Free(_)) {
                    self.u[node][c] += v;
                }
            }
        }
        if !moves.is_empty() && self.evaluate(t, true).is_ok() {
            let mut moved = self.r_free.clone();
            self.add_kfp_dp(&mut moved);
            let moved_norm = norm(&moved);
            if moved_norm.is_finite() && moved_norm < plain_norm {
                return Ok(true);
            }
        }
        self.u.copy_from_slice(&self.committed);
        self.evaluate(t, true)?;
        Ok(false)
    }

    /// Sets the free dofs to `base + s * rhs` and, in the first iteration,
    /// the prescribed dofs to their target values.
    fn set_state(&mut self, s: f64, prescribed: bool) {
        let u = self.u.as_flattened_mut();
        for ((&g, b), d) in self.dofs.free.iter().zip(&self.base).zip(&self.rhs) {
            u[g] = b + s * d;
        }
        if prescribed {
            for (p, v) in self.dofs.prescribed.iter().zip(&self.target) {
                u[p.dof] = *v;
            }
        }
    }

    /// Factorizes and solves for the correction in `rhs`: the tangent alone,
    /// or, when Lagrange constraints are active, the saddle-point system
    /// (then `dlambda` receives the multiplier corrections, applied to the
    /// pairs at once). `first`: the prescribed increment enters the
    /// constraint right-hand side.
    fn factorize_solve(&mut self, first: bool) -> Result<(), Failure> {
        self.dlambda.clear();
        let constraints = self.contacts.constraints();
        let Some(saddle) = self.saddle.as_mut().filter(|_| !constraints.is_empty()) else {
            let start = Instant::now();
            let cpu0 = thread_cpu_seconds();
            let updates = self.linear.stats().low_rank;
            crate::solve::memory::trace("before factorize (assembled)");
            let r = self.linear.factorize(&self.scatter.pattern, &self.values);
            crate::solve::memory::trace("factorized (petsc matrix, pc)");
            let mid = Instant::now();
            let cpu1 = thread_cpu_seconds();
            self.timings.factorization += (mid - start).as_secs_f64();
            self.timings.cpu[2] += cpu1 - cpu0;
            if self.linear.stats().low_rank > updates {
                self.timings.low_rank += (mid - start).as_secs_f64();
            }
            r.map_err(|e| self.linear_failure(e))?;
            let mode = self.linear.zero_mode().cloned();
            self.zero_mode.1 = mode.is_some();
            if self.zero_mode.0.is_none() {
                self.zero_mode.0 = mode;
            }
            let r = self.linear.solve(&mut self.rhs);
            crate::solve::memory::trace("solved");
            self.timings.solve += mid.elapsed().as_secs_f64();
            self.timings.cpu[3] += thread_cpu_seconds() - cpu1;
            return r.map_err(|e| self.linear_failure(e));
        };
        self.zero_mode.1 = false;
        let start = Instant::now();
        let cpu0 = thread_cpu_seconds();
        let r = saddle.factorize(&self.scatter.pattern, &self.values, constraints);
        let mid = Instant::now();
        let cpu1 = thread_cpu_seconds();
        self.timings.factorization += (mid - start).as_secs_f64();
        self.timings.cpu[2] += cpu1 - cpu0;
        r.map_err(|e| Failure::new(FailureKind::Singular, e.to_string()))?;
        self.saddle_largest = self.saddle_largest.max(saddle.system());
        // G du = g + (d g / d u_p) dp
        for (k, g) in constraints.gap.iter().enumerate() {
            let mut v = *g;
            if first {
                for &(p, n) in constraints.prescribed.row(k) {
                    v += n * self.dp[p];
                }
            }
            self.dlambda.push(v);
        }
        saddle
            .solve(&mut self.rhs, &mut self.dlambda)
            .map_err(|e| Failure::new(FailureKind::Singular, e.to_string()))?;
        self.contacts.apply_multiplier_corrections(&self.dlambda);
        self.timings.solve += mid.elapsed().as_secs_f64();
        self.timings.cpu[3] += thread_cpu_seconds() - cpu1;
        Ok(())
    }

    /// Halves the Newton step (from `base` along `rhs`) until every element
    /// is valid again, at most [`VALID_HALVINGS`] times: the step length
    /// reached and the evaluation there (tangent included), or `failure`
    /// (the invalid element of the full step) when even the smallest step
    /// inverts an element.
    fn backtrack_to_valid(
        &mut self,
        t: f64,
        first: bool,
        failure: Failure,
    ) -> Result<(f64, Eval), Failure> {
        for h in 1..=VALID_HALVINGS {
            let s = 0.5f64.powi(h);
            self.set_state(s, first);
            match self.evaluate(t, true) {
                Ok(ev) => return Ok((s, ev)),
                Err(f) if f.kind == FailureKind::Element => continue,
                Err(f) => return Err(f),
            }
        }
        Err(Failure::new(
            failure.kind,
            format!(
                "{} (also at 1/{} of the Newton step)",
                failure.detail,
                1u32 << VALID_HALVINGS
            ),
        ))
    }

    /// The failure of a factorization, in words: a zero-energy mode is named
    /// by its node, body and component, and the direction of the motion.
    fn linear_failure(&self, e: LinearError) -> Failure {
        let LinearError::ZeroPivot(mode) = &e else {
            let kind = match e {
                LinearError::NotConverged(_) => FailureKind::LinearSolver,
                _ => FailureKind::Singular,
            };
            return Failure::new(kind, e.to_string());
        };
        let nc = self.dofs.components();
        let model = self.model;
        let body_of = |node: usize| {
            model
                .bodies
                .iter()
                .find(|b| b.nodes.contains(&node))
                .map_or("?", |b| b.name.as_str())
        };
        let g = self.dofs.free[mode.dof];
        let (node, c) = (g / nc, g % nc);
        let p = model.mesh.nodes[node];
        let mut nodes: Vec<usize> = mode.rows.iter().map(|&i| self.dofs.free[i] / nc).collect();
        nodes.dedup();
        let mut bodies: Vec<&str> = nodes.iter().map(|&n| body_of(n)).collect();
        bodies.sort_unstable();
        bodies.dedup();
        // components the mode moves (3D: z too; a planar mode never has one)
        let mut comps = [0usize; 3];
        for &i in &mode.rows {
            comps[(self.dofs.free[i] % nc).min(2)] += 1;
        }
        let along = match comps {
            [_, 0, 0] => "along x",
            [0, _, 0] => "along y",
            [0, 0, _] => "along z",
            [_, _, 0] => "in x and y (a rotation, or a mechanism)",
            _ => "in several directions (a rotation, or a mechanism)",
        };
        Failure::new(
            FailureKind::Singular,
            format!(
                "the stiffness matrix is singular: a zero pivot at node {node} ({}) of body `{}`, \
                 dof {}; its zero-energy mode moves {} node(s) of {} {along} \
                 (||K v|| / ||diag(K) v|| = {:.1e}): a rigid-body motion that no `fix` / \
                 `displace` condition and no closed contact holds",
                p.iter()
                    .map(|v| format!("{v:.4}"))
                    .collect::<Vec<_>>()
                    .join(", "),
                body_of(node),
                ["ux", "uy", "uz"][c.min(2)],
                nodes.len(),
                bodies
                    .iter()
                    .map(|b| format!("`{b}`"))
                    .collect::<Vec<_>>()
                    .join(", "),
                mode.ratio
            ),
        )
    }

    /// Next correction `(du, dlambda)` for the current residual estimated
    /// with the factorization at hand; `None` when there is none for the
    /// current system: the constraint set changed since that
    /// factorization, or the sparsity pattern grew (the factorization was
    /// dropped with the old pattern).
    fn next_correction_norm(&mut self, saddle_used: bool) -> Option<f64> {
        for (d, r) in self.rhs.iter_mut().zip(&self.r_free) {
            *d = -r;
        }
        let constraints = self.contacts.constraints();
        if !saddle_used {
            if !constraints.is_empty() || !self.linear.is_factorized() {
                return None;
            }
            let start = Instant::now();
            let solved = self.linear.solve(&mut self.rhs);
            self.timings.solve += start.elapsed().as_secs_f64();
            return solved.ok().map(|()| norm(&self.rhs));
        }
        let saddle = self.saddle.as_ref()?;
        if saddle.factorized_rows() != Some(constraints.len()) {
            return None;
        }
        let start = Instant::now();
        let mut dl = constraints.gap.clone();
        let solved = saddle.solve(&mut self.rhs, &mut dl);
        self.timings.solve += start.elapsed().as_secs_f64();
        solved.ok().map(|()| norm(&self.rhs))
    }
}

impl NewtonLoop for Newton<'_, 2> {
    fn contact_state(&mut self) -> (&Model, &mut [PairState], &[Vec<NodeContact>]) {
        (self.model, &mut self.contacts.pairs, &self.contacts.contact)
    }

    fn newton_loop(
        &mut self,
        settings: &NewtonSettings,
        t: f64,
        step: usize,
        increment: usize,
        observer: &mut dyn Observer,
    ) -> Result<Converged, Failure> {
        Newton::newton_loop(self, settings, t, step, increment, observer)
    }
}

impl<const D: usize> Newton<'_, D>
where
    Const<D>: Dimension<D>,
{
    /// One Newton loop at time `t` with the Lagrange active sets and the
    /// multipliers `lambda*` of `update = converged` pairs fixed.
    ///
    /// A singular tangent (a zero-energy mode, [`LinearSystem::zero_mode`])
    /// is still solved (LU: a body held only by a contact about to close
    /// falls onto it), but the loop never converges on one (the motion
    /// along the mode would be arbitrary), and a loop that fails after
    /// meeting one fails as singular, naming the mode's node and dof (the
    /// other symptoms, residuals of 1e-14 that "grow", follow from it).
    pub fn newton_loop(
        &mut self,
        settings: &NewtonSettings,
        t: f64,
        step: usize,
        increment: usize,
        observer: &mut dyn Observer<D>,
    ) -> Result<Converged, Failure> {
        self.zero_mode = (None, false);
        let result = self.newton_iterations(settings, t, step, increment, observer);
        match (result, self.zero_mode.0.clone()) {
            (Err(f), Some(mode)) if f.kind != FailureKind::Singular => {
                let mut singular = self.linear_failure(LinearError::ZeroPivot(mode));
                singular.detail = format!("{}; then: {}", singular.detail, f.detail);
                Err(singular.with_residuals(&f.residuals))
            }
            (r, _) => r,
        }
    }

    /// The iterations of [`Newton::newton_loop`].
    fn newton_iterations(
        &mut self,
        settings: &NewtonSettings,
        t: f64,
        step: usize,
        increment: usize,
        observer: &mut dyn Observer<D>,
    ) -> Result<Converged, Failure> {
        let model = self.model;
        self.inner_updates = 0;
        self.flips.start_attempt();
        // (the hold of frictional node-to-facet nodes: quasi-static steps,
        // `DeformablePair::hold_friction`)
        self.contacts
            .guard_start(model.steps.get(step).is_none_or(|s| s.dynamic.is_none()));
        let newton_update = model.contacts.iter().any(|c| {
            matches!(
                c.method,
                ContactMethod::AugmentedLagrange {
                    update: MultiplierUpdate::Newton,
                    ..
                }
            )
        });
        let mut criteria = Criteria::new(settings, self.saddle.is_some());
        // friction and mortar make the contact tangent non-symmetric: LU
        // (and so does the nodal normal smoothing of node-to-segment pairs)
        let contact_unsymmetric = model.contacts.iter().any(|c| {
            c.friction.is_some()
                || c.formulation == crate::model::ContactFormulation::Mortar
                || c.smoothing == crate::model::NormalSmoothing::Nodal
        });
        // and so does the load stiffness of a follower pressure
        let potential = self.assembler.symmetric() && !contact_unsymmetric && !self.follower;
        // the line search's energy test along the step (`du . r(u + du)`
        // against `du . r(u)`) needs a potential, or a tangent that departs
        // from one only by a follower pressure's load stiffness or by F-bar
        // (the exact linearisation of a modified potential): that test
        // still measures descent along the step, where the residual-norm
        // test halves the first steps of a plate bending under a gas
        // pressure to 1/32 (an F-bar plate: 1975 iterations instead of 41;
        // tests/suite/follower_plate.rs). Friction and the non-symmetric contact
        // formulations: residual only.
        let energy_test = !contact_unsymmetric;
        self.linear.set_symmetric(potential);
        self.begin_dynamics(t, step)?;
        external_forces(model, t, &mut self.f_ext);
        self.assembler.begin_increment(t);
        if let Some(s) = model.steps.get(step) {
            self.stabilization.begin_increment(step, s, t);
        }
        self.dofs.prescribed_values(model, t, &mut self.target);
        {
            let u = self.u.as_flattened();
            for ((d, p), v) in self
                .dp
                .iter_mut()
                .zip(&self.dofs.prescribed)
                .zip(&self.target)
            {
                *d = v - u[p.dof];
            }
        }
        let mut dp_norm = norm(&self.dp);
        let fresh = std::mem::take(&mut self.fresh);
        self.attempt = (step, t);
        let mut residuals: Vec<f64> = Vec::new();
        let mut divergence = DivergenceMonitor::default();
        let mut tangent_valid = false;
        // the first iteration of the increment's start: 1, or the one after
        // an abandoned predicted start (`predictor::guarded`)
        let mut first_k = 1;
        let mut may_predict = fresh;
        // the prescribed increment of the plain start while a predicted
        // start is in use
        let mut plain_dp: Option<Vec<f64>> = None;
        // the edge and first-touch rules of the predictor (off after a
        // moved start is retaken) and whether the start in use was moved
        // by one
        let mut edge_rule = true;
        let mut moved_start = false;
        for k in 1..=settings.max_iter {
            let first = k == first_k;
            // 1. residual and tangent at the current state (the first of the
            // analysis with the touching contact nodes closed)
            if !tangent_valid {
                let touching = first && self.touch_start && !model.contacts.is_empty();
                if touching {
                    self.touch_start = false;
                    self.contacts.set_touching(model, true);
                }
                let ev = self.evaluate(t, true);
                if touching {
                    self.contacts.set_touching(model, false);
                }
                if self.start_closed.is_none() && ev.is_ok() {
                    let closed = self
                        .contacts
                        .contact()
                        .iter()
                        .map(|pair| {
                            pair.iter()
                                .filter(|c| c.status == crate::contact::ContactStatus::Closed)
                                .count()
                        })
                        .collect();
                    self.start_closed = Some(closed);
                }
                ev.map_err(|f| f.with_residuals(&residuals))?;
                if first && may_predict && settings.predictor && predictor::applies(model) {
                    let is_dynamic = model.steps.get(step).is_some_and(|s| s.dynamic.is_some());
                    if let Some(ratio) = self.history.ratio(step, t).filter(|_| !is_dynamic) {
                        let dp = self.dp.clone();
                        let (kept, moved) = self.predict(t, ratio, edge_rule)?;
                        if kept {
                            dp_norm = 0.0;
                            plain_dp = Some(dp);
                            moved_start = moved;
                        }
                    } else if edge_rule && !is_dynamic && !self.any_committed {
                        // the analysis' first increment: no history, the
                        // first-touch rule (retaken like a moved start)
                        let t_n = model.steps.get(step).map_or(t, |s| s.t_start);
                        moved_start = self.first_touch(t, t_n)?;
                    }
                }
            }
            self.iterations += 1;
            // 2. right-hand side -(r_f + K_fp dp)
            self.rhs.copy_from_slice(&self.r_free);
            if first {
                let mut rhs = std::mem::take(&mut self.rhs);
                self.add_kfp_dp(&mut rhs);
                self.rhs = rhs;
            }
            for v in &mut self.rhs {
                *v = -*v;
            }
            let ref_norm = norm(&self.rhs);
            if first {
                criteria.first_ref = ref_norm;
            }
            if self.rhs0.len() != self.rhs.len() {
                self.rhs0.resize(self.rhs.len(), 0.0);
            }
            self.rhs0.copy_from_slice(&self.rhs);
            // 3. solve for the correction
            self.factorize_solve(first)
                .map_err(|f| f.with_residuals(&residuals))?;
            let saddle_used = !self.dlambda.is_empty();
            let du_norm = norm(&self.rhs);
            if !du_norm.is_finite() {
                return Err(Failure::new(
                    FailureKind::NotFinite,
                    format!("iteration {k}: the displacement correction is not finite"),
                )
                .with_residuals(&residuals));
            }
            {
                let u = self.u.as_flattened();
                for (b, &g) in self.base.iter_mut().zip(&self.dofs.free) {
                    *b = u[g];
                }
            }
            // 4. update, residual at the full step, line search; a full step
            // that inverts an element is backtracked along the Newton
            // direction until every element is valid (before any cutback)
            self.set_state(1.0, first);
            let mut s = 1.0;
            let mut ev = match self.evaluate(t, true) {
                Ok(ev) => ev,
                Err(f) if f.kind == FailureKind::Element && settings.line_search => {
                    let (valid, ev) = self
                        .backtrack_to_valid(t, first, f)
                        .map_err(|f| f.with_residuals(&residuals))?;
                    s = valid;
                    ev
                }
                Err(f) => return Err(f.with_residuals(&residuals)),
            };
            tangent_valid = true;
            let energy_ok =
                line_search::energy_decreases(energy_test, &self.rhs, &self.rhs0, &self.r_free);
            if settings.line_search
                && !saddle_used
                && !energy_ok
                && ev.abs > ref_norm
                && ev.rel > settings.tol
                && ref_norm > 0.0
                && ev.abs.is_finite()
            {
                let s0 = s;
                let found = line_search::backtrack(ref_norm, ev, |trial| {
                    self.set_state(s0 * trial, first);
                    match self.evaluate(t, false) {
                        // an invalid trial is never kept: the search goes on
                        Err(f) if f.kind == FailureKind::Element => Ok(Eval {
                            abs: f64::INFINITY,
                            rel: f64::INFINITY,
                            floor: 0.0,
                            scale: 1.0,
                        }),
                        r => r.map_err(|f| f.with_residuals(&residuals)),
                    }
                })?;
                s = s0 * found.s;
                ev = found.eval;
                if found.last_trial != found.s {
                    self.set_state(s, first);
                    ev = self
                        .evaluate(t, found.s == 1.0)
                        .map_err(|f| f.with_residuals(&residuals))?;
                    tangent_valid = found.s == 1.0;
                } else {
                    tangent_valid = false;
                }
            }
            // 5. convergence
            let u_norm = norm(self.u.as_flattened()).max(TINY);
            let dp_step = if first { dp_norm } else { 0.0 };
            let rel_du = convergence::relative_correction(s, du_norm, dp_step, u_norm);
            residuals.push(ev.rel);
            // a moved start (`predictor::edge_moves`, or
            // `predictor::first_touch_moves` in the first increment) whose
            // first step had to be shortened opened a node that belongs
            // closed: retaken from the unmoved start (the abandoned
            // iteration counts)
            // the iteration reported when the first step is abandoned
            let shortened_first = (first && s < 1.0).then(|| IterationInfo {
                step,
                increment,
                iteration: k,
                residual: ev.rel,
                displacement: rel_du,
                step_length: s,
                active_contacts: self.active_contacts(),
            });
            if let (Some(info), true) = (&shortened_first, moved_start) {
                self.predictor_retakes += 1;
                dp_norm = self.abandon_first_step(info, plain_dp.take().as_deref(), observer);
                first_k = k + 1;
                edge_rule = false;
                moved_start = false;
                tangent_valid = false;
                divergence = DivergenceMonitor::default();
                continue;
            }
            // a predicted start whose first step had to be shortened is
            // abandoned at finite strain: on from the plain start
            if let (Some(info), true) = (&shortened_first, predictor::guarded(model)) {
                if let Some(dp) = plain_dp.take() {
                    dp_norm = self.abandon_first_step(info, Some(&dp), observer);
                    first_k = k + 1;
                    may_predict = false;
                    tangent_valid = false;
                    // the divergence test sees the residuals from there on
                    divergence = DivergenceMonitor::default();
                    continue;
                }
            }
            if first {
                plain_dp = None;
            }
            self.flips.record(self.contacts.contact());
            let mut reported_du = rel_du;
            let mut converged = false;
            let gap_ok = criteria.gaps_small(norm(&self.contacts.constraints().gap), u_norm);
            if criteria.residual_small(ev) && gap_ok {
                // at the round-off floor the next correction is the response
                // to round-off: nothing more accurate exists
                // settled: the correction is small against the displacement
                // or, for a body that does not move (`u = 0` exactly: a held
                // heated body), against the model's size
                let settled = rel_du * u_norm / u_norm.max(self.model_size);
                if criteria.correction_small(rel_du)
                    || (ev.at_floor() && !saddle_used && settled <= convergence::FLOOR_SETTLED)
                {
                    converged = true;
                } else if let Some(next) = self.next_correction_norm(saddle_used) {
                    // next correction estimated with the factorization at hand
                    reported_du = next / u_norm;
                    converged = criteria.correction_small(reported_du);
                }
            }
            let active_contacts = self.active_contacts();
            observer.iteration(&IterationInfo {
                step,
                increment,
                iteration: k,
                residual: ev.rel,
                displacement: reported_du,
                step_length: s,
                active_contacts,
            });
            if !ev.rel.is_finite() {
                return Err(Failure::new(
                    FailureKind::NotFinite,
                    format!("iteration {k}: the residual is not finite"),
                )
                .with_residuals(&residuals));
            }
            // augmented Lagrangian, `update = newton`: lambda* updated inside
            // the loop while a penetration exceeds its tolerance
            let mut updated = newton_update && self.contacts.newton_multiplier_update(model);
            // mortar with Lagrange multipliers: the semi-smooth Newton active
            // set, decided at every iterate; converged only on an unchanged
            // set
            updated |= self.contacts.semismooth_update(model);
            if updated {
                self.inner_updates += 1;
                converged = false;
                tangent_valid = false;
            }
            // the penalty cycling guard's frozen nodes must agree with the
            // contact law at the converged state; else released, on
            if converged && !self.contacts.guard_consistent() {
                converged = false;
                tangent_valid = false;
            }
            if converged && self.zero_mode.1 {
                // converged with a singular tangent: the motion along its
                // zero-energy mode is arbitrary
                let mode = self.zero_mode.0.clone().expect("recorded with the flag");
                return Err(self
                    .linear_failure(LinearError::ZeroPivot(mode))
                    .with_residuals(&residuals));
            }
            if converged {
                return Ok(Converged {
                    iterations: k,
                    residuals,
                    active_contacts,
                    contact_iterations: self.inner_updates,
                    max_penetration: self.max_penetration(),
                });
            }
            // the penalty cycling guard: nodes whose contact statuses came
            // back (A -> B -> A) are frozen closed and sticking from here on
            if self.contacts.guard_cycle(model) {
                tangent_valid = false;
            }
            // a multiplier update changes the problem: no divergence test
            if divergence.diverges(&residuals[first_k - 1..], updated, ev.rel_floor()) {
                return Err(Failure::new(
                    FailureKind::Diverged,
                    format!(
                        "the residual grew in {} consecutive iterations (iteration {k})",
                        convergence::DIVERGENCE_GROWTHS
                    ),
                )
                .with_residuals(&residuals));
            }
        }
        Err(Failure::new(
            FailureKind::MaxIterations,
            format!(
                "no convergence in max_iter = {} iterations",
                settings.max_iter
            ),
        )
        .with_residuals(&residuals))
    }
}
