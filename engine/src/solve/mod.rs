//! Assembly, sparse linear solvers, the contact Newton loop and load stepping.
//!
//! Entry point: [`run`]. The loop reads as the algorithm (seed flowchart):
//! for each step, for each increment: contact search -> contact forces ->
//! internal forces -> residual -> tangent -> solve -> update, until the
//! residual and the displacement increment are small; cut the increment
//! back on divergence, NaN or too many iterations.
//!
//! - [`check`]: the model is checked first, every problem reported at once
//!   (indices, parameters, unheld bodies);
//! - [`dofs`]: `D` dofs per node, free / prescribed (eliminated) / inactive;
//! - [`linalg`]: the CSC pattern and scatter map ([`linalg::pattern`]),
//!   `trait LinearSystem` (faer direct: Cholesky, `L D L^T`, LU) and
//!   `trait SaddlePointSystem` (Lagrange multipliers);
//! - [`assembly`], [`loads`]: element loop and external forces;
//! - [`contact_assembly`]: contact forces and tangent blocks into the
//!   global system, pattern growth, Lagrange rows (the only place where
//!   contact meets the dof numbering);
//! - [`constraints`]: variable-length constraint rows in dof terms;
//! - [`newton`]: one Newton loop (predictor with the prescribed increment,
//!   line search, convergence, NaN and divergence detection, typed
//!   failures, commit / rollback);
//! - [`contact_loop`]: contact iterations around the Newton loops (Lagrange
//!   active set with a cycling guard, augmented-Lagrangian Uzawa updates,
//!   Lagrange friction statuses);
//! - [`stepping`]: increments, cutback and grow-back;
//! - [`share`]: the cells and nodes one MPI rank assembles (distributed
//!   assembly under `ctc run --solver petsc`) and which models allow it;
//! - [`scene`]: the seams of the dimension-generic solver (contact scene,
//!   heat coupling; 3D has neither yet);
//! - [`diagnosis`]: the likely cause and remedy of a failed run;
//! - [`jumps`]: warnings for slave nodes that moved farther than the
//!   contact search window in one increment;
//! - [`health`]: warnings after the run (a pair that never closed,
//!   penetrations large against the element size or the tool's travel).

pub mod assembly;
pub mod bulk_tangent;
pub mod cell_rotation;
pub mod check;
pub mod constraints;
pub mod contact_assembly;
pub mod contact_loop;
pub mod contact_mass;
pub mod control;
pub mod diagnosis;
pub mod discrete;
pub mod dofs;
pub mod dynamics;
pub mod follower;
pub mod free_tool;
pub mod health;
pub mod inertia_points;
pub mod jumps;
pub mod linalg;
pub mod loads;
pub mod memory;
pub mod newton;
pub mod parallel;
pub mod restart;
pub mod rigid_body;
pub mod rotation_chart;
pub mod rotation_vector;
pub mod scene;
pub mod share;
pub mod stabilize;
pub mod stepping;
pub mod surface_assembly;

use crate::contact::NodeContact;
use crate::geom::Dimension;
use crate::model::{AnalysisKind, Model};
use nalgebra::Const;
use newton::{ContactOf, Converged, Failure, Newton};
use scene::{ContactScene, HeatCoupling};
use std::time::Instant;
use stepping::{IncrementSolver, StepError};

/// One Newton iteration, reported to observers as it happens.
#[derive(Debug, Clone, serde::Serialize)]
pub struct IterationInfo {
    /// Step index (0-based).
    pub step: usize,
    /// Increment number within the run (1-based, counting converged ones).
    pub increment: usize,
    /// Iteration number (1-based).
    pub iteration: usize,
    /// Relative residual norm after the iteration.
    pub residual: f64,
    /// Relative displacement-increment norm.
    pub displacement: f64,
    /// Line-search step length used (1 = full Newton step).
    pub step_length: f64,
    /// Number of closed contact nodes.
    pub active_contacts: usize,
}

/// What observers see of a converged increment of a model of dimension
/// `D`.
#[derive(Debug)]
pub struct IncrementView<'a, const D: usize = 2> {
    /// The model being solved.
    pub model: &'a Model<D>,
    /// Step index (0-based).
    pub step: usize,
    /// Converged increment number in the run (1-based).
    pub increment: usize,
    /// Time at the end of the increment.
    pub time: f64,
    /// Nodal displacements.
    pub displacement: &'a [[f64; D]],
    /// Nodal reaction forces (non-zero only at constrained dofs).
    pub reaction: &'a [[f64; D]],
    /// Contact evaluation of each pair at the converged state (empty in
    /// 3D until the 3D contact issue).
    pub contact: &'a [Vec<NodeContact<D>>],
    /// Relative residual after each Newton iteration of this increment.
    pub residuals: &'a [f64],
    /// Converged integration points per global cell for bodies with
    /// nonlinear laws (stress, strain, internal variables such as the
    /// equivalent plastic strain); empty for small-strain linear elastic
    /// cells.
    pub points: &'a [Vec<crate::element::MaterialPoint>],
    /// Isotropic thermal strain of each cell this increment was solved with
    /// (thermal scenes; empty otherwise): the stress of a linear elastic
    /// cell is `D (eps - eps_th I)`.
    pub thermal_strain: &'a [f64],
    /// What each pressure controller did in this increment (the model's
    /// controlled loads in order; empty without controllers).
    pub controls: &'a [control::ControlRecord],
    /// The free tools' angle, angular velocity and moments (tool order;
    /// empty without free tools, `free_tool.rs`).
    pub tools: &'a [free_tool::ToolRecord],
    /// Nodal temperatures (thermal scenes only; 0 at nodes without
    /// temperature).
    pub temperature: Option<&'a [f64]>,
    /// The heat step of the increment (thermal scenes only).
    pub thermal: Option<&'a crate::thermal::solver::ThermalIncrement>,
    /// The energy audit (models with a dynamic step).
    pub energy: Option<&'a dynamics::Energy>,
    /// Committed velocity per dof `node D + c` (models with a dynamic
    /// step).
    pub velocity: Option<&'a [f64]>,
    /// Committed acceleration per dof (models with a dynamic step).
    pub acceleration: Option<&'a [f64]>,
}

