//! Rigid bodies with mass and rotary inertia on spring bearings (issue
//! 19; deck `rigid_body NODES { .. }`, `engine/src/solve/rigid_body.rs`);
//! tags `dynamics rigid_body`.
//!
//! - `rigid_body_bearing_frequency`: a disc (annulus, density 1) made
//!   rigid by `rigid_body disc.all` with a mass `M` at its centre, on an
//!   isotropic bearing spring `k`, given the velocity `v0` along x: it
//!   vibrates at `omega = sqrt(k / m_total)`, `m_total = M + rho A t`
//!   (Thomson & Dahleh, Theory of Vibration with Applications, 1998,
//!   section 2.1), average-acceleration Newmark at `dt = T/20, T/40`: the
//!   period against `2 pi / omega`, the energy balance, the ties' gap.
//! - `jeffcott_rotor_whirl`: a massless square (point masses `m0` at its
//!   corners) carrying an eccentric point mass `m_e` at radius `r_e`,
//!   rigid about its centre (mass `M`), spun up to `omega` on an isotropic
//!   bearing (`k`, dashpot `c`: `zeta = 0.1`) and held: after the
//!   transient the centre whirls on a circle of radius (Jeffcott rotor,
//!   Genta, Dynamics of Rotating Systems, 2005, section 4.2; Den Hartog,
//!   Mechanical Vibrations, section 7.4) `e r^2 / sqrt((1 - r^2)^2 + (2
//!   zeta r)^2)`, `e = m_e r_e / m_total`, `r = omega / omega_n`,
//!   `omega_n = sqrt(k / m_total)`: below (`r = 0.5`) and above (`r = 2`)
//!   the critical speed, average-acceleration Newmark at `dt = T_n/40,
//!   T_n/80`; the energy balance (kinetic + ties + bearing + dashpot
//!   against the work of the drive).
//! - `rigid_hub_spins_a_disc`: a finite-strain elastic disc whose inner
//!   edge is a rigid hub turned quasi-statically by 3 rad (172 degrees) in
//!   10 increments, nothing else holding it: every node of the disc
//!   follows the rigid rotation (no spurious strain at large angle).
//!
//! ```text
//!            y                       k, c (isotropic bearing)
//!            |   . m_e            /\/\/\--[=]--
//!         .--+--.  r_e              |
//!        |   o   |----->x        (o) pilot: u_c, theta = omega t
//!         '-----'                   |
//!      rigid square, mass M    M x'' + c x' + k x = m_e r_e omega^2 R(wt) e_1
//! ```

use super::error;
use crate::case::{Check, Quantity};
use crate::measure::Value;
use crate::registry::{CaseKind, ProgramCase, ProgramLevel, VerifyCase};
use ctc_engine::model::{InitialVelocity, Model};
use ctc_engine::solve::{IncrementView, Observer, RunSummary};

const PERIOD: &str = "bearing: period vs 2 pi sqrt(m_total / k)";
const BEARING_BALANCE: &str = "bearing: energy balance max |K + W_int - K0| / K0";
const TIE_GAP: &str = "bearing: max tie gap / amplitude";
const WHIRL_SUB: &str =
    "Jeffcott r = 0.5: whirl radius vs e r^2 / sqrt((1 - r^2)^2 + (2 zeta r)^2)";
const WHIRL_SUPER: &str =
    "Jeffcott r = 2: whirl radius vs e r^2 / sqrt((1 - r^2)^2 + (2 zeta r)^2)";
const WHIRL_ROUND: &str = "Jeffcott r = 0.5: orbit out-of-roundness (max - min) / mean radius";
const WHIRL_BALANCE: &str = "Jeffcott: energy balance max |balance| / max energy";
const SPIN_ERROR: &str = "hub spun 3 rad: max |u - u_rigid| / outer radius";

/// Records the pilot's displacement, the energy audit and the ties'
/// largest gap at every converged increment.
#[derive(Default)]
struct Trace {
    pilot: usize,
    centre: Vec<[f64; 2]>,
    time: Vec<f64>,
    balance: f64,
    scale: f64,
    gap: f64,
}

impl Observer<2> for Trace {
    fn converged(&mut self, view: &IncrementView<'_, 2>) -> Result<(), String> {
        self.centre.push(view.displacement[self.pilot]);
        self.time.push(view.time);
        if let Some(e) = view.energy {
            self.balance = self.balance.max(e.balance.abs());
            self.scale = self
                .scale
                .max(e.kinetic.abs())
                .max(e.internal.abs())
                .max(e.external.abs());
        }
        self.gap = self.gap.max(ctc_engine::solve::rigid_body::max_tie_gap(
            view.model,
            view.displacement.as_flattened(),
        ));
        Ok(())
    }
}

