//! Sparse direct solution of the free-free system with faer.
//!
//! The symbolic factorization (fill-reducing ordering: AMD, or nested
//! dissection for large patterns when its factor is smaller; elimination tree,
//! supernodes) depends only on the pattern, which is fixed for the run: it is
//! computed on the first factorization and reused by every Newton
//! iteration, so each iteration pays one numeric factorization and one
//! triangular solve. The factor storage and the scratch memory are kept
//! between iterations too.
//!
//! Order of attempts for each matrix:
//! 1. sparse Cholesky `L L^T` (symmetric positive definite tangent);
//! 2. if a pivot is not positive — a destabilizing contact tangent such as
//!    the curvature term of a convex tool at a large trial penetration —
//!    sparse `L D L^T` **on the same symbolic factorization** (no pivoting:
//!    same cost as Cholesky); the number of negative pivots is recorded (it
//!    counts the tangent's negative eigenvalues, like Abaqus' warning);
//! 3. if `L D L^T` meets a zero pivot or produces non-finite values, sparse
//!    LU with partial pivoting (symbolic part also computed once).
//!
//! The first method that worked is tried first at the next factorization;
//! [`LinearSolver::prefer_cholesky`] goes back to Cholesky (each increment).
//!
//! Large tangents that differ from the last factorized one only in the rows
//! and columns of a few dofs (linear-elastic bodies in contact with rigid
//! tools: only the contact blocks change) are solved by a low-rank update
//! of that factorization instead of a new one ([`super::low_rank`]).
//!
//! This is the [`LinearSystem`] of the default build (serial, direct).

use super::low_rank::{LowRank, COLUMN_BATCH};
use super::pattern::SparsePattern;
use super::schur::Schur;
use super::{FactorStats, LinearError, LinearSystem, ZeroMode};
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::cholesky::ldlt::factor::LdltRegularization;
use faer::linalg::cholesky::llt::factor::LltRegularization;
use faer::linalg::solvers::Solve;
use faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, CholeskySymbolicParams, LdltRef, LltRef, SymbolicCholesky,
    SymmetricOrdering,
};
use faer::sparse::linalg::solvers::{Lu, SymbolicLu};
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};
use faer::{Conj, MatMut, Par, Side};

/// Which factorization is in use.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Method {
    /// Sparse Cholesky (symmetric positive definite tangent).
    Cholesky,
    /// Sparse L D L^T without pivoting (symmetric indefinite tangent).
    Ldlt,
    /// Sparse LU (when L D L^T breaks down, or an unsymmetric tangent).
    Lu,
}

impl Method {
    /// Name used in the run summary.
    pub fn name(self) -> &'static str {
        match self {
            Method::Cholesky => "cholesky",
            Method::Ldlt => "ldlt",
            Method::Lu => "lu",
        }
    }
}

/// What the last numeric factorization left behind.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Factor {
    None,
    /// The matrix has no rows (nothing to solve).
    Empty,
    /// `l_values` hold the Cholesky factor.
    Llt,
    /// `l_values` hold the L D L^T factor.
    Ldlt,
    /// `lu` holds the LU factors.
    Lu,
}

/// A reusable sparse direct solver for one pattern.
pub struct LinearSolver {
    method: Method,
    /// Successful Cholesky factorizations.
    pub cholesky_count: usize,
    /// Successful L D L^T factorizations.
    pub ldlt_count: usize,
    /// Successful LU factorizations.
    pub lu_count: usize,
    /// Negative pivots of the last L D L^T factorization (negative
    /// eigenvalues of the tangent); 0 after Cholesky.
    pub negative_pivots: usize,
    /// Largest `negative_pivots` over the run.
    pub max_negative_pivots: usize,
    symbolic: Option<SymbolicCholesky<usize>>,
    l_values: Vec<f64>,
    scratch: Option<MemBuffer>,
    symbolic_lu: Option<SymbolicLu<usize>>,
    lu: Option<Box<Lu<usize, f64>>>,
    factor: Factor,
    /// The zero-energy mode of the last matrix, if it was singular.
    zero_mode: Option<ZeroMode>,
    /// Low-rank updates of the last full factorization ([`LowRank`]).
    low_rank: LowRank,
    /// Whether low-rank updates are used (matrices of at least
    /// `low_rank_min_rows` rows).
    low_rank_enabled: bool,
    low_rank_min_rows: usize,
    /// Tangents solved by a low-rank update instead of a factorization.
    pub low_rank_count: usize,
    /// Wall time of the symbolic analyses, seconds.
    symbolic_seconds: f64,
    /// Free dofs whose rows and columns alone change between tangents
    /// ([`LinearSystem::set_candidates`]).
    candidates: Vec<usize>,
    /// The candidate block ordered last and its Schur complement
    /// ([`super::schur`]), when the symbolic analysis ordered it so.
    schur: Schur,
}

/// Matrices with fewer rows are always factorized in full (a low-rank
/// update pays where a factorization is expensive).
pub const LOW_RANK_MIN_ROWS: usize = 20_000;

impl std::fmt::Debug for LinearSolver {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("LinearSolver")
            .field("method", &self.method)
            .finish()
    }
}

impl Default for LinearSolver {
    fn default() -> Self {
        Self::new()
    }
}

impl LinearSolver {
    /// A solver that will try Cholesky first.
    pub fn new() -> Self {
        LinearSolver {
            method: Method::Cholesky,
            cholesky_count: 0,
            ldlt_count: 0,
            lu_count: 0,
            negative_pivots: 0,
            max_negative_pivots: 0,
            symbolic: None,
            l_values: Vec::new(),
            scratch: None,
            symbolic_lu: None,
            lu: None,
            factor: Factor::None,
            zero_mode: None,
            low_rank: LowRank::default(),
            low_rank_enabled: true,
            low_rank_min_rows: LOW_RANK_MIN_ROWS,
            low_rank_count: 0,
            symbolic_seconds: 0.0,
            candidates: Vec::new(),
            schur: Schur::default(),
        }
    }

    /// With (`true`, the default) or without low-rank updates of the last
    /// factorization (matrices of at least `min_rows` rows).
    pub fn with_low_rank(mut self, enabled: bool, min_rows: usize) -> Self {
        self.low_rank_enabled = enabled;
        self.low_rank_min_rows = min_rows;
        self.low_rank.clear();
        self
    }

    /// The factorization in use (after the first call to `factorize`).
    pub fn method(&self) -> Method {
        self.method
    }

    /// Tries Cholesky again at the next factorization.
    pub fn prefer_cholesky(&mut self) {
        self.method = Method::Cholesky;
    }

    /// Uses LU at the next factorizations (unsymmetric tangents, e.g. F-bar
    /// elements), until [`LinearSolver::prefer_cholesky`].
    pub fn require_lu(&mut self) {
        self.method = Method::Lu;
    }

    /// Forgets the symbolic analyses: the next factorization recomputes them
    /// (the sparsity pattern grew, e.g. new node-to-segment couplings).
    pub fn reset_pattern(&mut self) {
        self.symbolic = None;
        self.l_values.clear();
        self.scratch = None;
        self.symbolic_lu = None;
        self.lu = None;
        self.factor = Factor::None;
        self.low_rank.clear();
        self.schur = Schur::default();
    }

