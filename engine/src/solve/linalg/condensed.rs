//! Lagrange multipliers condensed out of the saddle point (`method =
//! lagrange { formulation = condensed }`; issue 18: dual mortar "condensed,
//! no saddle point"; Popp, Gee & Wall, IJNME 79 (2009) 1354, §4.3;
//! Wohlmuth, SIAM J. Numer. Anal. 38 (2000) 989; Hüeber & Wohlmuth, CMAME
//! 194 (2005) 3147).
//!
//! The saddle point of [`super::saddle`] is, with `C` the force per unit
//! multiplier (one column per constraint) and `G` the constraint rows,
//!
//! `K du + C dlambda = -r`,  `G du = g`.
//!
//! Each multiplier lives on a node (the slave node of its row,
//! [`crate::contact::rows::NodeRow::node`]); `P` holds, per constraint, its
//! column restricted to that node's free dofs (`Constraints::pivots`). With
//! the dual mortar basis `D` is diagonal, so a slave node's equations hold
//! its own multiplier only: `W = P^T C` is diagonal (`W_cc = |p_c|^2`), and
//! `P^T` applied to the equilibrium gives the multipliers locally,
//!
//! `dlambda = W^-1 P^T (-r - K du)`.
//!
//! Put back, the equilibrium becomes `Q (K du + r) = 0` with the projector
//! `Q = I - C W^-1 P^T` (`P^T Q = 0`: it removes, at each active slave
//! node, the direction the multiplier acts along, and carries the slave
//! node's equations onto the master nodes through `M D^-1`); the `m`
//! equations it drops are replaced by the constraints, `S G du = S g` with
//! `S = P diag(s)` (`s_c` scales a row to the size of `K`'s diagonal), so
//! the system in the displacements alone is square:
//!
//! `(Q K + S G) du = -Q r + S g`
//!
//! (`P^T` of it gives back `G du = g` since `P^T Q = 0`; the rest is `Q (K
//! du + r) = 0`). The solution is the saddle point's to round-off for any
//! `P` with `W` invertible: nothing is approximated, so the Newton
//! iterates, the active set of the semi-smooth Newton and the recovered
//! multipliers (the reported pressure) are those of the saddle-point path.
//! `W` is block diagonal in general (a partly covered slave segment keeps
//! a small off-diagonal `D`; Lagrange friction puts a normal and a stick
//! row on one node; entries of round-off, [`ROUND_OFF`], do not couple):
//! its blocks (connected constraints) are inverted
//! densely up to [`MAX_BLOCK`] constraints; a larger or singular block
//! falls back to the saddle point (counted, [`CondensedSolver::fallbacks`]).
//!
//! The condensed matrix is **not symmetric**: `Q K` mixes the slave rows
//! into the master rows (`K_M - M^T D^-1 K_S`, not its transpose), and the
//! constraint rows replace equilibrium rows. It is factorized by sparse LU
//! (faer, partial pivoting); LDL^T / Cholesky do not apply (measured in
//! `ctc verify hertz_two_cylinders_mortar_condensed`: `|A - A^T|_F /
//! |A|_F`, see that case's doc).

use super::pattern::SparsePattern;
use super::saddle::SaddleSolver;
use super::{LinearError, SaddlePointSystem};
use crate::model::LagrangeFormulation;
use crate::solve::constraints::{ConstraintRows, Constraints};
use faer::linalg::solvers::Solve;
use faer::sparse::linalg::solvers::{Lu, SymbolicLu};
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};
use faer::MatMut;

/// Largest block of `W` (constraints coupled through their nodes) inverted
/// densely; a larger one falls back to the saddle point.
pub const MAX_BLOCK: usize = 64;

/// Relative size of the smallest pivot of a block of `W` below which the
/// block is singular (then the saddle point is factorized instead).
const SINGULAR: f64 = 1e-12;

/// Off-diagonal entries of `W` at most this fraction of `sqrt(W_aa W_bb)`
/// do not couple two constraints: the dual basis's biorthogonality leaves
/// `D_jk` of round-off on covered segments (measured 3e-17 to 6e-17 of
/// `D_jj` in `newton/condensed_tests.rs`); dropping them changes the
/// solution at round-off, keeping them would join every slave node of a
/// surface into one block.
const ROUND_OFF: f64 = 1e-13;