/// Compiles `deck`; the pilot node of its (only) rigid body.
fn compile(name: &str, deck: String) -> Result<(Model, usize), String> {
    let src = ctc_lang::Source::new(name, deck);
    let model = ctc_lang::compile(&src).map_err(|d| d.render(&src))?;
    let pilot = ctc_engine::solve::rigid_body::bodies(&model)
        .next()
        .ok_or("no rigid body")?
        .0;
    Ok((model, pilot))
}

fn run(model: &Model, pilot: usize) -> Result<(Trace, RunSummary), String> {
    let mut trace = Trace {
        pilot,
        ..Trace::default()
    };
    let summary = ctc_engine::solve::run(model, &mut trace).map_err(|e| e.message)?;
    if !summary.completed {
        return Err("the run did not complete".into());
    }
    Ok((trace, summary))
}

fn value(name: &'static str, computed: f64, reference: f64) -> Value {
    Value {
        quantity: Quantity::Named(name),
        reference: Some(reference),
        computed,
        error: (computed - reference).abs() / reference.abs(),
    }
}

/// Zero crossings of `x(t)` (linearly interpolated times).
pub(super) fn crossings(x: &[f64], t: &[f64]) -> Vec<f64> {
    let mut out = Vec::new();
    for i in 1..x.len() {
        if x[i - 1] < 0.0 && x[i] >= 0.0 || x[i - 1] > 0.0 && x[i] <= 0.0 {
            let s = x[i - 1] / (x[i - 1] - x[i]);
            out.push(t[i - 1] + s * (t[i] - t[i - 1]));
        }
    }
    out
}

const BEARING_K: f64 = 4.0;
const BEARING_M: f64 = 0.5;
const RHO: f64 = 1.0;

fn bearing(level: usize) -> Result<ProgramLevel, String> {
    let (inner, outer, thickness) = (0.2_f64, 1.0_f64, 0.1);
    // the disc's area (the annulus' straight-sided cells: the polygon)
    let n_c = 16;
    let polygon = |r: f64| 0.5 * n_c as f64 * r * r * (std::f64::consts::TAU / n_c as f64).sin();
    let m_total = BEARING_M + RHO * thickness * (polygon(outer) - polygon(inner));
    let omega = (BEARING_K / m_total).sqrt();
    let t = std::f64::consts::TAU / omega;
    let n = 20 << level;
    let dt = t / n as f64;
    let deck = format!(
        "analysis {{ dimension = plane_strain  thickness = {thickness} }}\n\
         material m {{ elastic {{ E = 1e3  nu = 0.3 }}  density = {RHO} }}\n\
         body disc {{ mesh = annulus {{ center = (0, 0)  inner = {inner}  outer = {outer}  radial = 2  circumferential = {n_c} }}  material = m  kinematics = finite }}\n\
         rigid_body disc.all {{ center = (0, 0)  mass = {BEARING_M}  inertia = 0.1  stiffness = {BEARING_K}  tie_stiffness = 1e4 }}\n\
         initial_velocity disc.all {{ vx = 1 }}\n\
         step vibrate {{\n  time = 0 .. {}\n  increments = {}\n  dynamic {{ scheme = newmark }}\n  newton {{ tol = 1e-10 }}\n}}\n",
        3.0 * t,
        3 * n
    );
    let (mut model, pilot) = compile("bearing.ctc", deck)?;
    // the pilot moves with the disc from the start
    model.initial_velocities.push(InitialVelocity {
        label: "pilot".into(),
        nodes: vec![pilot],
        component: 0,
        value: 1.0,
    });
    let (trace, summary) = run(&model, pilot)?;
    let x: Vec<f64> = trace.centre.iter().map(|u| u[0]).collect();
    let c = crossings(&x, &trace.time);
    if c.len() < 3 {
        return Err(format!("too few cycles: {} crossings", c.len()));
    }
    let m = c.len() - 1;
    let t_h = 2.0 * (c[m] - c[0]) / m as f64;
    if summary.cutbacks > 0 {
        return Err(format!("{} cutbacks", summary.cutbacks));
    }
    let k0 = 0.5 * m_total;
    let mut out = ProgramLevel {
        h: dt,
        values: vec![
            value(PERIOD, t_h, t),
            error(BEARING_BALANCE, trace.balance / k0),
            error(TIE_GAP, trace.gap * omega),
        ],
        ..ProgramLevel::default()
    };
    out.add_run(&summary);
    Ok(out)
}

const J_M: f64 = 0.8;
const J_M0: f64 = 0.025;
const J_ME: f64 = 0.1;
const J_K: f64 = 1.0;
const J_ZETA: f64 = 0.1;
const J_HALF: f64 = 0.1;

