//! Discrete elements in implicit dynamics (tag `dynamics`): point masses
//! and springs / dashpots to the ground or between nodes
//! (`model::Discrete`).
//!
//! - `spring_mass_oscillator_period`: a mass `m = 1` on a spring `k = 4`
//!   (a massless quad carrying a point mass `m/4` and a ground spring `k/4`
//!   at each node, moving along x: a single dof, `omega = sqrt(k/m) = 2`),
//!   released with `v0 = 1`, average-acceleration Newmark at `dt = T/20,
//!   T/40, T/80`, six periods: the period against `T = 2 pi sqrt(m/k)`
//!   (the rule's elongation `omega_h dt = 2 atan(omega dt / 2)`: Hughes,
//!   The Finite Element Method, 2000, section 9.3.2, is second order in
//!   dt), against the rule's own period (round-off of the zero-crossing
//!   fit), and the amplitude against `v0 / omega` (the rule conserves
//!   energy).
//! - `dashpot_decrement`: the same oscillator with a dashpot `c` to the
//!   ground, `zeta = c / (2 sqrt(k m)) = 0.05`: the damping ratio from the
//!   logarithmic decrement (Chopra, Dynamics of Structures, 2012, section
//!   2.2) and the energy balance with the dashpot's dissipation.
//!
//! - `two_mass_oscillator`: two masses `m1 = 1`, `m2 = 3` (massless
//!   quads with point masses `m/4` at each node, `uy` held) linked by a
//!   spring `k = 3` between their nodes (deck `spring a.all -> b.all`,
//!   four links `k/4`), released with the relative velocity 1 and no
//!   momentum: the relative motion has `omega = sqrt(k (m1 + m2) / (m1
//!   m2)) = 2` (Thomson & Dahleh, Theory of Vibration with Applications,
//!   1998, section 5.1, the semi-definite system), the momentum stays 0;
//!   the spring's energy is internal work (balance to round-off); with a
//!   dashpot `c` between the nodes, `zeta = c / (2 sqrt(k mu))`, `mu = m1
//!   m2 / (m1 + m2)`, from the decrement of the relative motion, and the
//!   dashpot's dissipation in the balance.
//!
//! ```text
//!        v0 -->
//!   |/\/\/\[ m ]          m x'' + c x' + k x = 0,  x(0) = 0,  x'(0) = v0
//!   |--[=]-[   ]
//!
//!   [ m1 ]-/\/\/\-[ m2 ]     mu x'' + c x' + k x = 0,  x = u1 - u2
//!         --[=]--
//! ```

use super::dynamics::crossings_and_peaks;
use super::error;
use crate::case::{Check, Quantity};
use crate::measure::Value;
use crate::registry::{CaseKind, ProgramCase, ProgramLevel, VerifyCase};
use ctc_engine::model::{ContactMass, Dynamic, MassMatrix, NewtonSettings, Rayleigh, Scheme};
use ctc_engine::solve::RunSummary;
use ctc_engine::testkit::grid::grid;
use ctc_engine::testkit::{solve, ModelBuilder};

const MASS: f64 = 1.0;
const STIFFNESS: f64 = 4.0;
const PERIOD: &str = "period vs 2 pi sqrt(m/k)";
const RULE_PERIOD: &str = "period vs the average-acceleration rule's 2 pi dt / (2 atan(w dt / 2))";
const AMPLITUDE: &str = "amplitude vs v0 / w";
const ZETA: f64 = 0.05;
const DECREMENT: &str = "dashpot damping ratio from the logarithmic decrement";
const BALANCE: &str = "energy balance with the dashpot: max |K + W_int + W_d - K0| / K0";

/// The oscillator at `steps_per_period` increments per period, dashpot
/// `c` (total): the displacement after every increment (0 first), `dt`,
/// the run.
fn oscillator(steps_per_period: usize, c: f64) -> Result<(Vec<f64>, f64, RunSummary), String> {
    let omega = (STIFFNESS / MASS).sqrt();
    let dt = std::f64::consts::TAU / omega / steps_per_period as f64;
    let increments = 6 * steps_per_period;
    let all = vec![0, 1, 2, 3];
    let model = ModelBuilder::plane_strain()
        .elastic("m", 1.0, 0.0)
        .density(0.0)
        .body(
            "block",
            grid(1, 1, [0.0, 0.0], [1.0, 1.0], 0.0, 1, false),
            "m",
        )
        .fix(all.clone(), 1)
        .point_mass(all.clone(), MASS / 4.0)
        .ground_spring(all.clone(), STIFFNESS / 4.0, c / 4.0)
        .initial_velocity(all, 0, 1.0)
        .step("vibrate", dt * increments as f64, increments)
        .dynamic(Dynamic {
            scheme: Scheme::Newmark {
                beta: 0.25,
                gamma: 0.5,
            },
            mass: MassMatrix::Lumped,
            contact_mass: ContactMass::Redistributed,
            rayleigh: Rayleigh::default(),
            adaptive: None,
            max_rotation: None,
            energy_tol: None,
        })
        .newton(NewtonSettings {
            tol: 1e-12,
            tol_displacement: 1e-12,
            ..NewtonSettings::default()
        })
        .build();
    let (summary, rec) = solve(&model)?;
    let mut u = vec![0.0];
    u.extend(rec.increments.iter().map(|i| i.displacement[2][0]));
    Ok((u, dt, summary))
}

