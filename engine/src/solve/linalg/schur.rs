//! The contact block of a factorized tangent as a dense Schur complement
//! (issue 20): the cheaper Newton iteration of a linear-elastic body in
//! contact, without the columns of `K0^{-1}` of [`super::low_rank`].
//!
//! The *candidate* dofs `c` (the free dofs of the contact surfaces, given
//! by the Newton loop when every body's stiffness is constant) are ordered
//! last by the fill-reducing ordering (`direct.rs`: AMD or nested
//! dissection of the whole pattern, the candidates moved to the end in
//! their order). The `L D L^T` factor of the base tangent `K0` then holds
//!
//! ```text
//! K0 = [K_ii K_ic; K_ci K_cc] = [L_ii 0; L_ci L_cc] diag(D_i, D_c) [L_ii 0; L_ci L_cc]^T,
//! S0 = K_cc - K_ci K_ii^{-1} K_ic = L_cc D_c L_cc^T   (dense, m x m)
//! ```
//!
//! A new tangent `K` that differs from `K0` only inside the candidate block
//! (`K_cc + dK`: the contact blocks of a rigid tool, or of two contact
//! surfaces) has the same `L_ii`, `L_ci`, `D_i` and the Schur complement
//! `S = S0 + dK`, so
//!
//! ```text
//! w_i = L_ii^{-1} b_i,   r_c = b_c - L_ci w_i,   (S0 + dK) x_c = r_c,
//! x_i = L_ii^{-T} (D_i^{-1} w_i - L_ci^T x_c)
//! ```
//!
//! is one forward and one backward sweep over the interior supernodes and a
//! dense solve of order `m`. The sweeps are plain loops over each
//! supernode's columns ([`Supernode`]): 2D AMD gives supernodes of a few
//! columns, on which faer's `matmul` and triangular solves spent more in
//! dispatch than in arithmetic (issue 20, tutorial Hertz deck, `ctc run
//! tutorial.ctc --threads 1` with either sweep, 2 alternating runs under
//! load 11: the solve phase 0.93 -> 0.57 s wall, process CPU 0.93 -> 0.84
//! s; `verification/fenicsx/SPEED.md`). The dense solve uses the LU of `S0` (once per
//! base) and a [`LowRank`] (Woodbury) update of it for the changed dofs,
//! whose columns `S0^{-1} e_j` are all computed with that LU: per Newton
//! iteration a dense LU of order `|changed|` and `O(m |changed|)` work.
//! Deterministic: fixed orders, one thread.

use super::low_rank::{LowRank, SINGULAR};
use faer::linalg::solvers::{PartialPivLu, Solve};
use faer::sparse::linalg::cholesky::supernodal::{SupernodalLdltRef, SymbolicSupernodalCholesky};
use faer::sparse::linalg::cholesky::{SymbolicCholesky, SymbolicCholeskyRaw};
use faer::{Accum, Mat, MatMut, Par};

/// The candidate block, the dense Schur complement of the base and its
/// update.
#[derive(Debug, Default)]
pub struct Schur {
    /// Whether each free dof is a candidate.
    candidate: Vec<bool>,
    /// Candidate count.
    m: usize,
    /// Interior dofs (factor positions `0..n_i`); set with a base.
    n_i: usize,
    /// Position in the candidate block of each free dof (`u32::MAX`:
    /// interior); set with a base.
    slot: Vec<u32>,
    /// `S0`, column-major `m x m`.
    s0: Vec<f64>,
    /// LU of `S0`.
    lu: Option<PartialPivLu<f64>>,
    /// Woodbury update of `S0` (its cache: every column of `S0^{-1}`).
    dense: LowRank,
    /// The full `m x m` pattern (column pointers and rows).
    col_ptr: Vec<usize>,
    row_idx: Vec<usize>,
    /// `S0 + dK` of the current update.
    s: Vec<f64>,
    /// Whether a base is held (the factor is the base's).
    pub ready: bool,
    /// Whether the current factorization is the base plus the update.
    pub active: bool,
}

