//! Sparse direct solution of the Lagrange-multiplier saddle-point system
//! (seed slides, "Part II – Lagrange multipliers").
//!
//! Unknowns: the free displacement correction `du` and one multiplier
//! correction `dlambda` per active constraint. With `G` the constraint rows
//! (`G = -d g / d u` on the free dofs, so that the system is symmetric):
//!
//! `[K  G^T; G  0] [du; dlambda] = [-r_u; g]`
//!
//! (with a separate column `C` where the force per unit multiplier is not
//! the constraint's gradient, `[K C^T; G 0]`: mortar rows, whose force
//! holds `D`, `M` and the normal fixed while the row is the gap's full
//! derivative; Single only, LU does not need the symmetry)
//!
//! - [`LagrangeFormulation::Single`]: the matrix above, factorized by sparse
//!   LU with partial pivoting (the zero block makes it indefinite, Cholesky
//!   does not apply).
//! - [`LagrangeFormulation::Doubled`]: the seed's doubled multipliers
//!   (energy `1/2 q^T K q - q^T F - 1/2 (lambda1 - lambda2)^2 +
//!   (lambda1 + lambda2)^T (A q - b)`), unknowns ordered `lambda1, q,
//!   lambda2`:
//!
//!   `[-I  G  I; G^T  K  G^T; I  G  -I] [dl1; du; dl2] = [g; -r_u; g]`,
//!   `dlambda = dl1 + dl2` (the two rows give `G du = g`, `dl1 = dl2`).
//!
//!   Eliminating `lambda1` first gives the pivots `-1`, then `K + G^T G`
//!   (positive definite when `K` is), then `-4 G (K + G^T G)^-1 G^T`
//!   (negative definite): a symmetric `L D L^T` factorization exists
//!   WITHOUT any pivoting. faer's sparse `L D L^T` is used with the
//!   fill-reducing ordering disabled (`SymmetricOrdering::Identity`), the
//!   matrix being assembled directly in the order `lambda1, q, lambda2`
//!   (`q` in the free-dof numbering, node order): the elimination order is
//!   exactly the seed's, no regularization, no pivoting.
//!
//! The pattern is free-free + one row/column per active constraint (two for
//! the doubled form). It is rebuilt at each factorization (O(nnz)) and
//! compared with the previous one: the symbolic factorization is reused
//! while it is unchanged (same active set), recomputed otherwise.

use super::pattern::SparsePattern;
use super::{LinearError, SaddlePointSystem};
use crate::model::LagrangeFormulation;
use crate::solve::constraints::ConstraintRows;
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::cholesky::ldlt::factor::LdltRegularization;
use faer::linalg::solvers::Solve;
use faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, CholeskySymbolicParams, LdltRef, SymbolicCholesky,
    SymmetricOrdering,
};
use faer::sparse::linalg::solvers::{Lu, SymbolicLu};
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};
use faer::{Conj, MatMut, Par, Side};

enum Factor {
    None,
    Lu(Box<Lu<usize, f64>>),
    Ldlt(Vec<f64>),
}

/// Reusable sparse solver of the saddle-point system.
pub struct SaddleSolver {
    formulation: LagrangeFormulation,
    pattern: SparsePattern,
    values: Vec<f64>,
    n_free: usize,
    m: usize,
    symbolic_lu: Option<SymbolicLu<usize>>,
    symbolic_ldlt: Option<SymbolicCholesky<usize>>,
    factor: Factor,
    /// Symbolic factorizations computed (one per distinct active set).
    pub symbolic_count: usize,
    /// Numeric factorizations computed.
    pub numeric_count: usize,
}

impl std::fmt::Debug for SaddleSolver {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("SaddleSolver")
            .field("formulation", &self.formulation)
            .field("n_free", &self.n_free)
            .field("constraints", &self.m)
            .finish()
    }
}

