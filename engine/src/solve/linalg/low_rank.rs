//! Low-rank updates of a factorized tangent (Woodbury): the cheaper Newton
//! iteration of issue 20 for bodies whose bulk stiffness does not change.
//!
//! A small-strain linear-elastic body in contact with a rigid tool has the
//! same element stiffness at every iteration (cached, summed in the same
//! order, so bit for bit the same values); only the contact blocks at the
//! contact dofs change. When a new tangent `K` differs from the last
//! factorized one `K0` (the *base*) only in the rows and columns of a small
//! set `S` of dofs, `K = K0 + E_S dK E_S^T` with `dK` the dense `|S| x |S|`
//! difference, and
//!
//! ```text
//! K x = b:   x0 = K0^{-1} b,   Z = K0^{-1} E_S,
//!            (I + dK Z_SS) y = dK x0_S,   x = x0 - Z y
//! ```
//!
//! (exact: `K0 x = b - E_S y` and `y = dK E_S^T x`). The columns of `Z` are
//! computed once per dof with the base factor (several right-hand sides at
//! once) and cached for the run; each iteration then costs a comparison of
//! the values, a dense LU of order `|S|`, one sparse solve and `Z y`, instead
//! of a numeric factorization. The set `S` is found by comparing the
//! values bit for bit, so the path is chosen by the matrices themselves: a
//! nonlinear material changes every entry and keeps the full factorization.
//! `S` (or the cache) outgrowing its bound ([`LowRank::limit`]), or a
//! nearly singular `I + dK Z_SS` (pivot below [`SINGULAR`] times the
//! largest entry), makes the next tangent a full factorization and the new
//! base. Deterministic: no timings, fixed orders.

/// Smallest pivot of the dense LU of `I + dK Z_SS`, relative to its largest
/// entry, accepted (below: the updated tangent is nearly singular; the full
/// factorization decides, and names a zero-energy mode if there is one).
pub const SINGULAR: f64 = 1e-13;

/// Values of `K0^{-1}` columns kept at most (256 MiB), unless the factor
/// of `K0` holds more ([`LowRank::limit`]).
pub const CACHE_VALUES: usize = 32 << 20;

/// The base matrix, the cached columns of `K0^{-1}` and the current update.
#[derive(Debug, Clone, Default)]
pub struct LowRank {
    /// Values of the base matrix `K0` (the pattern's `nnz`).
    pub base: Vec<f64>,
    /// Order of the matrix.
    n: usize,
    /// Cached columns `K0^{-1} e_j`, column-major `n x cols`.
    z: Vec<f64>,
    /// Column of `z` of each dof (`u32::MAX`: not computed).
    col_of: Vec<u32>,
    /// Dofs of the current update, increasing.
    pub s: Vec<usize>,
    /// `dK`, row-major `|S| x |S|`.
    dk: Vec<f64>,
    /// LU factors of `I + dK Z_SS` (row-major, unit lower part below the
    /// diagonal) and the row permutation.
    lu: Vec<f64>,
    perm: Vec<usize>,
    /// [`LowRank::limit`] of the base: largest `|S|` and cached column
    /// count.
    bound: usize,
    /// Whether the current factorization is the base plus this update.
    pub active: bool,
}

impl LowRank {
    /// Largest `|S|` and cached column count for a matrix of order `n`
    /// whose factor holds `factor_values` values: `2 sqrt(n)` (the dense
    /// work and `Z y` stay below a triangular solve's order of cost) and at
    /// most [`CACHE_VALUES`] cached values or, when the factor is larger
    /// (3D tangents: 88M values at 85k dofs), as many as the factor (the
    /// cache at most doubles the factor's memory), at least 16.
    pub fn limit(n: usize, factor_values: usize) -> usize {
        let by_cost = (2.0 * (n as f64).sqrt()).ceil() as usize;
        by_cost
            .min(CACHE_VALUES.max(factor_values) / n.max(1))
            .max(16)
    }

    /// The [`LowRank::limit`] of the base (0 without one).
    pub fn bound(&self) -> usize {
        self.bound
    }