/// Sparse LU of the condensed system, with the saddle point as fallback.
pub struct CondensedSolver {
    /// Pattern and values of the condensed matrix `Q K + S G`.
    pattern: SparsePattern,
    values: Vec<f64>,
    symbolic: Option<SymbolicLu<usize>>,
    factor: Option<Box<Lu<usize, f64>>>,
    n: usize,
    m: usize,
    /// `C`, `P` and `s` of the last factorization.
    columns: ConstraintRows,
    pivots: ConstraintRows,
    scale: Vec<f64>,
    /// Rows of `W^-1` (constraint -> constraints of its block).
    w_inverse: ConstraintRows,
    /// Rows of `Y = W^-1 P^T K` (multiplier recovery).
    y: ConstraintRows,
    /// The saddle point, when the last factorization could not condense.
    fallback: SaddleSolver,
    /// Whether the last factorization is the fallback's.
    fell_back: bool,
    /// Symbolic and numeric LU factorizations of the condensed matrix.
    symbolic_count: usize,
    numeric_count: usize,
    /// Factorizations that fell back to the saddle point.
    pub fallbacks: usize,
    /// Largest block of `W` met.
    pub largest_block: usize,
    // scratch
    slot: Vec<usize>,
    acc: Vec<f64>,
    seen: Vec<bool>,
}

impl std::fmt::Debug for CondensedSolver {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("CondensedSolver")
            .field("n", &self.n)
            .field("constraints", &self.m)
            .field("fallbacks", &self.fallbacks)
            .finish()
    }
}

impl Default for CondensedSolver {
    fn default() -> Self {
        Self::new()
    }
}

impl CondensedSolver {
    /// A solver with no factorization.
    pub fn new() -> Self {
        CondensedSolver {
            pattern: SparsePattern {
                n: 0,
                col_ptr: vec![0],
                row_idx: vec![],
            },
            values: Vec::new(),
            symbolic: None,
            factor: None,
            n: 0,
            m: 0,
            columns: ConstraintRows::default(),
            pivots: ConstraintRows::default(),
            scale: Vec::new(),
            w_inverse: ConstraintRows::default(),
            y: ConstraintRows::default(),
            fallback: SaddleSolver::new(LagrangeFormulation::Single),
            fell_back: false,
            symbolic_count: 0,
            numeric_count: 0,
            fallbacks: 0,
            largest_block: 0,
            slot: Vec::new(),
            acc: Vec::new(),
            seen: Vec::new(),
        }
    }

    /// Order and stored entries of the last factorized matrix (the
    /// saddle point's `n + m` after a fallback).
    pub fn order_and_nonzeros(&self) -> (usize, usize) {
        if self.fell_back {
            (self.n + self.m, 0)
        } else {
            (self.pattern.n, self.pattern.nnz())
        }
    }

    /// The recovered multipliers' change `-Y v = -W^-1 P^T K v` along a
    /// displacement direction `v` (the homogeneous part of [`Self::solve`]'s
    /// recovery).
    pub fn recovery(&self, v: &[f64]) -> Vec<f64> {
        (0..self.m)
            .map(|c| -self.y.row(c).iter().map(|&(j, y)| y * v[j]).sum::<f64>())
            .collect()
    }

    /// `A v` with the last condensed matrix.
    pub fn apply(&self, v: &[f64]) -> Vec<f64> {
        let p = &self.pattern;
        let mut out = vec![0.0; p.n];
        for (j, &vj) in v.iter().enumerate().take(p.n) {
            for s in p.col_ptr[j]..p.col_ptr[j + 1] {
                out[p.row_idx[s]] += self.values[s] * vj;
            }
        }
        out
    }

    /// `dr - S dg`: a residual change `dr` (free dofs) and a gap change
    /// `dg` (one per constraint) as the condensed matrix combines them.
    pub fn subtract_scaled_pivots(&self, dr: &[f64], dg: &[f64]) -> Vec<f64> {
        let mut out = dr.to_vec();
        for (c, &d) in dg.iter().enumerate().take(self.m) {
            for &(i, p) in self.pivots.row(c) {
                out[i] -= self.scale[c] * p * d;
            }
        }
        out
    }

