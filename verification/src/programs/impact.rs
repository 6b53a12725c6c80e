//! Contact in implicit dynamics (tags `dynamics`, `contact`): elastic bars
//! in impact against 1D wave theory (Graff, Wave Motion in Elastic
//! Solids, 1975, section 1.4; the rod-impact solution of Johnson, Impact
//! Strength of Materials, 1972, section 1.3):
//!
//! ```text
//!   wall |<- [==== bar L = 10 ====] v0          [== a ==]-> v0  v0 <-[== b ==]
//! ```
//!
//! A bar of length `L`, wave speed `c = sqrt(E / rho)`, moving at `v0`
//! against a rigid wall (or against an identical bar moving at `-v0`)
//! stays in contact for `2 L / c`, the contact force is `rho c v0 A` during
//! it, and the bar leaves at `-v0`: the impulse is `2 m v0`, no energy is
//! lost or created. Measured on the discrete bar (E = 1, nu = 0, rho = 1,
//! 40 cells along the bar, dt = 0.1, plane strain with uy held, 3D with uy
//! and uz held):
//!
//! - `bar_impact_wave_theory`: quad4 bar on a rigid plane (penalty 100,
//!   generalized-alpha rho_inf = 0.9, consistent mass), hex8 bar on a
//!   rigid plane (same), two quad4 bars (node-to-segment, Lagrange
//!   multipliers, average-acceleration Newmark); impulse, contact duration,
//!   the mean force of the plateau (t in [2, 18]) and the energy gain over
//!   the initial kinetic energy, with the contact nodes' mass redistributed
//!   (`dynamic { contact_mass = redistributed }`, the default; Khenous,
//!   Laborde & Renard 2008), and the gain of the same run with the full
//!   mass (`contact_mass = full`: the nodes chatter and the contact creates
//!   energy) without the energy control of dynamic steps (`energy_tol =
//!   0`: plain generalized-alpha / Newmark with penalty) and with it (the
//!   default, `energy_tol = 1e-3`) reported beside it.
//! - `bar_impact_adaptive`: the quad4 bar on the wall with adaptive time
//!   stepping (`dynamic { adaptive = true  dt_max = 1  error_tol = 5e-3 }`:
//!   the Zienkiewicz-Xie error estimate, contact events) against the same
//!   run at the fixed dt = 0.1: contact duration (the end of the first
//!   increment without contact force), rebound speed `sqrt(2 K / m)` at t =
//!   30 and energy gain against 1D wave theory, and the ratio of the
//!   increments taken.

use crate::case::{Check, Quantity};
use crate::measure::Value;
use crate::registry::{CaseKind, ProgramCase, ProgramLevel, VerifyCase};
use ctc_engine::model::AnyModel;
use ctc_engine::solve::{run, IncrementView, Observer, RunSummary};

/// Wave speed `sqrt(E / rho)` of the decks.
const C: f64 = 1.0;
/// Initial speed of each bar.
const V0: f64 = 0.1;
/// Length of each bar.
const L: f64 = 10.0;

/// The scene names (their decks: [`deck`]).
const SCENES: [&str; 3] = [
    "quad4 bar on a wall",
    "hex8 bar on a wall",
    "two quad4 bars",
];

const NAMES: [[&str; 6]; 3] = [
    [
        "quad4 bar on a wall: impulse / (2 m v0) - 1",
        "quad4 bar on a wall: contact duration / (2 L / c) - 1",
        "quad4 bar on a wall: plateau force / (rho c v0 A) - 1",
        "quad4 bar on a wall: energy gain / K0",
        "quad4 bar on a wall: energy gain / K0 with the full mass (not judged)",
        "quad4 bar on a wall: energy gain / K0 with the full mass and the energy control (not judged)",
    ],
    [
        "hex8 bar on a wall: impulse / (2 m v0) - 1",
        "hex8 bar on a wall: contact duration / (2 L / c) - 1",
        "hex8 bar on a wall: plateau force / (rho c v0 A) - 1",
        "hex8 bar on a wall: energy gain / K0",
        "hex8 bar on a wall: energy gain / K0 with the full mass (not judged)",
        "hex8 bar on a wall: energy gain / K0 with the full mass and the energy control (not judged)",
    ],
    [
        "two quad4 bars: impulse / (2 m v0) - 1",
        "two quad4 bars: contact duration / (2 L / c) - 1",
        "two quad4 bars: plateau force / (rho c v0 A) - 1",
        "two quad4 bars: energy gain / K0",
        "two quad4 bars: energy gain / K0 with the full mass (not judged)",
        "two quad4 bars: energy gain / K0 with the full mass and the energy control (not judged)",
    ],
];

