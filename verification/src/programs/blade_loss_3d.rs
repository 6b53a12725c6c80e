//! Blade loss in a reduced rotor, 3D (issue 19; tags `dynamics`,
//! `contact`, `friction`, `rigid_body`, `3d`, `example`):
//! `examples/blade_loss_3d.ctc`, the rotor of `examples/blade_loss.ctc`
//! as a hex8 slice of its plane-strain thickness (10 mm, one cell
//! axially): a shaft (3D rigid body, 6 dofs, rotation prescribed about z)
//! on isotropic damped bearings, a disc with six flexible blades, blade 1
//! released at 6 ms, node-to-facet contact with Coulomb friction on the
//! casing.
//!
//! Reference: Coulomb friction's dissipation (the friction work against
//! `sum mu |R_N| |slip|`, `R_N` the normal part of the node's force), the
//! energy audit (its error `energy_balance + numerical_dissipation`
//! against the largest kinetic energy), the released blade's root outside
//! the disc's rim (R = 100 mm) and flying outward, the shaft's orbit
//! bounded (0.6 mm clearance). The slice against the planar run (a slice
//! whose nodes are held axially is the plane-strain model, so the orbits
//! agree to the release) is the cargo test
//! `blade_loss_3d_slice_follows_the_planar_orbit`
//! (`tests/suite/blade_loss_3d.rs`); the Jeffcott ODE is the planar case
//! [`super::blade_loss`].
//!
//! ```text
//!      z ^   casing (springs outside)      one hex8 layer, 10 mm:
//!        |  .-~~~~~~~~~~~-.                 the planar deck extruded
//!        | /   \   |   /   \                blade 1 released at 6 ms
//!        ||  ---( (o) )---  |               shaft: 3D rigid body on
//!        | \   /   |   \   /                k, c bearings (x, y, z),
//!        |  '-~~~~~~~~~~-'                 spun about z (tilt held)
//! ```
//!
//! Levels: the deck's flight (increments of 25 us after the release at 6
//! ms) to 7 ms (level 0, 40 flight increments: the run of the cargo tests,
//! `tests/suite/blade_loss_3d.rs`, shared with the examples test, so the
//! catalogue test leaves it out: [`crate::registry::RUN_BY_THE_CTC_SUITE`]),
//! to 9 ms as written (level 1, 120) and to 20 ms (level 2, 560).
//! Measured (`ctc verify blade_loss_3d --max-level 2 -j 1`, debug, 206 s
//! CPU for the three levels):
//!
//! | level | flight | its | energy error / K | orbit max mm | root min mm | friction work mJ |
//! | --- | --- | --- | --- | --- | --- | --- |
//! | 0 | 7 ms | 461 (102 increments, 1 cutback) | 5.7e-6 | 0.574 | 99.936 | 6.15e4 |
//! | 1 | 9 ms | 801 | 1.29e-5 | 0.769 | 99.84 | 5.36e5 |
//! | 2 | 20 ms | 3053 | 1.93e-4 | 0.996 | - | 5.47e6 |

use crate::case::{Check, Quantity};
use crate::measure::Value;
use crate::registry::{CaseKind, ProgramCase, ProgramLevel, VerifyCase};
use ctc_engine::geom::Dimension;
use ctc_engine::model::{AnyModel, Model};
use ctc_engine::solve::{IncrementView, Observer, RunSummary};
use nalgebra::Const;

/// Per level: the flight's end and its increments (level 1 is the deck
/// as written).
pub const LEVELS: [(&str, usize); 3] = [("7e-3", 40), ("9e-3", 120), ("20e-3", 560)];

/// The disc's rim radius (mm).
pub const RIM: f64 = 100.0;

/// The names of the measured values.
const NAMES: [&str; 12] = [
    "friction work (summary) vs the sum of the nodes' dissipations",
    "return map's -T_1 . slip vs sum mu |R_N| |slip|",
    "energy error (balance + numerical dissipation) / largest K",
    "released blade's root mean radius inside the rim (mm, 0 outside)",
    "released blade's root inside the rim at the end (mm, 0 outside: it flies outward)",
    "largest orbit radius of the shaft (mm)",
    "friction work (mJ, not judged)",
    "energy balance / largest K (the scheme's dissipation in it, not judged)",
    "numerical dissipation / largest K (not judged)",
    "largest kinetic energy K (mJ, not judged)",
    "largest axial motion of the shaft (mm, not judged)",
    "largest contact force of a pair (N, not judged)",
];