fn value(name: &'static str, computed: f64, reference: f64) -> Value {
    Value {
        quantity: Quantity::Named(name),
        reference: Some(reference),
        computed,
        error: (computed - reference).abs() / reference.abs(),
    }
}

fn period(level: usize) -> Result<ProgramLevel, String> {
    let omega = (STIFFNESS / MASS).sqrt();
    let (u, dt, summary) = oscillator(20 << level, 0.0)?;
    let (crossings, peaks) = crossings_and_peaks(&u);
    if crossings.len() < 3 || peaks.len() < 3 {
        return Err(format!(
            "too few cycles: {} crossings, {} peaks",
            crossings.len(),
            peaks.len()
        ));
    }
    let m = crossings.len() - 1;
    let t_h = (crossings[m] - crossings[0]) / m as f64 * dt;
    let t = std::f64::consts::TAU / omega;
    let t_rule = std::f64::consts::TAU * dt / (2.0 * (omega * dt / 2.0).atan());
    let amplitude = peaks.iter().sum::<f64>() / peaks.len() as f64;
    let mut out = ProgramLevel {
        h: dt,
        values: vec![
            value(PERIOD, t_h, t),
            value(RULE_PERIOD, t_h, t_rule),
            value(AMPLITUDE, amplitude, 1.0 / omega),
        ],
        ..ProgramLevel::default()
    };
    out.add_run(&summary);
    Ok(out)
}

fn decrement(level: usize) -> Result<ProgramLevel, String> {
    let c = 2.0 * ZETA * (STIFFNESS * MASS).sqrt();
    let (u, dt, summary) = oscillator(20 << level, c)?;
    let (_, peaks) = crossings_and_peaks(&u);
    if peaks.len() < 4 {
        return Err(format!("too few cycles: {} peaks", peaks.len()));
    }
    let n = peaks.len() - 1;
    let delta = (peaks[0] / peaks[n]).ln() / n as f64;
    let zeta_h = delta / (4.0 * std::f64::consts::PI.powi(2) + delta * delta).sqrt();
    let energies: Vec<_> = summary.increments.iter().filter_map(|i| i.energy).collect();
    let first = energies.first().ok_or("no increment")?;
    let k0 = 0.5 * MASS * 1.0;
    // the initial kinetic energy of the audit is the point masses'
    let k_audit = first.kinetic + first.internal + first.damping - first.balance;
    if (k_audit - k0).abs() > 1e-12 * k0 {
        return Err(format!("initial kinetic energy {k_audit} instead of {k0}"));
    }
    let balance = energies.iter().map(|e| e.balance.abs()).fold(0.0, f64::max) / k0;
    let dissipated = energies.last().map_or(0.0, |e| e.damping) / k0;
    if dissipated < 0.5 {
        return Err(format!(
            "the dashpot dissipated only {dissipated:.3} of the initial energy"
        ));
    }
    let mut out = ProgramLevel {
        h: dt,
        values: vec![value(DECREMENT, zeta_h, ZETA), error(BALANCE, balance)],
        ..ProgramLevel::default()
    };
    out.add_run(&summary);
    Ok(out)
}

const M1: f64 = 1.0;
const M2: f64 = 3.0;
const K12: f64 = 3.0;
const TWO_PERIOD: &str = "two masses: relative period vs 2 pi / sqrt(k (m1 + m2) / (m1 m2))";
const TWO_MOMENTUM: &str = "two masses: max |momentum| / (m1 v1)";
const TWO_BALANCE: &str = "two masses: energy balance max |K + W_int - K0| / K0";
const TWO_DECREMENT: &str = "two masses with a dashpot: damping ratio from the decrement";
const TWO_DAMPED_BALANCE: &str =
    "two masses with a dashpot: energy balance max |K + W_int + W_d - K0| / K0";

