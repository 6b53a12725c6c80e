//! Linear algebra of the solver, behind two traits so that the Newton loop
//! never names a library:
//!
//! - [`LinearSystem`]: the free-free tangent `K du = -r` on a fixed sparsity
//!   pattern. Factorize once per Newton iteration, solve one or more
//!   right-hand sides with that factorization, reuse the symbolic analysis
//!   while the pattern is unchanged, report negative pivots, fall back to a
//!   more general factorization on its own. Today: [`direct::LinearSolver`]
//!   (faer: Cholesky, then `L D L^T`, then LU). A PETSc implementation
//!   (KSP/PC, MPI) plugs in here (`Newton::with_linear_system`).
//! - [`SaddlePointSystem`]: the Lagrange-multiplier system
//!   `[K G^T; G 0]` built from the tangent and variable-length constraint
//!   rows ([`crate::solve::constraints::ConstraintRows`]). Today:
//!   [`saddle::SaddleSolver`] (faer LU, or `L D L^T` of the doubled form),
//!   or the multipliers condensed out locally ([`condensed::CondensedSolver`]:
//!   the displacements alone, by LU).
//!
//! Contract shared by both: `solve` uses the last successful `factorize`;
//! without one (never factorized, the last factorization failed, or the
//! pattern was reset since) it returns [`LinearError::NotFactorized`]
//! instead of panicking, and the Newton loop only calls it when it holds a
//! factorization of the current pattern.
//!
//! [`pattern`] holds the CSC pattern and the scatter map (dof-numbering
//! aware: element and contact blocks -> value slots).

pub mod condensed;
pub mod direct;
pub mod export;
pub mod low_rank;
pub mod ordering;
pub mod pattern;
pub mod saddle;
pub mod schur;

pub use pattern::{Scatter, SparsePattern, MAX_BLOCK, NO_SLOT};

use super::constraints::Constraints;

/// Why a factorization or a solve failed.
#[derive(Debug, Clone, PartialEq)]
pub enum LinearError {
    /// The symbolic analysis (ordering, elimination tree) failed.
    Symbolic(String),
    /// The numeric factorization failed: the matrix is singular.
    Singular(String),
    /// `solve` without a factorization of the current pattern.
    NotFactorized,
    /// An iterative solver stopped before its tolerance (a Krylov method at
    /// its iteration cap, a breakdown): what, in words. Not a property of
    /// the matrix: the Newton loop reports it as
    /// [`crate::solve::newton::FailureKind::LinearSolver`].
    NotConverged(String),
    /// The (symmetric) matrix is singular: `L D L^T` met a pivot at
    /// round-off level, and one step of inverse iteration with that factor
    /// gives a vector `v` with `||K v|| <= ZERO_MODE * ||diag(K) v||`, a
    /// zero-energy mode (a rigid-body motion nothing holds); raised by the
    /// Newton loop from [`LinearSystem::zero_mode`].
    ZeroPivot(ZeroMode),
}

/// A zero-energy mode of a singular matrix (see [`LinearError::ZeroPivot`]).
#[derive(Debug, Clone, PartialEq)]
pub struct ZeroMode {
    /// The row (free dof) with the largest component of the mode (the
    /// first within 1 % of it).
    pub dof: usize,
    /// Rows where the mode is at least a tenth of its largest component.
    pub rows: Vec<usize>,
    /// `||K v|| / ||diag(K) v||`.
    pub ratio: f64,
}

impl std::fmt::Display for LinearError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            LinearError::Symbolic(s) | LinearError::Singular(s) | LinearError::NotConverged(s) => {
                f.write_str(s)
            }
            LinearError::ZeroPivot(m) => write!(
                f,
                "the stiffness matrix is singular: a zero pivot, free dof {} (a zero-energy mode \
                 over {} dofs, ||K v|| / ||diag(K) v|| = {:.1e})",
                m.dof,
                m.rows.len(),
                m.ratio
            ),
            LinearError::NotFactorized => f.write_str(
                "internal: a linear solve was requested without a factorization of the current \
                 matrix pattern",
            ),
        }
    }
}

impl std::error::Error for LinearError {}

/// Counters of a linear system over the run (written to `summary.json`).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct FactorStats {
    /// Successful Cholesky factorizations.
    pub cholesky: usize,
    /// Successful `L D L^T` factorizations (symmetric indefinite).
    pub ldlt: usize,
    /// Successful LU factorizations.
    pub lu: usize,
    /// Negative pivots of the last factorization (negative eigenvalues of
    /// a symmetric tangent; 0 after Cholesky).
    pub negative_pivots: usize,
    /// Largest `negative_pivots` over the run.
    pub max_negative_pivots: usize,
    /// Tangents solved by a low-rank update of the last factorization
    /// instead of a factorization ([`low_rank`]).
    pub low_rank: usize,
    /// Stored entries of the Cholesky / `L D L^T` factor `L` (diagonal
    /// included) of the fill-reducing ordering; 0 before the first
    /// factorization or when only LU ran.
    pub factor_nonzeros: usize,
    /// Bytes held by the factorization: the values of `L` and the numeric
    /// scratch (the symbolic structure, a few index arrays, is not counted).
    pub factor_bytes: usize,
    /// Wall time of the symbolic analyses (orderings, elimination trees),
    /// seconds; 0 when the system does not report it.
    pub symbolic_seconds: f64,
}