/// The deck of scene `s` with `contact_mass`.
fn deck(s: usize, contact_mass: &str) -> String {
    deck_with(s, contact_mass, "")
}

/// The deck of scene `s` with `contact_mass` and `extra` keys in its
/// `dynamic` block.
fn deck_with(s: usize, contact_mass: &str, extra: &str) -> String {
    let dynamic = |scheme: &str| {
        format!(
            "step impact {{\n  time = 0 .. 30\n  increments = 300\n  \
             dynamic {{ {scheme}  mass = consistent  contact_mass = {contact_mass}{extra} }}\n  \
             newton {{ tol = 1e-10 }}\n}}\n"
        )
    };
    let material = "material m { elastic { E = 1  nu = 0 }  density = 1 }\n";
    match s {
        0 => format!(
            "analysis {{ dimension = plane_strain }}\n{material}\
             body bar {{\n  mesh = rectangle {{ origin = (0, 0)  size = (10, 1)  divisions = (40, 1) }}\n  material = m\n}}\n\
             tool wall = plane {{ point = (0, 0)  normal = (1, 0) }}\n\
             contact bar.left -> wall {{ method = penalty {{ stiffness = 100 }} }}\n\
             fix bar.bottom {{ uy }}\nfix bar.top {{ uy }}\n\
             initial_velocity bar.all {{ vx = -0.1 }}\n{}",
            dynamic("scheme = generalized_alpha  rho_inf = 0.9")
        ),
        1 => format!(
            "analysis {{ dimension = 3d }}\n{material}\
             body bar {{\n  mesh = box {{ size = (10, 1, 1)  divisions = (40, 1, 1) }}\n  material = m\n}}\n\
             tool wall = plane {{ point = (0, 0, 0)  normal = (1, 0, 0) }}\n\
             contact bar.xmin -> wall {{ method = penalty {{ stiffness = 100 }} }}\n\
             fix bar.all {{ uy uz }}\n\
             initial_velocity bar.all {{ vx = -0.1 }}\n{}",
            dynamic("scheme = generalized_alpha  rho_inf = 0.9")
        ),
        _ => format!(
            "analysis {{ dimension = plane_strain }}\n{material}\
             body a {{\n  mesh = rectangle {{ origin = (-10, 0)  size = (10, 1)  divisions = (40, 1) }}\n  material = m\n}}\n\
             body b {{\n  mesh = rectangle {{ origin = (0, 0)  size = (10, 1)  divisions = (40, 1) }}\n  material = m\n}}\n\
             contact a.right -> b.left {{ method = lagrange {{ }} }}\n\
             fix a.bottom {{ uy }}\nfix a.top {{ uy }}\nfix b.bottom {{ uy }}\nfix b.top {{ uy }}\n\
             initial_velocity a.all {{ vx = 0.1 }}\ninitial_velocity b.all {{ vx = -0.1 }}\n{}",
            dynamic("scheme = newmark")
        ),
    }
}

/// Per converged increment: time, the contact force along x on the first
/// pair's slave side (its magnitude), the energy gain and `K0`.
#[derive(Default)]
struct Trace {
    rows: Vec<(f64, f64)>,
    gain: f64,
    kinetic0: f64,
    /// Kinetic energy at the last increment.
    kinetic: f64,
}

impl Trace {
    /// The end of the first increment without contact force after the
    /// contact began.
    fn release(&self) -> Result<f64, String> {
        self.rows
            .iter()
            .skip_while(|(_, f)| *f == 0.0)
            .find(|(_, f)| *f == 0.0)
            .map(|(t, _)| *t)
            .ok_or_else(|| "the bar never left the contact".to_string())
    }
}