    /// `|A - A^T|_F / |A|_F` of the last condensed matrix (0 for a
    /// symmetric one).
    pub fn asymmetry(&self) -> f64 {
        asymmetry(&self.pattern, &self.values)
    }

    /// Assembles and factorizes the condensed matrix of the tangent
    /// (`k`, `k_values`) and `constraints`; falls back to the saddle point
    /// when `W` has a singular block or one above [`MAX_BLOCK`].
    pub fn factorize(
        &mut self,
        k: &SparsePattern,
        k_values: &[f64],
        constraints: &Constraints,
    ) -> Result<(), LinearError> {
        self.factor = None;
        self.fell_back = false;
        let (n, m) = (k.n, constraints.rows.len());
        self.n = n;
        self.m = m;
        if !self.eliminate(k, k_values, constraints) {
            self.fell_back = true;
            self.fallbacks += 1;
            return self
                .fallback
                .factorize(k, k_values, &constraints.rows, &constraints.columns);
        }
        self.assemble(k, k_values, &constraints.rows);
        let p = &self.pattern;
        if p.n == 0 {
            return Ok(());
        }
        let symbolic = SymbolicSparseColMatRef::new_checked(p.n, p.n, &p.col_ptr, None, &p.row_idx);
        if self.symbolic.is_none() {
            self.symbolic = Some(SymbolicLu::try_new(symbolic).map_err(|e| {
                LinearError::Symbolic(format!(
                    "symbolic LU of the condensed contact system failed: {e:?}"
                ))
            })?);
            self.symbolic_count += 1;
        }
        let sym = self.symbolic.clone().expect("set above");
        let mat = SparseColMatRef::new(symbolic, &self.values);
        let f = Lu::try_new_with_symbolic(sym, mat).map_err(|e| {
            LinearError::Singular(format!(
                "the condensed contact system is singular (LU failed: {e:?})"
            ))
        })?;
        self.factor = Some(Box::new(f));
        self.numeric_count += 1;
        Ok(())
    }