    /// The free dofs whose rows and columns alone change between tangents
    /// (see [`LinearSystem::set_candidates`]): for matrices where low-rank
    /// updates apply, the next symbolic analysis orders them last when
    /// they are at most [`Schur::limit`], and tangents that differ from
    /// the base only in their block are solved with its updated Schur
    /// complement ([`Schur`]).
    pub fn set_candidates(&mut self, dofs: &[usize]) {
        self.candidates = dofs.to_vec();
        self.candidates.sort_unstable();
        self.candidates.dedup();
        self.reset_pattern();
    }

    /// Whether the candidates of a matrix of order `n` are to be ordered
    /// last.
    fn schur_applies(&self, n: usize) -> bool {
        self.low_rank_enabled
            && n >= self.low_rank_min_rows
            && !self.candidates.is_empty()
            && self.candidates.len() <= Schur::limit(n)
            && self.candidates.len() < n
            && self.candidates.iter().all(|&d| d < n)
    }

    /// Numerically factorizes the matrix with `pattern` and `values` (the
    /// first `pattern.nnz()` entries are used; both triangles stored), or
    /// updates the last factorization when only a few dofs' rows and
    /// columns changed ([`LowRank`]).
    pub fn factorize(
        &mut self,
        pattern: &SparsePattern,
        values: &[f64],
    ) -> Result<(), LinearError> {
        let values = &values[..pattern.nnz()];
        self.schur.active = false;
        if self.try_schur(pattern, values) || self.try_low_rank(pattern, values) {
            return Ok(());
        }
        self.low_rank.active = false;
        let r = self.factorize_full(pattern, values);
        let base = matches!(self.factor, Factor::Llt | Factor::Ldlt | Factor::Lu);
        if self.low_rank_enabled
            && pattern.n >= self.low_rank_min_rows
            && r.is_ok()
            && base
            && self.zero_mode.is_none()
        {
            // the factor's size widens the column cache ([`LowRank::limit`]);
            // an LU factor keeps the fixed bound
            let factor_values = match self.factor {
                Factor::Llt | Factor::Ldlt => self.l_values.len(),
                _ => 0,
            };
            self.low_rank.rebase(pattern.n, values, factor_values);
            match (self.factor, self.symbolic.as_ref()) {
                (Factor::Ldlt, Some(sym)) if !self.schur.is_empty() => {
                    self.schur.rebase(sym, &self.l_values);
                }
                _ => self.schur.clear(),
            }
        } else {
            self.low_rank.clear();
            self.schur.clear();
        }
        r
    }

    /// The update of the base's Schur complement for `values` ([`Schur`]),
    /// when the candidates are ordered last, a base is held and `values`
    /// differ from it in the candidate block only; false otherwise.
    fn try_schur(&mut self, pattern: &SparsePattern, values: &[f64]) -> bool {
        if !self.schur.ready
            || self.factor != Factor::Ldlt
            || !self.low_rank.has_base(pattern.n, values.len())
        {
            return false;
        }
        let Some(s) = self.low_rank.changed_dofs(
            &pattern.col_ptr,
            &pattern.row_idx,
            values,
            self.schur.len(),
        ) else {
            return false;
        };
        if !self.schur.update(
            &s,
            &pattern.col_ptr,
            &pattern.row_idx,
            values,
            &self.low_rank.base,
        ) {
            return false;
        }
        self.low_rank.active = false;
        self.zero_mode = None;
        self.low_rank_count += 1;
        true
    }

    /// The low-rank update of the base factorization for `values`, when
    /// one is held, the changed dofs and the cached columns stay within
    /// [`LowRank::limit`] and the update is regular; false otherwise (the
    /// caller factorizes in full).
    fn try_low_rank(&mut self, pattern: &SparsePattern, values: &[f64]) -> bool {
        let n = pattern.n;
        if !self.low_rank_enabled
            || n < self.low_rank_min_rows
            || !self.low_rank.has_base(n, values.len())
            || !matches!(self.factor, Factor::Llt | Factor::Ldlt | Factor::Lu)
        {
            return false;
        }
        let limit = self.low_rank.bound();
        let Some(s) = self
            .low_rank
            .changed_dofs(&pattern.col_ptr, &pattern.row_idx, values, limit)
        else {
            return false;
        };
        let missing = self.low_rank.missing(&s);
        if self.low_rank.cached() + missing.len() > limit {
            return false;
        }
        if !missing.is_empty() {
            let first = self.low_rank.push_unit_columns(&missing);
            let cols = self.low_rank.new_columns(first);
            let solved = match self.factor {
                Factor::Llt | Factor::Ldlt => match self.symbolic.as_ref() {
                    Some(sym) => {
                        solve_columns(
                            sym,
                            &self.l_values,
                            self.factor == Factor::Llt,
                            cols,
                            n,
                            super::super::parallel::threads(),
                        );
                        true
                    }
                    None => false,
                },
                Factor::Lu => match self.lu.as_ref() {
                    Some(lu) => {
                        for batch in cols.chunks_mut(n * COLUMN_BATCH) {
                            let ncols = batch.len() / n;
                            lu.solve_in_place(MatMut::from_column_major_slice_mut(batch, n, ncols));
                        }
                        true
                    }
                    None => false,
                },
                Factor::None | Factor::Empty => false,
            };
            if !solved || !cols.iter().all(|v| v.is_finite()) {
                self.low_rank.drop_columns(first);
                return false;
            }
        }
        if !self
            .low_rank
            .update(s, &pattern.col_ptr, &pattern.row_idx, values)
        {
            return false;
        }
        self.zero_mode = None;
        self.low_rank_count += 1;
        true
    }

