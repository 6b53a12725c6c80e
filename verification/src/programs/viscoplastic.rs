//! Perzyna visco-plasticity (linear over-stress, `d ep/dt = <q - sigma_y> /
//! eta`, E = 200e3, nu = 0.3, sigma_y = 250, eta = 5e3) as a `ctc verify`
//! case, against closed forms:
//!
//! - at a material point in pure shear, loading at a constant equivalent
//!   strain rate `r` from the yield point, perfect plasticity: the
//!   over-stress `s = q - sigma_y` obeys `ds/dt = 3 G (r - s / eta)`, so
//!   `s(t) = eta r (1 - exp(-3 G t / eta))`; two rates (0.01 and 1 x
//!   1e-3 / tau, tau = eta / 3G), 5 tau; error `max_t |s - s_exact| / (eta
//!   r)`;
//! - relaxation at a fixed strain (twice the yield strain, applied at once)
//!   with linear hardening H = 2e4: `s(t) = s0 exp(-(3 G + H) t / eta)`;
//!   error `max_t |s - s_exact| / s0`;
//! - through the solver: one axisymmetric quad (r0 = 1, h0 = 1) compressed
//!   at a constant rate (1e-4 and 1e-2 / tau, tau = eta / E) by a
//!   prescribed top displacement: uniaxial stress, after yield at `t_y`
//!   `s = eta rate (1 - exp(-E (t - t_y) / eta))`, axial force `(sigma_y +
//!   s) pi`; error `max_t |F - F_exact| / (eta rate pi)` (checks that the
//!   time increment reaches the law).
//!
//! Backward Euler in time: level l halves dt (`h` of the report is
//! `dt / tau` of the material-point loading); the errors are first order
//! in dt (the rate judged), and each level also measures the order of the
//! loading error directly from a run at dt / 2, `|log2(e(dt) / e(dt/2)) -
//! 1|`.
//! Source: Perzyna, Adv. Appl. Mech. 9 (1966); Simo & Hughes,
//! Computational Inelasticity §1.7 (closed forms of the linear over-stress
//! model). `verification/tests/suite/viscoplastic.rs` runs this entry.
//!
//! ```text
//!   q                      ___________ sigma_y + eta r  (steady over-stress)
//!   |                 ____/
//!   |     sigma_y ___/  s(t) = eta r (1 - exp(-t / tau))
//!   |           /
//!   +----------+----------------------------> t
//! ```

use super::error;
use crate::case::{Check, Quantity};
use crate::registry::{CaseKind, ProgramCase, ProgramLevel, VerifyCase};
use ctc_engine::material::j2::Elastic;
use ctc_engine::material::tensor::{deviator, norm2};
use ctc_engine::material::{History, NonlinearLaw};
use ctc_engine::mesh::{Cell, Mesh};
use ctc_engine::model::{Hardening, Kinematics, MaterialLaw, Model, NewtonSettings, Viscosity};
use ctc_engine::solve::{run, IncrementView, Observer};
use ctc_engine::testkit::{ramp, ModelBuilder};
use std::f64::consts::PI;

const E: f64 = 200e3;
const NU: f64 = 0.3;
const ETA: f64 = 5e3;
const YIELD: f64 = 250.0;

/// Increments of the material-point loading, relaxation and solver runs at
/// level 0.
const LOADING_N: usize = 400;
const RELAXATION_N: usize = 200;
const SOLVER_N: usize = 400;

const SLOW: &str = "shear loading, slow rate: max |s - s_exact| / (eta r)";
const FAST: &str = "shear loading, fast rate: max |s - s_exact| / (eta r)";
const SLOW_ORDER: &str = "shear loading, slow rate: |order in dt - 1|";
const FAST_ORDER: &str = "shear loading, fast rate: |order in dt - 1|";
const RELAX: &str = "relaxation, hardening: max |s - s_exact| / s0";
const SOLVER_SLOW: &str = "solver, uniaxial, slow rate: max |F - F_exact| / (eta rate pi)";
const SOLVER_FAST: &str = "solver, uniaxial, fast rate: max |F - F_exact| / (eta rate pi)";

/// Von Mises stress of a stress tensor.
pub(super) fn q_of(s: &[f64; 6]) -> f64 {
    (1.5 * norm2(&deviator(s))).sqrt()
}