/// The Jeffcott rotor at `omega = ratio omega_n`, `n` increments per
/// natural period: the mean and spread of the whirl radius over the last
/// natural period, its closed form, the energy balance.
fn jeffcott(ratio: f64, n: usize) -> Result<(f64, f64, f64, f64, RunSummary), String> {
    let m_total = J_M + 4.0 * J_M0 + J_ME;
    let omega_n = (J_K / m_total).sqrt();
    let c = 2.0 * J_ZETA * (J_K * m_total).sqrt();
    let t_n = std::f64::consts::TAU / omega_n;
    let omega = ratio * omega_n;
    let (spin_up, total) = (2.0 * t_n, 14.0 * t_n);
    let h = J_HALF;
    let deck = format!(
        "analysis {{ dimension = plane_strain }}\n\
         material m {{ elastic {{ E = 1e3  nu = 0.3 }}  density = 0 }}\n\
         body rotor {{ mesh = rectangle {{ origin = ({}, {})  size = ({}, {})  divisions = (1, 1) }}  material = m  kinematics = finite }}\n\
         point_mass rotor.all {{ mass = {J_M0} }}\n\
         point_mass rotor.node(near({h}, {h})) {{ mass = {J_ME} }}\n\
         rigid_body rotor.all {{ center = (0, 0)  mass = {J_M}  stiffness = {J_K}  damping = {c}  \
         angular_velocity = ramp(0, {omega}, 0, {spin_up})  tie_stiffness = 1e3 }}\n\
         step whirl {{\n  time = 0 .. {total}\n  increments = {}\n  dynamic {{ scheme = newmark }}\n  newton {{ tol = 1e-10 }}\n}}\n",
        -h,
        -h,
        2.0 * h,
        2.0 * h,
        14 * n
    );
    let (model, pilot) = compile("jeffcott.ctc", deck)?;
    let (trace, summary) = run(&model, pilot)?;
    let e = J_ME * h * std::f64::consts::SQRT_2 / m_total;
    let r2 = ratio * ratio;
    let exact = e * r2 / ((1.0 - r2).powi(2) + (2.0 * J_ZETA * ratio).powi(2)).sqrt();
    let last: Vec<f64> = trace
        .centre
        .iter()
        .zip(&trace.time)
        .filter(|(_, &t)| t > total - t_n * (1.0 + 1e-9))
        .map(|(u, _)| u[0].hypot(u[1]))
        .collect();
    if last.is_empty() {
        return Err("no increment in the last period".into());
    }
    let mean = last.iter().sum::<f64>() / last.len() as f64;
    let spread = last.iter().copied().fold(f64::MIN, f64::max)
        - last.iter().copied().fold(f64::MAX, f64::min);
    Ok((
        mean,
        exact,
        spread / mean,
        trace.balance / trace.scale.max(f64::MIN_POSITIVE),
        summary,
    ))
}

fn whirl(level: usize) -> Result<ProgramLevel, String> {
    let n = 40 << level;
    let (sub, sub_exact, round, balance_sub, s1) = jeffcott(0.5, n)?;
    let (sup, sup_exact, _, balance_sup, s2) = jeffcott(2.0, n)?;
    let m_total = J_M + 4.0 * J_M0 + J_ME;
    let t_n = std::f64::consts::TAU * (m_total / J_K).sqrt();
    let mut out = ProgramLevel {
        h: t_n / n as f64,
        values: vec![
            value(WHIRL_SUB, sub, sub_exact),
            value(WHIRL_SUPER, sup, sup_exact),
            error(WHIRL_ROUND, round),
            error(WHIRL_BALANCE, balance_sub.max(balance_sup)),
        ],
        ..ProgramLevel::default()
    };
    out.add_run(&s1);
    out.add_run(&s2);
    Ok(out)
}

