//! End-to-end verification: every case of the catalogue at its coarsest
//! level (the decks as written), judged with the level-0 tolerances (well
//! under a second); and every default level with the finest tolerances
//! (Hertz a and p0 within 2 %, rates), as `ctc verify` runs it (about 15 s
//! at the dev profile, most of it the 33k-dof finest rigid-cylinder level).

use ctc_verification::{run, VerifyOptions};

#[test]
fn verification_cases_coarsest_level() {
    let report = run(&VerifyOptions {
        max_level: Some(0),
        ..VerifyOptions::default()
    })
    .expect("verification runs");
    println!("{}", report.table());
    assert_eq!(report.cases.len(), ctc_verification::registry::all().len());
    assert!(
        report.passed(),
        "failures:\n{}",
        report.failures().join("\n")
    );
}

#[test]
fn verification_cases_all_default_levels_hertz_within_2_percent() {
    let dir = tempfile::tempdir().unwrap();
    let report = run(&VerifyOptions {
        report_dir: Some(dir.path().to_path_buf()),
        progress: true,
        ..VerifyOptions::default()
    })
    .expect("verification runs");
    println!("{}", report.table());
    assert!(dir.path().join("report.md").is_file());
    assert!(
        report.passed(),
        "failures:\n{}",
        report.failures().join("\n")
    );
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