/// `examples/blade_loss_3d.ctc` at `level` ([`LEVELS`]).
pub fn deck(level: usize) -> Result<ctc_lang::Source, String> {
    let (end, n) = LEVELS[level.min(LEVELS.len() - 1)];
    super::blade_loss::flight_deck("blade_loss_3d.ctc", end, n, "")
}

/// The deck of `level` compiled.
pub fn model(level: usize) -> Result<Model<3>, String> {
    let src = deck(level)?;
    match ctc_lang::compile_any(&src).map_err(|d| d.render(&src))? {
        AnyModel::D3(m) => Ok(m),
        AnyModel::D2(_) => Err("examples/blade_loss_3d.ctc is not a 3D deck".into()),
    }
}

/// The shaft's orbit and the audit of a run, in either dimension.
#[derive(Debug, Default)]
pub struct Probe {
    pilot: usize,
    /// Time, per increment.
    pub time: Vec<f64>,
    /// The pilot's displacement in the plane (and its z in 3D).
    pub centre: Vec<[f64; 3]>,
    /// Sum of the nodes' friction dissipation (the time scheme's:
    /// trapezoidal in dynamics), of the return map's `-T_1 . slip` and of
    /// mu |R_N| |slip|.
    pub dissipation: f64,
    /// See [`Probe::dissipation`].
    pub return_map: f64,
    /// See [`Probe::dissipation`].
    pub mu_rn_slip: f64,
    /// Largest `|energy_error|`, `|energy_balance|`, kinetic energy; the
    /// numerical dissipation at the end.
    pub error: f64,
    /// See [`Probe::error`].
    pub balance: f64,
    /// See [`Probe::error`].
    pub kinetic: f64,
    /// See [`Probe::error`].
    pub numerical: f64,
    /// Per increment: time, kinetic energy, energy balance, energy error.
    pub energy: Vec<[f64; 4]>,
    /// The released blade's root nodes and, per increment, their mean
    /// distance in the plane from the shaft's centre.
    root: Vec<usize>,
    /// See [`Probe::root`].
    pub root_radius: Vec<f64>,
    /// The largest contact force of a pair (its resultant) over the run.
    pub contact_force_max: f64,
}

impl<const D: usize> Observer<D> for Probe
where
    Const<D>: Dimension<D>,
{
    fn converged(&mut self, v: &IncrementView<'_, D>) -> Result<(), String> {
        self.time.push(v.time);
        let u = v.displacement[self.pilot];
        self.centre
            .push([u[0], u[1], if D == 3 { u[D - 1] } else { 0.0 }]);
        for (p, pair) in v.contact.iter().enumerate() {
            let mu = v.model.contacts[p].friction.map_or(0.0, |f| f.mu);
            let mut force = [0.0; D];
            for n in pair {
                // the normal part of the force (the friction traction off)
                let rn: f64 = (0..D)
                    .map(|k| (n.force[k] - n.friction.traction[k]) * n.normal[k])
                    .sum::<f64>()
                    .abs();
                self.dissipation += n.friction.dissipation;
                self.return_map -= (0..D)
                    .map(|k| n.friction.traction[k] * n.friction.slip_vector[k])
                    .sum::<f64>();
                self.mu_rn_slip += mu * rn * n.friction.slip.abs();
                for (f, nf) in force.iter_mut().zip(&n.force) {
                    *f += nf;
                }
            }
            let norm = force.iter().map(|f| f * f).sum::<f64>().sqrt();
            self.contact_force_max = self.contact_force_max.max(norm);
        }
        let at = v.positions();
        let c = at[self.pilot];
        let mean = self
            .root
            .iter()
            .map(|&n| (at[n][0] - c[0]).hypot(at[n][1] - c[1]))
            .sum::<f64>()
            / self.root.len().max(1) as f64;
        self.root_radius.push(mean);
        if let Some(e) = v.energy {
            self.error = self.error.max(e.error.abs());
            self.balance = self.balance.max(e.balance.abs());
            self.kinetic = self.kinetic.max(e.kinetic);
            self.numerical = e.numerical;
            self.energy.push([v.time, e.kinetic, e.balance, e.error]);
        }
        Ok(())
    }
}