impl Schur {
    /// Largest candidate count for a matrix of order `n`: `3 sqrt(n)`.
    /// The dense work of a base (`S0`, its LU and inverse: `O(m^3)`) then
    /// stays of the order of a 2D factorization (`O(n^1.5)`); the bound of
    /// the low-rank columns, `2 sqrt(n)` ([`LowRank::limit`]), left the top
    /// surface of `ctc bench`'s block (566 dofs at `n` = 79,806) on them.
    pub fn limit(n: usize) -> usize {
        (3.0 * (n as f64).sqrt()).ceil() as usize
    }

    /// The candidate dofs of `n` free dofs (out-of-range entries ignored);
    /// forgets the base.
    pub fn set_candidates(&mut self, n: usize, dofs: &[usize]) {
        self.candidate = vec![false; n];
        for &d in dofs {
            if d < n {
                self.candidate[d] = true;
            }
        }
        self.m = self.candidate.iter().filter(|&&c| c).count();
        self.clear();
    }

    /// Whether each of `n` free dofs is a candidate, when candidates are
    /// set for that order.
    pub fn candidates(&self, n: usize) -> Option<&[bool]> {
        (self.m > 0 && self.candidate.len() == n).then_some(&self.candidate[..])
    }

    /// Candidate count.
    pub fn len(&self) -> usize {
        self.m
    }

    /// Whether no candidate is set.
    pub fn is_empty(&self) -> bool {
        self.m == 0
    }

    /// Forgets the base.
    pub fn clear(&mut self) {
        self.ready = false;
        self.active = false;
        self.lu = None;
        self.dense.clear();
    }

    /// Makes the `L D L^T` factor (`sym`, `l_values`) of the base its own:
    /// `S0` and its LU; false (no base) when the factor is not supernodal,
    /// the candidates are not its last positions, or `S0` is nearly
    /// singular. The update is empty (the base itself).
    pub fn rebase(&mut self, sym: &SymbolicCholesky<usize>, l_values: &[f64]) -> bool {
        self.clear();
        let n = sym.nrows();
        let m = self.m;
        if m == 0 || self.candidate.len() != n || m >= n {
            return false;
        }
        let (SymbolicCholeskyRaw::Supernodal(sn), Some(perm)) = (sym.raw(), sym.perm()) else {
            return false;
        };
        let n_i = n - m;
        let (forward, _) = perm.arrays();
        if forward[n_i..].iter().any(|&d| !self.candidate[d]) {
            return false;
        }
        self.n_i = n_i;
        self.slot = vec![u32::MAX; n];
        for (k, &d) in forward[n_i..].iter().enumerate() {
            self.slot[d] = k as u32;
        }
        // L_cc (unit lower) and D_c from the trailing columns
        let ldlt = SupernodalLdltRef::new(sn, l_values);
        let mut l = Mat::<f64>::zeros(m, m);
        let mut d = vec![0.0; m];
        for s in first_block_supernode(sn, n_i)..sn.n_supernodes() {
            let node = ldlt.supernode(s);
            let (start, v) = (node.start(), node.val());
            let ncols = v.ncols();
            for cj in n_i.max(start) - start..ncols {
                let j = start + cj - n_i;
                d[j] = v[(cj, cj)];
                l[(j, j)] = 1.0;
                for r in cj + 1..ncols {
                    l[(start + r - n_i, j)] = v[(r, cj)];
                }
                for (idx, &row) in node.pattern().iter().enumerate() {
                    l[(row - n_i, j)] = v[(ncols + idx, cj)];
                }
            }
        }
        let mut ld = l.clone();
        for (j, dj) in d.iter().enumerate() {
            for i in 0..m {
                ld[(i, j)] *= dj;
            }
        }
        let mut s0 = Mat::<f64>::zeros(m, m);
        faer::linalg::matmul::matmul(
            s0.as_mut(),
            Accum::Replace,
            ld.as_ref(),
            l.transpose(),
            1.0,
            Par::Seq,
        );
        self.s0 = (0..m * m).map(|k| s0[(k % m, k / m)]).collect();
        let scale = self.s0.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        let lu = PartialPivLu::new(s0.as_ref());
        let u = lu.U();
        let regular = scale.is_finite()
            && (0..m).all(|k| u[(k, k)].is_finite() && u[(k, k)].abs() > SINGULAR * scale);
        if !regular {
            return false;
        }
        // every column of S0^{-1} for the dense updates
        self.dense.rebase(m, &self.s0, 0);
        let all: Vec<usize> = (0..m).collect();
        let first = self.dense.push_unit_columns(&all);
        let cols = self.dense.new_columns(first);
        lu.solve_in_place(MatMut::from_column_major_slice_mut(cols, m, m));
        if !cols.iter().all(|v| v.is_finite()) {
            self.dense.clear();
            return false;
        }
        if self.col_ptr.len() != m + 1 {
            self.col_ptr = (0..=m).map(|j| j * m).collect();
            self.row_idx = (0..m * m).map(|k| k % m).collect();
        }
        self.lu = Some(lu);
        self.ready = true;
        self.active = self
            .dense
            .update(Vec::new(), &self.col_ptr, &self.row_idx, &self.s0);
        self.active
    }

