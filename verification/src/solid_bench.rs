//! `ctc bench --solid N`: the direct solver on a 3D linear-elastic block,
//! `[0, 1]^3` in `N x N x N` hex8 (`3 N (N + 1)^2` free dofs: N = 32 is
//! ~100k, N = 46 ~300k), symmetry `u_n = 0` on `x = 0`, `y = 0`, `z = 0`,
//! `u_z = -0.01` on `z = 1`, one increment. Measured: time per Newton
//! iteration and per phase, factorization time, entries of the matrix and
//! of the Cholesky factor (fill), bytes of the factorization, and the
//! process's peak resident memory (`VmHWM` of `/proc/self/status`, Linux).

use ctc_engine::mesh::generate::{solid, Grading};
use ctc_engine::mesh::CellKind;
use ctc_engine::model::TimeFunction;
use ctc_engine::solve::{run, IncrementView, Observer, Timings};
use ctc_engine::testkit::ModelBuilder;
use std::fmt;
use std::time::Instant;

/// What the solid benchmark measured.
#[derive(Debug, Clone, serde::Serialize)]
pub struct SolidBenchReport {
    /// Cells per edge.
    pub divisions: usize,
    /// Nodes.
    pub nodes: usize,
    /// Free dofs.
    pub free_dofs: usize,
    /// Entries of the free-free matrix (both triangles).
    pub matrix_nonzeros: usize,
    /// Entries of the Cholesky factor.
    pub factor_nonzeros: usize,
    /// Factor entries over those of the lower triangle.
    pub factor_fill: f64,
    /// Bytes of the factorization (values of L and scratch).
    pub factor_bytes: usize,
    /// Newton iterations.
    pub newton_iterations: usize,
    /// Numeric Cholesky factorizations.
    pub cholesky_factorizations: usize,
    /// Wall time of the run, seconds.
    pub wall_time: f64,
    /// Phase totals, seconds.
    pub timings: Timings,
    /// Wall time per Newton iteration, seconds.
    pub time_per_iteration: f64,
    /// Factorization time per factorization (symbolic included in the
    /// first), seconds.
    pub factorization_time: f64,
    /// Peak resident memory of the process, bytes (0 where unknown).
    pub peak_memory_bytes: u64,
}

struct Quiet;
impl Observer<3> for Quiet {
    fn converged(&mut self, _: &IncrementView<'_, 3>) -> Result<(), String> {
        Ok(())
    }
}

/// Peak resident memory of this process (`VmHWM`), bytes; 0 if unknown.
pub use ctc_engine::solve::linalg::peak_memory_bytes;

/// Runs the block with `n` cells per edge.
pub fn run_solid_bench(n: usize) -> Result<SolidBenchReport, String> {
    if n == 0 {
        return Err("--solid needs at least 1 cell per edge".into());
    }
    let mesh = solid::brick(
        [0.0; 3],
        [1.0; 3],
        [n; 3],
        [Grading::Uniform; 3],
        CellKind::Hex8,
    )
    .map_err(|e| e.message)?;
    let mut b = ModelBuilder::solid()
        .elastic("m", 210e3, 0.3)
        .body("block", mesh, "m");
    for (set, c) in [("xmin", 0), ("ymin", 1), ("zmin", 2)] {
        let nodes = b.node_set(&format!("block.{set}"));
        b = b.fix(nodes, c);
    }
    let top = b.node_set("block.zmax");
    let model = b
        .displace(top, 2, TimeFunction::Constant(-0.01))
        .step("press", 1.0, 1)
        .build();
    let start = Instant::now();
    let s = run(&model, &mut Quiet).map_err(|e| e.message)?;
    let wall_time = start.elapsed().as_secs_f64();
    let factorizations =
        (s.cholesky_factorizations + s.ldlt_factorizations + s.lu_factorizations).max(1);
    Ok(SolidBenchReport {
        divisions: n,
        nodes: s.nodes,
        free_dofs: s.free_dofs,
        matrix_nonzeros: s.matrix_nonzeros,
        factor_nonzeros: s.factor_nonzeros,
        factor_fill: s.factor_fill,
        factor_bytes: s.factor_bytes,
        newton_iterations: s.newton_iterations,
        cholesky_factorizations: s.cholesky_factorizations,
        wall_time,
        time_per_iteration: s.timings.total / s.newton_iterations.max(1) as f64,
        factorization_time: s.timings.factorization / factorizations as f64,
        timings: s.timings,
        peak_memory_bytes: peak_memory_bytes(),
    })
}

impl fmt::Display for SolidBenchReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let gib = |b: f64| b / (1u64 << 30) as f64;
        writeln!(
            f,
            "3D linear-elastic block, {n} x {n} x {n} hex8: {} nodes, {} free dofs",
            self.nodes,
            self.free_dofs,
            n = self.divisions
        )?;
        writeln!(
            f,
            "matrix nonzeros {}, factor nonzeros {} (fill {:.1} x the lower triangle), factor {:.2} GiB, peak resident {:.2} GiB",
            self.matrix_nonzeros,
            self.factor_nonzeros,
            self.factor_fill,
            gib(self.factor_bytes as f64),
            gib(self.peak_memory_bytes as f64)
        )?;
        writeln!(
            f,
            "{} Newton iterations, {} Cholesky factorizations; per iteration {:.3} s; factorization {:.3} s each; assembly {:.3} s, solve {:.3} s (totals); wall {:.2} s",
            self.newton_iterations,
            self.cholesky_factorizations,
            self.time_per_iteration,
            self.factorization_time,
            self.timings.assembly,
            self.timings.solve,
            self.wall_time
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn solid_bench_small_block_reports_fill_and_memory() {
        let r = run_solid_bench(3).unwrap();
        // 4^3 nodes, 3 symmetry planes: 3 n (n + 1)^2 free dofs less the top's uz
        assert_eq!(r.nodes, 64);
        assert_eq!(r.free_dofs, 3 * 3 * 16 - 16);
        assert!(r.factor_nonzeros >= (r.matrix_nonzeros + r.free_dofs) / 2);
        assert!(r.factor_fill >= 1.0 && r.factor_bytes >= 8 * r.factor_nonzeros);
        assert!(r.newton_iterations >= 1 && r.cholesky_factorizations >= 1);
        assert!(run_solid_bench(0).is_err());
    }
}
