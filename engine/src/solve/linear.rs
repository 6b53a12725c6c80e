//! Sparse direct solution of the free-free system with faer.
//!
//! The symbolic factorization (fill-reducing ordering, elimination tree,
//! supernodes) depends only on the pattern, which is fixed for the run: it is
//! computed on the first factorization and reused by every Newton
//! iteration, so each iteration pays one numeric factorization and one
//! triangular solve. Sparse Cholesky (`L L^T`, lower triangle) is tried
//! first; if the tangent is not positive definite (a destabilizing contact
//! tangent, or a body not yet held) the solver switches to sparse LU with
//! partial pivoting (symbolic part also computed once) until
//! [`LinearSolver::prefer_cholesky`] is called (at each new increment).

use super::pattern::SparsePattern;
use faer::linalg::solvers::Solve;
use faer::sparse::linalg::solvers::{Llt, Lu, SymbolicLlt, SymbolicLu};
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};
use faer::{MatMut, Side};

/// Which factorization is in use.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Method {
    /// Sparse Cholesky (symmetric positive definite tangent).
    Cholesky,
    /// Sparse LU (indefinite or unsymmetric tangent).
    Lu,
}

impl Method {
    /// Name used in the run summary.
    pub fn name(self) -> &'static str {
        match self {
            Method::Cholesky => "cholesky",
            Method::Lu => "lu",
        }
    }
}

enum Factor {
    None,
    Llt(Llt<usize, f64>),
    Lu(Box<Lu<usize, f64>>),
}

