//! The tangent in Matrix Market (`ctc run --export-matrix FILE`, issue 20):
//! the first matrix a run factorizes, written so that other sparse direct
//! solvers (SciPy's SuperLU, CHOLMOD, MUMPS) can be timed on the same
//! matrix (`verification/fenicsx/factor_compare.py`).
//!
//! [`ExportFirst`] wraps any [`LinearSystem`]: its first `factorize` writes
//! the matrix (`coordinate real symmetric`, the lower triangle, 1-based,
//! 17 significant digits: the values read back are the same doubles) and
//! the wall time of that first factorization and of its symbolic analysis
//! into `FILE.json` (the numeric part is their difference; a Cholesky
//! attempt that broke down before the `L D L^T` one is in it), then every
//! call goes to the wrapped system. An unsymmetric pattern (a
//! non-symmetric tangent) is written `general` with both triangles.

use super::pattern::SparsePattern;
use super::{DistributedStats, FactorStats, LinearError, LinearSystem, ZeroMode};
use std::io::Write;
use std::path::PathBuf;
use std::time::Instant;

/// Writes `pattern`/`values` (CSC, both triangles stored) in Matrix Market:
/// `symmetric` (lower triangle) when the values are symmetric bit for bit,
/// `general` otherwise.
pub fn write_matrix_market<W: Write>(
    out: &mut W,
    pattern: &SparsePattern,
    values: &[f64],
) -> std::io::Result<()> {
    let n = pattern.n;
    let symmetric = (0..n).all(|j| {
        (pattern.col_ptr[j]..pattern.col_ptr[j + 1]).all(|k| {
            let i = pattern.row_idx[k];
            pattern
                .find(j, i)
                .is_some_and(|t| values[t].to_bits() == values[k].to_bits())
        })
    });
    let entries: Vec<(usize, usize, f64)> = (0..n)
        .flat_map(|j| {
            (pattern.col_ptr[j]..pattern.col_ptr[j + 1]).map(move |k| (pattern.row_idx[k], j, k))
        })
        .filter(|&(i, j, _)| !symmetric || i >= j)
        .map(|(i, j, k)| (i, j, values[k]))
        .collect();
    writeln!(
        out,
        "%%MatrixMarket matrix coordinate real {}",
        if symmetric { "symmetric" } else { "general" }
    )?;
    writeln!(
        out,
        "% ctc: the first tangent of the run (free dofs), written by --export-matrix"
    )?;
    writeln!(out, "{n} {n} {}", entries.len())?;
    for (i, j, v) in entries {
        writeln!(out, "{} {} {:.17e}", i + 1, j + 1, v)?;
    }
    Ok(())
}

/// A [`LinearSystem`] that writes the first matrix it is asked to
/// factorize (see the module documentation).
pub struct ExportFirst<'a> {
    inner: Box<dyn LinearSystem + 'a>,
    path: PathBuf,
    /// Whether the matrix was written (or the write failed: `error`).
    done: bool,
    /// The write's error, reported by [`ExportFirst::error`].
    error: Option<String>,
}

impl<'a> ExportFirst<'a> {
    /// Wraps `inner`; the first matrix goes to `path`.
    pub fn new(inner: Box<dyn LinearSystem + 'a>, path: PathBuf) -> Self {
        ExportFirst {
            inner,
            path,
            done: false,
            error: None,
        }
    }

    fn export(&mut self, pattern: &SparsePattern, values: &[f64]) -> Result<(), String> {
        let file = std::fs::File::create(&self.path)
            .map_err(|e| format!("cannot write {}: {e}", self.path.display()))?;
        let mut w = std::io::BufWriter::new(file);
        write_matrix_market(&mut w, pattern, &values[..pattern.nnz()])
            .and_then(|()| w.flush())
            .map_err(|e| format!("cannot write {}: {e}", self.path.display()))
    }

    /// Why the matrix could not be written, if it could not.
    pub fn error(&self) -> Option<&str> {
        self.error.as_deref()
    }
}

