//! Implicit dynamics as `ctc verify --tag dynamics` runs
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

/// Rayleigh damping (Chopra 2012, sections 2.2 and 11.4): one mode with
/// zeta = alpha / (2 w) + beta w / 2 = 0.05, the logarithmic decrement
/// and damped period at three dt, the dissipation in the energy audit.
///
/// ```text
///   |>[ ]--> vx = 1     x(t) = A exp(-zeta w t) sin(w_d t)
/// ```
#[test]
fn rayleigh_damping_decrement() {
    let report = registry::run_passing("rayleigh_damping_decrement");
    assert_eq!(report.levels.len(), 3, "dt = T/25, T/50, T/100");
}

#[test]
fn generalized_alpha_period_damping() {
    let report = registry::run_passing("generalized_alpha_period_damping");
    assert_eq!(report.levels.len(), 3, "dt = T/10, T/20, T/40");
}

/// Elastic bars in impact (Graff 1975, section 1.4): a bar on a rigid wall
/// in 2D and 3D and two bars colliding, with the contact nodes' mass
/// redistributed (Khenous, Laborde & Renard 2008); scenes and tolerances in
/// `verification/src/programs/impact.rs`.
///
/// ```text
///   wall |<- [==== bar ====] v0          [== a ==]-> v0  v0 <-[== b ==]
/// ```
#[test]
fn bar_impact_wave_theory() {
    let report = registry::run_passing("bar_impact_wave_theory");
    let values = &report.levels[0].values;
    assert_eq!(values.len(), 18, "three scenes, six values each");
    // the full mass without the energy control chatters and creates
    // energy: the redistribution removes it; the energy control (the
    // default) alone cuts it tenfold or more
    for scene in values.chunks(6) {
        assert!(scene[4].computed > 100.0 * scene[3].computed, "{scene:?}");
        assert!(scene[5].computed < 0.1 * scene[4].computed, "{scene:?}");
    }
}

/// Adaptive time stepping (Zienkiewicz & Xie 1991, Earthquake Eng.
/// Struct. Dyn. 20:871; 1D wave theory, Graff 1975, section 1.4): the
/// quad4 bar on the wall reaches the contact duration 2L/c, the rebound
/// speed v0 and the energy of the fixed-dt run with fewer increments
/// (`verification/src/programs/impact.rs`).
///
/// ```text
///   wall |<- [==== bar ====] v0      dt: small in contact, large in flight
/// ```
#[test]
fn bar_impact_adaptive() {
    let report = registry::run_passing("bar_impact_adaptive");
    let values = &report.levels[0].values;
    // fewer increments than the fixed run, as accurate as it within 2e-3
    assert!(values[3].computed < 0.9, "{values:?}");
    for (a, f) in values[..2].iter().zip(&values[4..6]) {
        assert!(a.computed <= f.computed + 2e-3, "{a:?} {f:?}");
    }
}

/// Discrete elements (Hughes 2000, section 9.3.2; Chopra 2012, section
/// 2.2): a point mass on a spring to the ground, its period at three dt,
/// and with a dashpot its logarithmic decrement and energy balance
/// (`verification/src/programs/discrete.rs`).
///
/// ```text
///   |/\/\/\[ m ] --> v0        |--[=]-[ m ]
/// ```
#[test]
fn spring_mass_oscillator_period() {
    let report = registry::run_passing("spring_mass_oscillator_period");
    assert_eq!(report.levels.len(), 3, "dt = T/20, T/40, T/80");
}

#[test]
fn dashpot_decrement() {
    let report = registry::run_passing("dashpot_decrement");
    assert_eq!(report.levels.len(), 3, "dt = T/20, T/40, T/80");
}

/// Gravity (`verification/src/programs/gravity.rs`): a column under its
/// own weight, quasi-static, in plane strain, axisymmetric and 3D (Timoshenko
/// & Gere 1997, section 2.3: the top moves by rho g L^2 / (2 E), the base
/// carries rho g V), and a mass on a spring dropped onto a rigid floor
/// (free fall, a shifted half sine in contact, rebound at the impact speed)
/// at three dt.
///
/// ```text
///    +--+ u = -rho g L^2/(2E)        [ M ]
///    |  |  | g                       |/\/|  | g
///    +--+  v                         +---+  v
///   /////                        ==============
/// ```
#[test]
fn self_weight_column() {
    let report = registry::run_passing("self_weight_column");
    assert_eq!(
        report.levels[0].values.len(),
        6,
        "three analyses, two values"
    );
}

#[test]
fn mass_spring_bounce_gravity() {
    let report = registry::run_passing("mass_spring_bounce_gravity");
    assert_eq!(report.levels.len(), 3, "dt = 0.005, 0.0025, 0.00125");
    // the trajectory error falls with dt
    let t: Vec<f64> = report.levels.iter().map(|l| l.values[0].error).collect();
    assert!(t[2] < t[1] && t[1] < t[0], "{t:?}");
}

/// Two masses linked by a spring (and a dashpot) between their nodes
/// (Thomson & Dahleh 1998, section 5.1): the relative period at three dt,
/// momentum and energy conserved, the dashpot's damping ratio and
/// dissipation (`verification/src/programs/discrete.rs`).
///
/// ```text
///   [ m1 ]-/\/\/\-[ m2 ]     omega = sqrt(k (m1 + m2) / (m1 m2))
///         --[=]--
/// ```
#[test]
fn two_mass_oscillator() {
    let report = registry::run_passing("two_mass_oscillator");
    assert_eq!(report.levels.len(), 3, "dt = T/20, T/40, T/80");
}

/// The energy audit under generalized-alpha (rho_inf = 0.9): a block
/// bouncing on a penalty floor and a block sliding to rest with Coulomb
/// friction; the scheme's numerical dissipation is its own term, so the
/// audit's error is the Newton residual's work; the contact forces' and
/// the friction forces' work vs K0 (the engine's `friction_work`, the
/// audit's trapezoidal rule, judged: the return map's force at the end
/// gave 0.960 of K0), the return map's `-T_1 . slip` vs `sum mu R_N
/// |slip|`, distance vs `v0^2 / (2 mu g)`
/// (`verification/src/programs/energy_audit.rs`).
///
/// ```text
///     [ ]  h0 | g          [block] -> v0, mu
///   ==========  floor     ==================== floor
/// ```
#[test]
fn energy_audit_generalized_alpha() {
    let report = registry::run_passing("energy_audit_generalized_alpha");
    let v = &report.levels[0].values;
    assert_eq!(v.len(), 11, "bounce and slide");
    // rho_inf = 0.9 dissipates: the scheme's loss is reported, and it is
    // what the balance without it shows
    assert!(v[1].computed > 0.0 && v[7].computed > 0.0, "{v:?}");
}