/// A reusable sparse direct solver for one pattern.
pub struct LinearSolver {
    method: Method,
    /// Successful Cholesky factorizations.
    pub cholesky_count: usize,
    /// Successful LU factorizations.
    pub lu_count: usize,
    symbolic_llt: Option<SymbolicLlt<usize>>,
    symbolic_lu: Option<SymbolicLu<usize>>,
    factor: Factor,
}

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
            lu_count: 0,
            symbolic_llt: None,
            symbolic_lu: None,
            factor: Factor::None,
        }
    }

    /// The factorization in use (after the first call to `factorize`).
    pub fn method(&self) -> Method {
        self.method
    }

    /// Tries Cholesky again at the next factorization (after a switch to LU).
    pub fn prefer_cholesky(&mut self) {
        self.method = Method::Cholesky;
    }

    /// Uses LU at the next factorizations (unsymmetric tangents, e.g. F-bar
    /// elements), until [`LinearSolver::prefer_cholesky`].
    pub fn require_lu(&mut self) {
        self.method = Method::Lu;
    }

    /// Numerically factorizes the matrix with `pattern` and `values` (the
    /// first `pattern.nnz()` entries are used).
    pub fn factorize(&mut self, pattern: &SparsePattern, values: &[f64]) -> Result<(), String> {
        let n = pattern.n;
        self.factor = Factor::None;
        if n == 0 {
            return Ok(());
        }
        let symbolic =
            SymbolicSparseColMatRef::new_checked(n, n, &pattern.col_ptr, None, &pattern.row_idx);
        let mat = SparseColMatRef::new(symbolic, &values[..pattern.nnz()]);
        if self.method == Method::Cholesky {
            if self.symbolic_llt.is_none() {
                self.symbolic_llt = Some(
                    SymbolicLlt::try_new(symbolic, Side::Lower)
                        .map_err(|e| format!("symbolic Cholesky factorization failed: {e:?}"))?,
                );
            }
            let sym = self.symbolic_llt.clone().expect("set above");
            match Llt::try_new_with_symbolic(sym, mat, Side::Lower) {
                Ok(f) => {
                    self.factor = Factor::Llt(f);
                    self.cholesky_count += 1;
                    return Ok(());
                }
                Err(_) => {
                    // not positive definite: LU from now on
                    self.method = Method::Lu;
                }
            }
        }
        if self.symbolic_lu.is_none() {
            self.symbolic_lu = Some(
                SymbolicLu::try_new(symbolic)
                    .map_err(|e| format!("symbolic LU factorization failed: {e:?}"))?,
            );
        }
        let sym = self.symbolic_lu.clone().expect("set above");
        let f = Lu::try_new_with_symbolic(sym, mat).map_err(|e| {
            format!("the stiffness matrix is singular (LU factorization failed: {e:?})")
        })?;
        self.factor = Factor::Lu(Box::new(f));
        self.lu_count += 1;
        Ok(())
    }

    /// Solves `K x = b` in place with the last factorization.
    pub fn solve(&self, rhs: &mut [f64]) {
        let n = rhs.len();
        if n == 0 {
            return;
        }
        let b = MatMut::from_column_major_slice_mut(rhs, n, 1);
        match &self.factor {
            Factor::Llt(f) => f.solve_in_place(b),
            Factor::Lu(f) => f.solve_in_place(b),
            Factor::None => panic!("LinearSolver::solve called before factorize"),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Full-pattern CSC of a dense symmetric matrix.
    fn csc(a: &[[f64; 3]; 3]) -> (SparsePattern, Vec<f64>) {
        let mut col_ptr = vec![0];
        let mut row_idx = vec![];
        let mut vals = vec![];
        for j in 0..3 {
            for (i, row) in a.iter().enumerate() {
                if row[j] != 0.0 {
                    row_idx.push(i);
                    vals.push(row[j]);
                }
            }
            col_ptr.push(row_idx.len());
        }
        (
            SparsePattern {
                n: 3,
                col_ptr,
                row_idx,
            },
            vals,
        )
    }

    fn residual(a: &[[f64; 3]; 3], x: &[f64], b: &[f64]) -> f64 {
        (0..3)
            .map(|i| (a[i][0] * x[0] + a[i][1] * x[1] + a[i][2] * x[2] - b[i]).abs())
            .fold(0.0, f64::max)
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
            s.solve(&mut x);
            let a2 = a.map(|r| r.map(|x| x * scale));
            assert!(residual(&a2, &x, &b) < 1e-14);
        }
        assert_eq!(s.method(), Method::Cholesky);
    }

    #[test]
    fn indefinite_matrix_falls_back_to_lu() {
        let a = [[1.0, 2.0, 0.0], [2.0, 1.0, 0.0], [0.0, 0.0, -3.0]];
        let (p, v) = csc(&a);
        let mut s = LinearSolver::new();
        s.factorize(&p, &v).unwrap();
        assert_eq!(s.method(), Method::Lu);
        assert_eq!((s.cholesky_count, s.lu_count), (0, 1));
        let b = [1.0, -1.0, 2.0];
        let mut x = b;
        s.solve(&mut x);
        assert!(residual(&a, &x, &b) < 1e-14, "{x:?}");
        // back to Cholesky when asked, and it works on an SPD matrix again
        s.prefer_cholesky();
        let spd = [[4.0, 1.0, 0.0], [1.0, 4.0, 0.0], [0.0, 0.0, 3.0]];
        let (_, v2) = csc(&spd);
        s.factorize(&p, &v2).unwrap();
        assert_eq!(s.method(), Method::Cholesky);
        assert_eq!((s.cholesky_count, s.lu_count), (1, 1));
    }

    #[test]
    fn singular_matrix_is_reported() {
        let a = [[1.0, 1.0, 0.0], [1.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
        let (p, v) = csc(&a);
        let mut s = LinearSolver::new();
        // faer's LU accepts the exactly zero pivot: the solution is then
        // non-finite, which the Newton loop reports as a singular system
        s.factorize(&p, &v).unwrap();
        assert_eq!(s.method(), Method::Lu);
        let mut x = [1.0, 0.0, 1.0];
        s.solve(&mut x);
        assert!(x.iter().any(|v| !v.is_finite()), "{x:?}");
    }
}