    /// Makes `values` (just factorized in full, into a factor of
    /// `factor_values` values; 0 when unknown) the base; the cache is
    /// emptied.
    pub fn rebase(&mut self, n: usize, values: &[f64], factor_values: usize) {
        self.base.clear();
        self.base.extend_from_slice(values);
        self.n = n;
        self.bound = Self::limit(n, factor_values);
        self.z.clear();
        // room for every column the bound allows: the cache never moves
        // (untouched capacity costs address space, not memory)
        let room = self.bound.saturating_mul(n);
        if self.z.capacity() < room {
            let _ = self.z.try_reserve_exact(room);
        }
        self.col_of.clear();
        self.col_of.resize(n, u32::MAX);
        self.s.clear();
        self.active = false;
    }

    /// Forgets the base (a failed or singular full factorization, a new
    /// pattern).
    pub fn clear(&mut self) {
        self.base.clear();
        self.n = 0;
        self.bound = 0;
        self.z.clear();
        self.col_of.clear();
        self.s.clear();
        self.active = false;
    }

    /// Whether a base is held for a matrix of order `n` with `nnz` values.
    pub fn has_base(&self, n: usize, nnz: usize) -> bool {
        self.n == n && n > 0 && self.base.len() == nnz
    }

    /// The dofs whose rows or columns differ (bit for bit) between the
    /// matrix (`col_ptr`, `row_idx`, `values`) and the base, increasing;
    /// `None` when more than `limit` differ.
    pub fn changed_dofs(
        &self,
        col_ptr: &[usize],
        row_idx: &[usize],
        values: &[f64],
        limit: usize,
    ) -> Option<Vec<usize>> {
        let mut mark = vec![false; self.n];
        let mut count = 0;
        for j in 0..self.n {
            for k in col_ptr[j]..col_ptr[j + 1] {
                if values[k].to_bits() != self.base[k].to_bits() {
                    for d in [row_idx[k], j] {
                        if !mark[d] {
                            mark[d] = true;
                            count += 1;
                        }
                    }
                    if count > limit {
                        return None;
                    }
                }
            }
        }
        Some((0..self.n).filter(|&d| mark[d]).collect())
    }

    /// Dofs of `s` without a cached column.
    pub fn missing(&self, s: &[usize]) -> Vec<usize> {
        s.iter()
            .copied()
            .filter(|&d| self.col_of[d] == u32::MAX)
            .collect()
    }

    /// Number of cached columns.
    pub fn cached(&self) -> usize {
        self.z.len() / self.n.max(1)
    }

    /// Appends the unit columns `e_d` of `dofs` to the cache, to be solved
    /// in place into `K0^{-1} e_d` ([`LowRank::new_columns`]); returns the
    /// index of the first new column.
    pub fn push_unit_columns(&mut self, dofs: &[usize]) -> usize {
        let first = self.cached();
        for &d in dofs {
            self.col_of[d] = self.cached() as u32;
            let start = self.z.len();
            self.z.resize(start + self.n, 0.0);
            self.z[start + d] = 1.0;
        }
        first
    }

    /// The cached columns from index `first` on (column-major).
    pub fn new_columns(&mut self, first: usize) -> &mut [f64] {
        &mut self.z[first * self.n..]
    }

    /// Forgets the cached columns from index `first` on (their solve
    /// failed).
    pub fn drop_columns(&mut self, first: usize) {
        self.z.truncate(first * self.n);
        for c in &mut self.col_of {
            if *c != u32::MAX && *c as usize >= first {
                *c = u32::MAX;
            }
        }
    }

    fn column(&self, d: usize) -> &[f64] {
        let c = self.col_of[d] as usize;
        &self.z[c * self.n..(c + 1) * self.n]
    }

