//! The benchmark of issue 3 (not a test): a rigid cylinder pushed into an
//! elastic block, about 80k degrees of freedom, timed phase by phase.
//!
//! Block [-4, 4] x [-4, 0], E = 1e3, nu = 0.3, plane strain, bottom
//! clamped; rigid circle R = 1 centred at (0, 1) pushed down to d = 0.02 in
//! 4 increments; rectangle mesh `divisions = (2n, n)` graded towards the
//! contact (`center(20)` in x, `geometric(0.05)` in y); area penalty
//! `10 E / h_min` with h_min the shortest cell edge of the generated mesh.
//! `size` scales the number of dofs (1 = the full ~80k-dof problem).

use crate::capture::Capture;
use crate::deck::compile_text;
use crate::measure::hertz::{measure as hertz_measure, HertzSetup};
use crate::measure::Value;
use crate::profile::Abscissa;
use crate::report::fmt_num;
use ctc_engine::model::{Model, PenaltyKind};
use ctc_engine::solve::{run_with, RunSummary, Timings};
use std::fmt;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Young's modulus of the block.
const YOUNG: f64 = 1e3;
/// Divisions n (y) of the full problem: (2n + 1)(n + 1) nodes ~ 80k dofs.
const FULL_N: f64 = 141.0;

/// Benchmark settings.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct BenchOptions {
    /// Fraction of the full problem's dof count (1.0 = ~80k dofs, 0.1 =
    /// ~8k); the divisions scale with its square root.
    pub size: f64,
    /// Number of increments to reach d = 0.02.
    pub increments: usize,
    /// Where to write the exact deck that was run (optional).
    pub deck_out: Option<PathBuf>,
    /// The increment predictor (`newton { predictor }`, on by default).
    pub predictor: bool,
    /// Low-rank (Woodbury) updates of the factorized tangent when only
    /// the contact dofs' blocks change (`linalg::low_rank`, on by default).
    pub low_rank: bool,
}

impl Default for BenchOptions {
    fn default() -> Self {
        BenchOptions {
            size: 1.0,
            increments: 4,
            deck_out: None,
            predictor: true,
            low_rank: true,
        }
    }
}

/// Mean wall time per Newton iteration of each phase, seconds.
#[derive(Debug, Clone, Default, PartialEq, serde::Serialize)]
pub struct PerIteration {
    /// Element assembly.
    pub assembly: f64,
    /// Contact search and contact forces/tangents.
    pub contact: f64,
    /// Sparse factorization.
    pub factorization: f64,
    /// Triangular solves.
    pub solve: f64,
}

/// What the benchmark measured.
#[derive(Debug, Clone, serde::Serialize)]
pub struct BenchReport {
    /// Requested size fraction.
    pub size: f64,
    /// Mesh divisions (x, y).
    pub divisions: [usize; 2],
    /// Number of nodes.
    pub nodes: usize,
    /// Free degrees of freedom.
    pub free_dofs: usize,
    /// Shortest cell edge of the mesh.
    pub h_min: f64,
    /// Area penalty used, `10 E / h_min`.
    pub penalty: f64,
    /// Converged increments.
    pub increments: usize,
    /// Newton iterations of each converged increment.
    pub iterations_per_increment: Vec<usize>,
    /// Newton iterations in total (all attempts).
    pub newton_iterations: usize,
    /// Increment cutbacks.
    pub cutbacks: usize,
    /// Linear solver the engine chose.
    pub linear_solver: String,
    /// Stored entries of the free-free stiffness matrix.
    pub matrix_nonzeros: usize,
    /// Numeric Cholesky factorizations.
    pub cholesky_factorizations: usize,
    /// Numeric L D L^T factorizations (indefinite tangent).
    pub ldlt_factorizations: usize,
    /// Most negative pivots met in one L D L^T factorization.
    pub max_negative_pivots: usize,
    /// Numeric LU factorizations.
    pub lu_factorizations: usize,
    /// Tangents solved by a low-rank update of the last factorization.
    pub low_rank_updates: usize,
    /// Deck compilation (parsing, mesh generation), seconds.
    pub compile_time: f64,
    /// Solve wall time measured around `run`, seconds.
    pub wall_time: f64,
    /// CPU time (user + system) of the process during `run`, seconds.
    pub cpu_time: f64,
    /// Wall time per Newton iteration (`wall_time` over the iterations),
    /// seconds.
    pub wall_per_iteration: f64,
    /// Mean time of one numeric factorization, seconds.
    pub time_per_factorization: f64,
    /// Wall time per Newton iteration over the time of one factorization
    /// (the bar: close to 1).
    pub iteration_over_factorization: f64,
    /// Whether the increment predictor was on.
    pub predictor: bool,
    /// Whether low-rank updates were allowed.
    pub low_rank: bool,
    /// Threads of the parallel kernels (`--threads`, `CTC_THREADS`).
    pub threads: usize,
    /// Entries of the factor `L` (diagonal included).
    pub factor_nonzeros: usize,
    /// Fill: factor entries over those of the matrix's lower triangle.
    pub factor_fill: f64,
    /// Peak resident memory of the process (`VmHWM`), bytes.
    pub peak_memory_bytes: u64,
    /// The engine's phase timings (totals), seconds.
    pub timings: Timings,
    /// Phase timings per Newton iteration.
    pub per_iteration: PerIteration,
    /// Hertz quantities of the final state (a, p0, force balance, L2 of
    /// p(x)) against Hertz for the computed load: a sanity check, the block
    /// is finite and the mesh is tuned for speed, not accuracy.
    pub accuracy: Vec<Value>,
    /// Why the solve stopped early, if it did.
    pub failure: Option<String>,
}

