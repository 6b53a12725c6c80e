//! VERIFICATION-CASES case 5, Cattaneo partial slip, as `ctc verify` runs
//! it: the registry entry `cattaneo_cylinders`
//! (`verification/src/programs/cattaneo.rs`, with the reference, sketch
//! and tolerances). Level 0 runs in the test; the refinement (`--ignored`,
//! release) runs levels 0-2.

use ctc_verification::registry;

fn run(max_level: usize) -> ctc_verification::report::CaseReport {
    let case = registry::find("cattaneo_cylinders").expect("registered");
    let report = case.run(
        &ctc_verification::default_cases_dir(),
        Some(max_level),
        &mut |l| eprintln!("{l}"),
    );
    for l in &report.levels {
        for v in &l.values {
            eprintln!(
                "level {}: {} = {:.4} (reference {:?}, error {:.1e}, tolerance {:?})",
                l.level, v.quantity, v.computed, v.reference, v.error, v.tolerance
            );
        }
    }
    report
}

#[test]
fn case5_cattaneo_stick_zone_level0() {
    let report = run(0);
    assert!(report.passed(), "{report:#?}");
}

#[test]
#[ignore = "mesh refinement (release: cargo test --release --test suite friction_cattaneo:: -- --ignored --nocapture)"]
fn case5_cattaneo_stick_zone_refinement() {
    let report = run(2);
    assert!(report.passed(), "{report:#?}");
    let e: Vec<f64> = report
        .levels
        .iter()
        .filter_map(|l| l.values.first().map(|v| v.error))
        .collect();
    assert!(e[2] < e[0], "{e:?}");
}