    /// `P`, `C`, `s`, `W^-1` and `Y = W^-1 P^T K`; `false` when `W` cannot
    /// be inverted block by block (then nothing is condensed).
    fn eliminate(&mut self, k: &SparsePattern, kv: &[f64], cs: &Constraints) -> bool {
        let (n, m) = (k.n, cs.rows.len());
        self.columns.clone_from(&cs.columns);
        self.pivots.clone_from(&cs.pivots);
        // W = P^T C: per pivot dof, the columns touching it
        self.slot.clear();
        self.slot.resize(n, usize::MAX);
        let mut touching: Vec<Vec<(usize, f64)>> = Vec::new();
        for pivot in self.pivots.iter() {
            for &(dof, _) in pivot {
                if self.slot[dof] == usize::MAX {
                    self.slot[dof] = touching.len();
                    touching.push(Vec::new());
                }
            }
        }
        for (c, column) in self.columns.iter().enumerate() {
            for &(dof, v) in column {
                if let Some(t) = touching.get_mut(self.slot[dof]) {
                    t.push((c, v));
                }
            }
        }
        let mut w: Vec<Vec<(usize, f64)>> = Vec::with_capacity(m);
        for pivot in self.pivots.iter() {
            let mut row: Vec<(usize, f64)> = Vec::new();
            for &(dof, p) in pivot {
                for &(c2, v) in &touching[self.slot[dof]] {
                    row.push((c2, p * v));
                }
            }
            row.sort_by_key(|e| e.0);
            let mut merged: Vec<(usize, f64)> = Vec::with_capacity(row.len());
            for (c2, v) in row {
                match merged.last_mut() {
                    Some(last) if last.0 == c2 => last.1 += v,
                    _ => merged.push((c2, v)),
                }
            }
            w.push(merged);
        }
        // blocks of W: union-find over its nonzero off-diagonal entries
        let mut parent: Vec<usize> = (0..m).collect();
        fn root(parent: &mut [usize], mut a: usize) -> usize {
            while parent[a] != a {
                parent[a] = parent[parent[a]];
                a = parent[a];
            }
            a
        }
        let diagonal: Vec<f64> = w
            .iter()
            .enumerate()
            .map(|(c, row)| row.iter().find(|e| e.0 == c).map_or(0.0, |e| e.1.abs()))
            .collect();
        for (c, row) in w.iter().enumerate() {
            for &(c2, v) in row {
                if c2 != c && v.abs() > ROUND_OFF * (diagonal[c] * diagonal[c2]).sqrt() {
                    let (a, b) = (root(&mut parent, c), root(&mut parent, c2));
                    if a != b {
                        parent[a.max(b)] = a.min(b);
                    }
                }
            }
        }
        let mut members: Vec<Vec<usize>> = vec![Vec::new(); m];
        for c in 0..m {
            let r = root(&mut parent, c);
            members[r].push(c);
        }
        let mut inverse: Vec<Vec<(usize, f64)>> = vec![Vec::new(); m];
        for block in members.iter().filter(|b| !b.is_empty()) {
            self.largest_block = self.largest_block.max(block.len());
            if block.len() > MAX_BLOCK {
                return false;
            }
            let Some(inv) = invert_block(block, &w) else {
                return false;
            };
            for (a, &c) in block.iter().enumerate() {
                inverse[c] = block
                    .iter()
                    .enumerate()
                    .map(|(b, &c2)| (c2, inv[a * block.len() + b]))
                    .collect();
            }
        }
        self.w_inverse.clear();
        for row in &inverse {
            self.w_inverse.push(row.iter().copied());
        }
        // s_c: the constraint rows at the size of K's diagonal
        self.scale.clear();
        for pivot in self.pivots.iter() {
            let norm2: f64 = pivot.iter().map(|e| e.1 * e.1).sum();
            let diag = pivot
                .iter()
                .filter_map(|&(dof, _)| k.find(dof, dof).map(|s| kv[s].abs()))
                .fold(0.0, f64::max);
            self.scale
                .push(if diag > 0.0 { diag } else { 1.0 } / norm2.max(f64::MIN_POSITIVE));
        }
        // Z = P^T K (rows of K by the pattern's symmetry), then Y = W^-1 Z
        self.acc.clear();
        self.acc.resize(n, 0.0);
        self.seen.clear();
        self.seen.resize(n, false);
        let mut z = ConstraintRows::default();
        let mut list = Vec::new();
        for pivot in self.pivots.iter() {
            list.clear();
            for &(s, p) in pivot {
                for &j in &k.row_idx[k.col_ptr[s]..k.col_ptr[s + 1]] {
                    // K[s][j], stored in column j (both triangles stored)
                    let Some(slot) = k.find(s, j) else { continue };
                    if !self.seen[j] {
                        self.seen[j] = true;
                        list.push(j);
                    }
                    self.acc[j] += p * kv[slot];
                }
            }
            list.sort_unstable();
            z.push(list.iter().map(|&j| (j, self.acc[j])));
            for &j in &list {
                self.acc[j] = 0.0;
                self.seen[j] = false;
            }
        }
        self.y.clear();
        for c in 0..m {
            list.clear();
            for &(c2, wi) in self.w_inverse.row(c) {
                for &(j, v) in z.row(c2) {
                    if !self.seen[j] {
                        self.seen[j] = true;
                        list.push(j);
                    }
                    self.acc[j] += wi * v;
                }
            }
            list.sort_unstable();
            self.y.push(list.iter().map(|&j| (j, self.acc[j])));
            for &j in &list {
                self.acc[j] = 0.0;
                self.seen[j] = false;
            }
        }
        true
    }