    /// Numerically factorizes the matrix with `pattern` and `values` in
    /// full.
    fn factorize_full(
        &mut self,
        pattern: &SparsePattern,
        values: &[f64],
    ) -> Result<(), LinearError> {
        let n = pattern.n;
        self.factor = Factor::None;
        self.zero_mode = None;
        if n == 0 {
            self.factor = Factor::Empty;
            return Ok(());
        }
        let symbolic =
            SymbolicSparseColMatRef::new_checked(n, n, &pattern.col_ptr, None, &pattern.row_idx);
        let mat = SparseColMatRef::new(symbolic, &values[..pattern.nnz()]);
        if self.method != Method::Lu {
            if self.symbolic.is_none() {
                let start = std::time::Instant::now();
                if self.schur_applies(n) {
                    self.schur.set_candidates(n, &self.candidates);
                } else {
                    self.schur = Schur::default();
                }
                let sym = symbolic_cholesky(symbolic, pattern, self.schur.candidates(n));
                self.symbolic_seconds += start.elapsed().as_secs_f64();
                let sym = sym?;
                let req = sym
                    .factorize_numeric_llt_scratch::<f64>(Par::Seq, Default::default())
                    .or(sym.factorize_numeric_ldlt_scratch::<f64>(Par::Seq, Default::default()))
                    .or(sym.solve_in_place_scratch::<f64>(1, Par::Seq));
                self.l_values = vec![0.0; sym.len_val()];
                self.scratch = Some(MemBuffer::new(req));
                self.symbolic = Some(sym);
            }
            let sym = self.symbolic.as_ref().expect("set above");
            let stack = MemStack::new(self.scratch.as_mut().expect("set with the symbolic"));
            // with the candidates last, L D L^T directly: the Schur path
            // needs it, and an indefinite contact block would break
            // Cholesky down at its very end
            if self.method == Method::Cholesky
                && self.schur.is_empty()
                && sym
                    .factorize_numeric_llt(
                        &mut self.l_values,
                        mat,
                        Side::Lower,
                        LltRegularization::default(),
                        Par::Seq,
                        stack,
                        Default::default(),
                    )
                    .is_ok()
                && numerically_regular(sym, &self.l_values, pattern, values)
            {
                self.factor = Factor::Llt;
                self.negative_pivots = 0;
                self.cholesky_count += 1;
                return Ok(());
            }
            // not positive definite: L D L^T on the same symbolic analysis
            let stack = MemStack::new(self.scratch.as_mut().expect("set with the symbolic"));
            let ldlt_ok = sym
                .factorize_numeric_ldlt(
                    &mut self.l_values,
                    mat,
                    Side::Lower,
                    LdltRegularization::default(),
                    Par::Seq,
                    stack,
                    Default::default(),
                )
                .is_ok();
            let (negatives, smallest) = pivot_stats(sym, &self.l_values);
            let largest_diagonal = max_abs_diagonal(pattern, values);
            if ldlt_ok
                && self.l_values.iter().all(|v| v.is_finite())
                && smallest > SINGULAR_PIVOT * largest_diagonal
            {
                self.negative_pivots = negatives;
                self.max_negative_pivots = self.max_negative_pivots.max(self.negative_pivots);
                self.factor = Factor::Ldlt;
                self.method = Method::Ldlt;
                self.ldlt_count += 1;
                return Ok(());
            }
            // a round-off pivot: a singular matrix (a zero-energy mode: kept
            // for the caller, who decides; LU still gives the step a body
            // held by a contact about to close needs), or an indefinite one
            // that needs pivoting (LU below)
            let scratch = self.scratch.as_mut().expect("set with the symbolic");
            self.zero_mode = zero_mode(sym, &self.l_values, pattern, values, scratch);
            self.method = Method::Lu;
        }
        if self.symbolic_lu.is_none() {
            let start = std::time::Instant::now();
            let sym = SymbolicLu::try_new(symbolic);
            self.symbolic_seconds += start.elapsed().as_secs_f64();
            self.symbolic_lu = Some(sym.map_err(|e| {
                LinearError::Symbolic(format!("symbolic LU factorization failed: {e:?}"))
            })?);
        }
        let sym = self.symbolic_lu.clone().expect("set above");
        let f = Lu::try_new_with_symbolic(sym, mat).map_err(|e| {
            LinearError::Singular(format!(
                "the stiffness matrix is singular (LU factorization failed: {e:?})"
            ))
        })?;
        self.lu = Some(Box::new(f));
        self.factor = Factor::Lu;
        self.lu_count += 1;
        Ok(())
    }

    /// Solves `K x = b` in place with the last factorization
    /// ([`LinearError::NotFactorized`] without one).
    pub fn solve(&mut self, rhs: &mut [f64]) -> Result<(), LinearError> {
        if self.schur.active {
            let sym = self.symbolic.as_ref().ok_or(LinearError::NotFactorized)?;
            self.schur.solve(sym, &self.l_values, rhs);
            return Ok(());
        }
        self.solve_base(rhs, 1)?;
        if self.low_rank.active {
            self.low_rank.correct(rhs);
        }
        Ok(())
    }

    /// Solves `K0 X = B` in place for the `ncols` columns of `rhs`
    /// (column-major) with the last full factorization `K0`.
    fn solve_base(&mut self, rhs: &mut [f64], ncols: usize) -> Result<(), LinearError> {
        let n = rhs.len() / ncols.max(1);
        if n == 0 {
            return Ok(());
        }
        let b = MatMut::from_column_major_slice_mut(rhs, n, ncols);
        match self.factor {
            Factor::Llt | Factor::Ldlt => {
                let (Some(sym), Some(scratch)) = (self.symbolic.as_ref(), self.scratch.as_mut())
                else {
                    return Err(LinearError::NotFactorized);
                };
                let mut many = (ncols > 1)
                    .then(|| MemBuffer::new(sym.solve_in_place_scratch::<f64>(ncols, Par::Seq)));
                let stack = MemStack::new(many.as_mut().unwrap_or(scratch));
                if self.factor == Factor::Llt {
                    LltRef::new(sym, &self.l_values).solve_in_place_with_conj(
                        Conj::No,
                        b,
                        Par::Seq,
                        stack,
                    );
                } else {
                    LdltRef::new(sym, &self.l_values).solve_in_place_with_conj(
                        Conj::No,
                        b,
                        Par::Seq,
                        stack,
                    );
                }
            }
            Factor::Lu => match self.lu.as_ref() {
                Some(lu) => lu.solve_in_place(b),
                None => return Err(LinearError::NotFactorized),
            },
            Factor::None | Factor::Empty => return Err(LinearError::NotFactorized),
        }
        Ok(())
    }
}

/// Solves `K0 X = E` in place for the columns of `cols` (column-major,
/// `n` rows) with the Cholesky (`llt`) or `L D L^T` factor `l_values`, in
/// batches of [`COLUMN_BATCH`] columns shared among `threads` threads:
/// each batch is solved as on one thread (the bits do not depend on
/// `threads`).
fn solve_columns(
    sym: &SymbolicCholesky<usize>,
    l_values: &[f64],
    llt: bool,
    cols: &mut [f64],
    n: usize,
    threads: usize,
) {
    let solve = |batches: &mut [f64]| {
        let mut scratch = MemBuffer::new(sym.solve_in_place_scratch::<f64>(COLUMN_BATCH, Par::Seq));
        for batch in batches.chunks_mut(n * COLUMN_BATCH) {
            let b = MatMut::from_column_major_slice_mut(batch, n, batch.len() / n);
            let stack = MemStack::new(&mut scratch);
            if llt {
                LltRef::new(sym, l_values).solve_in_place_with_conj(Conj::No, b, Par::Seq, stack);
            } else {
                LdltRef::new(sym, l_values).solve_in_place_with_conj(Conj::No, b, Par::Seq, stack);
            }
        }
    };
    let batches = cols.len().div_ceil(n * COLUMN_BATCH);
    let parts = threads.clamp(1, batches.max(1));
    if parts == 1 {
        solve(cols);
        return;
    }
    // whole batches per thread
    let per = batches.div_ceil(parts) * n * COLUMN_BATCH;
    std::thread::scope(|scope| {
        let solve = &solve;
        let mut parts = cols.chunks_mut(per);
        let own = parts.next();
        for part in parts {
            scope.spawn(move || solve(part));
        }
        if let Some(part) = own {
            solve(part);
        }
    });
}

impl LinearSystem for LinearSolver {
    fn set_symmetric(&mut self, symmetric: bool) {
        if symmetric {
            self.prefer_cholesky();
        } else {
            self.require_lu();
        }
    }

