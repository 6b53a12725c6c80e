//! VERIFICATION-CASES.md §8, thermal contact: steady conduction through a
//! pressed interface with the conductance `h = h0 + h1 p^n` (here
//! `3 + 0.5 sqrt(p)`), at two contact pressures, against the series
//! resistance of the slab(s) and the interface; and frictional heating of a
//! sliding block against `mu R_N du` (Wriggers, Computational Contact
//! Mechanics, 2nd ed., §10.2).
//!
//! ```text
//!   T_hot ───────────        T_hot ───────────
//!   │ block k1, l1  │        │ top  k2, l2   │
//!   ─── h(p) ───────         ─── h(p) ───────   node-to-segment
//!   ///// T_cold /////       │ base k1, l1   │
//!                            T_cold ──────────
//! ```

use super::{compile, error, read_case_deck, value};
use crate::case::{Check, Quantity};
use crate::registry::{CaseKind, ProgramCase, ProgramLevel, VerifyCase};
use ctc_engine::solve::{IncrementView, Observer, RunSummary};

/// Flux and interface temperatures are exact to round-off.
const EXACT: f64 = 1e-8;

/// The three cases.
pub fn cases() -> Vec<VerifyCase> {
    // exact flux and temperatures; nodal pressures uniform to 1e-9
    let checks = || -> Vec<Check> {
        let mut c: Vec<Check> = [
            "flux (low p)",
            "T_i (low p)",
            "flux (high p)",
            "T_i (high p)",
        ]
        .iter()
        .map(|n| Check::new(Quantity::Named(n), &[EXACT]))
        .collect();
        c.push(Check::new(Quantity::Named("p uniform"), &[1e-9]));
        c
    };
    vec![
        VerifyCase {
            name: "thermal_contact_tool",
            title: "Thermal contact: block pressed on a cold rigid tool, h(p), two pressures",
            source: "VERIFICATION-CASES.md §8 (series resistance l/k + 1/h)",
            tags: &[
                "thermal",
                "contact",
                "penalty",
                "plane_strain",
                "closed_form",
                "exact",
            ],
            levels: 1,
            checks: checks(),
            kind: CaseKind::Program(ProgramCase {
                max_levels: 1,
                run: |_| block_on_tool(),
            }),
        },
        VerifyCase {
            name: "thermal_contact_blocks",
            title: "Thermal contact: two blocks, node-to-segment, h(p), two pressures",
            source: "VERIFICATION-CASES.md §8 (series resistance l1/k1 + 1/h + l2/k2)",
            tags: &[
                "thermal",
                "contact",
                "node_to_segment",
                "plane_strain",
                "closed_form",
                "exact",
            ],
            levels: 1,
            checks: checks(),
            kind: CaseKind::Program(ProgramCase {
                max_levels: 1,
                run: |_| two_blocks(),
            }),
        },
        VerifyCase {
            name: "frictional_heating",
            title: "Frictional heating: sliding adiabatic block, work = mu R_N du, split 0.75",
            source: "VERIFICATION-CASES.md §8; Wriggers, Computational Contact Mechanics §10.2",
            tags: &[
                "thermal",
                "friction",
                "contact",
                "penalty",
                "plane_strain",
                "energy",
                "exact",
            ],
            levels: 1,
            checks: vec![
                Check::new(Quantity::Named("work / mu R_N du"), &[1e-9]),
                Check::new(Quantity::Named("stored = generated"), &[1e-12]),
                Check::new(Quantity::Named("generated / work"), &[1e-12]),
            ],
            kind: CaseKind::Program(ProgramCase {
                max_levels: 1,
                run: |_| frictional_heating(),
            }),
        },
    ]
}

/// The last converged increment's interface data.
#[derive(Default)]
struct Interface {
    /// Contact pressure of every closed node of pair 0.
    pressure: Vec<f64>,
    /// Total contact force (y) of pair 0.
    force: f64,
    /// Temperature of the slave nodes of pair 0.
    slave_temperature: Vec<f64>,
    /// Temperature of the master segment ends of pair 0 (deformable
    /// masters).
    master_temperature: Vec<f64>,
    /// Heat power into the slave side of pair 0.
    power: f64,
}