impl<const D: usize> IncrementView<'_, D> {
    /// The deformed nodal positions `x + u` of this increment.
    pub fn positions(&self) -> Vec<[f64; D]> {
        self.model
            .mesh
            .nodes
            .iter()
            .zip(self.displacement)
            .map(|(x, u)| std::array::from_fn(|k| x[k] + u[k]))
            .collect()
    }
}

/// Receives progress and converged states (writers, progress bars, tests)
/// of a run of dimension `D` (`Observer` without a parameter: planar).
pub trait Observer<const D: usize = 2> {
    /// After each Newton iteration.
    fn iteration(&mut self, _info: &IterationInfo) {}
    /// After each converged increment; an error aborts the run.
    fn converged(&mut self, _view: &IncrementView<'_, D>) -> Result<(), String> {
        Ok(())
    }
    /// When an increment is cut back: why, in one line (what failed, the
    /// number of iterations and the first and last residuals to three
    /// significant digits; the full sequence is in
    /// [`RunSummary::cutback_log`]), and the new increment size.
    fn cutback(&mut self, _reason: &str, _new_dt: f64) {}
    /// A warning about a converged increment (also kept in
    /// [`RunSummary::warnings`]).
    fn warning(&mut self, _message: &str) {}
    /// Whether [`Observer::checkpoint`] should be called (building a
    /// checkpoint copies the state, so it is done only on request).
    fn wants_checkpoint(&self) -> bool {
        false
    }
    /// After each converged increment (after [`Observer::converged`]): the
    /// state a restart continues from. An error aborts the run.
    fn checkpoint(&mut self, _checkpoint: &restart::Checkpoint<D>) -> Result<(), String> {
        Ok(())
    }
}

/// Record of one converged increment in the run summary.
#[derive(Debug, Clone, serde::Serialize)]
pub struct IncrementRecord {
    /// Step name.
    pub step: String,
    /// Converged increment number (1-based).
    pub increment: usize,
    /// Time at the end of the increment.
    pub time: f64,
    /// Increment size.
    pub dt: f64,
    /// Newton iterations of the converged attempt.
    pub iterations: usize,
    /// Relative residual after each iteration of the converged attempt.
    pub residuals: Vec<f64>,
    /// Failed attempts before this one converged.
    pub cutbacks: usize,
    /// Closed contact nodes at convergence.
    pub active_contacts: usize,
    /// Contact iterations: Lagrange active-set changes plus
    /// augmented-Lagrangian (Uzawa) multiplier updates (0 for penalty).
    pub contact_iterations: usize,
    /// Largest penetration `max(0, -g)` over all pairs at convergence
    /// (length).
    pub max_penetration: f64,
    /// Round-off floor of the relative residual at convergence
    /// (`4 eps || |K| |x| ||` over the force scale, see
    /// `newton::convergence`).
    pub residual_floor: f64,
    /// Whether the increment converged on its floor (the residual could
    /// not be computed more accurately than `tol` asks).
    pub at_floor: bool,
    /// Work dissipated by friction over the increment, per contact pair
    /// (empty without friction).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub friction_work: Vec<f64>,
    /// The heat step of the increment (thermal scenes only).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub thermal: Option<crate::thermal::solver::ThermalIncrement>,
    /// The stabilization of the increment (`newton { stabilize }` steps
    /// only).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stabilization: Option<stabilize::IncrementRecord>,
    /// The energy audit at the end of the increment (models with a dynamic
    /// step).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub energy: Option<dynamics::Energy>,
    /// The free tools at the end of the increment (tool order; models
    /// with `rotation = free` only).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub tools: Vec<free_tool::ToolRecord>,
}

/// Record of one failed increment attempt (a cutback) in the run summary.
#[derive(Debug, Clone, serde::Serialize)]
pub struct CutbackRecord {
    /// Step name.
    pub step: String,
    /// Time of the last converged state the attempt started from.
    pub from: f64,
    /// Time the attempt tried to reach.
    pub to: f64,
    /// Size of the next attempt.
    pub new_dt: f64,
    /// What failed, in words.
    pub reason: String,
    /// Relative residual after each iteration of the failed attempt (all
    /// Newton loops of the attempt).
    pub residuals: Vec<f64>,
}

