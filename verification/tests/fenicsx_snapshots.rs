//! Snapshot regression (issue 9): rounded summaries of the verification
//! cases at their coarsest level and of the ctc-vs-FEniCSx runs. Values
//! are rounded to 4 significant digits (below 1e-12: `~0`) and errors
//! below 1e-9 are written as round-off, so a snapshot changes only when a
//! result really changes; the numbers are also checked with explicit
//! tolerances (here and in
//! `cases_coarse.rs`, `fenicsx.rs`). Review a change with `cargo insta
//! review` (or `INSTA_UPDATE=always`) and say why in the commit.

use ctc_verification::fenicsx::{cases, compare_case, crate_dir, reference_dir, TOLERANCE};
use ctc_verification::{run, VerifyOptions};

/// `x` with 4 significant digits; `~0` below 1e-12 in magnitude (values
/// that are round-off, e.g. a patch test's displacement error).
fn sig4(x: f64) -> String {
    if x.abs() < 1e-12 {
        return "~0".into();
    }
    if !x.is_finite() {
        return format!("{x}");
    }
    format!("{x:.3e}")
}

/// An error: 2 significant digits, or `round-off` below 1e-9.
fn err2(e: f64) -> String {
    if e.abs() < 1e-9 {
        "round-off".into()
    } else {
        format!("{e:.1e}")
    }
}

#[test]
fn snapshot_verification_cases_coarsest_level() {
    let report = run(&VerifyOptions {
        max_level: Some(0),
        ..VerifyOptions::default()
    })
    .expect("verification runs");
    assert!(report.passed(), "{}", report.failures().join("\n"));
    let mut lines = Vec::new();
    for c in &report.cases {
        for l in &c.levels {
            lines.push(format!(
                "{} level {}: {} nodes, {} free dofs, {} increments, {} Newton iterations, {} cutbacks",
                c.name, l.level, l.nodes, l.free_dofs, l.increments, l.newton_total, l.cutbacks
            ));
            for v in &l.values {
                assert!(v.error.is_finite() && v.tolerance.is_none_or(|t| v.error <= t));
                lines.push(format!(
                    "  {:?}: computed {} reference {} error {}",
                    v.quantity,
                    sig4(v.computed),
                    v.reference.map_or("-".into(), sig4),
                    err2(v.error)
                ));
            }
        }
    }
    insta::assert_snapshot!("verification_coarsest_level", lines.join("\n"));
}

#[test]
fn snapshot_fenicsx_comparisons() {
    let mut lines = Vec::new();
    for case in cases() {
        let cmp = compare_case(&case, &crate_dir(), &reference_dir()).unwrap();
        assert!(cmp.within(TOLERANCE), "{cmp:#?}");
        lines.push(format!(
            "{}: {} nodes, Newton ctc {} FEniCSx {}, contact force y ctc {} FEniCSx {}, agree to 1e-6: {}",
            cmp.case,
            cmp.nodes,
            cmp.ctc_iterations,
            cmp.ref_iterations,
            cmp.ctc_force_y.map_or("-".into(), sig4),
            cmp.ref_force_y.map_or("-".into(), sig4),
            cmp.within(TOLERANCE)
        ));
    }
    insta::assert_snapshot!("fenicsx_comparisons", lines.join("\n"));
}

#[test]
fn snapshot_rounding_is_stable() {
    assert_eq!(sig4(1.23456e-3), "1.235e-3");
    assert_eq!(sig4(0.0), "~0");
    assert_eq!(sig4(2.7e-16), "~0");
    assert_eq!(err2(3e-12), "round-off");
    assert_eq!(err2(0.0123), "1.2e-2");
}
