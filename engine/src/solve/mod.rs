//! Assembly, sparse linear solvers, the contact Newton loop and load stepping.
//!
//! Entry point: [`run`]. The loop reads as the algorithm (seed flowchart):
//! for each step, for each increment: contact search -> contact forces ->
//! internal forces -> residual -> tangent -> solve -> update, until the
//! residual and the displacement increment are small; cut the increment
//! back on divergence, NaN or too many iterations.

pub mod dofs;
pub mod linear;
pub mod pattern;

use crate::contact::NodeContact;
use crate::model::Model;

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

/// What observers see of a converged increment.
#[derive(Debug)]
pub struct IncrementView<'a> {
    /// The model being solved.
    pub model: &'a Model,
    /// Step index (0-based).
    pub step: usize,
    /// Converged increment number in the run (1-based).
    pub increment: usize,
    /// Time at the end of the increment.
    pub time: f64,
    /// Nodal displacements.
    pub displacement: &'a [[f64; 2]],
    /// Nodal reaction forces (non-zero only at constrained dofs).
    pub reaction: &'a [[f64; 2]],
    /// Contact evaluation of each pair at the converged state.
    pub contact: &'a [Vec<NodeContact>],
    /// Relative residual after each Newton iteration of this increment.
    pub residuals: &'a [f64],
}

/// Receives progress and converged states (writers, progress bars, tests).
pub trait Observer {
    /// After each Newton iteration.
    fn iteration(&mut self, _info: &IterationInfo) {}
    /// After each converged increment; an error aborts the run.
    fn converged(&mut self, _view: &IncrementView<'_>) -> Result<(), String> {
        Ok(())
    }
    /// When an increment is cut back (why, new increment size).
    fn cutback(&mut self, _reason: &str, _new_dt: f64) {}
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
}

/// Wall time spent per phase, seconds.
#[derive(Debug, Clone, Default, serde::Serialize)]
pub struct Timings {
    /// Element internal forces and stiffness, scattered into the matrix.
    pub assembly: f64,
    /// Contact search and contact forces/tangents.
    pub contact: f64,
    /// Numeric sparse factorization (symbolic included on first use).
    pub factorization: f64,
    /// Triangular solves.
    pub solve: f64,
    /// Observers (result writing).
    pub output: f64,
    /// Whole run.
    pub total: f64,
}

/// What a run did; written as `summary.json`.
#[derive(Debug, Clone, Default, serde::Serialize)]
pub struct RunSummary {
    /// Number of nodes.
    pub nodes: usize,
    /// Number of free (unconstrained) degrees of freedom.
    pub free_dofs: usize,
    /// Converged increments.
    pub increments: Vec<IncrementRecord>,
    /// Total Newton iterations (converged and failed attempts).
    pub newton_iterations: usize,
    /// Total cutbacks.
    pub cutbacks: usize,
    /// Linear solver used (`cholesky` or `lu`).
    pub linear_solver: String,
    /// Wall time per phase.
    pub timings: Timings,
    /// Whether the whole analysis finished.
    pub completed: bool,
    /// Why the run stopped early, if it did.
    pub failure: Option<String>,
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

/// Runs every step of `model`, reporting to `observer`.
pub fn run(model: &Model, observer: &mut dyn Observer) -> Result<RunSummary, RunError> {
    let _ = (model, observer);
    Err(RunError {
        summary: RunSummary::default(),
        message: "solver not implemented yet".into(),
    })
}