/// The deck of the benchmark.
pub fn bench_deck(divisions: [usize; 2], penalty: f64, increments: usize) -> String {
    format!(
        "# Benchmark (issue 3): rigid cylinder R = 1 pushed 0.02 into an elastic block.\n\
         # Generated by ctc-verification::bench (divisions {nx} x {ny}, penalty 10 E / h_min).\n\
         analysis {{ dimension = plane_strain }}\n\
         material rubberish {{ elastic {{ E = {YOUNG:e}  nu = 0.3 }} }}\n\
         body block {{\n  mesh = rectangle {{ origin = (-4, -4)  size = (8, 4)  divisions = ({nx}, {ny})\n                     grading = (center(20), geometric(0.05))  element = quad4 }}\n  material = rubberish\n}}\n\
         tool punch = circle {{ center = (0, 1)  radius = 1  side = outside  motion {{ uy = ramp(0, -0.02) }} }}\n\
         contact block.top -> punch {{ method = penalty {{ kind = area  stiffness = {penalty:e} }} }}\n\
         fix block.bottom {{ ux uy }}\n\
         step press {{\n  time = 0 .. 1\n  increments = {increments}\n}}\n\
         output {{ fields = [displacement, contact] }}\n",
        nx = divisions[0],
        ny = divisions[1],
    )
}

/// Shortest cell edge of a model's mesh.
pub fn min_cell_edge(model: &Model) -> f64 {
    let nodes = &model.mesh.nodes;
    let mut h = f64::INFINITY;
    for c in &model.mesh.cells {
        let n = c.nodes;
        for i in 0..n.len() {
            let (a, b) = (nodes[n[i]], nodes[n[(i + 1) % n.len()]]);
            h = h.min(((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2)).sqrt());
        }
    }
    h
}

/// Runs the benchmark. Errors: invalid options or a deck that does not
/// compile; a solver failure is reported inside the [`BenchReport`].
pub fn run_bench(opts: &BenchOptions) -> Result<BenchReport, String> {
    if !(opts.size > 0.0 && opts.size.is_finite()) {
        return Err(format!(
            "bench size must be a positive number, got {}",
            opts.size
        ));
    }
    if opts.increments == 0 {
        return Err("bench increments must be at least 1".into());
    }
    let n = ((FULL_N * opts.size.sqrt()).round() as usize).max(4);
    let divisions = [2 * n, n];
    let path = Path::new("bench.ctc");
    // First pass: the mesh, to get h_min; the penalty does not affect it.
    let t0 = Instant::now();
    let probe = compile_text(path, &bench_deck(divisions, 1.0, opts.increments))?;
    let h_min = min_cell_edge(&probe);
    let penalty = 10.0 * YOUNG / h_min;
    let mut text = bench_deck(divisions, penalty, opts.increments);
    if !opts.predictor {
        let line = format!("  increments = {}\n", opts.increments);
        text = text.replace(&line, &format!("{line}  newton {{ predictor = false }}\n"));
    }
    let model = compile_text(path, &text)?;
    let compile_time = t0.elapsed().as_secs_f64() / 2.0;
    if let Some(out) = &opts.deck_out {
        std::fs::write(out, &text).map_err(|e| format!("cannot write {}: {e}", out.display()))?;
    }
    debug_assert!(matches!(
        model.contacts.first().map(|c| &c.method),
        Some(ctc_engine::model::ContactMethod::Penalty {
            kind: PenaltyKind::Area,
            ..
        })
    ));

    let mut capture = Capture::default();
    let cpu0 = ctc_engine::solve::memory::process_cpu_seconds();
    let t1 = Instant::now();
    let linear = (!opts.low_rank).then(|| {
        Box::new(
            ctc_engine::solve::linalg::direct::LinearSolver::new().with_low_rank(false, usize::MAX),
        ) as Box<dyn ctc_engine::solve::linalg::LinearSystem>
    });
    let outcome = run_with(&model, &mut capture, None, linear);
    let wall_time = t1.elapsed().as_secs_f64();
    let cpu_time = ctc_engine::solve::memory::process_cpu_seconds() - cpu0;
    let (summary, failure) = match outcome {
        Ok(s) => (s, None),
        Err(e) => (e.summary.clone(), Some(e.message)),
    };
    let accuracy = match capture.last.as_ref() {
        Some(state) => hertz_measure(
            &model,
            state,
            &HertzSetup::cylinder(YOUNG, 0.3, 1.0, 0, 0.0, false, Abscissa::Current),
        )
        .map(|m| m.values)
        .unwrap_or_default(),
        None => Vec::new(),
    };
    Ok(report_of(
        opts,
        divisions,
        &model,
        h_min,
        penalty,
        compile_time,
        (wall_time, cpu_time),
        summary,
        accuracy,
        failure,
    ))
}