impl SaddleSolver {
    /// A solver for `formulation` (`Condensed` factorizes the saddle point
    /// as `Single`: it is [`super::condensed::CondensedSolver`]'s fallback).
    pub fn new(formulation: LagrangeFormulation) -> Self {
        SaddleSolver {
            formulation,
            pattern: SparsePattern {
                n: 0,
                col_ptr: vec![0],
                row_idx: vec![],
            },
            values: Vec::new(),
            n_free: 0,
            m: 0,
            symbolic_lu: None,
            symbolic_ldlt: None,
            factor: Factor::None,
            symbolic_count: 0,
            numeric_count: 0,
        }
    }

    /// Number of constraints of the last factorization.
    pub fn constraints(&self) -> usize {
        self.m
    }

    /// Assembles the saddle-point matrix from the free-free block
    /// (`k`, `k_values`) and the constraint rows, in the formulation's order.
    fn assemble(
        &mut self,
        k: &SparsePattern,
        k_values: &[f64],
        rows: &ConstraintRows,
        columns: &ConstraintRows,
    ) {
        let n = k.n;
        let m = rows.len();
        // per free dof: constraints touching it (k ascending)
        let mut touching: Vec<Vec<(usize, f64)>> = vec![Vec::new(); n];
        for (c, row) in rows.iter().enumerate() {
            for &(dof, coef) in row {
                touching[dof].push((c, coef));
            }
        }
        let mut col_ptr = vec![0usize];
        let mut row_idx = Vec::new();
        let mut values = Vec::new();
        let push = |r: usize, v: f64, row_idx: &mut Vec<usize>, values: &mut Vec<f64>| {
            row_idx.push(r);
            values.push(v);
        };
        let k_col = |j: usize| k.col_ptr[j]..k.col_ptr[j + 1];
        match self.formulation {
            LagrangeFormulation::Single | LagrangeFormulation::Condensed => {
                // order: q (0..n), lambda (n..n+m)
                for (j, touch) in touching.iter().enumerate() {
                    for s in k_col(j) {
                        push(k.row_idx[s], k_values[s], &mut row_idx, &mut values);
                    }
                    for &(c, coef) in touch {
                        push(n + c, coef, &mut row_idx, &mut values);
                    }
                    col_ptr.push(row_idx.len());
                }
                for column in columns.iter() {
                    for &(dof, coef) in column {
                        push(dof, coef, &mut row_idx, &mut values);
                    }
                    col_ptr.push(row_idx.len());
                }
            }
            LagrangeFormulation::Doubled => {
                // order: lambda1 (0..m), q (m..m+n), lambda2 (m+n..m+n+m)
                let l2 = m + n;
                let lambda_col = |c: usize,
                                  diag: usize,
                                  other: usize,
                                  row_idx: &mut Vec<usize>,
                                  values: &mut Vec<f64>| {
                    let first = diag.min(other);
                    let (v_first, v_second) = if first == diag {
                        (-1.0, 1.0)
                    } else {
                        (1.0, -1.0)
                    };
                    row_idx.push(first);
                    values.push(v_first);
                    for &(dof, coef) in rows.row(c) {
                        row_idx.push(m + dof);
                        values.push(coef);
                    }
                    row_idx.push(diag.max(other));
                    values.push(v_second);
                };
                for c in 0..m {
                    lambda_col(c, c, l2 + c, &mut row_idx, &mut values);
                    col_ptr.push(row_idx.len());
                }
                for (j, touch) in touching.iter().enumerate() {
                    for &(c, coef) in touch {
                        push(c, coef, &mut row_idx, &mut values);
                    }
                    for s in k_col(j) {
                        push(m + k.row_idx[s], k_values[s], &mut row_idx, &mut values);
                    }
                    for &(c, coef) in touch {
                        push(l2 + c, coef, &mut row_idx, &mut values);
                    }
                    col_ptr.push(row_idx.len());
                }
                for c in 0..m {
                    lambda_col(c, l2 + c, c, &mut row_idx, &mut values);
                    col_ptr.push(row_idx.len());
                }
            }
        }
        let total = match self.formulation {
            LagrangeFormulation::Single | LagrangeFormulation::Condensed => n + m,
            LagrangeFormulation::Doubled => n + 2 * m,
        };
        let pattern = SparsePattern {
            n: total,
            col_ptr,
            row_idx,
        };
        if pattern != self.pattern {
            self.symbolic_lu = None;
            self.symbolic_ldlt = None;
            self.pattern = pattern;
        }
        self.values = values;
        self.n_free = n;
        self.m = m;
    }