    /// `A = K - C Y + S G` in CSC: `K`'s columns merged with the sorted
    /// extra entries (duplicates summed in a fixed order).
    fn assemble(&mut self, k: &SparsePattern, kv: &[f64], rows: &ConstraintRows) {
        let n = k.n;
        // (column, row, value)
        let mut extra: Vec<(usize, usize, f64)> = Vec::new();
        for c in 0..self.m {
            for &(i, cv) in self.columns.row(c) {
                for &(j, y) in self.y.row(c) {
                    extra.push((j, i, -cv * y));
                }
            }
            for &(i, p) in self.pivots.row(c) {
                for &(j, g) in rows.row(c) {
                    extra.push((j, i, self.scale[c] * p * g));
                }
            }
        }
        // stable: equal (column, row) keep the order above
        extra.sort_by_key(|e| (e.0, e.1));
        let mut col_ptr = Vec::with_capacity(n + 1);
        col_ptr.push(0);
        let mut row_idx = Vec::with_capacity(k.nnz() + extra.len());
        let mut values = Vec::with_capacity(k.nnz() + extra.len());
        let mut e = 0;
        for j in 0..n {
            let mut s = k.col_ptr[j];
            let end = k.col_ptr[j + 1];
            loop {
                let next_k = (s < end).then(|| k.row_idx[s]);
                let next_e = (e < extra.len() && extra[e].0 == j).then(|| extra[e].1);
                let (i, v) = match (next_k, next_e) {
                    (None, None) => break,
                    (Some(i), ne) if ne.is_none_or(|r| i <= r) => {
                        s += 1;
                        (i, kv[s - 1])
                    }
                    (_, Some(r)) => {
                        e += 1;
                        (r, extra[e - 1].2)
                    }
                    (Some(_), None) => unreachable!("matched above"),
                };
                if row_idx.len() > col_ptr[j] && row_idx.last() == Some(&i) {
                    *values.last_mut().expect("an entry") += v;
                } else {
                    row_idx.push(i);
                    values.push(v);
                }
            }
            col_ptr.push(row_idx.len());
        }
        let pattern = SparsePattern {
            n,
            col_ptr,
            row_idx,
        };
        if pattern != self.pattern {
            self.symbolic = None;
            self.pattern = pattern;
        }
        self.values = values;
    }

    /// Solves with the last factorization: on entry `du = -r` and `dl = g`,
    /// on exit the corrections `du` and `dlambda = W^-1 P^T (-r - K du)`.
    pub fn solve(&self, du: &mut [f64], dl: &mut [f64]) -> Result<(), LinearError> {
        if self.fell_back {
            return self.fallback.solve(du, dl);
        }
        let (n, m) = (self.n, self.m);
        if (du.len(), dl.len()) != (n, m) {
            return Err(LinearError::NotFactorized);
        }
        if n == 0 {
            return Ok(());
        }
        let Some(f) = &self.factor else {
            return Err(LinearError::NotFactorized);
        };
        // t = W^-1 P^T (-r)
        let pt: Vec<f64> = self
            .pivots
            .iter()
            .map(|p| p.iter().map(|&(i, v)| v * du[i]).sum())
            .collect();
        let t: Vec<f64> = (0..m)
            .map(|c| {
                self.w_inverse
                    .row(c)
                    .iter()
                    .map(|&(c2, w)| w * pt[c2])
                    .sum()
            })
            .collect();
        // -Q r + S g
        for c in 0..m {
            for &(i, v) in self.columns.row(c) {
                du[i] -= v * t[c];
            }
            for &(i, p) in self.pivots.row(c) {
                du[i] += self.scale[c] * p * dl[c];
            }
        }
        let b = MatMut::from_column_major_slice_mut(du, n, 1);
        f.solve_in_place(b);
        for (c, d) in dl.iter_mut().enumerate() {
            *d = t[c] - self.y.row(c).iter().map(|&(j, y)| y * du[j]).sum::<f64>();
        }
        Ok(())
    }
}

/// `|A - A^T|_F / |A|_F` of a CSC matrix (0 for a symmetric one).
pub fn asymmetry(p: &SparsePattern, values: &[f64]) -> f64 {
    let (mut diff, mut all) = (0.0, 0.0);
    for j in 0..p.n {
        for s in p.col_ptr[j]..p.col_ptr[j + 1] {
            let i = p.row_idx[s];
            let v = values[s];
            all += v * v;
            let t = p.find(j, i).map_or(0.0, |k| values[k]);
            diff += (v - t) * (v - t);
        }
    }
    if all > 0.0 {
        (diff / all).sqrt()
    } else {
        0.0
    }
}

