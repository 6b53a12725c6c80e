//! Rate-dependent J2 flow beyond the linear Perzyna law, as a `ctc verify`
//! case against closed forms: the Norton-Hoff law (the superplastic law,
//! `q = sigma0 (r / r0)^m`, no static yield) and the Perzyna power law
//! (`r = r0 (q / sigma_y - 1)^N`). E = 200e3, nu = 0.3.
//!
//! With a rate exponent of 2 both have a `tanh` closed form: loading at a
//! constant equivalent strain rate `r` from the stress-free (Norton-Hoff)
//! or yield (Perzyna, perfect plasticity) state, the flowing stress `s`
//! (Norton-Hoff: `q`; Perzyna: the over-stress `q - sigma_y`) obeys
//! `ds/dt = M (r - r_p(s))` with `M = 3 G` in pure shear, `M = E` in
//! uniaxial stress, and
//! - Norton-Hoff, `m = 1/2`: `r_p = r0 (s / sigma0)^2`,
//! - Perzyna power, `N = 2`: `r_p = r0 (s / sigma_y)^2`,
//!
//! so `s(t) = s_ss tanh(M r t / s_ss)` with the steady stress `s_ss =
//! sigma0 (r / r0)^(1/2)` (Norton-Hoff) or `sigma_y (r / r0)^(1/2)`
//! (Perzyna). Checked
//! - at a material point in pure shear, two rates 1000 x apart each, error
//!   `max_t |s - s_exact| / s_ss` over 4 time constants `s_ss / (M r)` (in
//!   these units the error does not depend on the rate: the two agree to
//!   round-off, a check of the law's scaling);
//! - through the solver at finite strain: one axisymmetric quad of unit
//!   radius and height compressed at a constant logarithmic strain rate
//!   (top at `h0 exp(-r t)` at every increment end) in two steps: the
//!   elastic transient (5 time constants `s_ss / (E r)`), then the flow to
//!   60 % of its height. In uniaxial stress the Kirchhoff stress is `tau =
//!   E (ln(h0 / h) - ep)` exactly for the exponential-map return with
//!   Hencky elasticity, so the same `tanh` holds for `tau`, measured as `F
//!   h / (pi h0)` (the current area is `J pi h0 / h`).
//!
//! Backward Euler in time: first order in dt (the rate judged; level l
//! halves dt).
//! Source: Norton (1929), Hoff (1954); Perzyna, Adv. Appl. Mech. 9 (1966);
//! the superplastic law as used in forming: Chandra, J. Eng. Mater.
//! Technol. 124 (2002) 91. `verification/tests/suite/viscoplastic.rs` runs this
//! entry.
//!
//! ```text
//!   s                 ______________ s_ss = sigma0 (r / r0)^m
//!   |            ____/
//!   |        _-'     s(t) = s_ss tanh(M r t / s_ss)
//!   |      /
//!   +-----+----------------------------> t
//! ```

use super::error;
use super::viscoplastic::{q_of, shear};
use crate::case::{Check, Quantity};
use crate::registry::{CaseKind, ProgramCase, ProgramLevel, VerifyCase};
use ctc_engine::material::j2::Elastic;
use ctc_engine::material::{History, NonlinearLaw};
use ctc_engine::mesh::{Cell, Mesh};
use ctc_engine::model::{
    Hardening, Kinematics, MaterialLaw, Model, NewtonSettings, TimeFunction, Viscosity,
};
use ctc_engine::solve::{run, IncrementView, Observer};
use ctc_engine::testkit::ModelBuilder;
use std::f64::consts::PI;

const E: f64 = 200e3;
const NU: f64 = 0.3;
/// Norton-Hoff flow stress at the reference rate, and the reference rate.
const SIGMA0: f64 = 50.0;
const R0: f64 = 1e-3;
/// Perzyna power law: static yield stress, reference rate, exponent.
const YIELD: f64 = 250.0;
const PR0: f64 = 1e-2;

/// Increments of a material-point loading and of the solver run, level 0.
const POINT_N: usize = 200;
const SOLVER_N: usize = 100;