/// The probe of a run (planar or 3D): the rigid body's pilot, the
/// released blade's root.
pub fn probe_of<const D: usize>(model: &Model<D>) -> Result<Probe, String>
where
    Const<D>: Dimension<D>,
{
    let (pilot, _) = ctc_engine::solve::rigid_body::bodies(model)
        .next()
        .ok_or("no rigid body in the deck")?;
    // the released blade's root: the first side of the released links
    let root = model
        .discrete
        .iter()
        .flat_map(|d| match d {
            ctc_engine::model::Discrete::Link {
                pairs,
                release_at: Some(_),
                ..
            } => pairs.iter().map(|p| p.0).collect(),
            _ => Vec::new(),
        })
        .collect();
    Ok(Probe {
        pilot,
        root,
        ..Probe::default()
    })
}

/// What [`measure`] finds in a run.
#[derive(Debug, Clone, Default)]
pub struct Measured {
    /// Converged increments, Newton iterations, cutbacks.
    pub increments: usize,
    /// See [`Measured::increments`].
    pub iterations: usize,
    /// See [`Measured::increments`].
    pub cutbacks: usize,
    /// The summary's friction work, its relative difference from the sum
    /// of the nodes' dissipations.
    pub friction_total: f64,
    /// See [`Measured::friction_total`].
    pub friction_vs_nodes: f64,
    /// The return map's `-T_1 . slip`, `sum mu |R_N| |slip|`, their
    /// relative difference.
    pub return_map: f64,
    /// See [`Measured::return_map`].
    pub mu_rn_slip: f64,
    /// See [`Measured::return_map`].
    pub friction_error: f64,
    /// Largest `|error|`, largest `|balance|`, numerical dissipation at the
    /// end, over the largest kinetic energy; that energy.
    pub error: f64,
    /// See [`Measured::error`].
    pub balance: f64,
    /// See [`Measured::error`].
    pub numerical: f64,
    /// See [`Measured::error`].
    pub kinetic: f64,
    /// The released blade's root mean radius: least after the release, at
    /// the end.
    pub root_min: f64,
    /// See [`Measured::root_min`].
    pub root_end: f64,
    /// The largest orbit radius (in the plane), the largest axial motion.
    pub peak: f64,
    /// See [`Measured::peak`].
    pub axial: f64,
    /// The largest resultant contact force of a pair.
    pub contact_force_max: f64,
}

/// Measures a run ([`Probe`] and summary).
pub fn measure(probe: &Probe, summary: &RunSummary) -> Result<Measured, String> {
    let friction_total: f64 = summary.friction_work.iter().sum();
    let release = probe
        .time
        .iter()
        .position(|&t| t > 6e-3)
        .ok_or("the run ended before the release")?;
    let kinetic = probe.kinetic.max(f64::MIN_POSITIVE);
    Ok(Measured {
        increments: summary.increments.len(),
        iterations: summary.newton_iterations,
        cutbacks: summary.cutbacks,
        friction_total,
        friction_vs_nodes: (friction_total - probe.dissipation).abs()
            / friction_total.abs().max(f64::MIN_POSITIVE),
        return_map: probe.return_map,
        mu_rn_slip: probe.mu_rn_slip,
        friction_error: (probe.return_map - probe.mu_rn_slip).abs()
            / probe.mu_rn_slip.max(f64::MIN_POSITIVE),
        error: probe.error / kinetic,
        balance: probe.balance / kinetic,
        numerical: probe.numerical / kinetic,
        kinetic: probe.kinetic,
        root_min: probe.root_radius[release..]
            .iter()
            .copied()
            .fold(f64::INFINITY, f64::min),
        root_end: probe.root_radius.last().copied().unwrap_or(f64::NAN),
        peak: probe
            .centre
            .iter()
            .map(|c| c[0].hypot(c[1]))
            .fold(0.0, f64::max),
        axial: probe.centre.iter().map(|c| c[2].abs()).fold(0.0, f64::max),
        contact_force_max: probe.contact_force_max,
    })
}

impl Measured {
    /// The values the case judges (and those it reports).
    pub fn values(&self) -> Vec<Value> {
        let e = super::error;
        vec![
            e(NAMES[0], self.friction_vs_nodes),
            e(NAMES[1], self.friction_error),
            e(NAMES[2], self.error),
            e(NAMES[3], (RIM - self.root_min).max(0.0)),
            e(NAMES[4], (RIM - self.root_end).max(0.0)),
            e(NAMES[5], self.peak),
            e(NAMES[6], self.friction_total),
            e(NAMES[7], self.balance),
            e(NAMES[8], self.numerical),
            e(NAMES[9], self.kinetic),
            e(NAMES[10], self.axial),
            e(NAMES[11], self.contact_force_max),
        ]
    }