/// Wall time spent per phase, seconds.
#[derive(Debug, Clone, Default, serde::Serialize)]
pub struct Timings {
    /// Element internal forces and stiffness, scattered into the matrix.
    pub assembly: f64,
    /// Contact search and contact forces/tangents.
    pub contact: f64,
    /// Numeric sparse factorization (symbolic included on first use), low-rank
    /// updates included.
    pub factorization: f64,
    /// Of `factorization`: the low-rank updates (`linalg::low_rank`: new
    /// columns of the base's inverse, the dense update).
    pub low_rank: f64,
    /// Triangular solves.
    pub solve: f64,
    /// Of `factorization`: the symbolic analyses (fill-reducing ordering,
    /// elimination tree), done once per sparsity pattern.
    pub symbolic: f64,
    /// Residual and convergence work of the evaluations outside the
    /// element loop and the contact: the residual and its norms, springs,
    /// stabilization, the round-off floor `|K| |x|`.
    pub residual: f64,
    /// Set-up before the first increment: model check, dof numbering,
    /// sparsity pattern, element matrices, the reference-state check.
    pub setup: f64,
    /// Observers (result writing).
    pub output: f64,
    /// Whole run.
    pub total: f64,
    /// Cells evaluated by the last element loop (this rank's cells under
    /// a distributed assembly, all cells otherwise); not a time, not
    /// written to `summary.json`'s `timings`.
    #[serde(skip)]
    pub cells_assembled: usize,
    /// CPU time of the phases above (this thread's run time,
    /// [`memory::thread_cpu_seconds`]): assembly, contact, factorization,
    /// solve; not written to `summary.json`'s `timings` (the distributed
    /// run reports them per rank).
    #[serde(skip)]
    pub cpu: [f64; 4],
}

/// What a run did; written as `summary.json`.
#[derive(Debug, Clone, Default, serde::Serialize)]
pub struct RunSummary {
    /// Number of nodes.
    pub nodes: usize,
    /// Number of free (unconstrained) degrees of freedom.
    pub free_dofs: usize,
    /// Stored entries of the free-free stiffness matrix (both triangles).
    pub matrix_nonzeros: usize,
    /// Entries of the sparse Cholesky factor `L` (AMD ordering, diagonal
    /// included); 0 when no symmetric factorization ran.
    pub factor_nonzeros: usize,
    /// Fill: `factor_nonzeros` over the entries of the lower triangle of
    /// the matrix, `(matrix_nonzeros + free_dofs) / 2`.
    pub factor_fill: f64,
    /// Bytes of the factorization (values of `L` plus numeric scratch).
    pub factor_bytes: usize,
    /// Peak resident memory of the process at the end of the run
    /// (`VmHWM`, Linux; 0 where unknown), bytes.
    pub peak_memory_bytes: u64,
    /// Conventions a reader of the results must know (e.g. axisymmetric
    /// forces are totals over 2*pi).
    pub notes: Vec<String>,
    /// Converged increments.
    pub increments: Vec<IncrementRecord>,
    /// Total Newton iterations (converged and failed attempts).
    pub newton_iterations: usize,
    /// Total cutbacks.
    pub cutbacks: usize,
    /// Increment starts moved by the predictor's edge or first-touch rule
    /// whose first Newton step the line search shortened, retaken from the
    /// unmoved start (`newton::predictor`; their abandoned iterations are
    /// in `newton_iterations`); absent: none.
    #[serde(skip_serializing_if = "is_zero")]
    pub predictor_retakes: usize,
    /// Every cutback: the failed attempt, its reason and its full residual
    /// sequence (the console shows one line each).
    pub cutback_log: Vec<CutbackRecord>,
    /// Linear solver used (`cholesky`, or `lu` if any factorization needed
    /// LU because the tangent was not positive definite).
    pub linear_solver: String,
    /// Numeric Cholesky factorizations.
    pub cholesky_factorizations: usize,
    /// Numeric L D L^T factorizations (symmetric indefinite tangent, e.g.
    /// the curvature term of a convex tool at a large trial penetration).
    pub ldlt_factorizations: usize,
    /// Largest number of negative pivots met in an L D L^T factorization
    /// (negative eigenvalues of the tangent).
    pub max_negative_pivots: usize,
    /// Numeric LU factorizations (Cholesky is retried at each increment).
    pub lu_factorizations: usize,
    /// Tangents solved by a low-rank (Woodbury) update of the last
    /// factorization instead of a factorization of their own
    /// (`linalg::low_rank`: only the contact dofs' blocks changed); 0: every
    /// tangent was factorized.
    #[serde(skip_serializing_if = "is_zero")]
    pub low_rank_updates: usize,
    /// Threads of the parallel kernels (`parallel::threads`: element
    /// loop, low-rank solves); the results do not depend on it.
    pub threads: usize,
    /// Symbolic factorizations of the Lagrange-multiplier saddle-point
    /// system (one per distinct active set met).
    pub saddle_symbolic_factorizations: usize,
    /// Numeric factorizations of the saddle-point system (sparse LU, or
    /// `L D L^T` for the doubled-multiplier formulation).
    pub saddle_factorizations: usize,
    /// Order and stored entries of the largest Lagrange-multiplier matrix
    /// factorized (the saddle point's `n + m`, or `n` with the multipliers
    /// condensed); not written to `summary.json`.
    #[serde(skip)]
    pub saddle_system: (usize, usize),
    /// `|A - A^T|_F / |A|_F` of the last condensed matrix (`None`: not
    /// condensed); not written to `summary.json`.
    #[serde(skip)]
    pub saddle_asymmetry: Option<f64>,
    /// Wall time per phase.
    pub timings: Timings,
    /// Temperature unknowns (0: the scene has no thermal part).
    #[serde(skip_serializing_if = "is_zero")]
    pub temperature_dofs: usize,
    /// Whether the whole analysis finished.
    pub completed: bool,
    /// Why the run stopped early, if it did.
    pub failure: Option<String>,
    /// Work dissipated by friction over the run, per contact pair (pair
    /// order of the model; empty without friction; axisymmetric: over 2*pi).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub friction_work: Vec<f64>,
    /// Warnings of converged increments (e.g. slave nodes that moved
    /// farther than the contact search window in one increment, or whose
    /// projection on a CAD face did not converge).
    pub warnings: Vec<String>,
    /// Search and projection figures of each pair against a surface tool
    /// (3D): projections per node, Newton iterations of the projections,
    /// faces tested, projections that did not converge.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub surface_search: Vec<crate::contact::surface::SearchFigures>,
    /// The stabilization of each `newton { stabilize }` step: its energy
    /// against the internal work, and its force at the step's end.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub stabilization: Vec<stabilize::StepRecord>,
    /// The deck's unit system and the unit of each quantity kind (absent
    /// when the deck declares none: numbers are then in the user's
    /// consistent units).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub units: Option<crate::model::UnitNames>,
    /// The energy audit at the end of the run (models with a dynamic step).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub energy: Option<dynamics::Energy>,
    /// Ranks, rows per rank, Krylov iterations and times of a distributed
    /// linear solver (`ctc run --solver petsc`; absent for the serial one).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub distributed: Option<linalg::DistributedStats>,
}

