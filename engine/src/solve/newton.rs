//! Newton-Raphson iterations of one increment (seed flowchart):
//! contact search and forces -> internal forces -> residual
//! `r = f_int - f_ext - f_contact` on the free dofs -> tangent
//! `K = K_int + K_contact` -> solve -> update, with a backtracking line
//! search, NaN/inf and divergence detection.
//!
//! Predictor: the first iteration starts from the last converged state and
//! applies the whole increment of prescribed displacements `dp` through the
//! tangent, `K_ff du = -(r_f + K_fp dp)`, so a linear problem is solved
//! exactly by one iteration.
//!
//! Convergence (after each update, on the updated state):
//! `||r|| / max(||f_ext + f_c|| + ||reactions||, ||f_int||, tiny) <= tol`
//! and `||du|| / max(||u||, tiny) <= tol_displacement`, where `du` is the
//! correction just applied or, when it is large but the residual is
//! already within tolerance (a linear or nearly linear increment), the
//! next correction `K^-1 r` estimated with the factorization already at
//! hand (one triangular solve, no factorization). A linear elastic
//! increment thus takes exactly one factorization, one solve plus one
//! back-substitution, and two residual evaluations.

use super::active_set::{self, Constraints};
use super::assembly::Assembler;
use super::dofs::{Dof, DofMap};
use super::linear::LinearSolver;
use super::loads::external_forces;
use super::pattern::{Scatter, NO_SLOT};
use super::saddle::SaddleSolver;
use super::{IterationInfo, Observer, Timings};
use crate::contact::{self, ContactStatus, NodeContact, PairState};
use crate::model::{ContactMethod, Model, MultiplierUpdate, NewtonSettings};
use std::time::Instant;

/// Floor of norms used as denominators.
const TINY: f64 = 1e-300;
/// Line-search halvings before giving up on decreasing the residual.
const LINE_SEARCH_HALVINGS: i32 = 6;
/// Consecutive residual increases that mean divergence.
const DIVERGENCE_GROWTHS: usize = 3;

/// A converged increment.
#[derive(Debug, Clone, PartialEq)]
pub struct Converged {
    /// Newton iterations (factorizations) used.
    pub iterations: usize,
    /// Relative residual after each iteration.
    pub residuals: Vec<f64>,
    /// Closed contact nodes at convergence.
    pub active_contacts: usize,
    /// Contact iterations: Lagrange active-set changes plus
    /// augmented-Lagrangian multiplier updates (0 for penalty).
    pub contact_iterations: usize,
    /// Largest penetration `max(0, -g)` over all pairs at convergence.
    pub max_penetration: f64,
}

/// Why an increment failed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FailureKind {
    /// `max_iter` iterations without convergence.
    MaxIterations,
    /// The residual grew over several consecutive iterations.
    Diverged,
    /// NaN or infinity in the solution or the residual.
    NotFinite,
    /// The linear system could not be factorized.
    Singular,
    /// An element could not be evaluated.
    Element,
    /// The Lagrange-multiplier active set came back to a set already met
    /// in the increment.
    ActiveSetCycling,
    /// Not a failure: a node first touched its master within the
    /// increment and the deck asks to cut the increment at that instant
    /// (`cut_at_impact = true`).
    ImpactCut,
}

/// A failed increment attempt.
#[derive(Debug, Clone, PartialEq)]
pub struct Failure {
    /// Category.
    pub kind: FailureKind,
    /// Relative residuals of the attempt, one per completed iteration.
    pub residuals: Vec<f64>,
    /// What happened, in words.
    pub detail: String,
}

