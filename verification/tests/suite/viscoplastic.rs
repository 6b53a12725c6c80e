//! Perzyna visco-plasticity (linear over-stress, `d ep/dt = <q - sigma_y> /
//! eta`) as `ctc verify` runs it: the registry entry
//! `perzyna_viscoplastic`, against closed forms: the over-stress at a
//! material point loaded in shear at two constant rates, `s(t) = eta r (1 -
//! exp(-3 G t / eta))`; relaxation at fixed strain with linear hardening,
//! `s(t) = s0 exp(-(3 G + H) t / eta)`; the axial force of one
//! axisymmetric quad compressed at two rates through the solver. Backward
//! Euler is first order in dt (halving dt halves the error: the observed
//! rate between the two levels and the order measured at each level).
//! Scene, references and tolerances:
//! `verification/src/programs/viscoplastic.rs` (Perzyna 1966; Simo &
//! Hughes §1.7).
//!
//! ```text
//!   q                      ___________ sigma_y + eta r  (steady over-stress)
//!   |                 ____/
//!   |     sigma_y ___/  s(t) = eta r (1 - exp(-t / tau))
//!   |           /
//!   +----------+----------------------------> t
//! ```

use ctc_verification::registry;

#[test]
fn perzyna_rates_relaxation_and_solver_match_closed_forms_first_order_in_dt() {
    let report = registry::run_passing("perzyna_viscoplastic");
    let judged: Vec<_> = report
        .rates
        .iter()
        .filter(|r| r.min_rate.is_some())
        .collect();
    assert_eq!(judged.len(), 5, "{:#?}", report.rates);
    for r in judged {
        println!(
            "{}: observed rate {:?} (>= {:?})",
            r.quantity, r.rate, r.min_rate
        );
        assert!(r.passed);
    }
    let level = report.levels.last().expect("a level");
    assert_eq!(level.values.len(), 7, "{:#?}", level.values);
}

/// Norton-Hoff (m = 1/2, no static yield) and the Perzyna power law (N =
/// 2): the `tanh` closed forms of constant-rate loading at a material
/// point, and the Kirchhoff stress of a finite-strain axisymmetric quad
/// compressed at a constant logarithmic rate through the solver; first
/// order in dt. Scene, references and tolerances:
/// `verification/src/programs/norton_hoff.rs`.
///
/// ```text
///   s                 ______________ s_ss = sigma0 (r / r0)^m
///   |            ____/
///   |        _-'     s(t) = s_ss tanh(M r t / s_ss)
///   +-----+----------------------------> t
/// ```
#[test]
fn norton_hoff_and_perzyna_power_match_the_tanh_closed_forms_first_order_in_dt() {
    let report = registry::run_passing("norton_hoff_rate");
    for l in &report.levels {
        for v in &l.values {
            println!("level {}: {} = {:.3e}", l.level, v.quantity, v.error);
        }
    }
    let judged: Vec<_> = report
        .rates
        .iter()
        .filter(|r| r.min_rate.is_some())
        .collect();
    assert_eq!(judged.len(), 5, "{:#?}", report.rates);
    for r in judged {
        println!("{}: observed rate {:?}", r.quantity, r.rate);
        assert!(r.passed);
    }
}

/// The pressure-cycle controller holds the target strain rate of a
/// Norton-Hoff cylinder (axisymmetric) and block (3D) under a follower
/// pressure; the steady pressure is the closed form `p* = |tau| exp((1 - 2
/// nu) |tau| / E)`, `tau = sigma0 (r* / r0)^m`. Scene, references and
/// tolerances: `verification/src/programs/pressure_control.rs`.
///
/// ```text
///      p(t) controlled
///    vvvvvvvvvv
///   +----------+  rate -> r* = 1e-2, p -> p* = 158.1639
///   +----------+
/// ```
#[test]
fn the_pressure_controller_holds_the_target_rate_at_the_closed_form_pressure() {
    let report = registry::run_passing("pressure_cycle_control");
    for l in &report.levels {
        for v in &l.values {
            println!("{} = {:.3e}", v.quantity, v.computed);
        }
    }
}

/// Free bulging of a clamped Norton-Hoff diaphragm under the pressure-cycle
/// controller watching the pole (`ctc verify superplastic_free_bulge`):
/// the pole's membrane equilibrium `p = 2 sigma s / rho`, the pole rate held
/// at the target, the pole thickness between Hill's (1950) and the uniform
/// cap's, and on Hill's curve for a nearly rate-insensitive sheet.
/// Sources: R. Hill, Phil. Mag. 41 (1950) 1133; F. Jovane, Int. J. Mech.
/// Sci. 10 (1968) 403.
///
/// ```text
///         .-~~~~~~~~~~-.        pole: s, rho, rate = r*
///   ===|==================|===  clamped at r = 50
///       ^  ^  ^  ^  ^  ^  p(t) controlled
/// ```
#[test]
fn a_free_bulge_under_the_pole_rate_controller_satisfies_the_membrane_relations() {
    let report = registry::run_passing("superplastic_free_bulge");
    for l in &report.levels {
        for v in &l.values {
            println!("{} = {:.3e}", v.quantity, v.computed);
        }
    }
}