fn is_zero(n: &usize) -> bool {
    *n == 0
}

/// A run that stopped before the end: the summary up to the failure and a
/// diagnosis.
#[derive(Debug, Clone)]
pub struct RunError {
    /// What was done before the failure (`completed = false`).
    pub summary: RunSummary,
    /// Diagnosis: what failed, where, the likely cause and a remedy.
    pub message: String,
}

impl std::fmt::Display for RunError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.message)
    }
}

impl std::error::Error for RunError {}

/// Note attached to axisymmetric results.
pub const AXISYMMETRIC_NOTE: &str =
    "axisymmetric: x = r, y = z, component zz = hoop (theta theta); \
     forces, reactions and contact forces are totals over the full 2*pi (Abaqus convention)";

/// Runs every step of `model`, reporting to `observer`.
///
/// The model is checked first (all problems reported at once); then each
/// step is solved increment by increment (see [`stepping`] and [`newton`]).
// The error carries the summary of the run so far (contract signature).
#[allow(clippy::result_large_err)]
pub fn run<const D: usize>(
    model: &Model<D>,
    observer: &mut dyn Observer<D>,
) -> Result<RunSummary, RunError>
where
    Const<D>: Dimension<D>,
{
    run_from(model, observer, None)
}

/// Like [`run`], but continues from the restart point `from` (a
/// [`restart::Checkpoint`] of a run of the same model) when given: the
/// increments that follow are the same, bit for bit, as in the
/// uninterrupted run. The summary covers the continued part only.
#[allow(clippy::result_large_err)]
pub fn run_from<const D: usize>(
    model: &Model<D>,
    observer: &mut dyn Observer<D>,
    from: Option<&restart::Checkpoint<D>>,
) -> Result<RunSummary, RunError>
where
    Const<D>: Dimension<D>,
{
    run_with(model, observer, from, None)
}