impl FactorStats {
    /// The most general factorization the run needed: `lu`, else `ldlt`,
    /// else `cholesky`.
    pub fn most_general(&self) -> &'static str {
        if self.lu > 0 {
            direct::Method::Lu.name()
        } else if self.ldlt > 0 {
            direct::Method::Ldlt.name()
        } else {
            direct::Method::Cholesky.name()
        }
    }
}

/// The free-free tangent system `K x = b` on a sparsity pattern that
/// changes rarely (contact couplings).
pub trait LinearSystem {
    /// Whether the next matrices are symmetric (a potential: symmetric
    /// factorizations are tried first) or not (friction, F-bar: a general
    /// one is used).
    fn set_symmetric(&mut self, symmetric: bool);
    /// Numeric factorization of the matrix with `pattern` and `values`
    /// (the first `pattern.nnz()` values are used, both triangles stored).
    fn factorize(&mut self, pattern: &SparsePattern, values: &[f64]) -> Result<(), LinearError>;
    /// Solves `K x = b` in place with the last factorization.
    fn solve(&mut self, rhs: &mut [f64]) -> Result<(), LinearError>;
    /// Whether `solve` has a factorization to use.
    fn is_factorized(&self) -> bool;
    /// The pattern changed: forget the symbolic analyses and the
    /// factorization.
    fn reset_pattern(&mut self);
    /// The zero-energy mode of the last factorized matrix when it was
    /// singular (found by [`direct::LinearSolver`] from a round-off pivot;
    /// the factorization may still have succeeded by pivoting, and the
    /// caller decides). `None`: regular, or not known.
    fn zero_mode(&self) -> Option<&ZeroMode> {
        None
    }
    /// The free dofs whose rows and columns are the only ones that change
    /// between tangents (the contact surfaces' dofs of a model whose bodies
    /// have a constant stiffness): a direct solver may order them last and
    /// update their Schur complement instead of factorizing
    /// ([`schur`]). A hint: the matrices still decide. Ignored by default.
    fn set_candidates(&mut self, _dofs: &[usize]) {}
    /// Counters.
    fn stats(&self) -> FactorStats;
    /// What a distributed solver (PETSc over MPI) did, with the engine's
    /// phase `timings` of this rank gathered from every rank into
    /// [`DistributedStats::per_rank`]; `None` for the serial direct solver.
    /// Collective for a distributed solver: the run calls it once, at its
    /// end, on every rank.
    fn distributed(&self, _timings: &super::Timings) -> Option<DistributedStats> {
        None
    }
    /// The cells and nodes this rank assembles (distributed assembly,
    /// [`super::share`]); `None`: the whole model.
    fn share(&self) -> Option<std::sync::Arc<super::share::AssemblyShare>> {
        None
    }
    /// Sums `v` over the ranks, in place, with the same bits on every rank
    /// (collective under a distributed assembly; nothing otherwise).
    fn sum_over_ranks(&self, _v: &mut [f64]) {}
    /// Whether `flag` is set on any rank (collective under a distributed
    /// assembly; `flag` otherwise).
    fn any_rank(&self, flag: bool) -> bool {
        flag
    }
    /// The ranks' `local` vectors concatenated rank by rank on the first
    /// rank, `None` on the others (collective under a distributed
    /// assembly; `local` otherwise).
    fn gather_on_first(&self, local: &[f64]) -> Option<Vec<f64>> {
        Some(local.to_vec())
    }
}

pub use super::memory::peak_memory_bytes;

