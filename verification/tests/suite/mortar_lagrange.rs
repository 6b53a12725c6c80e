//! Mortar contact with Lagrange multipliers (issue 18): the full
//! linearization of the constraint row and the semi-smooth Newton active
//! set, seen in the residual history of a run.
//!
//! Source: the deck `verification/cases/hertz_two_cylinders_mortar.ctc`
//! (Hertz, two elastic cylinders on non-matching arcs; K. L. Johnson,
//! Contact Mechanics (1985) §4.3) at its coarsest level with `method =
//! lagrange`, as `ctc verify hertz_two_cylinders_mortar_lagrange` runs it.
//! Method: Popp, Gee & Wall, IJNME 79 (2009) 1354 (dual mortar, full
//! linearization, semi-smooth Newton: one Newton loop per increment,
//! quadratic convergence); Hüeber & Wohlmuth, CMAME 194 (2005) 3147.
//!
//! ```text
//!          |  top quarter cylinder R = 1, flat pushed down 0.02 in 5 increments
//!   -------+---- slave top.arc -> master bottom.arc (mortar, Lagrange)
//!          |  bottom quarter cylinder R = 1, flat fixed
//! ```
//!
//! Before (the row `B / A` with `D`, `M`, `n` held fixed, the active set
//! an outer loop): 26 Newton iterations in 9 Newton loops, e.g. increment
//! 2 ending 1.1e-7, 7.8e-11 (linear); now 18 in 5 loops, each ending
//! quadratically (e.g. 1.1e-7 -> 2.8e-14).

use ctc_engine::solve::{run, IterationInfo, Observer};
use ctc_verification::programs::{compile, read_case_deck};

/// `v` as `[1.234e-5, ..]`.
fn show(v: &[f64]) -> String {
    let items: Vec<String> = v.iter().map(|x| format!("{x:.3e}")).collect();
    format!("[{}]", items.join(", "))
}

/// The residuals of every Newton loop (a loop starts at iteration 1).
#[derive(Default)]
struct Loops(Vec<Vec<f64>>);

impl Observer for Loops {
    fn iteration(&mut self, info: &IterationInfo) {
        if info.iteration == 1 {
            self.0.push(Vec::new());
        }
        if let Some(l) = self.0.last_mut() {
            l.push(info.residual);
        }
    }
}

#[test]
fn semismooth_newton_one_loop_per_increment_ending_quadratically() {
    let saddle = semismooth_loops("lagrange");
    // the multipliers condensed out (`formulation = condensed`): the same
    // Newton iterates, so the same loops and iterations, residuals equal
    // but for round-off
    let condensed = semismooth_loops("lagrange { formulation = condensed }");
    let lengths = |l: &[Vec<f64>]| l.iter().map(Vec::len).collect::<Vec<_>>();
    assert_eq!(lengths(&condensed), lengths(&saddle));
    let worst = condensed
        .iter()
        .flatten()
        .zip(saddle.iter().flatten())
        .map(|(c, s)| (c - s).abs() / s.abs().max(1e-6))
        .fold(0.0, f64::max);
    println!("residuals condensed vs saddle: {worst:.2e} (relative, floor 1e-6)");
    for (c, s) in condensed.iter().flatten().zip(saddle.iter().flatten()) {
        assert!(
            (c - s).abs() <= 1e-6 * s.abs() + 1e-12,
            "condensed {c:.6e} vs saddle {s:.6e}"
        );
    }
}

/// The residuals of every Newton loop of the Hertz deck with `method`.
fn semismooth_loops(method: &str) -> Vec<Vec<f64>> {
    let (path, text) = read_case_deck("hertz_two_cylinders_mortar.ctc").unwrap();
    let penalty = "penalty { kind = area  stiffness = 1e7 }";
    assert_eq!(text.matches(penalty).count(), 1);
    let model = compile(&path, &text.replace(penalty, method)).unwrap();
    let mut loops = Loops::default();
    let s = run(&model, &mut loops).unwrap();
    assert!(s.completed);
    println!(
        "{} increments, {} iterations",
        s.increments.len(),
        s.newton_iterations
    );
    for l in &loops.0 {
        println!("{}", show(l));
    }
    // no outer active-set loop: one Newton loop per increment
    assert_eq!(loops.0.len(), s.increments.len(), "{:?}", loops.0);
    assert_eq!(s.cutbacks, 0);
    // each loop's last step is quadratic (or reaches the round-off floor)
    for l in &loops.0 {
        let [.., prev, last] = l[..] else {
            continue;
        };
        assert!(
            last <= (100.0 * prev * prev).max(1e-12),
            "{prev:.3e} -> {last:.3e} is not quadratic: {}",
            show(l)
        );
    }
    loops.0
}

/// No output.
struct Quiet;
impl Observer for Quiet {}

/// Cost of the condensed dual multipliers (`lagrange { formulation =
/// condensed }`) against the saddle point on the Hertz deck of
/// `ctc verify hertz_two_cylinders_mortar_condensed`, levels 1-3: free
/// dofs, order and entries of the largest factorized matrix, Newton
/// iterations, CPU of the factorizations (assembly of the system
/// included) and of the solves, process CPU, and the asymmetry `|A -
/// A^T|_F / |A|_F` of the last condensed matrix. The two paths take the
/// same iterations (asserted). Measurement (level 3: ~10 s CPU in debug):
/// `cargo test -p ctc-verification --test suite -- --ignored
/// condensed_vs_saddle_point_cost --nocapture`.
#[test]
#[ignore = "measurement, ~10 s CPU in debug"]
fn condensed_vs_saddle_point_cost() {
    use ctc_engine::solve::memory::process_cpu_seconds;
    use ctc_verification::programs::mortar::hertz_deck;
    use ctc_verification::programs::mortar_condensed::{CONDENSED, SADDLE};
    println!("| level | method | free dofs | order (entries) | Newton | factorize CPU [s] | solve CPU [s] | process CPU [s] | asymmetry |");
    println!("| --- | --- | --- | --- | --- | --- | --- | --- | --- |");
    for level in 1..=3 {
        let mut iterations = Vec::new();
        for method in [SADDLE, CONDENSED] {
            let (path, text) = hertz_deck(level, method).unwrap();
            let model = compile(&path, &text).unwrap();
            let cpu = process_cpu_seconds();
            let s = run(&model, &mut Quiet).unwrap();
            let cpu = process_cpu_seconds() - cpu;
            assert!(s.completed);
            iterations.push(s.newton_iterations);
            println!(
                "| {level} | {method} | {} | {} ({}) | {} | {:.3} | {:.3} | {cpu:.3} | {} |",
                s.free_dofs,
                s.saddle_system.0,
                s.saddle_system.1,
                s.newton_iterations,
                s.timings.cpu[2],
                s.timings.cpu[3],
                s.saddle_asymmetry
                    .map_or("-".to_string(), |a| format!("{a:.2e}")),
            );
        }
        assert_eq!(iterations[0], iterations[1], "level {level}");
    }
}