impl<const D: usize> Observer<D> for Trace {
    fn converged(&mut self, view: &IncrementView<'_, D>) -> Result<(), String> {
        let fx: f64 = view
            .contact
            .first()
            .map_or(0.0, |p| p.iter().map(|n| n.force[0]).sum());
        self.rows.push((view.time, fx.abs()));
        if let Some(e) = view.energy {
            self.gain = e.gain;
            self.kinetic = e.kinetic;
            if self.kinetic0 == 0.0 {
                // K + W_int - W_ext at the first increment minus the gain
                self.kinetic0 = e.kinetic + e.internal - e.external - e.gain;
            }
        }
        Ok(())
    }
}

/// Runs scene `s`; the trace and the summary.
fn solve(s: usize, contact_mass: &str) -> Result<(Trace, RunSummary), String> {
    solve_deck(s, deck(s, contact_mass))
}

/// Runs the deck `text` of scene `s`; the trace and the summary.
fn solve_deck(s: usize, text: String) -> Result<(Trace, RunSummary), String> {
    let src = ctc_lang::Source::new("bar_impact.ctc", text);
    let mut trace = Trace::default();
    let summary = match ctc_lang::compile_any(&src).map_err(|d| d.render(&src))? {
        AnyModel::D2(m) => run(&m, &mut trace),
        AnyModel::D3(m) => run(&m, &mut trace),
    }
    .map_err(|e| e.message)?;
    if !summary.completed {
        return Err(format!("{}: the run did not complete", SCENES[s]));
    }
    Ok((trace, summary))
}

fn measure(_level: usize) -> Result<ProgramLevel, String> {
    let mut out = ProgramLevel {
        h: f64::NAN,
        ..ProgramLevel::default()
    };
    let (rho, area) = (1.0, 1.0);
    let mass = rho * L * area;
    for (s, names) in NAMES.iter().enumerate() {
        let (trace, summary) = solve(s, "redistributed")?;
        // the full mass without the energy control, then with it (the
        // default)
        let (full, _) = solve_deck(s, deck_with(s, "full", "  energy_tol = 0"))?;
        let (full_controlled, _) = solve(s, "full")?;
        let dt = 0.1;
        // the impulse of the force history (constant per increment, the
        // force at its end: the backward rectangle rule)
        let impulse: f64 = trace.rows.iter().map(|(_, f)| f * dt).sum();
        let release = trace.release()?;
        let plateau: Vec<f64> = trace
            .rows
            .iter()
            .filter(|(t, _)| (2.0..=18.0).contains(t))
            .map(|(_, f)| *f)
            .collect();
        let plateau = plateau.iter().sum::<f64>() / plateau.len().max(1) as f64;
        let k0 = 0.5 * mass * V0 * V0 * if s == 2 { 2.0 } else { 1.0 };
        let rel = |name: &'static str, computed: f64, reference: f64| Value {
            quantity: Quantity::Named(name),
            reference: Some(reference),
            computed,
            error: (computed / reference - 1.0).abs(),
        };
        out.values.push(rel(names[0], impulse, 2.0 * mass * V0));
        out.values.push(rel(names[1], release, 2.0 * L / C));
        out.values.push(rel(names[2], plateau, rho * C * V0 * area));
        out.values
            .push(super::error(names[3], trace.gain.abs() / k0));
        out.values
            .push(super::error(names[4], full.gain.abs() / k0));
        out.values
            .push(super::error(names[5], full_controlled.gain.abs() / k0));
        if trace.kinetic0 > 0.0 && (trace.kinetic0 / k0 - 1.0).abs() > 1e-6 {
            return Err(format!(
                "{}: initial kinetic energy {:e}, expected {k0:e}",
                SCENES[s], trace.kinetic0
            ));
        }
        out.add_run(&summary);
    }
    Ok(out)
}

/// Names of `bar_impact_adaptive`'s values.
const ADAPTIVE: [&str; 7] = [
    "adaptive: contact duration / (2 L / c) - 1",
    "adaptive: rebound speed / v0 - 1",
    "adaptive: energy gain / K0",
    "adaptive: increments / increments at fixed dt = 0.1",
    "fixed dt = 0.1: contact duration / (2 L / c) - 1 (not judged)",
    "fixed dt = 0.1: rebound speed / v0 - 1 (not judged)",
    "fixed dt = 0.1: energy gain / K0 (not judged)",
];

