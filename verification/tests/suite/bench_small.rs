//! The issue-3 benchmark at a small size: it runs, converges, and its
//! report is consistent (the full ~80k-dof run is `ctc bench`).

use ctc_verification::{run_bench, BenchOptions};

#[test]
fn bench_rigid_cylinder_block_small_size_report_is_consistent() {
    let r = run_bench(&BenchOptions {
        size: 0.01,
        ..BenchOptions::default()
    })
    .expect("bench deck compiles");
    assert!(r.failure.is_none(), "{:?}", r.failure);
    assert_eq!(r.divisions, [28, 14]);
    assert_eq!(r.nodes, 29 * 15);
    assert_eq!(r.increments, 4);
    assert_eq!(r.iterations_per_increment.len(), 4);
    assert!(r.newton_iterations >= 4);
    // Penalty 10 E / h_min with h_min the shortest cell edge.
    assert!((r.penalty * r.h_min - 1e4).abs() < 1e-6 * 1e4);
    // Phase times are parts of the engine's total.
    let t = &r.timings;
    assert!(t.assembly + t.contact + t.factorization + t.solve <= t.total * 1.0001);
    let n = r.newton_iterations as f64;
    assert!((r.per_iteration.factorization * n - t.factorization).abs() < 1e-12);
    // The contact force balances the clamp reaction.
    let balance = r
        .accuracy
        .iter()
        .find(|v| v.quantity.name() == "contact force")
        .unwrap();
    assert!(balance.error < 1e-7, "{}", balance.error);
    let text = r.to_string();
    assert!(
        text.contains("factorization") && text.contains("per iter"),
        "{text}"
    );
    let json: serde_json::Value = serde_json::from_str(&r.to_json()).unwrap();
    assert_eq!(json["divisions"][0], 28);
}

/// The increment predictor (issue 20) moves only the first iterate of each
/// increment: the converged results agree with the plain start's to the
/// Newton tolerance (1e-8), in no more iterations.
#[test]
fn bench_predictor_keeps_results_and_saves_iterations() {
    let run = |predictor| {
        let r = run_bench(&BenchOptions {
            size: 0.01,
            predictor,
            ..BenchOptions::default()
        })
        .expect("bench deck compiles");
        assert!(r.failure.is_none(), "{:?}", r.failure);
        r
    };
    let (on, off) = (run(true), run(false));
    assert!(on.predictor && !off.predictor);
    assert!(
        on.newton_iterations <= off.newton_iterations,
        "predictor {:?} vs plain {:?}",
        on.iterations_per_increment,
        off.iterations_per_increment
    );
    // the first increment has no history, and its first touch closes too
    // few nodes for the first-touch rule (`predictor::first_touch_moves`,
    // 16): identical
    assert_eq!(
        on.iterations_per_increment[0],
        off.iterations_per_increment[0]
    );
    assert_eq!(on.accuracy.len(), off.accuracy.len());
    for (a, b) in on.accuracy.iter().zip(&off.accuracy) {
        assert_eq!(a.quantity.name(), b.quantity.name());
        let scale = a.computed.abs().max(b.computed.abs()).max(1e-12);
        assert!(
            (a.computed - b.computed).abs() <= 1e-6 * scale,
            "{}: {} vs {}",
            a.quantity.name(),
            a.computed,
            b.computed
        );
    }
}
