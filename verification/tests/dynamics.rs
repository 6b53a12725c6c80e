//! Implicit dynamics without contact as `ctc verify --tag dynamics` runs
//! it: the registry entries `newmark_energy_cantilever` (average-
//! acceleration Newmark conserves the energy of a free-vibrating elastic
//! cantilever to round-off per step; Hughes 2000, section 9.3.2) and
//! `generalized_alpha_period_damping` (period elongation and damping ratio
//! of generalized-alpha at three dt vs Chung & Hulbert 1993, eqs. 16-20).
//! Scenes, references and tolerances:
//! `verification/src/programs/dynamics.rs`.
//!
//! ```text
//!   |>=========================  v0 (uy)        |>[ ]--> vx = 1
//! ```

use ctc_verification::registry;

#[test]
fn newmark_energy_cantilever() {
    let report = registry::run_passing("newmark_energy_cantilever");
    // energy drift and balance error, consistent and lumped mass
    assert_eq!(report.levels[0].values.len(), 4, "consistent and lumped");
}

#[test]
fn generalized_alpha_period_damping() {
    let report = registry::run_passing("generalized_alpha_period_damping");
    assert_eq!(report.levels.len(), 3, "dt = T/10, T/20, T/40");
}