    fn factorize(&mut self, pattern: &SparsePattern, values: &[f64]) -> Result<(), LinearError> {
        LinearSolver::factorize(self, pattern, values)
    }

    fn solve(&mut self, rhs: &mut [f64]) -> Result<(), LinearError> {
        LinearSolver::solve(self, rhs)
    }

    fn is_factorized(&self) -> bool {
        self.factor != Factor::None
    }

    fn zero_mode(&self) -> Option<&ZeroMode> {
        self.zero_mode.as_ref()
    }

    fn reset_pattern(&mut self) {
        LinearSolver::reset_pattern(self);
    }

    fn set_candidates(&mut self, dofs: &[usize]) {
        LinearSolver::set_candidates(self, dofs);
    }

    fn stats(&self) -> FactorStats {
        FactorStats {
            cholesky: self.cholesky_count,
            ldlt: self.ldlt_count,
            lu: self.lu_count,
            negative_pivots: self.negative_pivots,
            max_negative_pivots: self.max_negative_pivots,
            low_rank: self.low_rank_count,
            factor_nonzeros: self.l_values.len(),
            factor_bytes: self.l_values.len() * std::mem::size_of::<f64>()
                + self.scratch.as_ref().map_or(0, |b| b.len()),
            symbolic_seconds: self.symbolic_seconds,
        }
    }
}

/// Entries of the Cholesky factor `L` of a matrix with `pattern` (both
/// triangles stored), with the ordering a factorization would choose: the
/// symbolic analysis alone, no numeric work (how large a model fits in
/// memory, `ctc bench --solid N --symbolic`).
pub fn factor_nonzeros(pattern: &SparsePattern) -> Result<usize, LinearError> {
    if pattern.n == 0 {
        return Ok(0);
    }
    let symbolic = SymbolicSparseColMatRef::new_checked(
        pattern.n,
        pattern.n,
        &pattern.col_ptr,
        None,
        &pattern.row_idx,
    );
    Ok(symbolic_cholesky(symbolic, pattern, None)?.len_val())
}

/// Patterns with fewer rows are ordered by AMD (see
/// [`prefers_nested_dissection`]).
pub const NESTED_DISSECTION_MIN: usize = 20_000;

/// Stored entries per column from which a large pattern is ordered by
/// nested dissection (`ordering.rs`): 3D meshes (hex8 ~75, tet4 ~45),
/// where its factor is smaller than AMD's; 2D meshes (linear ~14-18,
/// quadratic ~30) keep AMD, whose factor is smaller there.
pub const NESTED_DISSECTION_DENSITY: usize = 40;

/// The symbolic Cholesky factorization of `symbolic` (the pattern
/// `pattern`) with the fill-reducing ordering chosen by
/// [`prefers_nested_dissection`]: AMD, or nested dissection for large 3D
/// patterns (deterministic: the pattern alone decides). With
/// `last`, the dofs marked there are moved to the end of either ordering
/// (the candidate block of [`Schur`]); AMD is then that of the node graph
/// ([`amd_by_blocks`]).
fn symbolic_cholesky(
    symbolic: SymbolicSparseColMatRef<'_, usize>,
    pattern: &SparsePattern,
    last: Option<&[bool]>,
) -> Result<SymbolicCholesky<usize>, LinearError> {
    let failed = |e: faer::sparse::FaerError| {
        LinearError::Symbolic(format!("symbolic Cholesky factorization failed: {e:?}"))
    };
    let custom = |forward: &[usize]| {
        let mut inverse = vec![0; forward.len()];
        for (k, &v) in forward.iter().enumerate() {
            inverse[v] = k;
        }
        let perm = faer::perm::PermRef::new_checked(forward, &inverse, forward.len());
        // the Schur path reads a supernodal factor
        let mut params = CholeskySymbolicParams::default();
        if last.is_some() {
            params.supernodal_flop_ratio_threshold =
                faer::sparse::linalg::SupernodalThreshold::FORCE_SUPERNODAL;
        }
        factorize_symbolic_cholesky(
            symbolic,
            Side::Lower,
            SymmetricOrdering::Custom(perm),
            params,
        )
    };
    let amd = || match last {
        None => factorize_symbolic_cholesky(
            symbolic,
            Side::Lower,
            SymmetricOrdering::Amd,
            CholeskySymbolicParams::default(),
        ),
        Some(last) => {
            // AMD of the node graph (issue 20: a quarter of the entries in
            // 2D; same fill on the tutorial mesh, 4,716,176 entries against
            // 4,716,155 for the dof graph, and half the symbolic time)
            let forward = amd_by_blocks(pattern.n, &pattern.col_ptr, &pattern.row_idx)?;
            custom(&super::schur::candidates_last(&forward, last))
        }
    };
    if !prefers_nested_dissection(pattern) {
        return amd().map_err(failed);
    }
    let forward = super::ordering::nested_dissection(pattern);
    match last {
        None => custom(&forward),
        Some(last) => custom(&super::schur::candidates_last(&forward, last)),
    }
    .map_err(failed)
}

/// faer's AMD order (forward array) of the symmetric pattern (`n`,
/// `col_ptr`, `row_idx`: both triangles, rows sorted).
fn amd_order(
    n: usize,
    col_ptr: &[usize],
    row_idx: &[usize],
) -> Result<Vec<usize>, faer::sparse::FaerError> {
    let sym = SymbolicSparseColMatRef::new_checked(n, n, col_ptr, None, row_idx);
    let (mut forward, mut inverse) = (vec![0usize; n], vec![0usize; n]);
    let mut mem = MemBuffer::try_new(faer::sparse::linalg::amd::order_maybe_unsorted_scratch::<
        usize,
    >(n, row_idx.len()))
    .map_err(|_| faer::sparse::FaerError::OutOfMemory)?;
    faer::sparse::linalg::amd::order_maybe_unsorted(
        &mut forward,
        &mut inverse,
        sym,
        Default::default(),
        MemStack::new(&mut mem),
    )?;
    Ok(forward)
}

/// AMD on the graph of blocks of consecutive columns with the same rows
/// (the dofs of a node: a free dof's column holds the rows of the node's
/// other free dofs), each block expanded in its order (forward array).
/// Any symmetric pattern works: a column unlike its predecessor starts a
/// block of its own.
fn amd_by_blocks(
    n: usize,
    col_ptr: &[usize],
    row_idx: &[usize],
) -> Result<Vec<usize>, faer::sparse::FaerError> {
    let col = |j: usize| &row_idx[col_ptr[j]..col_ptr[j + 1]];
    // block of each column, first column of each block
    let mut block = vec![0usize; n];
    let mut first = Vec::with_capacity(n + 1);
    for (j, b) in block.iter_mut().enumerate() {
        if j == 0 || col(j) != col(j - 1) {
            first.push(j);
        }
        *b = first.len() - 1;
    }
    let nb = first.len();
    first.push(n);
    let mut bptr = Vec::with_capacity(nb + 1);
    let mut brow = Vec::with_capacity(row_idx.len() / 2);
    bptr.push(0);
    for &f in &first[..nb] {
        let start = brow.len();
        for &r in col(f) {
            let rb = block[r];
            if brow.len() == start || brow[brow.len() - 1] != rb {
                brow.push(rb);
            }
        }
        bptr.push(brow.len());
    }
    let order = amd_order(nb, &bptr, &brow)?;
    let mut out = Vec::with_capacity(n);
    for b in order {
        out.extend(first[b]..first[b + 1]);
    }
    Ok(out)
}