/// Pure shear with equivalent strain `eb`: tensor shear `sqrt(3) eb / 2`.
pub(super) fn shear(eb: f64) -> [f64; 6] {
    [0.0, 0.0, 0.0, 3f64.sqrt() * eb / 2.0, 0.0, 0.0]
}

fn law(h: f64) -> NonlinearLaw {
    NonlinearLaw::J2 {
        elastic: Elastic::from_young(E, NU),
        hardening: Hardening::Linear {
            yield_stress: YIELD,
            modulus: h,
        },
        viscosity: Some(Viscosity::Perzyna { eta: ETA }),
    }
}

fn shear_modulus() -> f64 {
    Elastic::from_young(E, NU).shear
}

/// Max relative error of the over-stress during loading at rate `r` over
/// `t_end`, with `n` increments.
fn loading_error(r: f64, t_end: f64, n: usize) -> Result<f64, String> {
    let g = shear_modulus();
    let law = law(0.0);
    let e_yield = YIELD / (3.0 * g);
    let dt = t_end / n as f64;
    let mut h = History::initial(Kinematics::Small);
    let mut worst = 0.0f64;
    for k in 1..=n {
        let t = k as f64 * dt;
        let up = law
            .small(&shear(e_yield + r * t), &h, dt)
            .map_err(|e| format!("J2 update at t = {t:e}: {e}"))?;
        h = up.history;
        let s = q_of(&up.stress) - YIELD;
        let exact = ETA * r * (1.0 - (-3.0 * g * t / ETA).exp());
        worst = worst.max((s - exact).abs() / (ETA * r));
    }
    Ok(worst)
}

/// Max relative error of the over-stress relaxing at fixed strain with
/// hardening, `n` increments over 5 tau.
fn relaxation_error(n: usize) -> Result<f64, String> {
    let g = shear_modulus();
    let hmod = 2e4;
    let law = law(hmod);
    let tau = ETA / (3.0 * g + hmod);
    let eb = 2.0 * YIELD / (3.0 * g); // twice the yield strain, applied at once
    let dt = 5.0 * tau / n as f64;
    let mut h = History::initial(Kinematics::Small);
    // instantaneous loading over a tiny time: elastic trial, no flow
    let up = law
        .small(&shear(eb), &h, 1e-12 * tau)
        .map_err(|e| format!("J2 update: {e}"))?;
    h = up.history;
    let s0 = q_of(&up.stress) - YIELD - hmod * h.ep;
    if s0 <= 240.0 {
        return Err(format!(
            "relaxation: initial over-stress {s0} (elastic trial 250 expected)"
        ));
    }
    let mut worst = 0.0f64;
    for k in 1..=n {
        let up = law
            .small(&shear(eb), &h, dt)
            .map_err(|e| format!("J2 update: {e}"))?;
        h = up.history;
        let s = q_of(&up.stress) - YIELD - hmod * h.ep;
        let exact = s0 * (-(k as f64) * dt / tau).exp();
        worst = worst.max((s - exact).abs() / s0);
    }
    Ok(worst)
}

struct Force(Vec<(f64, f64)>);

impl Observer for Force {
    fn converged(&mut self, v: &IncrementView<'_>) -> Result<(), String> {
        let fy: f64 = [0usize, 1].iter().map(|&n| v.reaction[n][1]).sum();
        self.0.push((v.time, fy));
        Ok(())
    }
}

/// One axisymmetric quad compressed at `rate` up to `t_end`.
fn solver_model(rate: f64, t_end: f64, increments: usize) -> Model {
    ModelBuilder::axisymmetric()
        .material(
            "m",
            MaterialLaw::ElastoPlastic {
                young: E,
                poisson: NU,
                hardening: Hardening::Linear {
                    yield_stress: YIELD,
                    modulus: 0.0,
                },
                viscosity: Some(Viscosity::Perzyna { eta: ETA }),
            },
        )
        .body(
            "b",
            Mesh::new(
                vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]],
                vec![Cell::quad(0, 1, 2, 3)],
            ),
            "m",
        )
        .fix([0, 1], 1)
        .fix([0, 3], 0)
        .displace([2, 3], 1, ramp(0.0, t_end, -rate * t_end))
        .step("s", t_end, increments)
        .min_fraction(1.0 / 64.0)
        .newton(NewtonSettings {
            tol: 1e-11,
            tol_displacement: 1e-11,
            max_iter: 20,
            line_search: true,
            predictor: true,
            stabilize: None,
        })
        .build()
}