/// Counters of a distributed linear solver over the run (the `distributed`
/// section of `summary.json`).
#[derive(Debug, Clone, Default, PartialEq, serde::Serialize)]
pub struct DistributedStats {
    /// Library and method: `petsc: ksp preonly, pc lu (mumps)`, ...
    pub solver: String,
    /// MPI ranks of the run.
    pub ranks: usize,
    /// Free dofs (matrix rows) owned by each rank.
    pub rows_per_rank: Vec<usize>,
    /// How the ranks were assembled: `distributed` (each rank its cells
    /// and contact nodes, `crate::solve::share`, added into the
    /// distributed matrix) or `replicated: REASON` (every rank assembles
    /// the whole matrix and inserts its own rows; the reason the model is
    /// not distributed, `crate::solve::share::replicated_reason`).
    pub assembly: String,
    /// Matrix set-ups (preconditioner or factorization built).
    pub setups: usize,
    /// Linear solves.
    pub solves: usize,
    /// Krylov iterations over all solves (1 per solve for a direct solve).
    pub krylov_iterations: usize,
    /// Most Krylov iterations of one solve.
    pub max_krylov_iterations: usize,
    /// Solves CG could not do (an indefinite tangent) and GMRES did; from
    /// the first one on, `solver` names GMRES.
    pub fallbacks: usize,
    /// Why CG gave up at the first fallback (`indefinite matrix` or
    /// `indefinite preconditioner`); empty without a fallback.
    pub fallback_reason: String,
    /// Wall time of matrix insertion + assembly, seconds (this rank).
    pub assembly_seconds: f64,
    /// Wall time of set-ups (factorization / AMG hierarchy), seconds.
    pub setup_seconds: f64,
    /// Wall time of the solves, seconds.
    pub solve_seconds: f64,
    /// Krylov iterations of each solve, one list per tangent set-up (a
    /// Newton iteration: the correction, then, when the engine estimates
    /// the next correction with the same tangent, that solve).
    pub krylov_per_setup: Vec<Vec<usize>>,
    /// Each rank's share: its part of the mesh, its halo (the
    /// communication volume of a matrix-vector product) and its times and
    /// peak memory, gathered at the end of the run.
    pub per_rank: Vec<RankStats>,
}

/// One rank of a distributed run (an entry of
/// [`DistributedStats::per_rank`]).
#[derive(Debug, Clone, Default, PartialEq, serde::Serialize)]
pub struct RankStats {
    /// The rank.
    pub rank: usize,
    /// Cells of its part of the mesh partition (METIS).
    pub cells: usize,
    /// Nodes it owns (their rows are its rows).
    pub owned_nodes: usize,
    /// Ghost nodes: nodes of its cells owned by another rank.
    pub ghost_nodes: usize,
    /// Matrix rows it owns.
    pub rows: usize,
    /// Stored entries of its rows (last sparsity pattern).
    pub nonzeros: usize,
    /// Of those, entries in columns owned by other ranks.
    pub off_rank_nonzeros: usize,
    /// Distinct columns of other ranks its rows touch: the values it
    /// receives in every matrix-vector product (halo size).
    pub halo_columns: usize,
    /// Ranks it receives halo values from.
    pub neighbours: usize,
    /// Element assembly on this rank (the engine's phase), seconds.
    pub assembly_seconds: f64,
    /// Contact search, forces and tangents on this rank, seconds.
    pub contact_seconds: f64,
    /// The tangent handed to PETSc: insertion and set-up (what the serial
    /// run calls factorization), seconds.
    pub tangent_seconds: f64,
    /// Solves (Krylov iterations and the scatter of the solution), seconds.
    pub solve_seconds: f64,
    /// PETSc matrix insertion and assembly alone, seconds.
    pub insertion_seconds: f64,
    /// Preconditioner / factorization set-ups alone, seconds.
    pub setup_seconds: f64,
    /// Peak resident memory of the rank's process (`VmHWM`), bytes.
    pub peak_memory_bytes: u64,
    /// Cells the rank's last element loop evaluated (its `cells` under a
    /// distributed assembly, all cells of the mesh under a replicated one).
    pub assembled_cells: usize,
    /// CPU time of the rank's phases (the thread's run time,
    /// `crate::solve::memory::thread_cpu_seconds`), seconds: element
    /// assembly, contact, tangent hand-over, solves, and the whole process.
    pub assembly_cpu_seconds: f64,
    pub contact_cpu_seconds: f64,
    pub tangent_cpu_seconds: f64,
    pub solve_cpu_seconds: f64,
    pub process_cpu_seconds: f64,
}

/// The Lagrange-multiplier saddle-point system built from the tangent and
/// the constraint rows.
pub trait SaddlePointSystem {
    /// Assembles and factorizes `[K C^T; G 0]` from the free-free block
    /// (`k`, `k_values`), the rows `G` and the columns `C` of
    /// `constraints` (the force per unit multiplier; `C = G` for a
    /// symmetric saddle point), or its condensed form.
    fn factorize(
        &mut self,
        k: &SparsePattern,
        k_values: &[f64],
        constraints: &Constraints,
    ) -> Result<(), LinearError>;
    /// On entry `du = -r_u` and `dl = g`; on exit the corrections.
    fn solve(&self, du: &mut [f64], dl: &mut [f64]) -> Result<(), LinearError>;
    /// Number of constraint rows of the last factorization (`None`: no
    /// factorization at hand).
    fn factorized_rows(&self) -> Option<usize>;
    /// Symbolic and numeric factorizations computed.
    fn counts(&self) -> (usize, usize);
    /// Order and stored entries of the last factorized matrix.
    fn system(&self) -> (usize, usize);
    /// `|A - A^T|_F / |A|_F` of the last factorized matrix, where the
    /// solver measures it (the condensed one).
    fn asymmetry(&self) -> Option<f64> {
        None
    }
}