/// Whether the fill-reducing ordering of `pattern` is nested dissection
/// rather than AMD: at least [`NESTED_DISSECTION_MIN`] rows and at least
/// [`NESTED_DISSECTION_DENSITY`] stored entries per column (a 3D mesh).
/// One analysis, chosen by the pattern alone (issue 20; factor entries
/// with candidates none, AMD against nested dissection: 2D tutorial mesh,
/// 80,200 rows, 13.9 entries per column, 3.91M vs 8.3M... ; `ctc bench`
/// 2D, 79,806 rows, 17.9 per column, 7.44M vs 9.14M; 3D hex8 blocks of
/// `ctc bench --solid N --symbolic`, 72-75 per column: N = 20 (26,019
/// rows) 24.6M vs 25.4M, N = 26 (56,133) 99.9M vs 74.3M, N = 32 (103,455)
/// 222.6M vs 173.6M).
pub fn prefers_nested_dissection(pattern: &SparsePattern) -> bool {
    pattern.n >= NESTED_DISSECTION_MIN && pattern.nnz() >= NESTED_DISSECTION_DENSITY * pattern.n
}

/// An L D L^T pivot smaller than this times the largest diagonal entry of
/// the matrix means a (numerically) singular tangent — a body not held, a
/// zero-energy mode: without pivoting the factors are then meaningless, and
/// LU with partial pivoting takes over.
const SINGULAR_PIVOT: f64 = 1e-12;

/// Whether a Cholesky factor `L` is numerically regular: a singular
/// tangent (a body not held) can pass `L L^T` with a round-off pivot
/// `L_jj^2 ~ 1e-16 max |K_jj|`, whose solve is meaningless; such a factor
/// is refused like an L D L^T one with a pivot below [`SINGULAR_PIVOT`].
fn numerically_regular(
    sym: &SymbolicCholesky<usize>,
    l_values: &[f64],
    pattern: &SparsePattern,
    values: &[f64],
) -> bool {
    let (_, smallest) = pivot_stats(sym, l_values);
    smallest * smallest > SINGULAR_PIVOT * max_abs_diagonal(pattern, values)
}

/// A mode `v` with `||K v|| <= ZERO_MODE * ||diag(K) v||` certifies that a
/// symmetric matrix is singular (Jacobi-scaled: a stiff penalty beside soft
/// elements is not mistaken for a zero-energy mode, whose ratio is at
/// round-off level, ~1e-14).
pub const ZERO_MODE: f64 = 1e-9;

/// One step of inverse iteration with an `L D L^T` factor that met a
/// round-off pivot: `x = (L D L^T)^-1 b` for a fixed, deterministic `b` is
/// dominated by the mode of the tiny pivot; it is a zero-energy mode of `K`
/// when `||K x|| <= ZERO_MODE ||diag(K) x||` (`None`: no such mode, the
/// matrix needs pivoting instead).
fn zero_mode(
    sym: &SymbolicCholesky<usize>,
    l_values: &[f64],
    pattern: &SparsePattern,
    values: &[f64],
    scratch: &mut MemBuffer,
) -> Option<ZeroMode> {
    let n = pattern.n;
    // refactorized with round-off (or exactly zero) pivots replaced by a
    // tiny positive one (faer's dynamic regularization, the signs of the
    // other pivots kept): the solve then amplifies their modes instead of
    // producing infinities
    let floor = SINGULAR_PIVOT * max_abs_diagonal(pattern, values);
    let signs: Vec<i8> = pivot_slots(sym)
        .into_iter()
        .map(|k| if l_values[k] < -floor { -1 } else { 1 })
        .collect();
    let symbolic =
        SymbolicSparseColMatRef::new_checked(n, n, &pattern.col_ptr, None, &pattern.row_idx);
    let mat = SparseColMatRef::new(symbolic, &values[..pattern.nnz()]);
    let mut regular = vec![0.0; l_values.len()];
    sym.factorize_numeric_ldlt(
        &mut regular,
        mat,
        Side::Lower,
        LdltRegularization {
            dynamic_regularization_signs: Some(&signs),
            dynamic_regularization_delta: floor,
            dynamic_regularization_epsilon: floor,
        },
        Par::Seq,
        MemStack::new(scratch),
        Default::default(),
    )
    .ok()?;
    // fixed pseudo-random right-hand side (Weyl sequence): deterministic
    let mut x: Vec<f64> = (0..n)
        .map(|i| ((i as f64 * 0.618_033_988_749_895).fract() - 0.5) + 1e-3)
        .collect();
    let b = MatMut::from_column_major_slice_mut(&mut x, n, 1);
    LdltRef::new(sym, &regular).solve_in_place_with_conj(
        Conj::No,
        b,
        Par::Seq,
        MemStack::new(scratch),
    );
    let big = x.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    if !big.is_finite() || big == 0.0 {
        return None;
    }
    for v in &mut x {
        *v /= big;
    }
    let mut kx = vec![0.0; n];
    let mut dx2 = 0.0;
    for (j, xj) in x.iter().enumerate() {
        let range = pattern.col_ptr[j]..pattern.col_ptr[j + 1];
        for (&i, k) in pattern.row_idx[range.clone()].iter().zip(&values[range]) {
            kx[i] += k * xj;
            if i == j {
                dx2 += (k * xj).powi(2);
            }
        }
    }
    let kx_norm = kx.iter().map(|v| v * v).sum::<f64>().sqrt();
    let ratio = kx_norm / dx2.sqrt().max(f64::MIN_POSITIVE);
    if ratio.is_nan() || ratio > ZERO_MODE {
        return None;
    }
    let dof = x.iter().position(|v| v.abs() >= 0.99)?;
    let rows = (0..n).filter(|&i| x[i].abs() >= 0.1).collect();
    Some(ZeroMode { dof, rows, ratio })
}

/// Largest |K_jj| of a matrix given by its pattern and values.
fn max_abs_diagonal(pattern: &SparsePattern, values: &[f64]) -> f64 {
    let mut m = 0.0f64;
    for j in 0..pattern.n {
        let range = pattern.col_ptr[j]..pattern.col_ptr[j + 1];
        for (&i, v) in pattern.row_idx[range.clone()].iter().zip(&values[range]) {
            if i == j {
                m = m.max(v.abs());
            }
        }
    }
    m
}

/// Number of negative entries of D and the smallest |D_jj| in an L D L^T
/// factor (see [`pivot_slots`]).
fn pivot_stats(sym: &SymbolicCholesky<usize>, values: &[f64]) -> (usize, f64) {
    let mut count = 0;
    let mut smallest = f64::INFINITY;
    for k in pivot_slots(sym) {
        let d = values[k];
        if d < 0.0 {
            count += 1;
        }
        smallest = smallest.min(d.abs());
    }
    (count, smallest)
}