    /// Sets the update of the dofs `s` (all with cached columns) for the
    /// matrix (`col_ptr`, `row_idx`, `values`): `dK` and the LU of
    /// `I + dK Z_SS`. Returns false (and leaves the update inactive) when
    /// that matrix is nearly singular.
    pub fn update(
        &mut self,
        s: Vec<usize>,
        col_ptr: &[usize],
        row_idx: &[usize],
        values: &[f64],
    ) -> bool {
        self.active = false;
        let m = s.len();
        let mut pos = vec![u32::MAX; self.n];
        for (a, &d) in s.iter().enumerate() {
            pos[d] = a as u32;
        }
        let mut dk = vec![0.0; m * m];
        for (b, &j) in s.iter().enumerate() {
            for k in col_ptr[j]..col_ptr[j + 1] {
                let a = pos[row_idx[k]];
                if a != u32::MAX {
                    dk[a as usize * m + b] = values[k] - self.base[k];
                }
            }
        }
        // Z_SS (row-major): zss[b][c] = (K0^{-1} e_{s_c})[s_b]
        let mut zss = vec![0.0; m * m];
        for (c, &d) in s.iter().enumerate() {
            let col = self.column(d);
            for (b, &r) in s.iter().enumerate() {
                zss[b * m + c] = col[r];
            }
        }
        // M = I + dK Z_SS
        let mut lu = vec![0.0; m * m];
        for a in 0..m {
            for b in 0..m {
                let x = dk[a * m + b];
                if x != 0.0 {
                    let (row, zrow) = (&mut lu[a * m..(a + 1) * m], &zss[b * m..(b + 1) * m]);
                    for (l, z) in row.iter_mut().zip(zrow) {
                        *l += x * z;
                    }
                }
            }
            lu[a * m + a] += 1.0;
        }
        let Some(perm) = lu_in_place(&mut lu, m) else {
            return false;
        };
        self.s = s;
        self.dk = dk;
        self.lu = lu;
        self.perm = perm;
        self.active = true;
        true
    }

    /// `x = x0 - Z y` with `(I + dK Z_SS) y = dK x0_S`; `x` holds
    /// `x0 = K0^{-1} b` on entry. On [`crate::solve::parallel::threads`]
    /// threads (the same bits whatever their number).
    pub fn correct(&self, x: &mut [f64]) {
        self.correct_with(x, crate::solve::parallel::threads());
    }

    /// [`LowRank::correct`] on `threads` threads (one below
    /// [`PARALLEL_MIN_WORK`]).
    pub fn correct_with(&self, x: &mut [f64], threads: usize) {
        let parts = if x.len() * self.s.len() >= PARALLEL_MIN_WORK {
            threads
        } else {
            1
        };
        self.correct_parts(x, parts);
    }

    /// [`LowRank::correct`] with the rows cut into `parts` ranges, one per
    /// thread, each row updated in column order as on one thread.
    pub(crate) fn correct_parts(&self, x: &mut [f64], parts: usize) {
        let m = self.s.len();
        if !self.active || m == 0 {
            return;
        }
        let xs: Vec<f64> = self.s.iter().map(|&d| x[d]).collect();
        let t: Vec<f64> = (0..m)
            .map(|a| {
                self.dk[a * m..(a + 1) * m]
                    .iter()
                    .zip(&xs)
                    .map(|(k, v)| k * v)
                    .sum()
            })
            .collect();
        let y = lu_solve(&self.lu, &self.perm, m, &t);
        let terms: Vec<(&[f64], f64)> = self
            .s
            .iter()
            .zip(&y)
            .filter(|(_, &yb)| yb != 0.0)
            .map(|(&d, &yb)| (self.column(d), yb))
            .collect();
        // x_i -= y_b Z_ib in column order b; each column streamed once
        // (sequential reads: faster than row blocks that jump between the
        // columns, measured on the tutorial deck)
        let rows = |start: usize, xs: &mut [f64]| {
            let len = xs.len();
            for &(z, yb) in &terms {
                for (xi, zi) in xs.iter_mut().zip(&z[start..start + len]) {
                    *xi -= yb * zi;
                }
            }
        };
        let n = x.len();
        let parts = parts.clamp(1, n.max(1));
        if parts == 1 {
            rows(0, x);
            return;
        }
        let per = n.div_ceil(parts);
        std::thread::scope(|scope| {
            let rows = &rows;
            let mut parts = x.chunks_mut(per).enumerate();
            let own = parts.next();
            for (p, xs) in parts {
                scope.spawn(move || rows(p * per, xs));
            }
            if let Some((_, xs)) = own {
                rows(0, xs);
            }
        });
    }
}

/// Work (`n` times the columns) below which `Z y` stays on one thread.
const PARALLEL_MIN_WORK: usize = 1 << 20;