    /// The update for the matrix (`col_ptr`, `row_idx`, `values`) whose
    /// entries differ from the base's (`base`) in the rows and columns of
    /// `changed` only: false (inactive) when one of them is not a
    /// candidate or `S0 + dK` is nearly singular.
    pub fn update(
        &mut self,
        changed: &[usize],
        col_ptr: &[usize],
        row_idx: &[usize],
        values: &[f64],
        base: &[f64],
    ) -> bool {
        self.active = false;
        if !self.ready || changed.iter().any(|&d| self.slot[d] == u32::MAX) {
            return false;
        }
        let m = self.m;
        self.s.clear();
        self.s.extend_from_slice(&self.s0);
        for &j in changed {
            let cj = self.slot[j] as usize;
            for k in col_ptr[j]..col_ptr[j + 1] {
                let r = self.slot[row_idx[k]];
                if r == u32::MAX {
                    // an interior-candidate coupling changed: not this path
                    if values[k].to_bits() != base[k].to_bits() {
                        return false;
                    }
                    continue;
                }
                self.s[cj * m + r as usize] += values[k] - base[k];
            }
        }
        let mut local: Vec<usize> = changed.iter().map(|&d| self.slot[d] as usize).collect();
        local.sort_unstable();
        self.active = self
            .dense
            .update(local, &self.col_ptr, &self.row_idx, &self.s);
        self.active
    }

    /// Solves `K x = b` in place (`rhs`: `b` on entry) with the interior
    /// part of the `L D L^T` factor (`sym`, `l_values`) of the base and the
    /// dense `S0 + dK`.
    pub fn solve(&self, sym: &SymbolicCholesky<usize>, l_values: &[f64], rhs: &mut [f64]) {
        let (SymbolicCholeskyRaw::Supernodal(sn), Some(perm), Some(lu)) =
            (sym.raw(), sym.perm(), self.lu.as_ref())
        else {
            return;
        };
        let (forward, _) = perm.arrays();
        let n_i = self.n_i;
        let mut x: Vec<f64> = forward.iter().map(|&d| rhs[d]).collect();
        // the supernodes with interior columns (the last one may hold
        // candidate columns too)
        let last = sn.supernode_begin().partition_point(|&b| b < n_i);
        let mut tmp = Vec::new();
        for s in 0..last {
            let node = Supernode::new(sn, l_values, s, n_i);
            node.forward(&mut x, &mut tmp);
        }
        // x_c = (S0 + dK)^{-1} r_c
        lu.solve_in_place(MatMut::from_column_major_slice_mut(
            &mut x[n_i..],
            self.m,
            1,
        ));
        self.dense.correct_with(&mut x[n_i..], 1);
        for s in (0..last).rev() {
            let node = Supernode::new(sn, l_values, s, n_i);
            node.backward(&mut x, &mut tmp);
        }
        for (&d, xv) in forward.iter().zip(&x) {
            rhs[d] = *xv;
        }
    }
}

/// One supernode of a supernodal `L D L^T` factor, as the sweeps of
/// [`Schur::solve`] read it: its first column `start`, `p` interior columns
/// (of its `ncols`), the rows below its columns (`pattern`), and its values
/// (column-major, `ncols + pattern.len()` rows: the unit lower triangle
/// with `D` on the diagonal, then the rows of `pattern`).
struct Supernode<'a> {
    start: usize,
    ncols: usize,
    p: usize,
    pattern: &'a [usize],
    values: &'a [f64],
}