impl Observer for Interface {
    fn converged(&mut self, v: &IncrementView<'_>) -> Result<(), String> {
        let t = v.temperature.ok_or("no thermal scene")?;
        let pair = v.contact.first().ok_or("no contact pair")?;
        self.pressure = pair.iter().map(|c| c.pressure).collect();
        self.force = pair.iter().map(|c| c.force[1]).sum();
        self.slave_temperature = pair.iter().map(|c| t[c.node]).collect();
        self.master_temperature = pair
            .iter()
            .filter_map(|c| c.master.as_ref())
            .flat_map(|m| [t[m.nodes[0]], t[m.nodes[1]]])
            .collect();
        self.power = v.thermal.ok_or("no heat report")?.contact_power[0];
        Ok(())
    }
}

/// Adds the iteration counts of a run.
fn count(level: &mut ProgramLevel, nodes: usize, s: &RunSummary) {
    level.nodes = level.nodes.max(nodes);
    level.free_dofs = level.free_dofs.max(s.free_dofs);
    level.increments += s.increments.len();
    level.newton_total += s.newton_iterations;
    level.newton_max = level
        .newton_max
        .max(s.increments.iter().map(|i| i.iterations).max().unwrap_or(0));
    level.cutbacks += s.cutbacks;
}

/// Runs `cases/<deck>` with its top displacement `ramp` replaced by a push
/// of `stroke`; returns the probe, the (uniform) pressure and the largest
/// relative deviation of a nodal pressure from it.
fn run_pushed(
    deck: &str,
    ramp: &str,
    stroke: f64,
    level: &mut ProgramLevel,
) -> Result<(Interface, f64, f64), String> {
    let (path, text) = read_case_deck(deck)?;
    if !text.contains(ramp) {
        return Err(format!("{deck} has no `{ramp}` to replace"));
    }
    let text = text.replace(ramp, &format!("ramp(0, {})", -stroke));
    let model = compile(&path, &text)?;
    let mut probe = Interface::default();
    let s = ctc_engine::solve::run(&model, &mut probe).map_err(|e| e.message)?;
    count(level, model.mesh.nodes.len(), &s);
    let p = probe.force;
    let spread = probe
        .pressure
        .iter()
        .map(|pi| (pi - p).abs() / p.abs())
        .fold(0.0, f64::max);
    Ok((probe, p, spread))
}

/// Pushes the deck at two strokes and judges flux and interface
/// temperatures against `exact(p) -> (q, [(temperatures, T_exact)])`.
fn two_pressures(
    deck: &str,
    ramp: &str,
    strokes: [f64; 2],
    exact: impl Fn(&Interface, f64) -> (f64, f64),
) -> Result<ProgramLevel, String> {
    let mut level = ProgramLevel {
        h: f64::NAN,
        ..ProgramLevel::default()
    };
    let names = [
        ("flux (low p)", "T_i (low p)"),
        ("flux (high p)", "T_i (high p)"),
    ];
    let mut pressures = Vec::new();
    let mut spread = 0.0f64;
    for (stroke, (flux, t_i)) in strokes.into_iter().zip(names) {
        let (probe, p, s) = run_pushed(deck, ramp, stroke, &mut level)?;
        let (q, t_error) = exact(&probe, p);
        // heat leaves through the slave side: power into the slave < 0
        level.values.push(value(flux, -probe.power, q));
        level.values.push(error(t_i, t_error));
        pressures.push(p);
        spread = spread.max(s);
    }
    level.values.push(error("p uniform", spread));
    if pressures[1] <= 5.0 * pressures[0] {
        return Err(format!(
            "the two pressures {pressures:?} are too close to test h(p)"
        ));
    }
    Ok(level)
}

/// Case 8 on a rigid tool: block k = 2, l = 2, T_hot = 100, T_cold = 20.
fn block_on_tool() -> Result<ProgramLevel, String> {
    two_pressures(
        "thermal_contact_tool.ctc",
        "ramp(0, -0.004)",
        [0.004, 0.04],
        |probe, p| {
            let (k1, l1, t_hot, t_cold) = (2.0, 2.0, 100.0, 20.0);
            let h = 3.0 + 0.5 * p.sqrt();
            let q = (t_hot - t_cold) / (l1 / k1 + 1.0 / h);
            let t_i = t_cold + q / h;
            let t_error = probe
                .slave_temperature
                .iter()
                .map(|t| (t - t_i).abs() / (t_hot - t_cold))
                .fold(0.0, f64::max);
            (q, t_error)
        },
    )
}