const NH_SLOW: &str = "Norton-Hoff m = 1/2, shear, slow: max |q - q_exact| / q_ss";
const NH_FAST: &str = "Norton-Hoff m = 1/2, shear, fast: max |q - q_exact| / q_ss";
const PP_SLOW: &str = "Perzyna N = 2, shear, slow: max |s - s_exact| / s_ss";
const PP_FAST: &str = "Perzyna N = 2, shear, fast: max |s - s_exact| / s_ss";
const NH_SOLVER: &str = "Norton-Hoff, solver, finite strain: max |tau - tau_exact| / tau_ss";

fn norton_hoff() -> Viscosity {
    Viscosity::NortonHoff {
        stress: SIGMA0,
        rate: R0,
        m: 0.5,
    }
}

/// The Norton-Hoff law without static yield (`sigma_y = 0`).
fn no_yield() -> Hardening {
    Hardening::Linear {
        yield_stress: 0.0,
        modulus: 0.0,
    }
}

/// Max relative error of the flowing stress at a material point in pure
/// shear loaded at the equivalent rate `r` from `eb0` (the start of flow)
/// for 4 time constants, `n` increments. `static_yield` is subtracted from
/// `q` (the over-stress of Perzyna), `s_ss` is the steady value.
fn point_error(
    law: &NonlinearLaw,
    r: f64,
    eb0: f64,
    static_yield: f64,
    s_ss: f64,
    n: usize,
) -> Result<f64, String> {
    let m = 3.0 * Elastic::from_young(E, NU).shear;
    let t_end = 4.0 * s_ss / (m * r);
    let dt = t_end / n as f64;
    let mut h = History::initial(Kinematics::Small);
    let mut worst = 0.0f64;
    for k in 1..=n {
        let t = k as f64 * dt;
        let up = law
            .small(&shear(eb0 + r * t), &h, dt)
            .map_err(|e| format!("J2 update at t = {t:e}: {e}"))?;
        h = up.history;
        let s = q_of(&up.stress) - static_yield;
        let exact = s_ss * (m * r * t / s_ss).tanh();
        worst = worst.max((s - exact).abs() / s_ss);
    }
    Ok(worst)
}

struct Force(Vec<(f64, f64, f64)>);

impl Observer for Force {
    fn converged(&mut self, v: &IncrementView<'_>) -> Result<(), String> {
        let fy: f64 = [0usize, 1].iter().map(|&n| v.reaction[n][1]).sum();
        self.0.push((v.time, fy, 1.0 + v.displacement[2][1]));
        Ok(())
    }
}