/// Max force error of the solver run at `rate` over `t_y + 5 tau`, and the
/// run's summary.
fn solver_error(
    rate: f64,
    increments: usize,
) -> Result<(f64, ctc_engine::solve::RunSummary), String> {
    let tau = ETA / E;
    let t_y = YIELD / (E * rate);
    let t_end = t_y + 5.0 * tau;
    let mut f = Force(Vec::new());
    let summary = run(&solver_model(rate, t_end, increments), &mut f)
        .map_err(|e| format!("solver: {}", e.message))?;
    let mut worst = 0.0f64;
    for &(t, fy) in &f.0 {
        let s = if t <= t_y {
            E * rate * t - YIELD
        } else {
            ETA * rate * (1.0 - (-(t - t_y) / tau).exp())
        };
        let exact = (YIELD + s) * PI;
        worst = worst.max((fy - exact).abs() / (ETA * rate * PI));
    }
    Ok((worst, summary))
}

fn level_run(level: usize) -> Result<ProgramLevel, String> {
    let scale = 1usize << level;
    let tau = ETA / (3.0 * shear_modulus());
    let t_end = 5.0 * tau;
    let n = LOADING_N * scale;
    let mut out = ProgramLevel {
        h: t_end / n as f64 / tau,
        nodes: 4,
        ..ProgramLevel::default()
    };
    for (rate, name, order) in [
        (1e-3 / tau * 0.01, SLOW, SLOW_ORDER),
        (1e-3 / tau, FAST, FAST_ORDER),
    ] {
        let e1 = loading_error(rate, t_end, n)?;
        let e2 = loading_error(rate, t_end, 2 * n)?;
        out.values.push(error(name, e1));
        out.values
            .push(error(order, ((e1 / e2).log2() - 1.0).abs()));
    }
    out.values
        .push(error(RELAX, relaxation_error(RELAXATION_N * scale)?));
    let tau_u = ETA / E;
    for (rate, name) in [(1e-4 / tau_u, SOLVER_SLOW), (1e-2 / tau_u, SOLVER_FAST)] {
        let (e, summary) = solver_error(rate, SOLVER_N * scale)?;
        out.values.push(error(name, e));
        out.add_run(&summary);
    }
    Ok(out)
}

/// The registry entry.
pub fn cases() -> Vec<VerifyCase> {
    vec![VerifyCase {
        name: "perzyna_viscoplastic",
        title: "Perzyna visco-plasticity: over-stress at two rates, relaxation with hardening, uniaxial force through the solver; first order in dt",
        source: "Perzyna, Adv. Appl. Mech. 9 (1966); Simo & Hughes, Computational Inelasticity §1.7",
        tags: &["viscoplastic", "plasticity", "material", "closed_form", "rate"],
        levels: 2,
        // Measured (levels 0-2): loading (both rates) 2.29e-3 1.15e-3
        // 5.74e-4 (rate 1.00), order 3.7e-3 1.9e-3 9.4e-4; relaxation
        // 4.55e-3 2.29e-3 1.15e-3 (0.99); solver slow 7.97e-3 4.01e-3
        // 2.00e-3 (0.99), fast 2.35e-3 1.18e-3 5.88e-4 (1.00).
        checks: vec![
            Check::new(Quantity::Named(SLOW), &[5e-3, 2.5e-3, 1.25e-3]).with_min_rate(0.93),
            Check::new(Quantity::Named(FAST), &[5e-3, 2.5e-3, 1.25e-3]).with_min_rate(0.93),
            Check::new(Quantity::Named(SLOW_ORDER), &[1e-2, 5e-3, 2.5e-3]),
            Check::new(Quantity::Named(FAST_ORDER), &[1e-2, 5e-3, 2.5e-3]),
            Check::new(Quantity::Named(RELAX), &[1e-2, 5e-3, 2.5e-3]).with_min_rate(0.93),
            Check::new(Quantity::Named(SOLVER_SLOW), &[1.6e-2, 8e-3, 4e-3]).with_min_rate(0.93),
            Check::new(Quantity::Named(SOLVER_FAST), &[5e-3, 2.5e-3, 1.25e-3]).with_min_rate(0.93),
        ],
        kind: CaseKind::Program(ProgramCase {
            max_levels: 3,
            run: level_run,
        }),
    }]
}