/// Dense inverse of the block `block` of `W` (rows `w`), row-major, by
/// Gauss-Jordan with partial pivoting; `None` when singular.
fn invert_block(block: &[usize], w: &[Vec<(usize, f64)>]) -> Option<Vec<f64>> {
    let b = block.len();
    let mut a = vec![0.0; b * b];
    for (r, &c) in block.iter().enumerate() {
        for &(c2, v) in &w[c] {
            if let Ok(col) = block.binary_search(&c2) {
                a[r * b + col] += v;
            }
        }
    }
    let largest = a.iter().fold(0.0f64, |x, v| x.max(v.abs()));
    if largest == 0.0 {
        return None;
    }
    let mut inv = vec![0.0; b * b];
    for i in 0..b {
        inv[i * b + i] = 1.0;
    }
    for col in 0..b {
        let p = (col..b).max_by(|&x, &y| a[x * b + col].abs().total_cmp(&a[y * b + col].abs()))?;
        if a[p * b + col].abs() <= SINGULAR * largest {
            return None;
        }
        if p != col {
            for j in 0..b {
                a.swap(p * b + j, col * b + j);
                inv.swap(p * b + j, col * b + j);
            }
        }
        let d = a[col * b + col];
        for j in 0..b {
            a[col * b + j] /= d;
            inv[col * b + j] /= d;
        }
        for r in 0..b {
            if r != col {
                let f = a[r * b + col];
                if f != 0.0 {
                    for j in 0..b {
                        a[r * b + j] -= f * a[col * b + j];
                        inv[r * b + j] -= f * inv[col * b + j];
                    }
                }
            }
        }
    }
    Some(inv)
}

impl SaddlePointSystem for CondensedSolver {
    fn factorize(
        &mut self,
        k: &SparsePattern,
        k_values: &[f64],
        constraints: &Constraints,
    ) -> Result<(), LinearError> {
        CondensedSolver::factorize(self, k, k_values, constraints)
    }

    fn solve(&self, du: &mut [f64], dl: &mut [f64]) -> Result<(), LinearError> {
        CondensedSolver::solve(self, du, dl)
    }

    fn factorized_rows(&self) -> Option<usize> {
        if self.fell_back {
            self.fallback.factorized_rows()
        } else {
            (self.factor.is_some() || self.n == 0).then_some(self.m)
        }
    }

    fn counts(&self) -> (usize, usize) {
        let (s, n) = self.fallback.counts();
        (self.symbolic_count + s, self.numeric_count + n)
    }

    fn system(&self) -> (usize, usize) {
        self.order_and_nonzeros()
    }