    /// Assembles and factorizes the saddle-point matrix of the free-free
    /// block `k` (values `k_values`, first `k.nnz()` used), `rows` (`G`)
    /// and `columns` (`C`, the multipliers' force columns; the doubled
    /// form needs `C = G`).
    pub fn factorize(
        &mut self,
        k: &SparsePattern,
        k_values: &[f64],
        rows: &ConstraintRows,
        columns: &ConstraintRows,
    ) -> Result<(), LinearError> {
        self.factor = Factor::None;
        if self.formulation == LagrangeFormulation::Doubled && rows != columns {
            return Err(LinearError::Singular(
                "the doubled Lagrange multipliers need a symmetric saddle point (a constraint \
                 whose force is not its gradient: use `formulation = single`)"
                    .into(),
            ));
        }
        self.assemble(k, &k_values[..k.nnz()], rows, columns);
        let p = &self.pattern;
        if p.n == 0 {
            return Ok(());
        }
        let symbolic = SymbolicSparseColMatRef::new_checked(p.n, p.n, &p.col_ptr, None, &p.row_idx);
        let mat = SparseColMatRef::new(symbolic, &self.values);
        match self.formulation {
            LagrangeFormulation::Single | LagrangeFormulation::Condensed => {
                if self.symbolic_lu.is_none() {
                    self.symbolic_lu = Some(SymbolicLu::try_new(symbolic).map_err(|e| {
                        LinearError::Symbolic(format!(
                            "symbolic LU of the saddle-point system failed: {e:?}"
                        ))
                    })?);
                    self.symbolic_count += 1;
                }
                let sym = self.symbolic_lu.clone().expect("set above");
                let f = Lu::try_new_with_symbolic(sym, mat).map_err(|e| {
                    LinearError::Singular(format!(
                        "the saddle-point system is singular (LU failed: {e:?})"
                    ))
                })?;
                self.factor = Factor::Lu(Box::new(f));
            }
            LagrangeFormulation::Doubled => {
                // with the identity ordering faer's symbolic analysis reads
                // the upper triangle whatever the side: pass exactly the
                // upper triangle (diagonal included) and `Side::Upper`
                let (lp, lr, lv) = upper_triangle(p, &self.values);
                let symbolic = SymbolicSparseColMatRef::new_checked(p.n, p.n, &lp, None, &lr);
                let mat = SparseColMatRef::new(symbolic, &lv);
                if self.symbolic_ldlt.is_none() {
                    self.symbolic_ldlt = Some(
                        factorize_symbolic_cholesky(
                            symbolic,
                            Side::Upper,
                            SymmetricOrdering::Identity,
                            CholeskySymbolicParams::default(),
                        )
                        .map_err(|e| {
                            LinearError::Symbolic(format!(
                                "symbolic LDL^T of the doubled system failed: {e:?}"
                            ))
                        })?,
                    );
                    self.symbolic_count += 1;
                }
                let sym = self.symbolic_ldlt.as_ref().expect("set above");
                let mut l_values = vec![0.0; sym.len_val()];
                let mut buf = MemBuffer::new(
                    sym.factorize_numeric_ldlt_scratch::<f64>(Par::Seq, Default::default()),
                );
                sym.factorize_numeric_ldlt(
                    &mut l_values,
                    mat,
                    Side::Upper,
                    LdltRegularization::default(),
                    Par::Seq,
                    MemStack::new(&mut buf),
                    Default::default(),
                )
                .map_err(|e| {
                    LinearError::Singular(format!(
                        "LDL^T of the doubled saddle-point system failed: {e:?}"
                    ))
                })?;
                self.factor = Factor::Ldlt(l_values);
            }
        }
        self.numeric_count += 1;
        Ok(())
    }

