//! End-to-end verification: every case of the catalogue on its default
//! levels, as `ctc verify` runs it (Hertz a and p0 within 2 %, rates), each
//! level judged with its own tolerances; the coarsest level's figures are
//! an insta snapshot (rounded: values to 4 significant digits, `~0` below
//! 1e-12, errors below 1e-9 as round-off), so a result that moves shows in
//! review; and the written report (plots, report.md, report.json) of the
//! same run. The cases whose level 0 the `ctc` crate's tests run
//! (`registry::RUN_BY_THE_CTC_SUITE`: the blade-loss flights, shared there
//! with the examples test) are left out here. The cases run once for the
//! whole suite binary
//! (`registry::run_default`): the tests of single cases share these runs.
//! Review a snapshot change with `cargo insta review` and say why in the
//! commit.

use crate::fenicsx_snapshots::{err2, sig4};
use ctc_verification::{registry, run, write_report_dir, VerifyOptions};

#[test]
fn verification_catalogue_on_default_levels() {
    // the cases whose default level the ctc crate's tests run
    // (`tests/suite/blade_loss*.rs`, with the examples test)
    let exclude: Vec<String> = registry::RUN_BY_THE_CTC_SUITE
        .iter()
        .map(|n| n.to_string())
        .collect();
    for name in &exclude {
        assert!(registry::find(name).is_some(), "no case {name}");
    }
    let report = run(&VerifyOptions {
        progress: true,
        exclude: exclude.clone(),
        ..VerifyOptions::default()
    })
    .expect("verification runs");
    println!("{}", report.table());
    assert_eq!(report.cases.len() + exclude.len(), registry::all().len());
    assert!(
        report.passed(),
        "failures:\n{}",
        report.failures().join("\n")
    );
    let dir = tempfile::tempdir().unwrap();
    write_report_dir(&report, dir.path()).expect("the report is written");
    assert!(dir.path().join("report.md").is_file());
    assert!(dir.path().join("report.json").is_file());
    let mut lines = Vec::new();
    for c in &report.cases {
        let l = &c.levels[0];
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
    insta::assert_snapshot!("verification_coarsest_level", lines.join("\n"));
}

#[test]
fn verification_filter_selects_cases() {
    let report = run(&VerifyOptions {
        filter: Some("no_such_case".into()),
        ..VerifyOptions::default()
    })
    .unwrap();
    assert!(report.cases.is_empty());
    assert!(!report.passed(), "an empty selection must not pass");
    let missing = run(&VerifyOptions {
        cases_dir: Some("/definitely/not/here".into()),
        ..VerifyOptions::default()
    });
    assert!(missing.unwrap_err().contains("does not exist"));
}