/// One finite-strain axisymmetric quad compressed at the constant
/// logarithmic rate `r` in two steps of `n` increments each: the elastic
/// transient (to 5 time constants `tau_ss / (E r)`), then the flow to `h =
/// 0.6`.
fn solver_model(r: f64, tau_ss: f64, n: usize) -> Model {
    let t1 = 5.0 * tau_ss / (E * r);
    let t_end = -(0.6f64).ln() / r;
    let times: Vec<f64> = (0..=n)
        .map(|k| t1 * k as f64 / n as f64)
        .chain((1..=n).map(|k| t1 + (t_end - t1) * k as f64 / n as f64))
        .collect();
    let top = TimeFunction::Table(times.iter().map(|&t| (t, (-r * t).exp() - 1.0)).collect());
    let newton = NewtonSettings {
        tol: 1e-11,
        tol_displacement: 1e-11,
        max_iter: 20,
        line_search: true,
        predictor: true,
        stabilize: None,
    };
    ModelBuilder::axisymmetric()
        .material(
            "m",
            MaterialLaw::ElastoPlastic {
                young: E,
                poisson: NU,
                hardening: no_yield(),
                viscosity: Some(norton_hoff()),
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
        .kinematics(Kinematics::Finite)
        .fix([0, 1], 1)
        .fix([0, 3], 0)
        .displace([2, 3], 1, top)
        .step("transient", t1, n)
        .min_fraction(1.0 / 64.0)
        .newton(newton)
        .step("flow", t_end, n)
        .min_fraction(1.0 / 64.0)
        .newton(newton)
        .build()
}

/// Max error of the Kirchhoff stress `F h / (pi h0)` of the solver run,
/// and the run's summary.
fn solver_error(n: usize) -> Result<(f64, ctc_engine::solve::RunSummary), String> {
    let r = 1e-2;
    let tau_ss = SIGMA0 * (r / R0).sqrt();
    let mut f = Force(Vec::new());
    let summary =
        run(&solver_model(r, tau_ss, n), &mut f).map_err(|e| format!("solver: {}", e.message))?;
    if f.0.len() < 2 * n {
        return Err(format!("solver: {} increments of {}", f.0.len(), 2 * n));
    }
    let mut worst = 0.0f64;
    for &(t, fy, h) in &f.0 {
        // compression: the bottom reaction is positive, the stress negative
        let tau = fy * h / PI;
        let exact = tau_ss * (E * r * t / tau_ss).tanh();
        worst = worst.max((tau - exact).abs() / tau_ss);
    }
    Ok((worst, summary))
}

fn level_run(level: usize) -> Result<ProgramLevel, String> {
    let scale = 1usize << level;
    let n = POINT_N * scale;
    let mut out = ProgramLevel {
        h: 1.0 / n as f64,
        nodes: 4,
        ..ProgramLevel::default()
    };
    let elastic = Elastic::from_young(E, NU);
    let nh = NonlinearLaw::J2 {
        elastic,
        hardening: no_yield(),
        viscosity: Some(norton_hoff()),
    };
    for (r, name) in [(1e-4, NH_SLOW), (1e-1, NH_FAST)] {
        let s_ss = SIGMA0 * (r / R0).sqrt();
        out.values
            .push(error(name, point_error(&nh, r, 0.0, 0.0, s_ss, n)?));
    }
    let pp = NonlinearLaw::J2 {
        elastic,
        hardening: Hardening::Linear {
            yield_stress: YIELD,
            modulus: 0.0,
        },
        viscosity: Some(Viscosity::PerzynaPower {
            rate: PR0,
            exponent: 2.0,
        }),
    };
    let eb_yield = YIELD / (3.0 * elastic.shear);
    for (r, name) in [(1e-4, PP_SLOW), (1e-1, PP_FAST)] {
        let s_ss = YIELD * (r / PR0).sqrt();
        out.values
            .push(error(name, point_error(&pp, r, eb_yield, YIELD, s_ss, n)?));
    }
    let (e, summary) = solver_error(SOLVER_N * scale)?;
    out.values.push(error(NH_SOLVER, e));
    out.add_run(&summary);
    Ok(out)
}

/// The registry entry.
pub fn cases() -> Vec<VerifyCase> {
    vec![VerifyCase {
        name: "norton_hoff_rate",
        title: "Norton-Hoff (m = 1/2) and Perzyna power (N = 2) flow at constant rate: tanh closed forms at a material point and through the solver at finite strain; first order in dt",
        source: "Norton (1929), Hoff (1954); Perzyna, Adv. Appl. Mech. 9 (1966); Chandra, J. Eng. Mater. Technol. 124 (2002) 91",
        tags: &["viscoplastic", "norton_hoff", "plasticity", "material", "finite_strain", "closed_form", "rate"],
        levels: 2,
        checks: vec![
            Check::new(Quantity::Named(NH_SLOW), &[1e-2, 5e-3, 2.5e-3]).with_min_rate(0.9),
            Check::new(Quantity::Named(NH_FAST), &[1e-2, 5e-3, 2.5e-3]).with_min_rate(0.9),
            Check::new(Quantity::Named(PP_SLOW), &[1e-2, 5e-3, 2.5e-3]).with_min_rate(0.9),
            Check::new(Quantity::Named(PP_FAST), &[1e-2, 5e-3, 2.5e-3]).with_min_rate(0.9),
            Check::new(Quantity::Named(NH_SOLVER), &[2e-2, 1e-2, 5e-3]).with_min_rate(0.9),
        ],
        kind: CaseKind::Program(ProgramCase {
            max_levels: 3,
            run: level_run,
        }),
    }]
}