    /// Solves with the last factorization: on entry `du` holds `-r_u` (free
    /// dofs) and `dl` holds `g` (one per constraint); on exit the
    /// corrections `du` and `dlambda`.
    pub fn solve(&self, du: &mut [f64], dl: &mut [f64]) -> Result<(), LinearError> {
        let (n, m) = (self.n_free, self.m);
        if (du.len(), dl.len()) != (n, m) {
            return Err(LinearError::NotFactorized);
        }
        let mut x = match self.formulation {
            LagrangeFormulation::Single | LagrangeFormulation::Condensed => {
                [&du[..], &dl[..]].concat()
            }
            LagrangeFormulation::Doubled => [&dl[..], &du[..], &dl[..]].concat(),
        };
        if x.is_empty() {
            return Ok(());
        }
        let len = x.len();
        let b = MatMut::from_column_major_slice_mut(&mut x, len, 1);
        match &self.factor {
            Factor::Lu(f) => f.solve_in_place(b),
            Factor::Ldlt(values) => {
                let Some(sym) = self.symbolic_ldlt.as_ref() else {
                    return Err(LinearError::NotFactorized);
                };
                let f = LdltRef::new(sym, values);
                let mut buf = MemBuffer::new(sym.solve_in_place_scratch::<f64>(1, Par::Seq));
                f.solve_in_place_with_conj(Conj::No, b, Par::Seq, MemStack::new(&mut buf));
            }
            Factor::None => return Err(LinearError::NotFactorized),
        }
        match self.formulation {
            LagrangeFormulation::Single | LagrangeFormulation::Condensed => {
                du.copy_from_slice(&x[..n]);
                dl.copy_from_slice(&x[n..]);
            }
            LagrangeFormulation::Doubled => {
                du.copy_from_slice(&x[m..m + n]);
                for (c, d) in dl.iter_mut().enumerate() {
                    *d = x[c] + x[m + n + c];
                }
            }
        }
        Ok(())
    }
}

impl SaddlePointSystem for SaddleSolver {
    fn factorize(
        &mut self,
        k: &SparsePattern,
        k_values: &[f64],
        constraints: &crate::solve::constraints::Constraints,
    ) -> Result<(), LinearError> {
        SaddleSolver::factorize(self, k, k_values, &constraints.rows, &constraints.columns)
    }

    fn solve(&self, du: &mut [f64], dl: &mut [f64]) -> Result<(), LinearError> {
        SaddleSolver::solve(self, du, dl)
    }

    fn factorized_rows(&self) -> Option<usize> {
        (!matches!(self.factor, Factor::None)).then_some(self.m)
    }

    fn counts(&self) -> (usize, usize) {
        (self.symbolic_count, self.numeric_count)
    }

    fn system(&self) -> (usize, usize) {
        (self.pattern.n, self.pattern.nnz())
    }
}