impl Failure {
    /// Likely cause and remedy, for the final error message.
    pub fn diagnose(&self, settings: &NewtonSettings) -> (String, String) {
        let last = self.residuals.last().copied().unwrap_or(f64::NAN);
        match self.kind {
            FailureKind::MaxIterations => {
                let n = self.residuals.len();
                let stagnant = n >= 3
                    && last < 1e-9
                    && self.residuals[n - 3..]
                        .iter()
                        .all(|r| *r < 1e3 * last.max(TINY));
                if stagnant {
                    (
                        format!(
                            "the residual stagnates at {last:.1e}: tol = {:.0e} (or tol_displacement = \
                             {:.0e}) is below what round-off allows for this problem",
                            settings.tol, settings.tol_displacement
                        ),
                        "raise `newton { tol = .. }` (1e-8 is usual; 1e-10 for verification)".into(),
                    )
                } else {
                    (
                        "the increment is too large for the nonlinearity (contact status \
                         changing back and forth, stiff penalty)"
                            .into(),
                        "use more `increments`, keep `line_search = true`, raise `max_iter`, or \
                         lower the penalty stiffness"
                            .into(),
                    )
                }
            }
            FailureKind::Diverged => (
                "the residual grows from iteration to iteration: the load or contact \
                 increment is too large, or the penalty stiffness is too high for the mesh"
                    .into(),
                "use more `increments`, a smaller penalty stiffness, `line_search = true`".into(),
            ),
            FailureKind::NotFinite | FailureKind::Singular => (
                "the stiffness matrix is singular or nearly so: a body (or part of one) can \
                 move rigidly (not enough `fix`/`displace`, or a body held only by a contact \
                 that is still open)"
                    .into(),
                "constrain every rigid-body motion (e.g. `fix` one node in x), or start the \
                 contact closed"
                    .into(),
            ),
            FailureKind::ActiveSetCycling => (
                "the contact active set cycles: nodes are introduced and released in turn \
                 (a node close to the contact boundary, or an increment too large for the \
                 change of contact zone)"
                    .into(),
                "use more `increments`; if it persists, use `augmented_lagrange` or \
                 `penalty` for this pair"
                    .into(),
            ),
            FailureKind::ImpactCut => (
                "increments are cut at each first impact (`cut_at_impact = true`)".into(),
                "set `cut_at_impact = false` or use more `increments`".into(),
            ),
            FailureKind::Element => (
                "an element is inverted or degenerate (mesh or deformation)".into(),
                "check the mesh orientation and quality, or use smaller increments".into(),
            ),
        }
    }
}

/// Norms of one evaluation of the residual.
#[derive(Debug, Clone, Copy)]
struct Eval {
    /// `||r||` on the free dofs.
    abs: f64,
    /// Relative residual.
    rel: f64,
}

/// The Newton solver of a model: numbering, pattern, factorization and the
/// evolving state.
pub struct Newton<'m> {
    pub(super) model: &'m Model,
    /// Dof numbering.
    pub dofs: DofMap,
    scatter: Scatter,
    assembler: Assembler,
    linear: LinearSolver,
    /// Current nodal displacements.
    pub u: Vec<[f64; 2]>,
    committed: Vec<[f64; 2]>,
    /// Contact state of each pair (search history, multipliers, active set).
    pub(super) pairs: Vec<PairState>,
    /// Lagrange constraints of the last evaluation.
    pub(super) constraints: Constraints,
    /// Saddle-point solver (models with a Lagrange-multiplier pair).
    saddle: Option<SaddleSolver>,
    /// Multiplier corrections of the last saddle-point solve.
    dlambda: Vec<f64>,
    /// Augmented-Lagrangian updates made inside the current Newton loop.
    inner_updates: usize,
    /// Contact evaluation of each pair at the last evaluated state.
    pub contact: Vec<Vec<NodeContact>>,
    values: Vec<f64>,
    f_int: Vec<f64>,
    f_ext: Vec<f64>,
    f_c: Vec<f64>,
    r_free: Vec<f64>,
    reactions: Vec<f64>,
    target: Vec<f64>,
    dp: Vec<f64>,
    rhs: Vec<f64>,
    /// Right-hand side of the current iteration before the solve
    /// (`-r` at the start of the step), for the line-search energy test.
    rhs0: Vec<f64>,
    base: Vec<f64>,
    x: Vec<[f64; 2]>,
    /// Wall time per phase.
    pub timings: Timings,
    /// Newton iterations done, all attempts included.
    pub iterations: usize,
    /// Contact status flips in the failed attempts since the last
    /// converged increment (diagnosis).
    pub flips: super::diagnosis::FlipTracker,
    /// Node couplings added to the sparsity pattern by node-to-segment
    /// contact elements (sorted, kept for the rest of the run).
    couplings: Vec<(usize, usize)>,
    /// Times the sparsity pattern grew.
    pub pattern_growths: usize,
}

impl std::fmt::Debug for Newton<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Newton")
            .field("free_dofs", &self.dofs.n_free())
            .field("nnz", &self.scatter.pattern.nnz())
            .finish()
    }
}

