//! VERIFICATION-CASES case 4 (NAFEMS CGS-4; Wriggers, Computational Contact
//! Mechanics §5.2) as `ctc verify` runs it: the registry entries
//! `friction_inclined_plane` (F/G = (tan a + mu) / (1 - mu tan a) for four
//! normal methods and mu = 0 .. 0.3), `friction_stick_slip` (stick below
//! mu N, no equilibrium above, work = mu N slip), `friction_alpha_t`
//! (creep = Q / alpha_T) and `friction_impact_cut` (increment cut at the
//! constant-velocity impact t = 0.325). Scene, sketch, references and
//! tolerances: `verification/src/programs/friction.rs` and
//! `friction_block.rs`.
//!
//! ```text
//!          N (weight or squeeze)
//!        +-----------+
//!  Q  -> |   block   |
//!        +-----------+
//!   ////// plane, tan(alpha) = 0.1 (or 0) //////
//! ```

use ctc_verification::programs::friction::{alpha_t_rows, inclined_reference};
use ctc_verification::registry;

/// Runs the registry entry `name` (it must pass) and asserts every listed
/// quantity was measured.
fn passes(name: &str, measured: &[&str]) {
    let report = registry::run_passing(name);
    let level = report.levels.last().expect("one level");
    for q in measured {
        assert!(
            level.values.iter().any(|v| v.quantity.to_string() == *q),
            "{name} does not measure {q}"
        );
    }
}

#[test]
fn case4_inclined_plane_slip_threshold_all_methods() {
    passes(
        "friction_inclined_plane",
        &[
            "F/G penalty (weight)",
            "F/G penalty (squeeze)",
            "F/G augmented Lagrangian",
            "F/G Lagrange",
            "F/G at mu = 0.3 vs 0.412371",
        ],
    );
    assert!((inclined_reference(0.3) - 0.412371).abs() < 5e-7);
}

#[test]
fn pulled_block_sticks_below_slides_above_and_friction_work_is_mu_n_slip() {
    passes(
        "friction_stick_slip",
        &[
            "Q < mu N: nodes not sticking",
            "Q < mu N: |sum R_T + Q| / Q",
            "Q < mu N: friction work",
            "Q > mu N: run refused with a diagnosis",
            "rigid pull: run work / (mu N slip) - 1",
            "shear pull, Lagrange: work / (mu N slip) - 1",
        ],
    );
}

#[test]
fn alpha_t_error_and_iterations() {
    passes(
        "friction_alpha_t",
        &[
            "creep vs Q / alpha_T",
            "creep x alpha_T constant",
            "F/G at every alpha_T",
            "Lagrange stick creep",
        ],
    );
    // the study's table (run with --nocapture)
    println!(
        "| alpha_T / alpha_N | stick creep | creep x alpha_T | F/G error | Newton iterations |"
    );
    println!("| --- | --- | --- | --- | --- |");
    for r in alpha_t_rows().unwrap() {
        println!(
            "| {:.0e} | {:.3e} | {:.4e} | {:.1e} | {} |",
            r.ratio,
            r.creep,
            r.creep * r.ratio * 1e7,
            r.threshold_error,
            r.newton
        );
    }
}

#[test]
fn increment_is_cut_at_the_first_impact() {
    passes(
        "friction_impact_cut",
        &[
            "first accepted time vs impact 0.325",
            "cut: at least one cutback",
            "no cut: first increment whole, no cutback",
        ],
    );
}