/// The upper triangle (diagonal included) of a CSC matrix.
fn upper_triangle(p: &SparsePattern, values: &[f64]) -> (Vec<usize>, Vec<usize>, Vec<f64>) {
    let mut col_ptr = vec![0usize];
    let mut row_idx = Vec::new();
    let mut vals = Vec::new();
    for j in 0..p.n {
        let range = p.col_ptr[j]..p.col_ptr[j + 1];
        for (&r, &v) in p.row_idx[range.clone()].iter().zip(&values[range]) {
            if r <= j {
                row_idx.push(r);
                vals.push(v);
            }
        }
        col_ptr.push(row_idx.len());
    }
    (col_ptr, row_idx, vals)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// 3-dof chain `K = [[2,-1,0],[-1,2,-1],[0,-1,2]]` (full pattern), one
    /// constraint `-u_1 = g`.
    fn chain() -> (SparsePattern, Vec<f64>) {
        let a = [[2.0, -1.0, 0.0], [-1.0, 2.0, -1.0], [0.0, -1.0, 2.0]];
        super::super::pattern::dense_to_csc(&a, false)
    }

    fn solve(form: LagrangeFormulation) -> (Vec<f64>, Vec<f64>, SaddleSolver) {
        let (k, v) = chain();
        let mut rows = ConstraintRows::default();
        rows.push([(1, -1.0)]);
        let mut s = SaddleSolver::new(form);
        s.factorize(&k, &v, &rows, &rows).unwrap();
        // load f = (1, 0, 1): rhs -r = f; constraint -u1 = g = 0.5 -> u1 = -0.5
        let mut du = vec![1.0, 0.0, 1.0];
        let mut dl = vec![0.5];
        s.solve(&mut du, &mut dl).unwrap();
        (du, dl, s)
    }

    #[test]
    fn single_and_doubled_formulations_solve_the_same_saddle_point() {
        let (u1, l1, _) = solve(LagrangeFormulation::Single);
        let (u2, l2, _) = solve(LagrangeFormulation::Doubled);
        // exact: u1 = -0.5; rows 0 and 2: 2 u0 + 0.5 = 1 -> u0 = u2 = 0.25;
        // row 1: -u0 + 2 u1 - u2 - lambda = 0 -> lambda = -1.5
        let exact = [0.25, -0.5, 0.25];
        for i in 0..3 {
            assert!((u1[i] - exact[i]).abs() < 1e-14, "{u1:?}");
            assert!((u2[i] - exact[i]).abs() < 1e-14, "{u2:?}");
        }
        assert!((l1[0] + 1.5).abs() < 1e-14 && (l2[0] + 1.5).abs() < 1e-14);
    }

    #[test]
    fn unsymmetric_column_solves_k_du_plus_c_dlambda() {
        // [K C^T; G 0]: G = (0, -1, 0), C = (-1, -1, 0); load (1, 0, 1),
        // g = 0.5. Exact: u1 = -0.5, and K u + C^T l = f:
        // 2 u0 + 0.5 - l = 1, -u0 - 1 - u2 - l = 0, 0.5 + 2 u2 = 1
        // -> u2 = 0.25, u0 = (0.5 + l) / 2, -(0.5 + l) / 2 - 1.25 = l
        // -> l = -1, u0 = -0.25
        let (k, v) = chain();
        let mut rows = ConstraintRows::default();
        rows.push([(1, -1.0)]);
        let mut columns = ConstraintRows::default();
        columns.push([(0, -1.0), (1, -1.0)]);
        let mut s = SaddleSolver::new(LagrangeFormulation::Single);
        s.factorize(&k, &v, &rows, &columns).unwrap();
        let mut du = vec![1.0, 0.0, 1.0];
        let mut dl = vec![0.5];
        s.solve(&mut du, &mut dl).unwrap();
        let exact = [-0.25, -0.5, 0.25];
        for i in 0..3 {
            assert!((du[i] - exact[i]).abs() < 1e-14, "{du:?}");
        }
        assert!((dl[0] + 1.0).abs() < 1e-14, "{dl:?}");
        let mut d = SaddleSolver::new(LagrangeFormulation::Doubled);
        assert!(d.factorize(&k, &v, &rows, &columns).is_err());
    }

    #[test]
    fn symbolic_factorization_reused_while_the_constraint_set_is_unchanged() {
        let (k, v) = chain();
        let mut rows = ConstraintRows::default();
        rows.push([(0, -1.0), (2, 0.5)]);
        for form in [LagrangeFormulation::Single, LagrangeFormulation::Doubled] {
            let mut s = SaddleSolver::new(form);
            s.factorize(&k, &v, &rows, &rows).unwrap();
            let v2: Vec<f64> = v.iter().map(|x| 2.0 * x).collect();
            s.factorize(&k, &v2, &rows, &rows).unwrap();
            assert_eq!((s.symbolic_count, s.numeric_count), (1, 2));
            s.factorize(
                &k,
                &v2,
                &ConstraintRows::default(),
                &ConstraintRows::default(),
            )
            .unwrap();
            assert_eq!(
                (s.symbolic_count, s.numeric_count, s.constraints()),
                (2, 3, 0)
            );
        }
    }
}