/// Like [`run_from`] with the tangent solved by `linear` (`None`: the
/// serial direct solver, [`linalg::direct::LinearSolver`]); this is how
/// `ctc run --solver petsc` plugs in PETSc over MPI (every rank runs the
/// same Newton loop on the same replicated model, so every decision is the
/// same on all ranks as long as the solver returns the same solution
/// everywhere).
#[allow(clippy::result_large_err)]
pub fn run_with<'m, const D: usize>(
    model: &'m Model<D>,
    observer: &mut dyn Observer<D>,
    from: Option<&restart::Checkpoint<D>>,
    linear: Option<Box<dyn linalg::LinearSystem + 'm>>,
) -> Result<RunSummary, RunError>
where
    Const<D>: Dimension<D>,
{
    let start = Instant::now();
    let mut summary = RunSummary {
        nodes: model.mesh.nodes.len(),
        linear_solver: linalg::direct::Method::Cholesky.name().to_string(),
        units: model.output.units.clone(),
        ..Default::default()
    };
    if model.analysis.kind == AnalysisKind::Axisymmetric {
        summary.notes.push(AXISYMMETRIC_NOTE.to_string());
    }
    for cp in &model.contacts {
        // self contact: the master surface's nodes are the slave nodes
        let self_contact = match &cp.master {
            crate::model::ContactMaster::Surface { nodes, .. } => {
                let mut slaves = cp.nodes.clone();
                slaves.sort_unstable();
                slaves.dedup();
                &slaves == nodes
            }
            crate::model::ContactMaster::Tool(_) => false,
        };
        if matches!(cp.method, crate::model::ContactMethod::Lagrange { .. })
            && (cp.strategy == crate::model::ContactStrategy::ModifiedDoublePass || self_contact)
        {
            summary.notes.push(format!(
                "contact `{}`: Lagrange multipliers on both sides at once (modified double \
                 pass or self contact) over-constrain the interface; a node's row nearly \
                 dependent on the rows of its neighbours (a node lying on a node of the other \
                 side) is redundant and dropped, its node held by those rows \
                 (`CTC_LOG=debug` counts them per evaluation)",
                cp.name
            ));
        }
    }
    let fail = |mut summary: RunSummary, message: String| {
        summary.failure = Some(message.clone());
        summary.timings.total = start.elapsed().as_secs_f64();
        RunError { summary, message }
    };
    let errors = check::check_model(model);
    if !errors.is_empty() {
        let message = format!("the model cannot be solved:\n  - {}", errors.join("\n  - "));
        return Err(fail(summary, message));
    }
    let built = match linear {
        Some(linear) => Newton::with_linear_system(model, linear),
        None => Newton::new(model),
    };
    let newton = match built {
        Ok(n) => n,
        Err(e) => return Err(fail(summary, format!("the model cannot be solved: {e}"))),
    };
    let mut newton = newton;
    memory::trace("newton built");
    let setup = start.elapsed().as_secs_f64();
    let thermal = match <Const<D> as Dimension<D>>::Heat::new(model) {
        Ok(t) => t,
        Err(e) => return Err(fail(summary, format!("the model cannot be solved: {e}"))),
    };
    if from.is_some() && !control::controls(model).is_empty() {
        let message = "cannot restart a run with a pressure controller: the restart file does not \
                       hold the controller's factor yet; run from the start"
            .to_string();
        return Err(fail(summary, message));
    }
    if let Some(th) = &thermal {
        if from.is_some() {
            let message = "cannot restart a thermo-mechanical run: restart points do not hold                            temperatures yet; run from the start"
                .to_string();
            return Err(fail(summary, message));
        }
        summary.temperature_dofs = th.free_dofs();
        let laws = th.cell_laws(model);
        if let Err(e) = laws.and_then(|l| newton.set_thermal_state(th.thermal_strains(model), l)) {
            return Err(fail(summary, format!("the model cannot be solved: {e}")));
        }
    }
    summary.free_dofs = newton.dofs.n_free();
    summary.matrix_nonzeros = newton.nnz();
    let mut increment = 0;
    if let Some(cp) = from {
        if cp.fingerprint != restart::fingerprint(model) {
            let message = "cannot restart: the restart point was written by a different model \
                           (the deck or a mesh file changed since); run from the start"
                .to_string();
            return Err(fail(summary, message));
        }
        if let Err(e) = newton.restore(cp) {
            return Err(fail(summary, format!("cannot restart: {e}")));
        }
        increment = cp.increment;
    }
    for s in model.steps.iter().filter(|s| s.newton.stabilize.is_some()) {
        if !newton.stabilization.any() {
            let w = format!(
                "step `{}`: `newton {{ stabilize }}` has nothing to act on: every body is held by \
                 its own `fix`/`displace` conditions (it stabilizes only bodies held by contact \
                 alone)",
                s.name
            );
            observer.warning(&w);
            summary.warnings.push(w);
        }
    }
    if from.is_none() {
        // slave nodes inside a tool at the start: a reversed side?
        for w in health::start_inside(model) {
            observer.warning(&w);
            summary.warnings.push(w);
        }
    }
    let mut driver = Driver {
        model,
        newton,
        observer,
        summary,
        increment,
        thermal,
        health: health::RunHealth::new(model),
        energy_alarms: Vec::new(),
        controls: control::controls(model),
        control_trend: vec![control::Trend::default(); control::controls(model).len()],
        attempt_span: (
            from.map_or_else(
                || model.steps.first().map_or(0.0, |s| s.t_start),
                |c| c.resume.time,
            ),
            0.0,
        ),
    };
    let result = stepping::drive_from(&model.steps, &mut driver, from.map(|c| c.resume));
    let Driver {
        newton,
        mut summary,
        observer,
        health,
        ..
    } = driver;
    for w in health.warnings(model) {
        observer.warning(&w);
        summary.warnings.push(w);
    }
    if let Some(dy) = newton.dynamics() {
        summary.energy = Some(dy.energy);
        summary.notes.extend(dy.mass_notes.iter().cloned());
    }
    let output = summary.timings.output;
    summary.timings = newton.timings.clone();
    summary.timings.output = output;
    summary.timings.setup = setup;
    summary.newton_iterations = newton.iterations;
    summary.predictor_retakes = newton.predictor_retakes;
    let stats = newton.factor_stats();
    summary.linear_solver = stats.most_general().to_string();
    if let Some(d) = newton.distributed_stats() {
        summary.linear_solver = d.solver.clone();
        summary.distributed = Some(d);
    }
    summary.cholesky_factorizations = stats.cholesky;
    summary.ldlt_factorizations = stats.ldlt;
    summary.lu_factorizations = stats.lu;
    summary.low_rank_updates = stats.low_rank;
    summary.threads = parallel::threads();
    summary.max_negative_pivots = stats.max_negative_pivots;
    summary.factor_nonzeros = stats.factor_nonzeros;
    summary.factor_bytes = stats.factor_bytes;
    summary.timings.symbolic = stats.symbolic_seconds;
    summary.peak_memory_bytes = memory::peak_memory_bytes();
    let lower = (summary.matrix_nonzeros + summary.free_dofs) / 2;
    summary.factor_fill = if lower > 0 {
        stats.factor_nonzeros as f64 / lower as f64
    } else {
        0.0
    };
    (
        summary.saddle_symbolic_factorizations,
        summary.saddle_factorizations,
    ) = newton.saddle_factorizations();
    summary.saddle_system = newton.saddle_largest_system();
    summary.saddle_asymmetry = newton.saddle_asymmetry();
    match result {
        Ok(()) => {
            summary.completed = true;
            summary.timings.total = start.elapsed().as_secs_f64();
            Ok(summary)
        }
        Err(StepError::Aborted(e)) => Err(fail(summary, format!("run aborted: {e}"))),
        Err(StepError::Cutbacks {
            step,
            time,
            dt,
            min_dt,
            failure,
            linear_repeat,
        }) => {
            let s = &model.steps[step];
            // a singular tangent (its zero pivot names the free motion) and a
            // residual stalled at round-off are not the contact's doing;
            // otherwise the contact health first
            let (cause, remedy) = if matches!(
                failure.kind,
                newton::FailureKind::Singular | newton::FailureKind::LinearSolver
            ) || diagnosis::stagnates(&failure.residuals)
            {
                diagnosis::failure_cause(&failure, &s.newton, newton.residual_floor().0)
            } else {
                let name = |i: usize| {
                    model
                        .contacts
                        .get(i)
                        .map_or_else(|| format!("{i}"), |c| c.name.clone())
                };
                let smoothed = |i: usize| {
                    model
                        .contacts
                        .get(i)
                        .is_some_and(|c| c.smoothing != crate::model::NormalSmoothing::None)
                };
                diagnosis::contact_cause(
                    newton.penalty_ratio().as_ref(),
                    &newton.flips,
                    &name,
                    &smoothed,
                )
                .unwrap_or_else(|| {
                    diagnosis::failure_cause(&failure, &s.newton, newton.residual_floor().0)
                })
            };
            // a body that only contact holds, singular at the step's start:
            // the stabilization is the remedy (issue 14, item 8)
            let remedy =
                match diagnosis::stabilize_hint(model, &failure, s, time, newton.start_closed()) {
                    Some(hint) => format!("{hint}; or: {remedy}"),
                    None => remedy,
                };
            let residuals: Vec<String> = failure
                .residuals
                .iter()
                .map(|r| format!("{r:.2e}"))
                .collect();
            // the linear solver failed the same way at dt and 2 dt: stopped
            // above the smallest increment (`stepping`, issue 21)
            let how = if linear_repeat {
                format!(
                    "the iterative linear solver failed the same way at dt = {:.3e} and, cut \
                     back once, at dt = {dt:.3e}: a smaller increment does not help it (the \
                     matrix hardly changes with the increment), so the run stopped without \
                     cutting back to the smallest allowed {min_dt:.3e}",
                    2.0 * dt
                )
            } else {
                format!(
                    "the increment was cut back to dt = {dt:.3e} and still failed; the smallest \
                     allowed is {min_dt:.3e}"
                )
            };
            let message = format!(
                "step `{}` (step {} of {}) could not advance from time t = {time}: {how} \
                 (min_increment {} x initial increment {:.3e}).\n  what: {}\n  last relative \
                 residuals: [{}]\n  likely cause: {cause}\n  remedy: {remedy}",
                s.name,
                step + 1,
                model.steps.len(),
                s.min_fraction,
                (s.t_end - s.t_start) / s.increments as f64,
                failure.detail,
                residuals.join(", "),
            );
            Err(fail(summary, message))
        }
    }
}