/// Columns of `K0^{-1}` solved together: the batches do not depend on the
/// thread count, so neither do the columns' bits.
pub const COLUMN_BATCH: usize = 16;

/// Dense LU with partial pivoting of the row-major `m x m` matrix `a`, in
/// place (unit lower factor below the diagonal); the row order, or `None`
/// when a pivot is below [`SINGULAR`] times the largest entry (or not
/// finite).
fn lu_in_place(a: &mut [f64], m: usize) -> Option<Vec<usize>> {
    let scale = a.iter().fold(0.0f64, |s, v| s.max(v.abs()));
    if !scale.is_finite() {
        return None;
    }
    let mut perm: Vec<usize> = (0..m).collect();
    for k in 0..m {
        let p = (k..m).fold(k, |p, i| {
            if a[i * m + k].abs() > a[p * m + k].abs() {
                i
            } else {
                p
            }
        });
        let pivot = a[p * m + k];
        if !pivot.is_finite() || pivot.abs() <= SINGULAR * scale {
            return None;
        }
        if p != k {
            for c in 0..m {
                a.swap(k * m + c, p * m + c);
            }
            perm.swap(k, p);
        }
        for i in k + 1..m {
            let f = a[i * m + k] / pivot;
            a[i * m + k] = f;
            if f != 0.0 {
                for c in k + 1..m {
                    a[i * m + c] -= f * a[k * m + c];
                }
            }
        }
    }
    Some(perm)
}

/// Solves with the factors of [`lu_in_place`].
#[allow(clippy::needless_range_loop)] // triangular sweeps over `y` itself
fn lu_solve(lu: &[f64], perm: &[usize], m: usize, b: &[f64]) -> Vec<f64> {
    let mut y: Vec<f64> = perm.iter().map(|&p| b[p]).collect();
    for i in 0..m {
        let s: f64 = (0..i).map(|c| lu[i * m + c] * y[c]).sum();
        y[i] -= s;
    }
    for i in (0..m).rev() {
        let s: f64 = (i + 1..m).map(|c| lu[i * m + c] * y[c]).sum();
        y[i] = (y[i] - s) / lu[i * m + i];
    }
    y
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_factor_larger_than_the_cache_bound_widens_it_and_a_smaller_one_does_not() {
        // 2D tutorial of issue 20: 80,200 dofs, 3.9M factor values: the
        // fixed 32M-value bound, 418 columns (below 2 sqrt(n) = 567)
        assert_eq!(LowRank::limit(80_200, 3_909_380), 418);
        assert_eq!(LowRank::limit(80_200, 0), 418);
        // 3D sphere, N = 40 (198,440 dofs): 169 columns by the fixed
        // bound; a factor of 300M values allows 2 sqrt(n) = 891
        assert_eq!(LowRank::limit(198_440, 0), 169);
        assert_eq!(LowRank::limit(198_440, 300_000_000), 891);
        // between the two: the factor's size over n
        assert_eq!(LowRank::limit(198_440, 100_000_000), 503);
        // small matrices: at least 16
        assert_eq!(LowRank::limit(10, 0), 16);
        let mut lr = LowRank::default();
        assert_eq!(lr.bound(), 0);
        lr.rebase(1000, &[1.0], 0);
        assert_eq!(lr.bound(), 64);
        lr.clear();
        assert_eq!(lr.bound(), 0);
    }

    #[test]
    fn dense_lu_solves_and_refuses_singular_matrices() {
        let m = 3;
        let a0 = vec![0.0, 2.0, 1.0, 1.0, 1.0, 0.0, 4.0, -1.0, 3.0];
        let mut a = a0.clone();
        let perm = lu_in_place(&mut a, m).unwrap();
        let x = [1.0, -2.0, 0.5];
        let b: Vec<f64> = (0..m)
            .map(|i| (0..m).map(|j| a0[i * m + j] * x[j]).sum())
            .collect();
        let y = lu_solve(&a, &perm, m, &b);
        for (u, v) in x.iter().zip(&y) {
            assert!((u - v).abs() < 1e-14, "{x:?} vs {y:?}");
        }
        let mut s = vec![1.0, 2.0, 2.0, 4.0];
        assert!(lu_in_place(&mut s, 2).is_none());
    }
}