fn norm(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

impl<'m> Newton<'m> {
    /// Numbers the dofs, builds the sparse pattern and checks every element
    /// of the (checked) `model` in its reference configuration.
    pub fn new(model: &'m Model) -> Result<Self, String> {
        let nn = model.mesh.nodes.len();
        let dofs = DofMap::new(model);
        let scatter = Scatter::new(&model.mesh, &dofs)?;
        let assembler = Assembler::new(model)?;
        let n_free = dofs.n_free();
        let n_presc = dofs.prescribed.len();
        let mut newton = Newton {
            model,
            values: vec![0.0; scatter.n_values()],
            scatter,
            assembler,
            linear: LinearSolver::new(),
            u: vec![[0.0; 2]; nn],
            committed: vec![[0.0; 2]; nn],
            pairs: (0..model.contacts.len())
                .map(|i| PairState::new(model, i))
                .collect(),
            contact: vec![Vec::new(); model.contacts.len()],
            constraints: Constraints::default(),
            saddle: model.contacts.iter().find_map(|c| match c.method {
                ContactMethod::Lagrange { formulation } => Some(SaddleSolver::new(formulation)),
                _ => None,
            }),
            dlambda: Vec::new(),
            inner_updates: 0,
            f_int: vec![0.0; 2 * nn],
            f_ext: vec![0.0; 2 * nn],
            f_c: vec![0.0; 2 * nn],
            r_free: vec![0.0; n_free],
            reactions: vec![0.0; n_presc],
            target: vec![0.0; n_presc],
            dp: vec![0.0; n_presc],
            rhs: vec![0.0; n_free],
            rhs0: vec![0.0; n_free],
            base: vec![0.0; n_free],
            x: model.mesh.nodes.clone(),
            dofs,
            timings: Timings::default(),
            iterations: 0,
            flips: Default::default(),
            couplings: Vec::new(),
            pattern_growths: 0,
        };
        // element check in the reference configuration (inverted, off-axis cells)
        let mut f = std::mem::take(&mut newton.f_int);
        let r = newton
            .assembler
            .assemble(&model.mesh, &newton.scatter, &newton.u, &mut f, None);
        newton.f_int = f;
        r?;
        Ok(newton)
    }

    /// The most general factorization the run needed: `lu`, else `ldlt`,
    /// else `cholesky`.
    pub fn linear_solver(&self) -> &'static str {
        use super::linear::Method;
        if self.linear.lu_count > 0 {
            Method::Lu.name()
        } else if self.linear.ldlt_count > 0 {
            Method::Ldlt.name()
        } else {
            Method::Cholesky.name()
        }
    }

    /// Numeric factorizations done (Cholesky, L D L^T, LU).
    pub fn factorizations(&self) -> (usize, usize, usize) {
        (
            self.linear.cholesky_count,
            self.linear.ldlt_count,
            self.linear.lu_count,
        )
    }

    /// Largest number of negative pivots met in an L D L^T factorization.
    pub fn max_negative_pivots(&self) -> usize {
        self.linear.max_negative_pivots
    }

    /// Saddle-point factorizations (symbolic, numeric) of the Lagrange
    /// multiplier systems; the symbolic one is recomputed only when the
    /// active set changes.
    pub fn saddle_factorizations(&self) -> (usize, usize) {
        self.saddle
            .as_ref()
            .map_or((0, 0), |s| (s.symbolic_count, s.numeric_count))
    }

    /// Number of nonzeros of the free-free matrix (both triangles).
    pub fn nnz(&self) -> usize {
        self.scatter.pattern.nnz()
    }

    /// Reaction forces per node at the last evaluated state (zero except at
    /// prescribed dofs).
    pub fn reaction_field(&self) -> Vec<[f64; 2]> {
        let mut out = vec![[0.0; 2]; self.u.len()];
        for (p, r) in self.dofs.prescribed.iter().zip(&self.reactions) {
            out[p.dof / 2][p.dof % 2] = *r;
        }
        out
    }

    /// Committed integration points per global cell (bodies with nonlinear
    /// laws; empty for small-strain linear elastic cells).
    pub fn material_points(&self) -> &[Vec<crate::element::MaterialPoint>] {
        self.assembler.points()
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

    /// Closed contact nodes at the last evaluated state.
    pub fn active_contacts(&self) -> usize {
        self.contact
            .iter()
            .flatten()
            .filter(|c| c.status == ContactStatus::Closed)
            .count()
    }

    /// Nodal displacements of the last converged state.
    pub(super) fn committed_displacement(&self) -> &[[f64; 2]] {
        &self.committed
    }

    /// Makes the current state the converged one.
    pub fn commit(&mut self) {
        self.flips.clear();
        self.committed.copy_from_slice(&self.u);
        self.assembler.commit();
        for p in &mut self.pairs {
            p.commit();
        }
    }

    /// The committed state as a restart checkpoint (stepping fields from
    /// the caller).
    pub(super) fn checkpoint(
        &self,
        increment: usize,
        resume: super::restart::Resume,
    ) -> super::restart::Checkpoint {
        super::restart::Checkpoint {
            fingerprint: super::restart::fingerprint(self.model),
            increment,
            resume,
            displacement: self.committed.clone(),
            pairs: self
                .pairs
                .iter()
                .map(|p| super::restart::PairHistory {
                    entity: p.committed_entity.clone(),
                    multiplier: p.committed_multiplier.clone(),
                    active: p.committed_active.clone(),
                    friction: p.friction.committed_values(),
                })
                .collect(),
            points: self.assembler.points().to_vec(),
            points_time: self.assembler.committed_time(),
            couplings: self.couplings.clone(),
        }
    }

    /// The largest ratio of a penalty coefficient `alpha_eff` to the element
    /// stiffness diagonal at its node, over the penalty and augmented
    /// Lagrangian pairs at the last evaluated state (tangent of the last
    /// iteration).
    pub fn penalty_ratio(&self) -> Option<super::diagnosis::PenaltyRatio> {
        let mut best: Option<super::diagnosis::PenaltyRatio> = None;
        for (p, list) in self.contact.iter().enumerate() {
            let cp = &self.model.contacts[p];
            let stiffness = match cp.method {
                ContactMethod::Penalty { stiffness, .. } => stiffness,
                ContactMethod::AugmentedLagrange { penalty, .. } => penalty,
                ContactMethod::Lagrange { .. } => continue,
            };
            for nc in list {
                let Some(i) = self.pairs[p].slave_index(nc.node) else {
                    continue;
                };
                let trib = self.pairs[p].tributary.get(i).copied().unwrap_or(0.0);
                let alpha = contact::penalty::effective_stiffness(&cp.method, trib);
                let slots = self.scatter.node_slots(nc.node);
                let k_elem = [0, 3]
                    .iter()
                    .zip([nc.stiffness[0][0], nc.stiffness[1][1]])
                    .filter(|(s, _)| slots[**s] != NO_SLOT)
                    .map(|(s, kc)| self.values[slots[*s] as usize] - kc)
                    .fold(0.0, f64::max);
                if k_elem <= 0.0 || !alpha.is_finite() {
                    continue;
                }
                let ratio = alpha / k_elem;
                if best.as_ref().is_none_or(|b| ratio > b.ratio) {
                    best = Some(super::diagnosis::PenaltyRatio {
                        ratio,
                        node: nc.node,
                        pair: cp.name.clone(),
                        stiffness,
                    });
                }
            }
        }
        best
    }

    /// Makes `cp` the committed (and current) state.
    pub(super) fn restore(&mut self, cp: &super::restart::Checkpoint) -> Result<(), String> {
        if cp.displacement.len() != self.u.len() || cp.pairs.len() != self.pairs.len() {
            return Err("the restart point does not match the model (nodes or pairs)".into());
        }
        for (s, h) in self.pairs.iter_mut().zip(&cp.pairs) {
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
            self.couplings.clone_from(&cp.couplings);
            self.scatter = Scatter::with_couplings(&self.model.mesh, &self.dofs, &self.couplings)?;
            self.values = vec![0.0; self.scatter.n_values()];
            self.linear.reset_pattern();
        }
        self.committed.copy_from_slice(&cp.displacement);
        self.u.copy_from_slice(&cp.displacement);
        Ok(())
    }

    /// Returns to the last converged state.
    pub fn rollback(&mut self) {
        self.u.copy_from_slice(&self.committed);
        self.assembler.rollback();
        for p in &mut self.pairs {
            p.rollback();
        }
    }

    /// Contact, internal forces and residual at the current `u` and time
    /// `t`; the tangent too if `with_tangent`.
    fn evaluate(&mut self, t: f64, with_tangent: bool) -> Result<Eval, Failure> {
        let model = self.model;
        let zeroing = Instant::now();
        if with_tangent {
            self.values.fill(0.0);
        }
        let start = Instant::now();
        self.timings.assembly += (start - zeroing).as_secs_f64();
        self.f_c.fill(0.0);
        if !model.contacts.is_empty() {
            for ((x, x0), u) in self.x.iter_mut().zip(&model.mesh.nodes).zip(&self.u) {
                *x = [x0[0] + u[0], x0[1] + u[1]];
            }
            for (i, state) in self.pairs.iter_mut().enumerate() {
                let res = contact::evaluate_pair(model, i, &self.x, t, state);
                for nc in &res {
                    self.f_c[2 * nc.node] += nc.force[0];
                    self.f_c[2 * nc.node + 1] += nc.force[1];
                    if let Some(ms) = &nc.master {
                        for (m, f) in ms.nodes.iter().zip(&ms.forces) {
                            self.f_c[2 * m] += f[0];
                            self.f_c[2 * m + 1] += f[1];
                        }
                    }
                }
                self.contact[i] = res;
            }
            if with_tangent {
                self.grow_pattern_for_contact().map_err(|detail| Failure {
                    kind: FailureKind::Singular,
                    residuals: Vec::new(),
                    detail,
                })?;
                for res in &self.contact {
                    for nc in res {
                        match &nc.master {
                            None => {
                                let slots = self.scatter.node_slots(nc.node);
                                for b in 0..2 {
                                    for a in 0..2 {
                                        let s = slots[a + 2 * b];
                                        if s != NO_SLOT {
                                            self.values[s as usize] += nc.stiffness[a][b];
                                        }
                                    }
                                }
                            }
                            Some(ms) => {
                                let nodes = [nc.node, ms.nodes[0], ms.nodes[1]];
                                for (bj, &nb) in nodes.iter().enumerate() {
                                    for (bi, &na) in nodes.iter().enumerate() {
                                        let Some(slots) =
                                            self.scatter.pair_slots(&self.dofs, na, nb)
                                        else {
                                            continue;
                                        };
                                        for b in 0..2 {
                                            for a in 0..2 {
                                                let s = slots[a + 2 * b];
                                                if s != NO_SLOT {
                                                    self.values[s as usize] +=
                                                        ms.tangent[2 * bi + a][2 * bj + b];
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
            if self.saddle.is_some() {
                self.constraints
                    .build(model, &self.dofs.dofs, &self.pairs, &self.contact);
            }
        }
        let mid = Instant::now();
        self.timings.contact += (mid - start).as_secs_f64();
        let values = if with_tangent {
            Some(&mut self.values[..])
        } else {
            None
        };
        let assembled =
            self.assembler
                .assemble(&model.mesh, &self.scatter, &self.u, &mut self.f_int, values);
        self.timings.assembly += mid.elapsed().as_secs_f64();
        assembled.map_err(|detail| Failure {
            kind: FailureKind::Element,
            residuals: Vec::new(),
            detail,
        })?;
        let (mut r2, mut load2, mut react2, mut fint2) = (0.0, 0.0, 0.0, 0.0);
        for (g, role) in self.dofs.dofs.iter().enumerate() {
            let r = self.f_int[g] - self.f_ext[g] - self.f_c[g];
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
            let l = self.f_ext[g] + self.f_c[g];
            load2 += l * l;
            fint2 += self.f_int[g] * self.f_int[g];
        }
        let abs = r2.sqrt();
        let denom = (load2.sqrt() + react2.sqrt())
            .max(fint2.sqrt())
            .max(self.assembler.thermal_scale())
            .max(TINY);
        Ok(Eval {
            abs,
            rel: abs / denom,
        })
    }

    /// Grows the sparsity pattern when a node-to-segment element of the
    /// last contact evaluation couples nodes that share no cell and are not
    /// coupled yet: the slave is coupled to the whole neighbourhood of its
    /// segment (see [`contact::node_to_segment::neighbourhood`]) so that the
    /// pattern grows rarely; added couplings stay for the rest of the run.
    /// Rebuilds the scatter map, resizes the value array (zeroed) and
    /// resets the symbolic factorization.
    fn grow_pattern_for_contact(&mut self) -> Result<(), String> {
        let mut missing = false;
        'scan: for res in &self.contact {
            for nc in res {
                if let Some(ms) = &nc.master {
                    for m in ms.nodes {
                        if self.scatter.pair_slots(&self.dofs, nc.node, m).is_none() {
                            missing = true;
                            break 'scan;
                        }
                    }
                }
            }
        }
        if !missing {
            return Ok(());
        }
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
            }
        }
        self.couplings.sort_unstable();
        self.couplings.dedup();
        self.scatter = Scatter::with_couplings(&self.model.mesh, &self.dofs, &self.couplings)?;
        self.values = vec![0.0; self.scatter.n_values()];
        self.linear.reset_pattern();
        self.pattern_growths += 1;
        Ok(())
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

    fn factorize(&mut self) -> Result<(), Failure> {
        let start = Instant::now();
        let r = self.linear.factorize(&self.scatter.pattern, &self.values);
        self.timings.factorization += start.elapsed().as_secs_f64();
        r.map_err(|detail| Failure {
            kind: FailureKind::Singular,
            residuals: Vec::new(),
            detail,
        })
    }

    fn solve_rhs(&mut self) {
        let start = Instant::now();
        self.linear.solve(&mut self.rhs);
        self.timings.solve += start.elapsed().as_secs_f64();
    }

    /// Factorizes and solves for the correction in `rhs`: the tangent alone,
    /// or, when Lagrange constraints are active, the saddle-point system
    /// (then `dlambda` receives the multiplier corrections, applied to the
    /// pairs at once). `first`: the prescribed increment enters the
    /// constraint right-hand side.
    fn factorize_solve(&mut self, first: bool) -> Result<(), Failure> {
        self.dlambda.clear();
        let Some(saddle) = self
            .saddle
            .as_mut()
            .filter(|_| !self.constraints.rows.is_empty())
        else {
            self.factorize()?;
            self.solve_rhs();
            return Ok(());
        };
        let start = Instant::now();
        let r = saddle.factorize(&self.scatter.pattern, &self.values, &self.constraints.rows);
        let mid = Instant::now();
        self.timings.factorization += (mid - start).as_secs_f64();
        r.map_err(|detail| Failure {
            kind: FailureKind::Singular,
            residuals: Vec::new(),
            detail,
        })?;
        // G du = g + (d g / d u_p) dp
        for (g, presc) in self
            .constraints
            .gap
            .iter()
            .zip(&self.constraints.prescribed)
        {
            let mut v = *g;
            if first {
                for &(p, n) in presc {
                    v += n * self.dp[p];
                }
            }
            self.dlambda.push(v);
        }
        saddle.solve(&mut self.rhs, &mut self.dlambda);
        for (k, (&(p, i), dl)) in self.constraints.owner.iter().zip(&self.dlambda).enumerate() {
            if self.constraints.tangential.get(k) == Some(&true) {
                self.pairs[p].friction.multiplier[i] += dl;
            } else {
                self.pairs[p].multiplier[i] += dl;
            }
        }
        self.timings.solve += mid.elapsed().as_secs_f64();
        Ok(())
    }

    /// Next correction `(du, dlambda)` for the current residual estimated
    /// with the factorization at hand; `None` if the constraint set changed
    /// since that factorization.
    fn next_correction_norm(&mut self, saddle_used: bool) -> Option<f64> {
        for (d, r) in self.rhs.iter_mut().zip(&self.r_free) {
            *d = -r;
        }
        if !saddle_used {
            if !self.constraints.rows.is_empty() {
                return None;
            }
            self.solve_rhs();
            return Some(norm(&self.rhs));
        }
        let saddle = self.saddle.as_ref()?;
        if saddle.constraints() != self.constraints.rows.len() {
            return None;
        }
        let start = Instant::now();
        let mut dl = self.constraints.gap.clone();
        saddle.solve(&mut self.rhs, &mut dl);
        self.timings.solve += start.elapsed().as_secs_f64();
        Some(norm(&self.rhs))
    }

    /// Smallest fraction of the increment at which a node of a pair with
    /// `cut_at_impact` first touched its master, at the last evaluation
    /// (`None`: no such impact).
    pub fn impact_fraction(&self) -> Option<f64> {
        self.model
            .contacts
            .iter()
            .zip(&self.pairs)
            .filter(|(c, _)| c.friction.is_some_and(|f| f.cut_at_impact))
            .filter_map(|(_, p)| p.friction.impact)
            .reduce(f64::min)
    }

    /// Largest penetration over all pairs at the last evaluation.
    pub fn max_penetration(&self) -> f64 {
        self.contact
            .iter()
            .map(|c| active_set::max_penetration(c))
            .fold(0.0, f64::max)
    }

    /// Iterates to equilibrium at time `t` from the current state (the last
    /// converged one), reporting each iteration of increment `increment` of
    /// step `step` to `observer`; contact iterations (Lagrange active set,
    /// augmented-Lagrangian updates) around the Newton loops, see
    /// [`active_set`].
    pub fn attempt(
        &mut self,
        settings: &NewtonSettings,
        t: f64,
        step: usize,
        increment: usize,
        observer: &mut dyn Observer,
    ) -> Result<Converged, Failure> {
        active_set::attempt(self, settings, t, step, increment, observer)
    }

    /// One Newton loop at time `t` with the Lagrange active sets and the
    /// multipliers `lambda*` of `update = converged` pairs fixed.
    pub(super) fn attempt_newton(
        &mut self,
        settings: &NewtonSettings,
        t: f64,
        step: usize,
        increment: usize,
        observer: &mut dyn Observer,
    ) -> Result<Converged, Failure> {
        let model = self.model;
        self.inner_updates = 0;
        self.flips.start_attempt();
        let newton_update = model.contacts.iter().any(|c| {
            matches!(
                c.method,
                ContactMethod::AugmentedLagrange {
                    update: MultiplierUpdate::Newton,
                    ..
                }
            )
        });
        let mut updated_last = false;
        // With Lagrange pairs the first Newton loop of an increment may carry
        // no force at all (a body moved rigidly towards a tool whose
        // constraints are not introduced yet): the relative residual is then
        // round-off over round-off. The residual is also accepted when small
        // against the increment's initial out-of-balance force.
        let force_free_ok = self.saddle.is_some();
        let mut first_ref = 0.0;
        // friction makes the contact tangent non-symmetric: LU
        let friction = model.contacts.iter().any(|c| c.friction.is_some());
        // a symmetric tangent derives from a potential: the line search's
        // energy test applies (friction and non-symmetric laws: residual only)
        let potential = self.assembler.symmetric() && !friction;
        if potential {
            self.linear.prefer_cholesky();
        } else {
            self.linear.require_lu();
        }
        external_forces(model, t, &mut self.f_ext);
        self.assembler.begin_increment(t);
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
        let dp_norm = norm(&self.dp);
        let mut residuals: Vec<f64> = Vec::new();
        let fail = |kind, residuals: &Vec<f64>, detail: String| Failure {
            kind,
            residuals: residuals.clone(),
            detail,
        };
        let mut tangent_valid = false;
        let mut growths = 0;
        for k in 1..=settings.max_iter {
            let first = k == 1;
            if !tangent_valid {
                self.evaluate(t, true).map_err(|mut f| {
                    f.residuals.clone_from(&residuals);
                    f
                })?;
            }
            self.iterations += 1;
            // right-hand side -(r_f + K_fp dp)
            self.rhs.copy_from_slice(&self.r_free);
            if first {
                self.scatter
                    .add_fp_product(&self.values, &self.dp, &mut self.rhs);
            }
            for v in &mut self.rhs {
                *v = -*v;
            }
            let ref_norm = norm(&self.rhs);
            if first {
                first_ref = ref_norm;
            }
            if self.rhs0.len() != self.rhs.len() {
                self.rhs0.resize(self.rhs.len(), 0.0);
            }
            self.rhs0.copy_from_slice(&self.rhs);
            self.factorize_solve(first).map_err(|mut f| {
                f.residuals.clone_from(&residuals);
                f
            })?;
            let saddle_used = !self.dlambda.is_empty();
            let du_norm = norm(&self.rhs);
            if !du_norm.is_finite() {
                return Err(fail(
                    FailureKind::NotFinite,
                    &residuals,
                    format!("iteration {k}: the displacement correction is not finite"),
                ));
            }
            {
                let u = self.u.as_flattened();
                for (b, &g) in self.base.iter_mut().zip(&self.dofs.free) {
                    *b = u[g];
                }
            }
            self.set_state(1.0, first);
            let with_residuals = |mut f: Failure, r: &Vec<f64>| {
                f.residuals.clone_from(r);
                f
            };
            let mut ev = self
                .evaluate(t, true)
                .map_err(|f| with_residuals(f, &residuals))?;
            tangent_valid = true;
            let mut s = 1.0;
            // Energy test along the step: phi'(s) = du . r(u + s du), with
            // phi'(0) = -du . K du < 0. The full step is kept when
            // phi'(1) < |phi'(0)| (the energy still decreases along the
            // step: a contact closing under a full step raises ||r|| without
            // making the step bad). Only with a potential (symmetric tangent).
            let slope0: f64 = self.rhs.iter().zip(&self.rhs0).map(|(d, r)| -d * r).sum();
            let slope1: f64 = self.rhs.iter().zip(&self.r_free).map(|(d, r)| d * r).sum();
            let energy_ok = potential && slope0 < 0.0 && slope1.is_finite() && slope1 < -slope0;
            // line search when the full step increases the residual and fails the
            // energy test (and has not already reached the tolerance: no
            // backtracking on round-off noise)
            // (not with Lagrange constraints: the multipliers are already updated)
            if settings.line_search
                && !saddle_used
                && !energy_ok
                && ev.abs > ref_norm
                && ev.rel > settings.tol
                && ref_norm > 0.0
                && ev.abs.is_finite()
            {
                let mut best = (1.0, ev);
                let mut last_s = 1.0;
                for h in 1..=LINE_SEARCH_HALVINGS {
                    let trial = 0.5f64.powi(h);
                    self.set_state(trial, first);
                    let e = self
                        .evaluate(t, false)
                        .map_err(|f| with_residuals(f, &residuals))?;
                    last_s = trial;
                    if e.abs < best.1.abs {
                        best = (trial, e);
                    }
                    if e.abs < ref_norm {
                        break;
                    }
                }
                s = best.0;
                ev = best.1;
                if last_s != s {
                    self.set_state(s, first);
                    ev = self
                        .evaluate(t, s == 1.0)
                        .map_err(|f| with_residuals(f, &residuals))?;
                    tangent_valid = s == 1.0;
                } else {
                    tangent_valid = false;
                }
            }
            let u_norm = norm(self.u.as_flattened()).max(TINY);
            let dp_step = if first { dp_norm } else { 0.0 };
            let rel_du = ((s * du_norm).powi(2) + dp_step * dp_step).sqrt() / u_norm;
            residuals.push(ev.rel);
            self.flips.record(&self.contact);
            let mut reported_du = rel_du;
            let mut converged = false;
            // Lagrange constraints: the gaps of the active nodes vanish too
            let gap_ok = norm(&self.constraints.gap) / u_norm <= settings.tol_displacement;
            let small =
                ev.rel <= settings.tol || (force_free_ok && ev.abs <= settings.tol * first_ref);
            if ev.rel.is_finite() && small && gap_ok {
                if rel_du <= settings.tol_displacement {
                    converged = true;
                } else if let Some(next) = self.next_correction_norm(saddle_used) {
                    // next correction estimated with the factorization at hand
                    reported_du = next / u_norm;
                    converged = reported_du <= settings.tol_displacement;
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
                return Err(fail(
                    FailureKind::NotFinite,
                    &residuals,
                    format!("iteration {k}: the residual is not finite"),
                ));
            }
            // augmented Lagrangian, `update = newton`: lambda* updated inside
            // the loop while a penetration exceeds its tolerance
            let updated = newton_update
                && active_set::uzawa_update(
                    model,
                    &mut self.pairs,
                    &self.contact,
                    MultiplierUpdate::Newton,
                );
            if updated {
                self.inner_updates += 1;
                converged = false;
                tangent_valid = false;
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
            let n = residuals.len();
            if updated || updated_last {
                // a multiplier update changes the problem: no divergence test
                growths = 0;
            } else if n >= 2 && residuals[n - 1] > residuals[n - 2] {
                growths += 1;
            } else {
                growths = 0;
            }
            updated_last = updated;
            if growths >= DIVERGENCE_GROWTHS {
                return Err(fail(
                    FailureKind::Diverged,
                    &residuals,
                    format!(
                        "the residual grew in {DIVERGENCE_GROWTHS} consecutive iterations \
                         (iteration {k})"
                    ),
                ));
            }
        }
        Err(fail(
            FailureKind::MaxIterations,
            &residuals,
            format!(
                "no convergence in max_iter = {} iterations",
                settings.max_iter
            ),
        ))
    }
}
