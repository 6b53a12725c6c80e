//! VERIFICATION-CASES case 6, upsetting of an axisymmetric J2 cylinder by a
//! rigid flat die, as `ctc verify` runs it: the registry entries
//! `upsetting_linear`, `upsetting_swift`, `upsetting_voce_fbar` (finite
//! strain, frictionless, 50 % reduction, against the exact force of the
//! model, the case-6 formula and the rigid-plastic formula) and
//! `upsetting_small_strain` (1 % compression against the uniaxial closed
//! form). Scene, references and tolerances:
//! `verification/src/programs/upsetting.rs` (Simo & Hughes §9, §2.2).
//!
//! ```text
//!        die (rigid plane, moves down)
//!   ===============
//!   |  J2 billet  |  r0 = 1, h0/2 = 0.5
//!   +-------------+  u_z = 0 (symmetry), u_r = 0 on the axis
//! ```

use ctc_verification::registry;
use ctc_verification::report::CaseReport;

/// Runs the registry entry `name` (it must pass its own tolerances) and
/// asserts that each `quantity` was measured and is within its `bound`.
fn passes(name: &str, bounds: &[(&str, f64)]) -> CaseReport {
    let report = registry::run_passing(name);
    let level = report.levels.last().expect("one level");
    for (quantity, bound) in bounds {
        let v = level
            .values
            .iter()
            .find(|v| v.quantity.to_string() == *quantity)
            .unwrap_or_else(|| panic!("{name} does not measure {quantity}"));
        assert!(v.error < *bound, "{name}: {quantity} error {}", v.error);
    }
    report
}

#[test]
fn upsetting_frictionless_linear_hardening_matches_closed_form() {
    passes(
        "upsetting_linear",
        &[
            ("F vs exact (Kirchhoff yield)", 1e-6),
            ("F vs case 6 (Cauchy yield)", 3e-3),
            ("F vs rigid-plastic", 1e-2),
            ("final h / h0", 1e-3),
        ],
    );
}

#[test]
fn upsetting_frictionless_swift_hardening_matches_closed_form() {
    passes(
        "upsetting_swift",
        &[
            ("F vs exact (Kirchhoff yield)", 1e-6),
            ("F vs case 6 (Cauchy yield)", 3e-3),
            ("F vs rigid-plastic", 1e-2),
        ],
    );
}

#[test]
fn upsetting_frictionless_fbar_voce_matches_closed_form() {
    // F-bar quads (unsymmetric exact tangent, LU) and Voce hardening
    let report = passes(
        "upsetting_voce_fbar",
        &[
            ("F vs exact (Kirchhoff yield)", 1e-6),
            ("F vs case 6 (Cauchy yield)", 3e-3),
            ("F vs rigid-plastic", 2e-2),
        ],
    );
    let newton_max = report.levels[0].newton_max;
    assert!(newton_max <= 8, "Newton iterations {newton_max}");
}

#[test]
fn upsetting_small_strain_j2_linear_hardening_matches_uniaxial_closed_form() {
    passes(
        "upsetting_small_strain",
        &[("F vs uniaxial closed form", 1e-6), ("final h / h0", 1e-6)],
    );
}