impl<'a> Supernode<'a> {
    fn new(
        sn: &'a SymbolicSupernodalCholesky<usize>,
        l_values: &'a [f64],
        s: usize,
        n_i: usize,
    ) -> Self {
        let start = sn.supernode_begin()[s];
        let ncols = sn.supernode_end()[s] - start;
        let rows = sn.col_ptr_for_row_idx();
        let vals = sn.col_ptr_for_val();
        Supernode {
            start,
            ncols,
            p: ncols.min(n_i - start),
            pattern: &sn.row_idx()[rows[s]..rows[s + 1]],
            values: &l_values[vals[s]..vals[s + 1]],
        }
    }

    /// Rows of the values.
    fn nrows(&self) -> usize {
        self.ncols + self.pattern.len()
    }

    /// Forward: `w = L^{-1} b` on the interior columns, the rows below
    /// updated (`tmp`: scratch), then `D^{-1}` on the interior columns.
    fn forward(&self, x: &mut [f64], tmp: &mut Vec<f64>) {
        let (start, ncols, p, nrows) = (self.start, self.ncols, self.p, self.nrows());
        tmp.clear();
        tmp.resize(nrows - p, 0.0);
        for k in 0..p {
            let col = &self.values[k * nrows..(k + 1) * nrows];
            let xk = x[start + k];
            for (xr, l) in x[start + k + 1..start + p].iter_mut().zip(&col[k + 1..p]) {
                *xr -= l * xk;
            }
            for (t, l) in tmp.iter_mut().zip(&col[p..]) {
                *t += l * xk;
            }
        }
        for (xr, t) in x[start + p..start + ncols].iter_mut().zip(&tmp[..]) {
            *xr -= t;
        }
        for (&row, t) in self.pattern.iter().zip(&tmp[ncols - p..]) {
            x[row] -= t;
        }
        for k in 0..p {
            x[start + k] /= self.values[k * nrows + k];
        }
    }

    /// Backward: `x = L^{-T} y` on the interior columns, the rows below
    /// (candidates and later interior columns) already solved.
    fn backward(&self, x: &mut [f64], tmp: &mut Vec<f64>) {
        let (start, ncols, p, nrows) = (self.start, self.ncols, self.p, self.nrows());
        tmp.clear();
        tmp.extend_from_slice(&x[start + p..start + ncols]);
        tmp.extend(self.pattern.iter().map(|&row| x[row]));
        for k in (0..p).rev() {
            let col = &self.values[k * nrows..(k + 1) * nrows];
            let mut s = dot(&col[p..], tmp);
            for (l, xr) in col[k + 1..p].iter().zip(&x[start + k + 1..start + p]) {
                s += l * xr;
            }
            x[start + k] -= s;
        }
    }
}

/// `a . b` with four partial sums in a fixed order (deterministic; the
/// compiler vectorizes it).
fn dot(a: &[f64], b: &[f64]) -> f64 {
    let n = a.len().min(b.len());
    let (a, b) = (&a[..n], &b[..n]);
    let mut acc = [0.0f64; 4];
    let (ac, bc) = (a.chunks_exact(4), b.chunks_exact(4));
    let (ar, br) = (ac.remainder(), bc.remainder());
    for (x, y) in ac.zip(bc) {
        for ((s, x), y) in acc.iter_mut().zip(x).zip(y) {
            *s += x * y;
        }
    }
    let mut s = (acc[0] + acc[1]) + (acc[2] + acc[3]);
    for (x, y) in ar.iter().zip(br) {
        s += x * y;
    }
    s
}

/// The first supernode with a column at or after `n_i` (the supernodes
/// cover the columns in order).
fn first_block_supernode(sn: &SymbolicSupernodalCholesky<usize>, n_i: usize) -> usize {
    let end = sn.supernode_end();
    end.partition_point(|&e| e <= n_i)
}

/// The elimination order `forward` (faer's forward array) with the
/// candidates moved to the end, both parts in their order.
pub fn candidates_last(forward: &[usize], candidate: &[bool]) -> Vec<usize> {
    let mut out: Vec<usize> = forward.iter().copied().filter(|&d| !candidate[d]).collect();
    out.extend(forward.iter().copied().filter(|&d| candidate[d]));
    out
}