    fn asymmetry(&self) -> Option<f64> {
        (!self.fell_back && self.factor.is_some()).then(|| CondensedSolver::asymmetry(self))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A dense unsymmetric 8 x 8 tangent (4 nodes x 2 dofs, diagonally
    /// dominant), every entry stored.
    fn tangent() -> (SparsePattern, Vec<f64>) {
        let mut seed = 12345u64;
        let mut next = || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        };
        let mut a = [[0.0; 8]; 8];
        for (i, row) in a.iter_mut().enumerate() {
            for (j, v) in row.iter_mut().enumerate() {
                *v = next() + if i == j { 6.0 } else { 0.0 };
            }
        }
        super::super::pattern::dense_to_csc(&a, true)
    }

    fn push(rows: &mut ConstraintRows, entries: &[(usize, f64)]) {
        rows.push(entries.iter().copied());
    }

    /// Sparse entries `(dof, coefficient)`.
    type Entries<'a> = &'a [(usize, f64)];

    /// Constraints: `(row G, column C, multiplier's node)`; `P` is `C` on
    /// the node's two dofs.
    fn constraints(list: &[(Entries<'_>, Entries<'_>, usize)]) -> Constraints {
        let mut c = Constraints::default();
        for (row, column, node) in list {
            push(&mut c.rows, row);
            push(&mut c.columns, column);
            let pivot: Vec<_> = column
                .iter()
                .copied()
                .filter(|e| e.0 / 2 == *node)
                .collect();
            push(&mut c.pivots, &pivot);
            c.gap.push(0.1 * (c.gap.len() as f64 + 1.0));
        }
        c
    }

    /// The condensed solve and the saddle point's: `(du, dlambda)` of each.
    fn both(c: &Constraints) -> ([Vec<f64>; 2], [Vec<f64>; 2], CondensedSolver) {
        let (k, v) = tangent();
        let rhs: Vec<f64> = (0..8).map(|i| (i as f64 * 0.7).sin()).collect();
        let mut s = SaddleSolver::new(LagrangeFormulation::Single);
        s.factorize(&k, &v, &c.rows, &c.columns).unwrap();
        let (mut du_s, mut dl_s) = (rhs.clone(), c.gap.clone());
        s.solve(&mut du_s, &mut dl_s).unwrap();
        let mut q = CondensedSolver::new();
        q.factorize(&k, &v, c).unwrap();
        let (mut du_c, mut dl_c) = (rhs, c.gap.clone());
        q.solve(&mut du_c, &mut dl_c).unwrap();
        ([du_s, du_c], [dl_s, dl_c], q)
    }

    fn close(a: &[f64], b: &[f64], tol: f64) {
        for (x, y) in a.iter().zip(b) {
            assert!((x - y).abs() <= tol * (1.0 + y.abs()), "{a:?} vs {b:?}");
        }
    }

    #[test]
    fn condensed_solution_is_the_saddle_points() {
        // two mortar-like multipliers on nodes 1 and 0: columns with a
        // slave part (a unit normal) and master parts, rows differing from
        // the columns (the full derivative)
        let c = constraints(&[
            (
                &[(2, 0.5), (3, 0.9), (4, -0.2), (6, -0.35), (7, -0.5)],
                &[
                    (2, 0.6),
                    (3, 0.8),
                    (4, -0.3),
                    (5, -0.4),
                    (6, -0.3),
                    (7, -0.4),
                ],
                1,
            ),
            (
                &[(0, 0.1), (1, 1.0), (4, -0.6), (5, -0.5)],
                &[(1, 1.0), (4, -0.5), (5, -0.5)],
                0,
            ),
        ]);
        let (du, dl, q) = both(&c);
        close(&du[1], &du[0], 1e-13);
        close(&dl[1], &dl[0], 1e-13);
        // the displacements alone: order 8 (the saddle point's is 10), W
        // diagonal, unsymmetric
        assert_eq!(q.order_and_nonzeros().0, 8);
        assert_eq!((q.largest_block, q.fallbacks), (1, 0));
        assert!(q.asymmetry() > 1e-3, "{}", q.asymmetry());
    }

    #[test]
    fn coupled_multipliers_are_eliminated_by_blocks() {
        // a normal and a stick row on node 1, and a multiplier on node 0
        // whose column also reaches node 1 (a partly covered segment's
        // off-diagonal D): one block of 3
        let c = constraints(&[
            (
                &[(2, 0.6), (3, 0.8), (6, -0.6)],
                &[(2, 0.6), (3, 0.8), (6, -0.6), (7, -0.8)],
                1,
            ),
            (
                &[(2, -0.8), (3, 0.6), (7, 0.6)],
                &[(2, -0.8), (3, 0.6), (7, 0.6)],
                1,
            ),
            (
                &[(1, 1.0), (3, 0.05), (5, -1.0)],
                &[(1, 1.0), (3, 0.1), (5, -1.1)],
                0,
            ),
        ]);
        let (du, dl, q) = both(&c);
        close(&du[1], &du[0], 1e-13);
        close(&dl[1], &dl[0], 1e-13);
        assert_eq!((q.largest_block, q.fallbacks), (3, 0));
    }

    #[test]
    fn a_singular_block_falls_back_to_the_saddle_point() {
        // two multipliers acting along the same direction of node 1: W's
        // block is singular, the saddle point (whose rows differ) is not
        let c = constraints(&[
            (&[(2, 1.0), (4, -1.0)], &[(2, 1.0), (4, -1.0)], 1),
            (&[(3, 1.0), (6, -1.0)], &[(2, 2.0), (6, -1.0)], 1),
        ]);
        let (du, dl, q) = both(&c);
        close(&du[1], &du[0], 1e-13);
        close(&dl[1], &dl[0], 1e-13);
        assert_eq!(q.fallbacks, 1);
        assert_eq!(q.order_and_nonzeros().0, 10);
        assert!(q.factorized_rows() == Some(2));
    }
}
