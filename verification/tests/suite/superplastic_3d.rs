//! Superplastic forming in 3D before the die (`ctc verify
//! superplastic_forming_3d`): a quarter of a clamped circular Norton-Hoff
//! sheet (m = 0.5, hex8 F-bar) blown under the pole-rate controller with
//! the IGES die of `examples/superplastic_forming_3d.ctc` in place; before
//! the first die contact, the pole's membrane equilibrium `p = 2 sigma s /
//! rho`, the controlled pole rate, the pole thickness between Hill's (1950)
//! and the uniform cap's, and the axisymmetric run of the same sheet at
//! equal pole height. Sources: R. Hill, Phil. Mag. 41 (1950) 1133; F.
//! Jovane, Int. J. Mech. Sci. 10 (1968) 403.
//!
//! ```text
//!   21 |____________________.      die bottom (IGES)
//!      |    .-~~~~~~~~-.      \    free bulge: h, s, rho
//!    1 |===|==============|====\   clamped at r = 50
//!          ^  ^  ^  ^  ^  p(t) controlled (pole rate 1e-3 /s)
//! ```

use ctc_verification::registry;

#[test]
fn the_3d_sheet_bulges_freely_until_the_die_as_the_membrane_and_axisymmetric_runs() {
    let report = registry::run_passing("superplastic_forming_3d");
    let level = &report.levels[0];
    let value = |prefix: &str| {
        level
            .values
            .iter()
            .find(|v| v.quantity.to_string().starts_with(prefix))
            .unwrap_or_else(|| panic!("no value `{prefix}`"))
            .computed
    };
    // the pole reaches the die's bottom (20 above the sheet's top) first
    let h = value("pole height h/a at the first die contact");
    assert!(h > 0.38 && h < 0.42, "first contact at h/a = {h}");
}