/// The two-mass deck at `n` increments per period, link dashpot `c`
/// (total).
fn two_mass_deck(n: usize, c: f64) -> String {
    let omega = (K12 * (M1 + M2) / (M1 * M2)).sqrt();
    let t = std::f64::consts::TAU / omega;
    // relative velocity 1, no momentum
    let (v1, v2) = (M2 / (M1 + M2), -M1 / (M1 + M2));
    format!(
        "analysis {{ dimension = plane_strain }}\n\
         material m {{ elastic {{ E = 1  nu = 0 }}  density = 0 }}\n\
         body a {{\n  mesh = rectangle {{ origin = (0, 0)  size = (1, 1)  divisions = (1, 1) }}\n  material = m\n}}\n\
         body b {{\n  mesh = rectangle {{ origin = (2, 0)  size = (1, 1)  divisions = (1, 1) }}\n  material = m\n}}\n\
         fix a.all {{ uy }}\nfix b.all {{ uy }}\n\
         point_mass a.all {{ mass = {} }}\npoint_mass b.all {{ mass = {} }}\n\
         spring a.all -> b.all {{ stiffness = {}  damping = {} }}\n\
         initial_velocity a.all {{ vx = {v1} }}\ninitial_velocity b.all {{ vx = {v2} }}\n\
         step vibrate {{\n  time = 0 .. {}\n  increments = {}\n  dynamic {{ scheme = newmark }}\n  newton {{ tol = 1e-12 }}\n}}\n",
        M1 / 4.0,
        M2 / 4.0,
        K12 / 4.0,
        c / 4.0,
        6.0 * t,
        6 * n
    )
}

/// Per increment: the relative displacement, the momentum, the energy.
#[derive(Default)]
struct TwoMass {
    x: Vec<f64>,
    momentum: f64,
    balance: f64,
    damping: f64,
}

impl ctc_engine::solve::Observer<2> for TwoMass {
    fn converged(&mut self, view: &ctc_engine::solve::IncrementView<'_, 2>) -> Result<(), String> {
        // node 0 of body a, node 4 (the same corner) of body b
        self.x
            .push(view.displacement[0][0] - view.displacement[4][0]);
        let v = view.velocity.ok_or("no velocity")?;
        let p: f64 = (0..8)
            .map(|n| v[2 * n] * if n < 4 { M1 } else { M2 } / 4.0)
            .sum();
        self.momentum = self.momentum.max(p.abs());
        if let Some(e) = view.energy {
            self.balance = self.balance.max(e.balance.abs());
            self.damping = e.damping;
        }
        Ok(())
    }
}

fn two_mass_run(n: usize, c: f64) -> Result<(TwoMass, RunSummary), String> {
    let src = ctc_lang::Source::new("two_mass.ctc", two_mass_deck(n, c));
    let model = ctc_lang::compile(&src).map_err(|d| d.render(&src))?;
    let mut trace = TwoMass {
        x: vec![0.0],
        ..TwoMass::default()
    };
    let summary = ctc_engine::solve::run(&model, &mut trace).map_err(|e| e.message)?;
    if !summary.completed {
        return Err("the two-mass run did not complete".into());
    }
    Ok((trace, summary))
}

fn two_masses(level: usize) -> Result<ProgramLevel, String> {
    let n = 20 << level;
    let mu = M1 * M2 / (M1 + M2);
    let omega = (K12 / mu).sqrt();
    let t = std::f64::consts::TAU / omega;
    let dt = t / n as f64;
    let k0 = 0.5 * mu; // relative velocity 1
    let (free, summary) = two_mass_run(n, 0.0)?;
    let (crossings, _) = crossings_and_peaks(&free.x);
    if crossings.len() < 3 {
        return Err(format!("too few cycles: {} crossings", crossings.len()));
    }
    let m = crossings.len() - 1;
    let t_h = (crossings[m] - crossings[0]) / m as f64 * dt;
    let c = 2.0 * ZETA * (K12 * mu).sqrt();
    let (damped, summary_d) = two_mass_run(n, c)?;
    let (_, peaks) = crossings_and_peaks(&damped.x);
    if peaks.len() < 4 {
        return Err(format!("too few cycles: {} peaks", peaks.len()));
    }
    let q = peaks.len() - 1;
    let delta = (peaks[0] / peaks[q]).ln() / q as f64;
    let zeta_h = delta / (4.0 * std::f64::consts::PI.powi(2) + delta * delta).sqrt();
    if damped.damping < 0.5 * k0 {
        return Err(format!(
            "the dashpot dissipated only {:.3} of the initial energy",
            damped.damping / k0
        ));
    }
    let mut out = ProgramLevel {
        h: dt,
        values: vec![
            value(TWO_PERIOD, t_h, t),
            error(TWO_MOMENTUM, free.momentum / (M1 * M2 / (M1 + M2))),
            error(TWO_BALANCE, free.balance / k0),
            value(TWO_DECREMENT, zeta_h, ZETA),
            error(TWO_DAMPED_BALANCE, damped.balance / k0),
        ],
        ..ProgramLevel::default()
    };
    out.add_run(&summary);
    out.add_run(&summary_d);
    Ok(out)
}