/// Assembles the report.
#[allow(clippy::too_many_arguments)]
fn report_of(
    opts: &BenchOptions,
    divisions: [usize; 2],
    model: &Model,
    h_min: f64,
    penalty: f64,
    compile_time: f64,
    (wall_time, cpu_time): (f64, f64),
    summary: RunSummary,
    accuracy: Vec<Value>,
    failure: Option<String>,
) -> BenchReport {
    let its = summary.newton_iterations.max(1) as f64;
    let t = &summary.timings;
    let factorizations =
        (summary.cholesky_factorizations + summary.ldlt_factorizations + summary.lu_factorizations)
            .max(1) as f64;
    // full factorizations only (the low-rank updates are timed apart)
    let time_per_factorization = (t.factorization - t.low_rank) / factorizations;
    BenchReport {
        size: opts.size,
        divisions,
        nodes: model.mesh.nodes.len(),
        free_dofs: summary.free_dofs,
        h_min,
        penalty,
        increments: summary.increments.len(),
        iterations_per_increment: summary.increments.iter().map(|i| i.iterations).collect(),
        newton_iterations: summary.newton_iterations,
        cutbacks: summary.cutbacks,
        linear_solver: summary.linear_solver.clone(),
        matrix_nonzeros: summary.matrix_nonzeros,
        cholesky_factorizations: summary.cholesky_factorizations,
        ldlt_factorizations: summary.ldlt_factorizations,
        max_negative_pivots: summary.max_negative_pivots,
        lu_factorizations: summary.lu_factorizations,
        low_rank_updates: summary.low_rank_updates,
        compile_time,
        wall_time,
        cpu_time,
        wall_per_iteration: wall_time / its,
        time_per_factorization,
        iteration_over_factorization: wall_time / its / time_per_factorization.max(1e-300),
        predictor: opts.predictor,
        low_rank: opts.low_rank,
        threads: summary.threads,
        factor_nonzeros: summary.factor_nonzeros,
        factor_fill: summary.factor_fill,
        peak_memory_bytes: summary.peak_memory_bytes,
        per_iteration: PerIteration {
            assembly: t.assembly / its,
            contact: t.contact / its,
            factorization: t.factorization / its,
            solve: t.solve / its,
        },
        timings: summary.timings,
        accuracy,
        failure,
    }
}

impl BenchReport {
    /// Engine time outside the timed phases (the Newton loop's own work:
    /// predictor, state updates, line-search bookkeeping, observers' calls).
    pub fn other_time(&self) -> f64 {
        let t = &self.timings;
        t.total
            - (t.assembly + t.contact + t.factorization + t.solve + t.residual + t.setup + t.output)
    }

    /// Pretty JSON.
    pub fn to_json(&self) -> String {
        serde_json::to_string_pretty(self).unwrap_or_else(|e| format!("{{\"error\": \"{e}\"}}"))
    }
}