fn spin(_level: usize) -> Result<ProgramLevel, String> {
    let (inner, outer, angle) = (0.3_f64, 1.0_f64, 3.0_f64);
    let deck = format!(
        "analysis {{ dimension = plane_strain }}\n\
         material m {{ neo_hookean {{ E = 1e3  nu = 0.3 }} }}\n\
         body disc {{ mesh = annulus {{ center = (0, 0)  inner = {inner}  outer = {outer}  radial = 3  circumferential = 12 }}  material = m  kinematics = finite }}\n\
         rigid_body disc.inner {{ center = (0, 0)  rotation = ramp(0, {angle})  stiffness = 1  tie_stiffness = 1e6 }}\n\
         step spin {{ time = 0 .. 1  increments = 10 }}\n"
    );
    let (model, pilot) = compile("spin.ctc", deck)?;
    let mut worst: f64 = 0.0;
    struct Last(Vec<[f64; 2]>);
    impl Observer<2> for Last {
        fn converged(&mut self, view: &IncrementView<'_, 2>) -> Result<(), String> {
            self.0 = view.displacement.to_vec();
            Ok(())
        }
    }
    let mut last = Last(Vec::new());
    let summary = ctc_engine::solve::run(&model, &mut last).map_err(|e| e.message)?;
    if !summary.completed {
        return Err("the spin did not complete".into());
    }
    let (s, c) = angle.sin_cos();
    for (n, x) in model.mesh.nodes.iter().enumerate().take(pilot) {
        let rigid = [c * x[0] - s * x[1] - x[0], s * x[0] + c * x[1] - x[1]];
        let u = last.0[n];
        worst = worst.max((u[0] - rigid[0]).hypot(u[1] - rigid[1]));
    }
    let mut out = ProgramLevel {
        h: 0.1,
        values: vec![error(SPIN_ERROR, worst / outer)],
        ..ProgramLevel::default()
    };
    out.add_run(&summary);
    Ok(out)
}

/// The registry entries.
pub fn cases() -> Vec<VerifyCase> {
    vec![
        VerifyCase {
            name: "rigid_body_bearing_frequency",
            title: "A disc made rigid (rigid_body disc.all, mass M at its centre) on an isotropic bearing spring k, given v0: period vs 2 pi sqrt(m_total / k) (M + the disc's mass), average-acceleration Newmark at dt = T/20, T/40; energy balance; the ties' gap",
            source: "Thomson & Dahleh, Theory of Vibration with Applications (5th ed. 1998), section 2.1",
            tags: &["dynamics", "rigid_body", "plane_strain"],
            levels: 2,
            // measured (levels 0, 1): period 8.16e-3, 2.06e-3 (rate 2.0,
            // the rule's elongation); balance 2.2e-11 (level 1); tie gap
            // 4.6e-6 of the amplitude
            checks: vec![
                Check::new(Quantity::Named(PERIOD), &[1e-2, 3e-3]),
                Check::new(Quantity::Named(BEARING_BALANCE), &[1e-8]),
                Check::new(Quantity::Named(TIE_GAP), &[1e-4]),
            ],
            kind: CaseKind::Program(ProgramCase {
                max_levels: 2,
                run: bearing,
            }),
        },
        VerifyCase {
            name: "jeffcott_rotor_whirl",
            title: "Jeffcott rotor: a rigid square with an eccentric point mass spun up to omega = 0.5 and 2 omega_n on an isotropic damped bearing (zeta = 0.1), Newmark at dt = T_n/40, T_n/80: steady whirl radius vs e r^2 / sqrt((1 - r^2)^2 + (2 zeta r)^2), orbit roundness, energy balance",
            source: "Genta, Dynamics of Rotating Systems (2005), section 4.2 (the Jeffcott rotor); Den Hartog, Mechanical Vibrations (1956), section 7.4",
            tags: &["dynamics", "rigid_body", "plane_strain"],
            levels: 2,
            // measured (levels 0, 1): r = 0.5 1.32e-3, 2.90e-4; r = 2
            // 4.96e-3, 1.07e-3 (rates 2.2); roundness 6.4e-4, 1.0e-3;
            // balance 3.4e-9, 3.1e-8
            checks: vec![
                Check::new(Quantity::Named(WHIRL_SUB), &[1e-2, 5e-3]),
                Check::new(Quantity::Named(WHIRL_SUPER), &[1e-2, 5e-3]),
                Check::new(Quantity::Named(WHIRL_ROUND), &[2e-2]),
                Check::new(Quantity::Named(WHIRL_BALANCE), &[1e-6]),
            ],
            kind: CaseKind::Program(ProgramCase {
                max_levels: 2,
                run: whirl,
            }),
        },
        VerifyCase {
            name: "rigid_hub_spins_a_disc",
            title: "A finite-strain elastic disc whose inner edge is a rigid hub (rigid_body disc.inner) turned by 3 rad in 10 quasi-static increments: every node follows the rigid rotation",
            source: "objectivity of the finite-strain kinematics (Belytschko, Liu & Moran, Nonlinear Finite Elements, 2000, section 3.7): a rigid rotation leaves no strain",
            tags: &["rigid_body", "finite_strain", "plane_strain"],
            levels: 1,
            // measured: 4.1e-14
            checks: vec![Check::new(Quantity::Named(SPIN_ERROR), &[1e-8])],
            kind: CaseKind::Program(ProgramCase {
                max_levels: 1,
                run: spin,
            }),
        },
    ]
}