    /// One line of figures (the cargo test prints it).
    pub fn line(&self) -> String {
        format!(
            "{} increments, {} iterations, {} cutbacks; orbit peak {:.4e}; axial {:.2e}; \
             friction work {:.4e} (the return map's {:.4e}) vs sum mu R_N slip {:.4e} ({:.1e}); \
             balance {:.2e}, numerical {:.2e}, error {:.2e} of max K {:.4e}; root radius min \
             {:.3} end {:.3}; max contact force {:.4e}",
            self.increments,
            self.iterations,
            self.cutbacks,
            self.peak,
            self.axial,
            self.friction_total,
            self.return_map,
            self.mu_rn_slip,
            self.friction_error,
            self.balance,
            self.numerical,
            self.error,
            self.kinetic,
            self.root_min,
            self.root_end,
            self.contact_force_max,
        )
    }
}

fn level_run(level: usize) -> Result<ProgramLevel, String> {
    let model = model(level)?;
    let mut probe = probe_of(&model)?;
    let summary = super::blade_loss::run_with(&model, &mut probe, &mut super::blade_loss::Quiet)?;
    let m = measure(&probe, &summary)?;
    let orbit: Vec<(f64, [f64; 2])> = probe
        .time
        .iter()
        .zip(&probe.centre)
        .map(|(t, c)| (*t, [c[0], c[1]]))
        .collect();
    let mut out = ProgramLevel {
        h: f64::NAN,
        values: m.values(),
        figures: super::blade_loss::figures(&orbit, &probe.energy),
        ..ProgramLevel::default()
    };
    out.add_run(&summary);
    Ok(out)
}

/// The registry entry.
pub fn cases() -> Vec<VerifyCase> {
    vec![VerifyCase {
        name: "blade_loss_3d",
        title: "Blade loss in a reduced rotor, 3D (examples/blade_loss_3d.ctc): the planar rotor as a hex8 slice, a shaft (3D rigid body, 6 dofs) on damped spring bearings, blade 1 released at 6 ms, node-to-facet contact with Coulomb friction on the casing, implicit generalized-alpha with energy control: friction work vs sum mu |R_N| |slip|, energy audit, released blade outside the disc, orbit bounded",
        source: "Coulomb friction's dissipation; the engine's energy audit; the planar case blade_loss (Genta, Dynamics of Rotating Systems (2005) section 4.2)",
        tags: &["dynamics", "contact", "friction", "rigid_body", "3d", "example"],
        levels: 1,
        checks: vec![
            Check::new(Quantity::Named(NAMES[0]), &[1e-9]),
            Check::new(Quantity::Named(NAMES[1]), &[1e-12]),
            // 2.6e-5 to 7 ms, 4.1e-5 to 9 ms, 1.9e-4 to 20 ms
            Check::new(Quantity::Named(NAMES[2]), &[1e-4, 1e-4, 3e-4]),
            // the root's mean radius is the rim's but for the penalty's
            // penetration (99.936 mm at least to 7 ms)
            Check::new(Quantity::Named(NAMES[3]), &[1.0]),
            Check::new(Quantity::Named(NAMES[4]), &[0.0]),
            // 0.6 mm clearance: 0.66 mm by 7 ms, 0.77 by 9, 1.00 by 20
            Check::new(Quantity::Named(NAMES[5]), &[1.5]),
        ],
        kind: CaseKind::Program(ProgramCase {
            max_levels: LEVELS.len(),
            run: level_run,
        }),
    }]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The levels' decks: the flight's end and increments replaced, the
    /// deck as written at level 1.
    #[test]
    fn the_levels_edit_the_flight() {
        let written =
            std::fs::read_to_string(super::super::examples_dir().join("blade_loss_3d.ctc"))
                .unwrap();
        let (end, n) = LEVELS[1];
        assert!(written.contains(&format!("\nlet flight_end = {end}\n")));
        assert!(written.contains(&format!("\nlet flight_increments = {n}\n")));
        for (level, (end, n)) in LEVELS.iter().enumerate() {
            let src = deck(level).unwrap();
            assert!(src.text.contains(&format!("let flight_end = {end}\n")));
            assert!(src.text.contains(&format!("let flight_increments = {n}\n")));
        }
    }
}