impl fmt::Display for BenchReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(
            f,
            "ctc bench: rigid cylinder into an elastic block (issue 3)"
        )?;
        writeln!(
            f,
            "  mesh           {} x {} quad4, {} nodes, {} free dofs, h_min {:.3e}",
            self.divisions[0], self.divisions[1], self.nodes, self.free_dofs, self.h_min
        )?;
        writeln!(
            f,
            "  penalty        area, 10 E / h_min = {:.3e}",
            self.penalty
        )?;
        writeln!(
            f,
            "  increments     {} converged, {} cutbacks; Newton iterations {} ({:?} per increment)",
            self.increments, self.cutbacks, self.newton_iterations, self.iterations_per_increment
        )?;
        writeln!(
            f,
            "  linear solver  {} ({} nonzeros; {} Cholesky, {} LDL^T (at most {} negative pivots), {} LU factorizations; {} low-rank updates)",
            self.linear_solver,
            self.matrix_nonzeros,
            self.cholesky_factorizations,
            self.ldlt_factorizations,
            self.max_negative_pivots,
            self.lu_factorizations,
            self.low_rank_updates
        )?;
        writeln!(
            f,
            "  factor         {} nonzeros, fill {:.2}; peak memory {:.1} MiB; predictor {}, low-rank {}; {} thread(s)",
            self.factor_nonzeros,
            self.factor_fill,
            self.peak_memory_bytes as f64 / (1u64 << 20) as f64,
            if self.predictor { "on" } else { "off" },
            if self.low_rank { "on" } else { "off" },
            self.threads
        )?;
        writeln!(f, "  compile        {:>9.3} s", self.compile_time)?;
        writeln!(
            f,
            "  solve (total)  {:>9.3} s wall, {:.3} s CPU",
            self.wall_time, self.cpu_time
        )?;
        writeln!(
            f,
            "  per iteration  {:>9.3} ms wall = {:.2} x one factorization ({:.3} ms)",
            1e3 * self.wall_per_iteration,
            self.iteration_over_factorization,
            1e3 * self.time_per_factorization
        )?;
        writeln!(
            f,
            "  {:<14} {:>10} {:>14} {:>7}",
            "phase", "total [s]", "per iter [ms]", "share"
        )?;
        let total = self.timings.total.max(1e-300);
        for (name, tot, per) in [
            (
                "assembly",
                self.timings.assembly,
                self.per_iteration.assembly,
            ),
            ("contact", self.timings.contact, self.per_iteration.contact),
            (
                "factorization",
                self.timings.factorization,
                self.per_iteration.factorization,
            ),
            (
                " low-rank part",
                self.timings.low_rank,
                self.timings.low_rank / self.newton_iterations.max(1) as f64,
            ),
            (" symbolic part", self.timings.symbolic, f64::NAN),
            ("solve", self.timings.solve, self.per_iteration.solve),
            (
                "residual",
                self.timings.residual,
                self.timings.residual / self.newton_iterations.max(1) as f64,
            ),
            ("setup", self.timings.setup, f64::NAN),
            ("output", self.timings.output, f64::NAN),
            ("other", self.other_time(), f64::NAN),
        ] {
            writeln!(
                f,
                "  {:<14} {:>10.3} {:>14} {:>6.1}%",
                name,
                tot,
                if per.is_nan() {
                    "-".to_string()
                } else {
                    format!("{:.3}", 1e3 * per)
                },
                100.0 * tot / total
            )?;
        }
        writeln!(f, "  {:<14} {:>10.3}", "engine total", self.timings.total)?;
        if !self.accuracy.is_empty() {
            let acc: Vec<String> = self
                .accuracy
                .iter()
                .map(|v| {
                    format!(
                        "{} {} (err {:.2e})",
                        v.quantity,
                        fmt_num(v.computed),
                        v.error
                    )
                })
                .collect();
            writeln!(f, "  vs Hertz       {}", acc.join(", "))?;
        }
        if let Some(e) = &self.failure {
            writeln!(f, "  FAILED: {e}")?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::refine::RefinableDeck;

    #[test]
    fn bench_deck_has_the_issue_parameters() {
        let d = bench_deck([282, 141], 1234.5, 4);
        assert!(d.contains("divisions = (282, 141)"));
        assert!(d.contains("grading = (center(20), geometric(0.05))"));
        assert!(d.contains("stiffness = 1.2345e3"));
        assert!(d.contains("uy = ramp(0, -0.02)"));
        assert!(d.contains("increments = 4"));
        // (2n + 1)(n + 1) nodes, 2 dofs each, about 80k dofs at full size.
        let dofs = 2 * 283 * 142;
        assert!((75_000..85_000).contains(&dofs));
        // The generated deck carries no refine marker.
        assert_eq!(RefinableDeck::parse(&d).unwrap().levels(), 1);
    }

    #[test]
    fn bench_rejects_bad_options() {
        let bad = BenchOptions {
            size: 0.0,
            ..BenchOptions::default()
        };
        assert!(run_bench(&bad).unwrap_err().contains("positive"));
    }
}
