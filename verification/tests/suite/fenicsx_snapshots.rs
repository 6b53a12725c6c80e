//! Snapshot regression (issue 9): rounded summaries of the ctc-vs-FEniCSx
//! runs (the catalogue's coarsest levels: `cases_coarse.rs`). Values
//! are rounded to 4 significant digits (below 1e-12: `~0`) and errors
//! below 1e-9 are written as round-off, so a snapshot changes only when a
//! result really changes; the numbers are also checked with explicit
//! tolerances (here and in
//! `cases_coarse.rs`, `fenicsx.rs`). Review a change with `cargo insta
//! review` (or `INSTA_UPDATE=always`) and say why in the commit.

use ctc_verification::fenicsx::{cases, compare_case, crate_dir, reference_dir, TOLERANCE};

/// `x` with 4 significant digits; `~0` below 1e-12 in magnitude (values
/// that are round-off, e.g. a patch test's displacement error).
pub(crate) fn sig4(x: f64) -> String {
    if x.abs() < 1e-12 {
        return "~0".into();
    }
    if !x.is_finite() {
        return format!("{x}");
    }
    format!("{x:.3e}")
}

/// An error: 2 significant digits, or `round-off` below 1e-9.
pub(crate) fn err2(e: f64) -> String {
    if e.abs() < 1e-9 {
        "round-off".into()
    } else {
        format!("{e:.1e}")
    }
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
