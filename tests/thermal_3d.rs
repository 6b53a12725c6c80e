//! Heat and thermo-mechanics in 3D (issue 15) as `ctc verify` runs them:
//! the registry entries of `verification/src/programs/thermal_3d.rs`, which
//! open with their references and sketches (Incropera & DeWitt §3.1,
//! Carslaw & Jaeger §3.3, Timoshenko & Goodier §150, VERIFICATION-CASES.md
//! §8, Simo & Hughes §2.3), judged against their tolerances.
//!
//! ```text
//!   T0 +--------+ h, T_inf      brick on a hot/cold rigid plane tool:
//!      |  k     |               q = (T_hot - T_tool) / (L/k + 1/h(p))
//!      +--------+
//! ```

use ctc_verification::registry;

fn passes(name: &str) {
    let case = registry::find(name).unwrap_or_else(|| panic!("no case {name}"));
    let report = case.run(&ctc_verification::default_cases_dir(), None, &mut |l| {
        eprintln!("{l}")
    });
    for l in &report.levels {
        for v in &l.values {
            eprintln!(
                "{name} level {}: {} = {:.6e} (error {:.1e}, tolerance {:?})",
                l.level, v.quantity, v.computed, v.error, v.tolerance
            );
        }
    }
    assert!(report.passed(), "{report:#?}");
}

#[test]
fn steady_conduction_3d_is_exact_on_tet4_and_distorted_hex8() {
    passes("thermal_steady_3d");
}

#[test]
fn transient_conduction_3d_converges_to_the_slab_series() {
    passes("thermal_transient_3d");
}

#[test]
fn thermal_expansion_3d_free_and_held_bricks() {
    passes("thermal_expansion_3d");
}

#[test]
fn thermal_contact_with_a_3d_rigid_tool_matches_closed_form_and_2d() {
    passes("thermal_contact_tool_3d");
}

#[test]
fn adiabatic_heating_3d_matches_beta_w_and_the_axisymmetric_run() {
    passes("adiabatic_heating_3d");
}
