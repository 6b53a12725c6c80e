//! The reduced stress matrix: every cell converges to the right answer or
//! stops with a diagnosis; never NaN, never a panic.

#[test]
fn reduced_stress_matrix_meets_every_expectation() {
    let report = ctc_verification::run_stress(true);
    println!("{}", report.table());
    assert!(report.cells.len() >= 6);
    for c in &report.cells {
        assert!(
            c.diagnosis
                .as_deref()
                .is_none_or(|d| !d.starts_with("PANIC")),
            "{} {} panicked",
            c.family,
            c.value
        );
        if c.converged {
            assert!(
                c.balance.is_finite(),
                "{} {}: non-finite",
                c.family,
                c.value
            );
        }
    }
    assert!(report.passed(), "{}", report.table());
}

#[test]
fn release_cell_returns_to_the_undeformed_state() {
    let release = ctc_verification::stress::cases(true)
        .into_iter()
        .find(|c| c.family == "release")
        .expect("release cell");
    let r = ctc_verification::stress::run_case(&release);
    assert!(r.converged, "{:?}", r.diagnosis);
    assert!(
        r.error.unwrap() <= 1e-9,
        "max |u| after release {:?}",
        r.error
    );
    assert!(r.worst_penetration > 0.0, "the tool never touched");
}