/// Where D sits in the stored values of an L D L^T factor: on the
/// diagonal of the stored L (unit lower triangular) — first entry of each
/// simplicial column, or the diagonal of each supernode's dense block.
fn pivot_slots(sym: &SymbolicCholesky<usize>) -> Vec<usize> {
    use faer::sparse::linalg::cholesky::SymbolicCholeskyRaw;
    let mut out = Vec::with_capacity(sym.nrows());
    match sym.raw() {
        SymbolicCholeskyRaw::Simplicial(s) => {
            let col_ptr = s.col_ptr();
            out.extend((0..s.nrows()).map(|j| col_ptr[j]));
        }
        SymbolicCholeskyRaw::Supernodal(s) => {
            for k in 0..s.n_supernodes() {
                let begin = s.supernode_begin()[k];
                let end = s.supernode_end()[k];
                let ncols = end - begin;
                let nrows = ncols + (s.col_ptr_for_row_idx()[k + 1] - s.col_ptr_for_row_idx()[k]);
                let start = s.col_ptr_for_val()[k];
                out.extend((0..ncols).map(|j| start + j * nrows + j));
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Full-pattern CSC of a dense symmetric matrix.
    fn csc(a: &[[f64; 3]; 3]) -> (SparsePattern, Vec<f64>) {
        super::super::pattern::dense_to_csc(a, false)
    }

    fn residual(a: &[[f64; 3]; 3], x: &[f64], b: &[f64]) -> f64 {
        (0..3)
            .map(|i| (a[i][0] * x[0] + a[i][1] * x[1] + a[i][2] * x[2] - b[i]).abs())
            .fold(0.0, f64::max)
    }

    #[test]
    fn symbolic_factor_size_is_the_numeric_one() {
        let a = [[4.0, 1.0, 0.0], [1.0, 3.0, 1.0], [0.0, 1.0, 2.0]];
        let (p, v) = csc(&a);
        let mut s = LinearSolver::new();
        s.factorize(&p, &v).unwrap();
        assert_eq!(super::factor_nonzeros(&p).unwrap(), s.l_values.len());
        assert_eq!(s.l_values.len(), 5);
    }

    #[test]
    fn cholesky_solves_spd_and_reuses_symbolic() {
        let a = [[4.0, -1.0, 0.0], [-1.0, 4.0, -1.0], [0.0, -1.0, 4.0]];
        let (p, v) = csc(&a);
        let mut s = LinearSolver::new();
        for scale in [1.0, 3.0] {
            let v: Vec<f64> = v.iter().map(|x| x * scale).collect();
            s.factorize(&p, &v).unwrap();
            let b = [1.0, 2.0, 3.0];
            let mut x = b;
            s.solve(&mut x).unwrap();
            let a2 = a.map(|r| r.map(|x| x * scale));
            assert!(residual(&a2, &x, &b) < 1e-14);
        }
        assert_eq!(s.method(), Method::Cholesky);
    }

    #[test]
    fn singular_matrix_passing_cholesky_by_round_off_goes_to_lu() {
        // a 2-spring chain held nowhere, perturbed so that the last pivot is
        // a positive round-off number: Cholesky would succeed
        let k = 1e3;
        let a = [
            [k, -k, 0.0],
            [-k, 2.0 * k, -k],
            [0.0, -k, k * (1.0 + 1e-15)],
        ];
        let (p, v) = csc(&a);
        let mut s = LinearSolver::new();
        let r = s.factorize(&p, &v);
        assert_eq!(s.cholesky_count, 0, "{r:?}");
        assert_ne!(s.method(), Method::Cholesky);
        // the zero-energy mode (1, 1, 1) is found: every dof, the first named
        let m = s.zero_mode.clone().expect("a zero-energy mode");
        assert_eq!((m.dof, m.rows), (0, vec![0, 1, 2]));
        assert!(m.ratio < 1e-10, "{}", m.ratio);
    }

    #[test]
    fn indefinite_matrix_uses_ldlt_and_counts_negative_eigenvalues() {
        // eigenvalues 3, -1, -3: two negative pivots whatever the ordering
        let a = [[1.0, 2.0, 0.0], [2.0, 1.0, 0.0], [0.0, 0.0, -3.0]];
        let (p, v) = csc(&a);
        let mut s = LinearSolver::new();
        s.factorize(&p, &v).unwrap();
        assert_eq!(s.method(), Method::Ldlt);
        assert_eq!((s.cholesky_count, s.ldlt_count, s.lu_count), (0, 1, 0));
        assert_eq!(s.negative_pivots, 2);
        let b = [1.0, -1.0, 2.0];
        let mut x = b;
        s.solve(&mut x).unwrap();
        assert!(residual(&a, &x, &b) < 1e-14, "{x:?}");
        // back to Cholesky when asked, and it works on an SPD matrix again
        s.prefer_cholesky();
        let spd = [[4.0, 1.0, 0.0], [1.0, 4.0, 0.0], [0.0, 0.0, 3.0]];
        let (_, v2) = csc(&spd);
        s.factorize(&p, &v2).unwrap();
        assert_eq!(s.method(), Method::Cholesky);
        assert_eq!((s.cholesky_count, s.ldlt_count, s.lu_count), (1, 1, 0));
        assert_eq!(s.negative_pivots, 0);
        assert_eq!(s.max_negative_pivots, 2);
    }

    #[test]
    fn zero_pivot_without_pivoting_falls_back_to_lu() {
        // L D L^T without pivoting meets a zero pivot; LU pivots it away
        let a = [[0.0, 1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]];
        let (p, v) = csc_with_diagonal(&a);
        let mut s = LinearSolver::new();
        s.factorize(&p, &v).unwrap();
        assert_eq!(s.method(), Method::Lu);
        assert_eq!(s.lu_count, 1);
        let b = [1.0, -1.0, 2.0];
        let mut x = b;
        s.solve(&mut x).unwrap();
        assert!(residual(&a, &x, &b) < 1e-14, "{x:?}");
    }

    /// Like [`csc`] but keeps explicit zeros on the diagonal (the engine's
    /// pattern always has the diagonal).
    fn csc_with_diagonal(a: &[[f64; 3]; 3]) -> (SparsePattern, Vec<f64>) {
        super::super::pattern::dense_to_csc(a, true)
    }

    #[test]
    fn singular_matrix_is_reported_with_its_zero_energy_mode() {
        // an exactly zero pivot: mode (1, -1, 0)
        let a = [[1.0, 1.0, 0.0], [1.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
        let (p, v) = csc(&a);
        let mut s = LinearSolver::new();
        // LU still factorizes (an exact zero pivot: a non-finite solution,
        // which the Newton loop reports), the mode is kept for the caller
        s.factorize(&p, &v).unwrap();
        assert_eq!(s.method(), Method::Lu);
        let m = s.zero_mode.clone().expect("a zero-energy mode");
        assert_eq!((m.dof, m.rows.clone()), (0, vec![0, 1]));
        // a regular matrix clears it
        let spd = [[4.0, 1.0, 0.0], [1.0, 4.0, 0.0], [0.0, 0.0, 3.0]];
        let (p2, v2) = csc(&spd);
        s.prefer_cholesky();
        s.factorize(&p2, &v2).unwrap();
        assert!(s.zero_mode.is_none());
        // a regular but badly scaled matrix (pivot 1e-14 of the largest
        // diagonal: refused by Cholesky and L D L^T) is not mistaken for a
        // singular one: its "mode" e_3 has ||K v|| = ||diag(K) v||
        let k = 1e12;
        let a = [[k, 0.0, 0.0], [0.0, k, 1.0], [0.0, 1.0, 1e-2]];
        let (p, v) = csc(&a);
        let mut s = LinearSolver::new();
        s.factorize(&p, &v).unwrap();
        assert!(s.zero_mode.is_none());
        let b = [1.0, 1.0, 1.0];
        let mut x = b;
        s.solve(&mut x).unwrap();
        assert!(residual(&a, &x, &b) < 1e-3, "{x:?}");
    }
}

#[cfg(test)]
mod low_rank_tests {
    use super::*;

    /// A 2-dof-per-node grid "stiffness": a 5-point Laplacian per
    /// component plus a coupling between the components, held by a
    /// diagonal shift (SPD), as a full CSC pattern.
    fn grid(nx: usize) -> (SparsePattern, Vec<f64>) {
        let nodes = nx * nx;
        let n = 2 * nodes;
        let mut cols: Vec<Vec<(usize, f64)>> = vec![Vec::new(); n];
        let node = |i: usize, j: usize| i * nx + j;
        for i in 0..nx {
            for j in 0..nx {
                let a = node(i, j);
                for c in 0..2 {
                    let d = 2 * a + c;
                    cols[d].push((d, 4.2));
                    cols[d].push((2 * a + 1 - c, 0.3));
                    for (di, dj) in [(0i64, 1i64), (1, 0), (0, -1), (-1, 0)] {
                        let (ii, jj) = (i as i64 + di, j as i64 + dj);
                        if ii >= 0 && jj >= 0 && (ii as usize) < nx && (jj as usize) < nx {
                            cols[d].push((2 * node(ii as usize, jj as usize) + c, -1.0));
                        }
                    }
                }
            }
        }
        let mut col_ptr = vec![0];
        let (mut row_idx, mut values) = (Vec::new(), Vec::new());
        for mut c in cols {
            c.sort_by_key(|e| e.0);
            for (r, v) in c {
                row_idx.push(r);
                values.push(v);
            }
            col_ptr.push(row_idx.len());
        }
        (
            SparsePattern {
                n,
                col_ptr,
                row_idx,
            },
            values,
        )
    }

    /// Adds `k n n^T` (plus `k2` on the diagonal) to the 2x2 block of each
    /// of `nodes`.
    fn contact(p: &SparsePattern, v: &mut [f64], nodes: &[usize], k: f64, k2: f64) {
        for (m, &a) in nodes.iter().enumerate() {
            let t = 0.3 * m as f64;
            let nrm = [t.sin(), t.cos()];
            for (r, nr) in nrm.iter().enumerate() {
                for (c, nc) in nrm.iter().enumerate() {
                    let slot = p.find(2 * a + r, 2 * a + c).unwrap();
                    v[slot] += k * nr * nc + if r == c { k2 } else { 0.0 };
                }
            }
        }
    }

    fn full_solution(p: &SparsePattern, v: &[f64], b: &[f64]) -> Vec<f64> {
        let mut s = LinearSolver::new().with_low_rank(false, 0);
        s.factorize(p, v).unwrap();
        let mut x = b.to_vec();
        s.solve(&mut x).unwrap();
        x
    }

    fn rel_diff(a: &[f64], b: &[f64]) -> f64 {
        let d = a.iter().zip(b).map(|(x, y)| (x - y).powi(2)).sum::<f64>();
        let n = b.iter().map(|y| y * y).sum::<f64>();
        (d / n).sqrt()
    }

    /// The Woodbury update of a factorized base against a full
    /// factorization of the updated matrix (issue 20): equal to 1e-10,
    /// through successive contact states (stiff penalty blocks, nodes
    /// added and released, an indefinite curvature term), without any new
    /// factorization; an update of every entry is factorized in full.
    #[test]
    fn low_rank_update_matches_the_full_factorization() {
        let (p, base) = grid(12);
        let n = p.n;
        let b: Vec<f64> = (0..n).map(|i| ((i * 7 % 13) as f64 - 6.0) / 6.0).collect();
        let mut s = LinearSolver::new().with_low_rank(true, 0);
        s.factorize(&p, &base).unwrap();
        assert_eq!((s.cholesky_count, s.low_rank_count), (1, 0));
        let states: [(&[usize], f64, f64); 4] = [
            (&[60, 61, 62], 1e4, 0.0),
            (&[59, 60, 61, 62, 63], 1e4, 0.0),
            (&[61, 62], 1e6, 0.0),
            // a destabilizing curvature term: indefinite blocks
            (&[60, 61, 62], 1e4, -5.0),
        ];
        for (k, (nodes, pen, curv)) in states.iter().enumerate() {
            let mut v = base.clone();
            contact(&p, &mut v, nodes, *pen, *curv);
            s.factorize(&p, &v).unwrap();
            assert_eq!(s.low_rank_count, k + 1, "state {k}: a low-rank update");
            let mut x = b.clone();
            s.solve(&mut x).unwrap();
            let e = rel_diff(&x, &full_solution(&p, &v, &b));
            assert!(e < 1e-10, "state {k}: {e:e}");
        }
        assert_eq!(s.cholesky_count + s.ldlt_count + s.lu_count, 1);
        // back to the base itself: an empty update
        s.factorize(&p, &base).unwrap();
        let mut x = b.clone();
        s.solve(&mut x).unwrap();
        assert!(rel_diff(&x, &full_solution(&p, &base, &b)) < 1e-12);
        // every entry changed (a nonlinear material): a full factorization
        let scaled: Vec<f64> = base.iter().map(|x| 1.1 * x).collect();
        s.factorize(&p, &scaled).unwrap();
        assert_eq!(s.cholesky_count, 2);
        let mut x = b.clone();
        s.solve(&mut x).unwrap();
        assert!(rel_diff(&x, &full_solution(&p, &scaled, &b)) < 1e-12);
    }

    /// The columns `K0^{-1} e_j` (several batches) and the update `Z y`
    /// are the same bits on 1, 2 and 3 threads (issue 20), and the columns
    /// are the inverse's.
    #[test]
    fn threads_do_not_change_the_low_rank_bits() {
        let (p, base) = grid(20);
        let n = p.n;
        let mut s = LinearSolver::new().with_low_rank(true, 0);
        s.factorize(&p, &base).unwrap();
        let sym = s.symbolic.as_ref().unwrap();
        // 77 distinct dofs: five batches, the last one partial
        let dofs: Vec<usize> = (0..5 * COLUMN_BATCH - 3).map(|k| (7 * k) % n).collect();
        let columns = |threads: usize| {
            let mut cols = vec![0.0; n * dofs.len()];
            for (c, &d) in dofs.iter().enumerate() {
                cols[c * n + d] = 1.0;
            }
            solve_columns(
                sym,
                &s.l_values,
                s.factor == Factor::Llt,
                &mut cols,
                n,
                threads,
            );
            cols
        };
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        let one = columns(1);
        assert!(bits(&columns(2)) == bits(&one));
        assert!(bits(&columns(3)) == bits(&one));
        for (c, &d) in dofs.iter().enumerate().step_by(19) {
            let mut e = vec![0.0; n];
            e[d] = 1.0;
            let exact = full_solution(&p, &base, &e);
            assert!(
                rel_diff(&one[c * n..(c + 1) * n], &exact) < 1e-12,
                "column {d}"
            );
        }
        // an update of 25 nodes (50 dofs), Z y on 1, 2 and 3 threads
        let nodes: Vec<usize> = (150..175).collect();
        let mut v = base.clone();
        contact(&p, &mut v, &nodes, 1e4, 0.0);
        s.factorize(&p, &v).unwrap();
        assert_eq!(s.low_rank_count, 1);
        let b: Vec<f64> = (0..n).map(|i| ((i * 5 % 11) as f64 - 5.0) / 5.0).collect();
        let mut x0 = b.clone();
        s.solve_base(&mut x0, 1).unwrap();
        let update = |parts: usize| {
            let mut x = x0.clone();
            s.low_rank.correct_parts(&mut x, parts);
            x
        };
        let serial = update(1);
        assert!(bits(&update(2)) == bits(&serial));
        assert!(bits(&update(3)) == bits(&serial));
        assert!(rel_diff(&serial, &full_solution(&p, &v, &b)) < 1e-10);
    }

    /// The candidate block ordered last and its updated Schur complement
    /// (issue 20) against a full factorization of each updated matrix:
    /// equal to 1e-10 through the contact states of the Woodbury test,
    /// without a new factorization and without a column of `K0^{-1}`; a
    /// change outside the candidates leaves the Schur path (a Woodbury
    /// update); the candidates are the last positions of the ordering.
    #[test]
    fn schur_complement_update_matches_the_full_factorization() {
        let (p, base) = grid(30);
        let n = p.n;
        let b: Vec<f64> = (0..n).map(|i| ((i * 7 % 13) as f64 - 6.0) / 6.0).collect();
        // the dofs of a row of nodes, as a contact surface
        let surface: Vec<usize> = (450..480).collect();
        let candidates: Vec<usize> = surface.iter().flat_map(|&a| [2 * a, 2 * a + 1]).collect();
        let mut s = LinearSolver::new().with_low_rank(true, 0);
        s.set_candidates(&candidates);
        s.factorize(&p, &base).unwrap();
        assert!(s.schur.ready && s.schur.active, "a Schur base");
        assert_eq!((s.ldlt_count, s.low_rank_count), (1, 0));
        let sym = s.symbolic.as_ref().unwrap();
        let forward = sym.perm().unwrap().arrays().0;
        let mut last = forward[n - candidates.len()..].to_vec();
        last.sort_unstable();
        assert_eq!(last, candidates);
        // the base itself through the Schur path
        let mut x = b.clone();
        s.solve(&mut x).unwrap();
        let e = rel_diff(&x, &full_solution(&p, &base, &b));
        assert!(e < 1e-12, "base: {e:e}");
        let states: [(&[usize], f64, f64); 4] = [
            (&[460, 461, 462], 1e4, 0.0),
            (&[459, 460, 461, 462, 463], 1e4, 0.0),
            (&[461, 462], 1e6, 0.0),
            (&[460, 461, 462], 1e4, -5.0),
        ];
        for (k, (nodes, pen, curv)) in states.iter().enumerate() {
            let mut v = base.clone();
            contact(&p, &mut v, nodes, *pen, *curv);
            s.factorize(&p, &v).unwrap();
            assert_eq!(s.low_rank_count, k + 1, "state {k}: an update");
            assert!(s.schur.active, "state {k}: the Schur path");
            let mut x = b.clone();
            s.solve(&mut x).unwrap();
            let e = rel_diff(&x, &full_solution(&p, &v, &b));
            assert!(e < 1e-10, "state {k}: {e:e}");
        }
        assert_eq!(s.cholesky_count + s.ldlt_count + s.lu_count, 1);
        assert_eq!(s.low_rank.cached(), 0, "no column of K0^-1");
        // a node outside the candidates: not the Schur path
        let mut v = base.clone();
        contact(&p, &mut v, &[100], 1e4, 0.0);
        s.factorize(&p, &v).unwrap();
        assert!(!s.schur.active);
        let mut x = b.clone();
        s.solve(&mut x).unwrap();
        assert!(rel_diff(&x, &full_solution(&p, &v, &b)) < 1e-10);
    }

    /// The node-graph AMD of the Schur path: each node's two dofs stay
    /// together and in their order, the order is a permutation, and a
    /// column unlike its neighbour (the dof grid of [`grid`], whose two
    /// components do not couple across nodes) is a block of its own.
    #[test]
    fn node_graph_amd_keeps_each_nodes_dofs_together() {
        let nx = 12;
        let node = |i: usize, j: usize| i * nx + j;
        let mut cols: Vec<Vec<usize>> = vec![Vec::new(); 2 * nx * nx];
        for i in 0..nx {
            for j in 0..nx {
                let a = node(i, j);
                for (di, dj) in [(0i64, 0i64), (0, 1), (1, 0), (0, -1), (-1, 0), (1, 1)] {
                    let (ii, jj) = (i as i64 + di, j as i64 + dj);
                    if ii >= 0 && jj >= 0 && (ii as usize) < nx && (jj as usize) < nx {
                        let b = node(ii as usize, jj as usize);
                        for c in 0..2 {
                            for e in 0..2 {
                                cols[2 * a + c].push(2 * b + e);
                                cols[2 * b + e].push(2 * a + c);
                            }
                        }
                    }
                }
            }
        }
        let mut col_ptr = vec![0];
        let mut row_idx = Vec::new();
        for mut c in cols {
            c.sort_unstable();
            c.dedup();
            row_idx.extend(c);
            col_ptr.push(row_idx.len());
        }
        let n = 2 * nx * nx;
        let order = amd_by_blocks(n, &col_ptr, &row_idx).unwrap();
        let mut seen = order.clone();
        seen.sort_unstable();
        assert_eq!(seen, (0..n).collect::<Vec<_>>(), "a permutation");
        for pair in order.chunks(2) {
            assert!(pair[0] % 2 == 0 && pair[1] == pair[0] + 1, "{pair:?}");
        }
        // the dof grid: no two consecutive columns alike, the plain order
        let (p, _) = grid(8);
        let by_blocks = amd_by_blocks(p.n, &p.col_ptr, &p.row_idx).unwrap();
        assert_eq!(by_blocks, amd_order(p.n, &p.col_ptr, &p.row_idx).unwrap());
    }

    /// Below the size threshold (and when disabled) every tangent is
    /// factorized: the general path is unchanged.
    #[test]
    fn small_matrices_are_always_factorized() {
        let (p, base) = grid(6);
        let mut s = LinearSolver::new();
        s.factorize(&p, &base).unwrap();
        let mut v = base.clone();
        contact(&p, &mut v, &[10, 11], 1e4, 0.0);
        s.factorize(&p, &v).unwrap();
        assert_eq!((s.cholesky_count, s.low_rank_count), (2, 0));
    }
}