/// Glue between the stepper, the Newton solver, the observer and the summary.
struct Driver<'m, 'o, const D: usize>
where
    Const<D>: Dimension<D>,
{
    model: &'m Model<D>,
    newton: Newton<'m, D>,
    observer: &'o mut dyn Observer<D>,
    summary: RunSummary,
    increment: usize,
    /// Heat conduction of a thermo-mechanical scene (staggered).
    thermal: Option<<Const<D> as Dimension<D>>::Heat>,
    /// Time of the last converged state and time of the last attempt.
    attempt_span: (f64, f64),
    /// Contact health over the converged increments (warnings at the end).
    health: health::RunHealth,
    /// The energy audit's alarms raised so far (each warned about once, at
    /// the first increment that raises it).
    energy_alarms: Vec<dynamics::EnergyAlarm>,
    /// Pressure-cycle controllers: load index and control.
    controls: Vec<(usize, crate::model::RateControl)>,
    /// Each controller's last estimate of the pressure factor that holds
    /// its target (the trend predictor of [`control::next_scale`]).
    control_trend: Vec<control::Trend>,
}

impl<const D: usize> Driver<'_, '_, D>
where
    Const<D>: Dimension<D>,
{
    /// Friction work of the converged increment per pair, added to the
    /// run totals (empty without friction).
    fn friction_work(&mut self) -> Vec<f64> {
        if self.model.contacts.iter().all(|c| c.friction.is_none()) {
            return Vec::new();
        }
        let work: Vec<f64> = self.newton.contacts().friction_work();
        self.summary.friction_work.resize(work.len(), 0.0);
        for (t, w) in self.summary.friction_work.iter_mut().zip(&work) {
            *t += w;
        }
        work
    }
}