/// The quad4 bar on the wall, adaptive against fixed stepping.
fn measure_adaptive(_level: usize) -> Result<ProgramLevel, String> {
    let mut out = ProgramLevel {
        h: f64::NAN,
        ..ProgramLevel::default()
    };
    let mass = L;
    let k0 = 0.5 * mass * V0 * V0;
    let (fixed, fixed_summary) = solve(0, "redistributed")?;
    let (adaptive, summary) = solve_deck(
        0,
        deck_with(
            0,
            "redistributed",
            "  adaptive = true  dt_max = 1  error_tol = 5e-3",
        ),
    )?;
    let figures = |t: &Trace| -> Result<[f64; 3], String> {
        Ok([
            t.release()? / (2.0 * L / C) - 1.0,
            (2.0 * t.kinetic / mass).sqrt() / V0 - 1.0,
            t.gain.abs() / k0,
        ])
    };
    let a = figures(&adaptive)?;
    let f = figures(&fixed)?;
    for (name, x) in ADAPTIVE[..3].iter().zip(a) {
        out.values.push(super::error(name, x.abs()));
    }
    out.values.push(super::error(
        ADAPTIVE[3],
        summary.increments.len() as f64 / fixed_summary.increments.len() as f64,
    ));
    for (name, x) in ADAPTIVE[4..].iter().zip(f) {
        out.values.push(super::error(name, x.abs()));
    }
    out.add_run(&summary);
    Ok(out)
}

/// The registry entry.
pub fn cases() -> Vec<VerifyCase> {
    // measured (redistributed contact mass; bar/wall 2D and 3D, two
    // bars): impulse 1.2e-3, 1.2e-3, 1.5e-3; duration 0 (released at the
    // increment of t = 20); plateau force 1.8e-3, 1.8e-3, 2.0e-3; gain
    // 5.3e-4, 5.3e-4, 1.0e-4 of K0 (with the full mass: 0.62, 0.62, 6.9;
    // the full mass with the energy control, the default: 5.4e-3, 3.3e-3,
    // 4.5e-3)
    let mut checks = Vec::new();
    for names in NAMES {
        checks.push(Check::new(Quantity::Named(names[0]), &[1e-2]));
        checks.push(Check::new(Quantity::Named(names[1]), &[1e-2]));
        checks.push(Check::new(Quantity::Named(names[2]), &[1e-2]));
        checks.push(Check::new(Quantity::Named(names[3]), &[2e-3]));
    }
    let adaptive = VerifyCase {
        name: "bar_impact_adaptive",
        title: "Adaptive time stepping (Zienkiewicz-Xie error estimate, contact events) on the elastic bar hitting a rigid wall: contact duration 2L/c, rebound speed v0 and energy as at the fixed dt, with fewer increments",
        source: "Graff, Wave Motion in Elastic Solids (1975), section 1.4; Zienkiewicz & Xie 1991, Earthquake Eng. Struct. Dyn. 20:871 (local error estimate)",
        tags: &["dynamics", "contact", "plane_strain", "adaptive"],
        levels: 1,
        checks: vec![
            Check::new(Quantity::Named(ADAPTIVE[0]), &[1e-2]),
            Check::new(Quantity::Named(ADAPTIVE[1]), &[1e-2]),
            Check::new(Quantity::Named(ADAPTIVE[2]), &[5e-3]),
            Check::new(Quantity::Named(ADAPTIVE[3]), &[0.9]),
        ],
        kind: CaseKind::Program(ProgramCase {
            max_levels: 1,
            run: measure_adaptive,
        }),
    };
    vec![adaptive, VerifyCase {
        name: "bar_impact_wave_theory",
        title: "Elastic bars in impact (bar on a rigid wall in 2D and 3D, two bars): impulse, contact duration 2L/c, force rho c v0 A and energy against 1D wave theory, with the contact nodes' mass redistributed",
        source: "Graff, Wave Motion in Elastic Solids (1975), section 1.4; Khenous, Laborde & Renard 2008, Eur. J. Mech. A/Solids 27:918 (mass redistribution)",
        tags: &["dynamics", "contact", "plane_strain", "3d"],
        levels: 1,
        checks,
        kind: CaseKind::Program(ProgramCase {
            max_levels: 1,
            run: measure,
        }),
    }]
}