/// The registry entries.
pub fn cases() -> Vec<VerifyCase> {
    vec![
        VerifyCase {
            name: "two_mass_oscillator",
            title: "Two masses (m1 = 1, m2 = 3) linked by a spring k = 3 between their nodes (deck `spring a.all -> b.all`), average-acceleration Newmark at dt = T/20, T/40, T/80: relative period vs 2 pi / sqrt(k (m1 + m2) / (m1 m2)), momentum, energy balance; with a dashpot between them, the damping ratio from the decrement and the balance with its dissipation",
            source: "Thomson & Dahleh, Theory of Vibration with Applications (5th ed. 1998), section 5.1 (semi-definite two-mass system); Chopra, Dynamics of Structures (2012), section 2.2",
            tags: &["dynamics", "plane_strain"],
            levels: 3,
            // measured (levels 0, 1, 2): period 8.13e-3, 2.05e-3, 5.14e-4
            // (rate 2.0, as the single oscillator: the same omega); momentum
            // 6.0e-15, 1.6e-14, 2.9e-14; balance 3.3e-14, 2.0e-14, 5.1e-14;
            // zeta 1.60e-2, 4.10e-3, 1.02e-3; damped balance 9.2e-15 ..
            // 3.6e-14
            checks: vec![
                Check::new(Quantity::Named(TWO_PERIOD), &[1e-2, 3e-3, 1e-3]),
                Check::new(Quantity::Named(TWO_MOMENTUM), &[1e-12]),
                Check::new(Quantity::Named(TWO_BALANCE), &[1e-10]),
                Check::new(Quantity::Named(TWO_DECREMENT), &[2e-2, 5e-3, 1.5e-3]),
                Check::new(Quantity::Named(TWO_DAMPED_BALANCE), &[1e-10]),
            ],
            kind: CaseKind::Program(ProgramCase {
                max_levels: 3,
                run: two_masses,
            }),
        },
        VerifyCase {
            name: "spring_mass_oscillator_period",
            title: "Point mass on a spring to the ground (m = 1, k = 4), average-acceleration Newmark at dt = T/20, T/40, T/80: period vs 2 pi sqrt(m/k) and vs the rule's own, amplitude vs v0 / w",
            source: "Hughes, The Finite Element Method (2000), section 9.3.2 (period elongation of the trapezoidal rule)",
            tags: &["dynamics", "plane_strain"],
            levels: 3,
            // measured (levels 0, 1, 2): period 8.13e-3, 2.05e-3, 5.14e-4
            // (rate 2.0); vs the rule's 3.8e-5, 5.1e-7, 1.9e-7; amplitude
            // 8.5e-5, 4.6e-6, 8.1e-8
            checks: vec![
                Check::new(Quantity::Named(PERIOD), &[1e-2, 3e-3, 1e-3]),
                Check::new(Quantity::Named(RULE_PERIOD), &[1e-4]),
                Check::new(Quantity::Named(AMPLITUDE), &[1e-3]),
            ],
            kind: CaseKind::Program(ProgramCase {
                max_levels: 3,
                run: period,
            }),
        },
        VerifyCase {
            name: "dashpot_decrement",
            title: "Point mass on a spring and a dashpot to the ground (zeta = c / (2 sqrt(k m)) = 0.05), average-acceleration Newmark at dt = T/20, T/40, T/80: damping ratio from the logarithmic decrement, energy balance with the dashpot's dissipation",
            source: "Chopra, Dynamics of Structures (4th ed. 2012), section 2.2",
            tags: &["dynamics", "plane_strain"],
            levels: 3,
            // measured (levels 0, 1, 2): zeta 1.60e-2, 4.10e-3, 1.02e-3
            // (rate 2.0); balance 1.0e-14, 2.4e-14, 1.8e-14
            checks: vec![
                Check::new(Quantity::Named(DECREMENT), &[2e-2, 5e-3, 1.5e-3]),
                Check::new(Quantity::Named(BALANCE), &[1e-10]),
            ],
            kind: CaseKind::Program(ProgramCase {
                max_levels: 3,
                run: decrement,
            }),
        },
    ]
}