impl<const D: usize> Driver<'_, '_, D>
where
    Const<D>: Dimension<D>,
{
    /// The stabilization of the converged increment of step `step` ending
    /// at `t` (`None`: the step has none), kept in the step's record; at
    /// the step's end, a warning when its energy exceeds
    /// [`stabilize::ENERGY_WARNING_FRACTION`] of the internal work.
    fn stabilization_record(&mut self, step: usize, t: f64) -> Option<stabilize::IncrementRecord> {
        let s = &self.model.steps[step];
        let c = s.newton.stabilize?;
        let st = &self.newton.stabilization;
        if !st.any() {
            return None;
        }
        let internal = st.internal_energy;
        let ratio = if internal.abs() > 0.0 {
            st.step_energy / internal.abs()
        } else {
            0.0
        };
        let completed = st.factor == 0.0 && stabilize::ramp(c, s, t) == 0.0;
        let record = stabilize::StepRecord {
            step: s.name.clone(),
            factor: c,
            bodies: st.bodies.clone(),
            energy: st.step_energy,
            internal_energy: internal,
            ratio,
            end_force: st.force,
            completed,
        };
        let increment = stabilize::IncrementRecord {
            factor: st.factor,
            energy: st.increment_energy,
            force: st.force,
        };
        match self.summary.stabilization.last_mut() {
            Some(last) if last.step == record.step => *last = record,
            _ => self.summary.stabilization.push(record),
        }
        if completed && ratio > stabilize::ENERGY_WARNING_FRACTION {
            let w = format!(
                "step `{}`: the stabilization energy is {:.1} % of the internal work (more than \
                 {:.0} %): it changed the solution along the step (the end state is unstabilized); \
                 lower `stabilize` (now {c:e}) or use more increments",
                s.name,
                100.0 * ratio,
                100.0 * stabilize::ENERGY_WARNING_FRACTION
            );
            self.observer.warning(&w);
            self.summary.warnings.push(w);
        }
        Some(increment)
    }
}

impl<const D: usize> Driver<'_, '_, D>
where
    Const<D>: Dimension<D>,
{
    /// The warnings of the energy audit's alarms that the increment just
    /// committed (ending at `t`) raises for the first time.
    fn energy_warnings(&mut self, t: f64) -> Vec<String> {
        let Some(dy) = self.newton.dynamics() else {
            return Vec::new();
        };
        let e = dy.energy;
        let mut out = Vec::new();
        for alarm in e.alarms(self.thermal.is_some()) {
            if !self.energy_alarms.contains(&alarm) {
                self.energy_alarms.push(alarm);
                out.push(e.warning(alarm, self.increment, t));
            }
        }
        out
    }
}

