//! Why an increment attempt failed: a typed taxonomy ([`FailureKind`]) that
//! callers decide on (the stepper cuts back; under MPI every rank must
//! agree on the kind), the residual history of the attempt and a sentence
//! for the user. The words of the final diagnosis (likely cause, remedy)
//! are in [`crate::solve::diagnosis`].

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
    /// An iterative linear solver (a Krylov method under `--solver petsc`)
    /// stopped before its tolerance: at its iteration cap, or broken down.
    LinearSolver,
    /// An element could not be evaluated.
    Element,
    /// The Lagrange-multiplier active set came back to a set already met
    /// in the increment.
    ActiveSetCycling,
    /// Not a failure: a node first touched its master within the
    /// increment and the deck asks to cut the increment at that instant
    /// (`cut_at_impact = true`).
    ImpactCut,
    /// Not a failure: the local error estimate of adaptive dynamic
    /// stepping exceeds twice its tolerance; the increment is redone
    /// smaller (`dynamic { adaptive = true  error_tol }`).
    ErrorEstimate,
    /// Not a failure: a cell turned by more than `dynamic { max_rotation
    /// }` in the increment; it is redone smaller.
    Rotation,
    /// Not a failure: the increment created more energy than `dynamic {
    /// energy_tol }` allows; it is redone smaller.
    Energy,
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
    /// A failure of `kind` with no residual history yet.
    pub fn new(kind: FailureKind, detail: impl Into<String>) -> Self {
        Failure {
            kind,
            residuals: Vec::new(),
            detail: detail.into(),
        }
    }

    /// The same failure with the residual history `residuals`.
    pub fn with_residuals(mut self, residuals: &[f64]) -> Self {
        self.residuals = residuals.to_vec();
        self
    }
}