impl LinearSystem for ExportFirst<'_> {
    fn set_symmetric(&mut self, symmetric: bool) {
        self.inner.set_symmetric(symmetric);
    }

    fn factorize(&mut self, pattern: &SparsePattern, values: &[f64]) -> Result<(), LinearError> {
        if self.done {
            return self.inner.factorize(pattern, values);
        }
        self.done = true;
        if let Err(e) = self.export(pattern, values) {
            self.error = Some(e);
            return self.inner.factorize(pattern, values);
        }
        // the timing of ctc's own factorization of this matrix, for the
        // comparison script: the first call (symbolic analysis included)
        let symbolic0 = self.inner.stats().symbolic_seconds;
        let start = Instant::now();
        let r = self.inner.factorize(pattern, values);
        let first = start.elapsed().as_secs_f64();
        let stats = self.inner.stats();
        let method = stats.most_general();
        let json = format!(
            "{{\n \"rows\": {},\n \"nonzeros\": {},\n \"first_factorization_seconds\": {first},\n \
             \"symbolic_seconds\": {},\n \"method\": \"{method}\",\n \"factor_nonzeros\": {},\n \
             \"ok\": {}\n}}\n",
            pattern.n,
            pattern.nnz(),
            stats.symbolic_seconds - symbolic0,
            stats.factor_nonzeros,
            r.is_ok()
        );
        let mut side = self.path.clone().into_os_string();
        side.push(".json");
        if let Err(e) = std::fs::write(&side, json) {
            self.error = Some(format!("cannot write {}: {e}", side.to_string_lossy()));
        }
        r
    }

    fn solve(&mut self, rhs: &mut [f64]) -> Result<(), LinearError> {
        self.inner.solve(rhs)
    }

    fn is_factorized(&self) -> bool {
        self.inner.is_factorized()
    }

    fn set_candidates(&mut self, dofs: &[usize]) {
        self.inner.set_candidates(dofs);
    }

    fn reset_pattern(&mut self) {
        self.inner.reset_pattern();
    }

    fn zero_mode(&self) -> Option<&ZeroMode> {
        self.inner.zero_mode()
    }

    fn stats(&self) -> FactorStats {
        self.inner.stats()
    }

    fn distributed(&self, timings: &crate::solve::Timings) -> Option<DistributedStats> {
        self.inner.distributed(timings)
    }

    fn share(&self) -> Option<std::sync::Arc<crate::solve::share::AssemblyShare>> {
        self.inner.share()
    }

    fn sum_over_ranks(&self, v: &mut [f64]) {
        self.inner.sum_over_ranks(v);
    }

    fn any_rank(&self, flag: bool) -> bool {
        self.inner.any_rank(flag)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn csc(a: &[[f64; 3]; 3]) -> (SparsePattern, Vec<f64>) {
        let mut col_ptr = vec![0];
        let (mut row_idx, mut values) = (Vec::new(), Vec::new());
        for j in 0..3 {
            for (i, row) in a.iter().enumerate() {
                if row[j] != 0.0 {
                    row_idx.push(i);
                    values.push(row[j]);
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
            values,
        )
    }

    /// Parses what [`write_matrix_market`] wrote back into a dense matrix.
    fn read_back(text: &str) -> (String, [[f64; 3]; 3]) {
        let mut lines = text
            .lines()
            .filter(|l| !l.starts_with('%') || l.starts_with("%%"));
        let header = lines.next().unwrap().to_string();
        let size: Vec<usize> = lines
            .next()
            .unwrap()
            .split_whitespace()
            .map(|v| v.parse().unwrap())
            .collect();
        let mut a = [[0.0; 3]; 3];
        let mut count = 0;
        for l in lines {
            let f: Vec<&str> = l.split_whitespace().collect();
            let (i, j): (usize, usize) = (f[0].parse().unwrap(), f[1].parse().unwrap());
            let v: f64 = f[2].parse().unwrap();
            a[i - 1][j - 1] = v;
            if header.ends_with("symmetric") {
                a[j - 1][i - 1] = v;
            }
            count += 1;
        }
        assert_eq!((size[0], size[1], size[2]), (3, 3, count));
        (header, a)
    }

    #[test]
    fn matrix_market_round_trips_symmetric_and_general_matrices() {
        let sym = [
            [4.0, -1.0 / 3.0, 0.0],
            [-1.0 / 3.0, 5.0e-7, 2.5e6],
            [0.0, 2.5e6, 1.0],
        ];
        let (p, v) = csc(&sym);
        let mut out = Vec::new();
        write_matrix_market(&mut out, &p, &v).unwrap();
        let (header, back) = read_back(std::str::from_utf8(&out).unwrap());
        assert_eq!(header, "%%MatrixMarket matrix coordinate real symmetric");
        // the doubles come back bit for bit
        for (r, b) in sym.iter().zip(&back) {
            for (x, y) in r.iter().zip(b) {
                assert_eq!(x.to_bits(), y.to_bits());
            }
        }
        let mut general = sym;
        general[0][1] = 1.0;
        let (p, v) = csc(&general);
        let mut out = Vec::new();
        write_matrix_market(&mut out, &p, &v).unwrap();
        let (header, back) = read_back(std::str::from_utf8(&out).unwrap());
        assert_eq!(header, "%%MatrixMarket matrix coordinate real general");
        assert_eq!(back, general);
    }

    #[test]
    fn the_first_factorized_matrix_is_written_and_the_solver_still_solves() {
        let a = [[4.0, 1.0, 0.0], [1.0, 3.0, 1.0], [0.0, 1.0, 2.0]];
        let (p, v) = csc(&a);
        let dir = std::env::temp_dir().join(format!("ctc_export_{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("k.mtx");
        let mut sys = ExportFirst::new(
            Box::new(crate::solve::linalg::direct::LinearSolver::new()),
            path.clone(),
        );
        sys.factorize(&p, &v).unwrap();
        let mut x = vec![5.0, 5.0, 3.0];
        sys.solve(&mut x).unwrap();
        for (xi, e) in x.iter().zip([1.0, 1.0, 1.0]) {
            assert!((xi - e).abs() < 1e-14);
        }
        assert!(sys.error().is_none());
        let (_, back) = read_back(&std::fs::read_to_string(&path).unwrap());
        assert_eq!(back, a);
        let side = std::fs::read_to_string(dir.join("k.mtx.json")).unwrap();
        assert!(
            side.contains("\"rows\": 3") && side.contains("\"ok\": true"),
            "{side}"
        );
        // a second matrix is not written
        std::fs::remove_file(&path).unwrap();
        sys.factorize(&p, &v).unwrap();
        assert!(!path.exists());
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