/// Case 8 between two blocks (node-to-segment, matching meshes): base
/// k = 2, l = 1, top k = 0.5, l = 1.5.
fn two_blocks() -> Result<ProgramLevel, String> {
    two_pressures(
        "thermal_contact_blocks.ctc",
        "ramp(0, -0.1)",
        [0.01, 0.1],
        |probe, p| {
            let (k1, l1, k2, l2, t_hot, t_cold) = (2.0, 1.0, 0.5, 1.5, 100.0, 20.0);
            let h = 3.0 + 0.5 * p.sqrt();
            let q = (t_hot - t_cold) / (l1 / k1 + 1.0 / h + l2 / k2);
            let t_base = t_cold + q * l1 / k1;
            let t_top = t_base + q / h;
            let slave = probe
                .slave_temperature
                .iter()
                .map(|t| (t - t_top).abs() / (t_hot - t_cold));
            let master = probe
                .master_temperature
                .iter()
                .map(|t| (t - t_base).abs() / (t_hot - t_cold));
            // no master temperature would be a broken probe: infinite error
            let t_error = if probe.master_temperature.is_empty() {
                f64::INFINITY
            } else {
                slave.chain(master).fold(0.0, f64::max)
            };
            (q, t_error)
        },
    )
}

/// Per increment: time, normal force, heat report, every node slipping.
#[derive(Default)]
struct Sliding {
    rows: Vec<(
        f64,
        f64,
        ctc_engine::thermal::solver::ThermalIncrement,
        bool,
    )>,
}

impl Observer for Sliding {
    fn converged(&mut self, v: &IncrementView<'_>) -> Result<(), String> {
        let pair = v.contact.first().ok_or("no contact pair")?;
        let normal: f64 = pair.iter().map(|c| c.force[1]).sum();
        let all_slip = pair
            .iter()
            .all(|c| c.friction.status == ctc_engine::contact::friction::FrictionStatus::Slip);
        let heat = v.thermal.ok_or("no heat report")?.clone();
        self.rows.push((v.time, normal, heat, all_slip));
        Ok(())
    }
}

/// The sliding block of `cases/frictional_heating.ctc` (mu = 0.3, split
/// 0.75, top increment du = 0.1 per increment while sliding).
fn frictional_heating() -> Result<ProgramLevel, String> {
    let (path, text) = read_case_deck("frictional_heating.ctc")?;
    let model = compile(&path, &text)?;
    let mut probe = Sliding::default();
    let s = ctc_engine::solve::run(&model, &mut probe).map_err(|e| e.message)?;
    let mut level = ProgramLevel {
        h: f64::NAN,
        ..ProgramLevel::default()
    };
    count(&mut level, model.mesh.nodes.len(), &s);
    let (mu, split, du) = (0.3, 0.75, 0.1);
    let (mut work, mut balance, mut share) = (0.0f64, 0.0f64, 0.0f64);
    let mut steady = 0;
    for (k, (_, rn, heat, all_slip)) in probe.rows.iter().enumerate() {
        // adiabatic block: what is generated is stored, to the round-off of
        // the heat content rho c V T = 1 x 20
        balance = balance.max((heat.stored - heat.generated).abs() / 20.0);
        let scale = heat.friction.abs().max(1e-300);
        share = share.max((heat.generated - split * heat.friction).abs() / scale);
        // steady sliding (every node slipping now and at the previous
        // increment): each node slides by the top's increment exactly
        if k >= 2 && *all_slip && probe.rows[k - 1].3 {
            let expect = mu * rn * du;
            work = work.max((heat.friction - expect).abs() / expect);
            steady += 1;
        }
    }
    if steady < 3 {
        return Err(format!(
            "expected at least 3 steady sliding increments, found {steady}"
        ));
    }
    level.values = vec![
        error("work / mu R_N du", work),
        error("stored = generated", balance),
        error("generated / work", share),
    ];
    Ok(level)
}