impl<const D: usize> IncrementSolver for Driver<'_, '_, D>
where
    Const<D>: Dimension<D>,
{
    fn attempt(&mut self, step: usize, t: f64) -> Result<Converged, Failure> {
        self.attempt_span.1 = t;
        let settings = self.model.steps[step].newton;
        ContactOf::<D>::attempt(
            &mut self.newton,
            &settings,
            t,
            step,
            self.increment + 1,
            &mut *self.observer,
        )
    }

    fn accept(
        &mut self,
        step: usize,
        t: f64,
        dt: f64,
        cutbacks: usize,
        converged: Converged,
    ) -> Result<(), String> {
        self.attempt_span.0 = t;
        let warnings = self.newton.contacts().increment_warnings(
            self.model,
            (self.newton.committed_displacement(), t - dt),
            (&self.newton.u, t),
            self.increment + 1,
        );
        let before = self
            .thermal
            .as_ref()
            .map(|_| self.newton.material_points().to_vec());
        // the thermal strains this increment was solved with (the heat step
        // below sets those of the next increment)
        let solved_thermal_strain = self
            .thermal
            .as_ref()
            .map(|_| self.newton.thermal_strains().to_vec());
        let control_before: Vec<Vec<f64>> = self
            .controls
            .iter()
            .map(|(_, c)| control::monitored_ep(self.model, self.newton.material_points(), c))
            .collect();
        let tool_records = free_tool::records(
            self.model,
            self.newton.committed_displacement(),
            &self.newton.u,
            self.newton.contact(),
            t,
            dt,
        );
        self.newton.commit();
        let mut control_records = Vec::with_capacity(self.controls.len());
        for (((i, c), before), trend) in self
            .controls
            .iter()
            .zip(&control_before)
            .zip(&mut self.control_trend)
        {
            let i = *i;
            let after = control::monitored_ep(self.model, self.newton.material_points(), c);
            let rate = control::max_rate(before, &after, dt);
            let scale = self.newton.load_scales()[i];
            let value = match &self.model.loads[i] {
                crate::model::Load::FollowerPressure { value, .. } => value.eval(t),
                _ => 0.0,
            };
            control_records.push(control::ControlRecord {
                pressure: scale * value,
                rate,
            });
            let next = control::next_scale(c, scale, rate, dt, trend);
            self.newton
                .set_load_scale(i, control::capped(c, next, value));
        }
        self.increment += 1;
        self.health.record(self.model, self.newton.contact(), t);
        if let (Some(th), Some(before)) = (self.thermal.as_mut(), before) {
            // staggered: heat on the converged mechanical state, then the
            // thermal strains of the next increment
            th.heat_step(
                self.model,
                t,
                dt,
                self.newton.contact(),
                &before,
                self.newton.material_points(),
            )?;
            let laws = th.cell_laws(self.model)?;
            self.newton
                .set_thermal_state(th.thermal_strains(self.model), laws)?;
        }
        let reaction = self.newton.reaction_field();
        let view = IncrementView {
            model: self.model,
            step,
            increment: self.increment,
            time: t,
            displacement: &self.newton.u,
            reaction: &reaction,
            contact: self.newton.contact(),
            residuals: &converged.residuals,
            points: self.newton.material_points(),
            thermal_strain: solved_thermal_strain.as_deref().unwrap_or(&[]),
            controls: &control_records,
            tools: &tool_records,
            temperature: self.thermal.as_ref().map(|t| t.temperature()),
            thermal: self.thermal.as_ref().map(|t| t.last()),
            energy: self.newton.dynamics().map(|d| &d.energy),
            velocity: self.newton.dynamics().map(|d| &d.v[..]),
            acceleration: self.newton.dynamics().map(|d| &d.a[..]),
        };
        let start = Instant::now();
        let r = self.observer.converged(&view);
        self.summary.timings.output += start.elapsed().as_secs_f64();
        let friction_work = self.friction_work();
        self.summary.surface_search = self.newton.contacts().search_figures(self.model);
        let (residual_floor, at_floor) = self.newton.residual_floor();
        let stabilization = self.stabilization_record(step, t);
        self.summary.increments.push(IncrementRecord {
            step: self.model.steps[step].name.clone(),
            increment: self.increment,
            time: t,
            dt,
            iterations: converged.iterations,
            residuals: converged.residuals,
            cutbacks,
            active_contacts: converged.active_contacts,
            contact_iterations: converged.contact_iterations,
            max_penetration: converged.max_penetration,
            residual_floor,
            at_floor,
            friction_work,
            thermal: self.thermal.as_ref().map(|t| t.last().clone()),
            stabilization,
            energy: self.newton.dynamics().map(|d| d.energy),
            tools: tool_records,
        });
        for w in warnings.into_iter().chain(self.energy_warnings(t)) {
            self.observer.warning(&w);
            self.summary.warnings.push(w);
        }
        r
    }

    fn checkpoint(&mut self, resume: &restart::Resume) -> Result<(), String> {
        if !self.observer.wants_checkpoint() {
            return Ok(());
        }
        let start = Instant::now();
        let cp = self.newton.checkpoint(self.increment, *resume);
        memory::trace("restart checkpoint built");
        let r = self.observer.checkpoint(&cp);
        self.summary.timings.output += start.elapsed().as_secs_f64();
        r
    }

    fn impact_fraction(&self) -> Option<f64> {
        self.newton.impact_fraction()
    }

    fn local_error(&self) -> Option<f64> {
        self.newton.local_error()
    }

    fn rotation(&self) -> Option<(f64, String)> {
        let (theta, cell) = self.newton.cell_rotation()?;
        let at = self
            .model
            .bodies
            .iter()
            .find(|b| b.cells.contains(&cell))
            .map_or_else(
                || format!("cell {cell}"),
                |b| {
                    format!(
                        "body `{}` cell {} (global {cell})",
                        b.name,
                        cell - b.cells.start
                    )
                },
            );
        Some((theta, at))
    }

    fn energy_created(&self) -> Option<(f64, f64, String)> {
        self.newton.energy_created()
    }

    fn reject(&mut self, step: usize, failure: &Failure, new_dt: f64) {
        self.newton.rollback();
        self.summary.cutbacks += 1;
        let name = &self.model.steps[step].name;
        let (from, to) = self.attempt_span;
        let reason = format!(
            "step `{name}`, t = {} -> {}: {}{}",
            sig3(from),
            sig3(to),
            failure.detail,
            residual_range(&failure.residuals)
        );
        self.observer.cutback(&reason, new_dt);
        self.summary.cutback_log.push(CutbackRecord {
            step: name.clone(),
            from,
            to,
            new_dt,
            reason: failure.detail.clone(),
            residuals: failure.residuals.clone(),
        });
    }
}

/// `x` to three significant digits (`1.25e-2`; plain for 0).
fn sig3(x: f64) -> String {
    if x == 0.0 {
        "0".into()
    } else {
        format!("{x:.2e}")
    }
}

/// ` (N iterations, residual r_first -> r_last)`: the residual history of
/// a failed attempt in a few characters (the sequence is in the summary).
fn residual_range(residuals: &[f64]) -> String {
    match residuals {
        [] => String::new(),
        [r] => format!(" (1 iteration, residual {r:.2e})"),
        [a, .., b] => format!(
            " ({} iterations, residual {a:.2e} -> {b:.2e})",
            residuals.len()
        ),
    }
}
