//! Blade loss in a reduced rotor, plane strain (issue 19; tags
//! `dynamics`, `contact`, `friction`, `rigid_body`, `plane_strain`,
//! `example`): `examples/blade_loss.ctc`, a shaft on damped spring
//! bearings (a rigid body) spinning a disc with six flexible blades inside
//! an elastic casing; blade 1 released at 6 ms; the tips rub on the
//! casing with Coulomb friction.
//!
//! Reference: the Jeffcott rotor (Genta, Dynamics of Rotating Systems,
//! 2005, section 4.2): after the release the remaining rotor (mass
//! `m_total`) carries the unbalance `m_b r_b` (the released blade's mass
//! at its centre's radius, opposite to it), so its centre obeys `m_total
//! x'' + c x' + k x = -m_b r_b omega^2 e_b(t)` from rest at the release
//! (`e_b` the blade's direction turning with the shaft); that ODE,
//! integrated by RK4 at 1/100 of the run's increment, is compared with the
//! run's orbit until a contact force on the rotor reaches 1 % of the
//! unbalance force. Then the friction work against `sum mu |R_N| |slip|`
//! (`R_N` the normal part of the node's contact force, `(force -
//! traction) . normal`: at a vertex of the casing the normal points to
//! the vertex while the friction acts along the segment, and `force .
//! normal` took `R_T t . n` with it, the 1.2e-4 this check once showed to
//! 12 ms, all of it one node-increment at 11.45 ms), the energy audit of
//! the whole run (its error `energy_balance + numerical_dissipation`:
//! the balance alone carries generalized-alpha's numerical dissipation),
//! the orbit bounded, and the released blade against the rotor: its nodes
//! never deeper in the deformed disc or another blade (and those blades'
//! nodes in it) than the penalty's penetration at the largest pressure of
//! those pairs, the depth measured geometrically (the distance inside the
//! convex polygon of the master edges), not by the contact's own gap.
//!
//! ```text
//!          casing (springs outside)
//!        .-~~~~~~~~~~~-.   0.6 mm clearance
//!      /   \   |   /    \      blade 1 (released at 6 ms) --> flies off
//!     |  ---( (o) )---   |     shaft: rigid body, k, c bearings, omega
//!      \   /   |   \    /
//!        '-~~~~~~~~~~~-'
//! ```
//!
//! Levels: the deck's flight (from the release at 6 ms, increments of 25
//! us) ended at 10 ms (level 0, 160 flight increments) and at 20 ms as
//! written (level 1, 560). `ctc verify` runs level 0 by default; the cargo
//! tests run level 0 in `tests/suite/blade_loss.rs` (the run shared with
//! the examples test's summary of the deck), so the catalogue test
//! (`cases_coarse`) leaves it out ([`crate::registry::RUN_BY_THE_CTC_SUITE`]).
//!
//! Measured (`ctc verify blade_loss --max-level 1 -j 1`, debug, 41.8 s
//! CPU for both levels; with the energy control by default and the cone
//! tie of node-to-segment friction; the rub is chaotic, each row is one
//! trajectory):
//!
//! | level | flight | its | orbit vs ODE | energy error / K | deepest / (4 p / eps) | orbit max mm | friction work mJ |
//! | --- | --- | --- | --- | --- | --- | --- | --- |
//! | 0 | 10 ms | 934 | 1.21e-1 | 1.76e-5 | 0.32 | 0.700 | 4.83e5 |
//! | 1 | 20 ms | 2918 | 1.21e-1 | 7.69e-5 | 0.45 | 0.783 | 3.48e6 |
//!
//! Level 0 is not the same bits as level 1's first 10 ms: the prescribed
//! angle's table (`rigid_body::angle_of`) is sampled over the whole
//! analysis, so its round-off differs from 5 ms on, and the impacts
//! amplify it.

use crate::case::{Check, Quantity};
use crate::measure::Value;
use crate::plot::{Curve, Figure, Panel};
use crate::registry::{CaseKind, ProgramCase, ProgramLevel, VerifyCase};
use ctc_engine::model::{ContactMaster, ContactStrategy, Discrete, Model};
use ctc_engine::solve::{IncrementView, Observer, RunSummary};

/// Per level: the flight's end and its increments (the deck's `let
/// flight_end` / `let flight_increments`; level 1 is the deck as written).
pub const LEVELS: [(&str, usize); 2] = [("10e-3", 160), ("20e-3", 560)];

/// The names of the measured values.
const NAMES: [&str; 14] = [
    "shaft orbit vs the Jeffcott ODE until the first rub, of the ODE's peak",
    "friction work (summary) vs the sum of the nodes' dissipations",
    "return map's -T_1 . slip vs sum mu |R_N| |slip|",
    "energy error (balance + numerical dissipation) / largest K",
    "released blade's deepest in the rotor / (4 p / eps)",
    "penalty penetration 4 p / eps at the rotor pairs' largest pressure (mm)",
    "released blade's root mean radius inside the disc's rim (mm, 0 outside)",
    "largest orbit radius of the shaft (mm)",
    "friction work (mJ, not judged)",
    "energy balance / largest K (the scheme's dissipation in it, not judged)",
    "numerical dissipation / largest K (not judged)",
    "largest kinetic energy K (mJ, not judged)",
    "first rub after the release (ms, not judged)",
    "largest contact force of a pair (N, not judged)",
];

/// An example deck with its flight step ended at `end` in `increments`
/// (its lines `let flight_end = ..` and `let flight_increments = ..`), and
/// `extra` items appended.
pub fn flight_deck(
    name: &str,
    end: &str,
    increments: usize,
    extra: &str,
) -> Result<ctc_lang::Source, String> {
    let path = super::examples_dir().join(name);
    let text = std::fs::read_to_string(&path)
        .map_err(|e| format!("cannot read {}: {e}", path.display()))?;
    let mut found = 0;
    let short: String = text
        .lines()
        .map(|l| {
            if l.starts_with("let flight_end = ") {
                found += 1;
                format!("let flight_end = {end}\n")
            } else if l.starts_with("let flight_increments = ") {
                found += 1;
                format!("let flight_increments = {increments}\n")
            } else {
                format!("{l}\n")
            }
        })
        .collect();
    if found != 2 {
        return Err(format!(
            "{}: expected one `let flight_end` and one `let flight_increments` line",
            path.display()
        ));
    }
    Ok(ctc_lang::Source::new(path, format!("{short}\n{extra}")))
}

/// `examples/blade_loss.ctc` at `level` ([`LEVELS`]).
pub fn deck(level: usize) -> Result<ctc_lang::Source, String> {
    let (end, n) = LEVELS[level.min(LEVELS.len() - 1)];
    flight_deck("blade_loss.ctc", end, n, "")
}

/// The deck of `level` compiled.
pub fn model(level: usize) -> Result<Model, String> {
    let src = deck(level)?;
    ctc_lang::compile(&src).map_err(|d| d.render(&src))
}

/// What the run records, per converged increment and over the run.
#[derive(Debug, Default)]
pub struct Probe {
    pilot: usize,
    spin: usize,
    /// The prescribed angle, per increment.
    pub angle: Vec<f64>,
    /// Time, per increment.
    pub time: Vec<f64>,
    /// The shaft's centre (the pilot's displacement), per increment.
    pub centre: Vec<[f64; 2]>,
    /// Per increment, the sum of the contact forces' magnitudes of the
    /// pairs acting on the rotor: blades 2..6 on the casing, the released
    /// blade on the disc and the other blades (every pair but the first).
    pub rub: Vec<f64>,
    /// Sum of the nodes' friction dissipation (the time scheme's), of the
    /// return map's `-T_1 . slip` and of mu |R_N| |slip|.
    pub dissipation: f64,
    /// See [`Probe::dissipation`].
    pub return_map: f64,
    /// See [`Probe::dissipation`].
    pub mu_rn_slip: f64,
    /// Largest `|energy_balance|` and `|energy_error|` over the run, and
    /// the numerical dissipation at the end.
    pub balance: f64,
    /// See [`Probe::balance`].
    pub error: f64,
    /// See [`Probe::balance`].
    pub numerical: f64,
    /// Largest kinetic energy.
    pub kinetic: f64,
    /// Per increment: time, kinetic energy, energy balance, energy error.
    pub energy: Vec<[f64; 4]>,
    /// The nodes' positions at the release.
    pub at_release: Option<Vec<[f64; 2]>>,
    release: f64,
    /// The largest resultant contact force of a pair over the run.
    pub contact_force_max: f64,
    /// The released blade's root nodes (the link's first side).
    root: Vec<usize>,
    /// Per increment: the mean distance of the root nodes from the
    /// shaft's centre.
    pub root_radius: Vec<f64>,
    /// Rotor surfaces the released blade must stay out of: the master
    /// edges `[a, b]` (outward to the right) of its pairs with the disc
    /// and the other blades, and the slave nodes tested against them
    /// (the released blade's boundary; the other blade's boundary against
    /// the released blade's edges).
    pub rotor: Vec<(String, Vec<[usize; 2]>, Vec<usize>)>,
    /// Per surface: the largest penetration (>= 0) over the run.
    pub penetration: Vec<f64>,
    /// The contact pairs' largest normal pressure over the run, per pair.
    pub pressure: Vec<f64>,
    /// The last increment's contact work of the audit.
    pub contact_work: f64,
}

/// The depth of `x` inside the convex polygon of `edges` (outward normal
/// to the right of `a -> b`), 0 outside: `-max_e d_e` when every signed
/// distance `d_e` to the edges' lines is negative.
fn depth(x: [f64; 2], edges: &[[usize; 2]], at: &[[f64; 2]]) -> f64 {
    let mut d = f64::NEG_INFINITY;
    for &[a, b] in edges {
        let (pa, pb) = (at[a], at[b]);
        let t = [pb[0] - pa[0], pb[1] - pa[1]];
        let l = t[0].hypot(t[1]);
        let n = [t[1] / l, -t[0] / l];
        d = d.max((x[0] - pa[0]) * n[0] + (x[1] - pa[1]) * n[1]);
    }
    (-d).max(0.0)
}

impl Observer<2> for Probe {
    fn converged(&mut self, v: &IncrementView<'_, 2>) -> Result<(), String> {
        self.time.push(v.time);
        self.centre.push(v.displacement[self.pilot]);
        self.angle.push(v.displacement[self.spin][0]);
        let mut rub = 0.0;
        for (p, pair) in v.contact.iter().enumerate() {
            let mu = v.model.contacts[p].friction.map_or(0.0, |f| f.mu);
            let mut force = [0.0; 2];
            for n in pair {
                if p > 0 {
                    rub += n.force[0].hypot(n.force[1]);
                }
                // the normal part of the force (the friction traction off)
                let normal = [
                    n.force[0] - n.friction.traction[0],
                    n.force[1] - n.friction.traction[1],
                ];
                let rn = (normal[0] * n.normal[0] + normal[1] * n.normal[1]).abs();
                self.dissipation += n.friction.dissipation;
                let (t, s) = (n.friction.traction, n.friction.slip_vector);
                self.return_map -= t[0] * s[0] + t[1] * s[1];
                self.mu_rn_slip += mu * rn * n.friction.slip.abs();
                force[0] += n.force[0];
                force[1] += n.force[1];
            }
            self.contact_force_max = self.contact_force_max.max(force[0].hypot(force[1]));
        }
        self.rub.push(rub);
        let at: Vec<[f64; 2]> = v.positions();
        let c = at[self.pilot];
        let mean = self
            .root
            .iter()
            .map(|&n| (at[n][0] - c[0]).hypot(at[n][1] - c[1]))
            .sum::<f64>()
            / self.root.len().max(1) as f64;
        self.root_radius.push(mean);
        self.penetration.resize(self.rotor.len(), 0.0);
        for ((_, edges, nodes), worst) in self.rotor.iter().zip(&mut self.penetration) {
            for &n in nodes {
                *worst = worst.max(depth(at[n], edges, &at));
            }
        }
        self.pressure.resize(v.contact.len(), 0.0);
        for (pair, worst) in v.contact.iter().zip(&mut self.pressure) {
            for n in pair {
                *worst = worst.max(n.pressure);
            }
        }
        if let Some(e) = v.energy {
            self.balance = self.balance.max(e.balance.abs());
            self.error = self.error.max(e.error.abs());
            self.numerical = e.numerical;
            self.kinetic = self.kinetic.max(e.kinetic);
            self.contact_work = e.contact;
            self.energy.push([v.time, e.kinetic, e.balance, e.error]);
        }
        if self.at_release.is_none() && v.time >= self.release {
            // the state the blade is released from: the last increment
            // before (this one has it free already; its positions then)
            self.at_release = Some(v.positions());
        }
        Ok(())
    }
}

/// A body's mass: its cells' areas times density and thickness.
fn body_mass(model: &Model, body: usize) -> f64 {
    let b = &model.bodies[body];
    let rho = model.materials[b.material].density;
    let t = model.analysis.thickness;
    b.cells
        .clone()
        .map(|c| {
            let n = model.mesh.cells.nodes(c);
            let x: Vec<[f64; 2]> = n.iter().map(|&i| model.mesh.nodes[i]).collect();
            // shoelace
            let mut a = 0.0;
            for i in 0..x.len() {
                let j = (i + 1) % x.len();
                a += x[i][0] * x[j][1] - x[j][0] * x[i][1];
            }
            0.5 * a.abs() * rho * t
        })
        .sum()
}

/// The body called `name`.
fn body(model: &Model, name: &str) -> Result<usize, String> {
    model
        .bodies
        .iter()
        .position(|b| b.name == name)
        .ok_or_else(|| format!("no body `{name}` in the deck"))
}

/// The probe of the run: the rigid body's pilot and spin nodes, the
/// release time, the released blade's root, the rotor's surfaces against
/// the released blade.
pub fn probe_of(model: &Model) -> Result<Probe, String> {
    let (pilot, spin) = ctc_engine::solve::rigid_body::bodies(model)
        .next()
        .ok_or("no rigid body in the deck")?;
    let release = model
        .discrete
        .iter()
        .filter_map(|d| match d {
            Discrete::Link {
                release_at: Some(t),
                ..
            } => Some(*t),
            _ => None,
        })
        .next_back()
        .unwrap_or(f64::INFINITY);
    let blade1 = body(model, "blade1")?;
    let casing = body(model, "casing")?;
    // the released blade's root: the first side of its released links
    let root: Vec<usize> = model
        .discrete
        .iter()
        .flat_map(|d| match d {
            Discrete::Link {
                pairs,
                release_at: Some(_),
                ..
            } => pairs.iter().map(|p| p.0).collect(),
            _ => Vec::new(),
        })
        .collect();
    if root.is_empty() {
        return Err("no released link in the deck".into());
    }
    // the rotor's surfaces against the released blade, both ways for the
    // blades (double pass)
    let mut rotor = Vec::new();
    for pair in &model.contacts {
        if let ContactMaster::Surface {
            body, edges, nodes, ..
        } = &pair.master
        {
            if pair.body == blade1 && *body != casing {
                rotor.push((pair.name.clone(), edges.clone(), pair.nodes.clone()));
                if pair.strategy != ContactStrategy::SinglePass {
                    rotor.push((
                        format!("{} (its nodes in the released blade)", pair.name),
                        pair.edges.clone(),
                        nodes.clone(),
                    ));
                }
            }
        }
    }
    if rotor.len() != 11 {
        return Err(format!(
            "{} surfaces of the rotor against the released blade, expected the disc and five blades both ways (11)",
            rotor.len()
        ));
    }
    Ok(Probe {
        pilot,
        spin,
        release,
        root,
        rotor,
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
    /// The released blade's mass, its centre's radius at the release, the
    /// remaining rotor's mass (shaft, disc, five blades).
    pub m_b: f64,
    /// See [`Measured::m_b`].
    pub r_b: f64,
    /// See [`Measured::m_b`].
    pub m_rotor: f64,
    /// The first increment after the release, the first with a contact
    /// force on the rotor above 1 % of the unbalance force.
    pub release_increment: usize,
    /// See [`Measured::release_increment`].
    pub first_rub: usize,
    /// The time of [`Measured::first_rub`].
    pub first_rub_time: f64,
    /// The shaft's angular velocity at the release.
    pub omega: f64,
    /// The unbalance force `m_b r_b omega^2`, the largest contact force on
    /// the rotor before the first rub.
    pub unbalance: f64,
    /// See [`Measured::unbalance`].
    pub graze: f64,
    /// The orbit against the Jeffcott ODE until the first rub, over the
    /// ODE's peak; that peak.
    pub whirl_error: f64,
    /// See [`Measured::whirl_error`].
    pub ode_peak: f64,
    /// The largest orbit radius of the run.
    pub radius_max: f64,
    /// The summary's friction work, the relative difference from the sum
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
    /// Largest `|balance|`, largest `|error|`, numerical dissipation at
    /// the end, all over the largest kinetic energy; that energy.
    pub balance: f64,
    /// See [`Measured::balance`].
    pub error: f64,
    /// See [`Measured::balance`].
    pub numerical: f64,
    /// See [`Measured::balance`].
    pub kinetic: f64,
    /// The disc's rim radius; the released blade's root mean radius:
    /// least after the release and at the end.
    pub r_disc: f64,
    /// See [`Measured::r_disc`].
    pub root_min: f64,
    /// See [`Measured::r_disc`].
    pub root_end: f64,
    /// The released blade's deepest penetration into the rotor, the
    /// surface, the penalty's `4 p / eps` at the rotor pairs' largest
    /// pressure `p`, and that pressure.
    pub deepest: f64,
    /// See [`Measured::deepest`].
    pub worst_surface: String,
    /// See [`Measured::deepest`].
    pub tolerance: f64,
    /// See [`Measured::deepest`].
    pub p_rotor: f64,
    /// The largest pressure of the blade / disc pair and of all pairs.
    pub p_disc: f64,
    /// See [`Measured::p_disc`].
    pub p_max: f64,
    /// The penalty of the blade / disc pair.
    pub eps: f64,
    /// The largest resultant contact force of a pair over the run.
    pub contact_force_max: f64,
}

/// Measures a run of the deck ([`Probe`] and summary of `model`).
pub fn measure(model: &Model, probe: &Probe, summary: &RunSummary) -> Result<Measured, String> {
    let (pilot, _) = ctc_engine::solve::rigid_body::bodies(model)
        .next()
        .ok_or("no rigid body")?;
    let (mut k, mut c, mut m_shaft, mut release) = (0.0, 0.0, 0.0, f64::INFINITY);
    for d in &model.discrete {
        match d {
            Discrete::Ground {
                nodes,
                stiffness,
                damping,
                ..
            } if nodes == &[pilot] => (k, c) = (*stiffness, *damping),
            Discrete::Mass { nodes, mass, .. } if nodes == &[pilot] => m_shaft = *mass,
            Discrete::Link {
                release_at: Some(t),
                ..
            } => release = *t,
            _ => {}
        }
    }
    let blade1 = body(model, "blade1")?;
    let casing = body(model, "casing")?;
    let m_b = body_mass(model, blade1);
    let m_rotor = m_shaft
        + (0..model.bodies.len())
            .filter(|&b| b != blade1 && b != casing)
            .map(|b| body_mass(model, b))
            .sum::<f64>();
    // the released blade's centre of mass (its cells' area centroids) at
    // the release
    let at = probe
        .at_release
        .as_ref()
        .ok_or("the run ended before the release")?;
    let (mut area, mut cb) = (0.0, [0.0, 0.0]);
    for cell in model.bodies[blade1].cells.clone() {
        let x: Vec<[f64; 2]> = model
            .mesh
            .cells
            .nodes(cell)
            .iter()
            .map(|&i| at[i])
            .collect();
        for i in 0..x.len() {
            let j = (i + 1) % x.len();
            let w = x[i][0] * x[j][1] - x[j][0] * x[i][1];
            area += 0.5 * w;
            cb[0] += (x[i][0] + x[j][0]) * w / 6.0;
            cb[1] += (x[i][1] + x[j][1]) * w / 6.0;
        }
    }
    let cb = [cb[0] / area, cb[1] / area];
    let r_b = cb[0].hypot(cb[1]);
    let phi_b = cb[1].atan2(cb[0]);
    // the ODE from the release: x(t_r) = x_run(t_r - dt) ~ 0, at rest
    let i0 = probe
        .time
        .iter()
        .position(|&t| t >= release)
        .filter(|&i| i > 0)
        .ok_or("no increment after the release")?;
    // the ODE holds until a contact force on the rotor reaches 1 % of
    // the unbalance force m_b r_b omega^2
    let omega = (probe.angle[i0] - probe.angle[i0 - 1]) / (probe.time[i0] - probe.time[i0 - 1]);
    let unbalance = m_b * r_b * omega * omega;
    let first_rub = (i0..probe.rub.len())
        .find(|&i| probe.rub[i] > 1e-2 * unbalance)
        .unwrap_or(probe.rub.len());
    if first_rub <= i0 + 5 {
        return Err(format!(
            "the rotor rubs too early for the Jeffcott ODE: increments {i0} .. {first_rub}"
        ));
    }
    let graze = probe.rub[i0..first_rub].iter().copied().fold(0.0, f64::max);
    let t0 = probe.time[i0 - 1];
    let force = |t: f64| {
        let a = phi_b + omega * (t - t0);
        let f = -m_b * r_b * omega * omega;
        [f * a.cos(), f * a.sin()]
    };
    let rhs = |t: f64, y: [f64; 4]| {
        let f = force(t);
        [
            y[2],
            y[3],
            (f[0] - c * y[2] - k * y[0]) / m_rotor,
            (f[1] - c * y[3] - k * y[1]) / m_rotor,
        ]
    };
    let x0 = probe.centre[i0 - 1];
    let mut y = [x0[0], x0[1], 0.0, 0.0];
    let mut t = t0;
    let (mut err, mut peak) = (0.0f64, 0.0f64);
    for i in i0..first_rub {
        let steps = 100;
        let h = (probe.time[i] - t) / steps as f64;
        for _ in 0..steps {
            let add = |y: [f64; 4], k: [f64; 4], s: f64| {
                [
                    y[0] + s * k[0],
                    y[1] + s * k[1],
                    y[2] + s * k[2],
                    y[3] + s * k[3],
                ]
            };
            let k1 = rhs(t, y);
            let k2 = rhs(t + h / 2.0, add(y, k1, h / 2.0));
            let k3 = rhs(t + h / 2.0, add(y, k2, h / 2.0));
            let k4 = rhs(t + h, add(y, k3, h));
            for (j, yj) in y.iter_mut().enumerate() {
                *yj += h / 6.0 * (k1[j] + 2.0 * k2[j] + 2.0 * k3[j] + k4[j]);
            }
            t += h;
        }
        let u = probe.centre[i];
        err = err.max((u[0] - y[0]).hypot(u[1] - y[1]));
        peak = peak.max(y[0].hypot(y[1]));
    }
    let friction_total: f64 = summary.friction_work.iter().sum();
    let radius_max = probe
        .centre
        .iter()
        .map(|u| u[0].hypot(u[1]))
        .fold(0.0, f64::max);
    // the released blade against the rotor: its root's mean radius from
    // the shaft's centre after the release, the deepest penetration of
    // its nodes into the disc and of blade nodes into one another
    let centre = model.mesh.nodes[pilot];
    let disc_pair = model
        .contacts
        .iter()
        .position(|c| c.name == "blade1.boundary -> disc.outer")
        .ok_or("no pair `blade1.boundary -> disc.outer`")?;
    let ContactMaster::Surface { nodes: rim, .. } = &model.contacts[disc_pair].master else {
        return Err("the blade-to-disc pair has no deformable master".into());
    };
    let r_disc = rim
        .iter()
        .map(|&n| (model.mesh.nodes[n][0] - centre[0]).hypot(model.mesh.nodes[n][1] - centre[1]))
        .fold(0.0, f64::max);
    let eps = match model.contacts[disc_pair].method {
        ctc_engine::model::ContactMethod::Penalty { stiffness, .. } => stiffness,
        ref m => {
            return Err(format!(
                "the blade-to-disc pair is not a penalty pair: {m:?}"
            ))
        }
    };
    let root_min = probe.root_radius[i0..]
        .iter()
        .copied()
        .fold(f64::INFINITY, f64::min);
    let root_end = probe.root_radius.last().copied().unwrap_or(f64::NAN);
    let deepest = probe.penetration.iter().copied().fold(0.0, f64::max);
    let worst_surface = probe
        .rotor
        .iter()
        .zip(&probe.penetration)
        .max_by(|a, b| a.1.total_cmp(b.1))
        .map(|(s, _)| s.0.clone())
        .unwrap_or_default();
    // the penalty's own penetration at the largest pressure of the rotor
    // pairs. The modified double pass reports the interface pressure
    // (`contact::interface_pressures`): a slave node's force eps g A / 2
    // (half its area A) over its full area is eps g / 2, averaged with the
    // other side's traction at its foot (>= 0, as low as 0 under a corner
    // on a flat side): p >= eps g / 4 at the node, so g <= 4 p / eps
    let p_rotor = model
        .contacts
        .iter()
        .enumerate()
        .filter(|(_, c)| c.body == blade1 && c.name != "blade1.boundary -> casing.inner")
        .map(|(p, _)| probe.pressure.get(p).copied().unwrap_or(0.0))
        .fold(0.0, f64::max);
    let kinetic = probe.kinetic.max(f64::MIN_POSITIVE);
    Ok(Measured {
        increments: summary.increments.len(),
        iterations: summary.newton_iterations,
        cutbacks: summary.cutbacks,
        m_b,
        r_b,
        m_rotor,
        release_increment: i0,
        first_rub,
        first_rub_time: probe.time.get(first_rub).copied().unwrap_or(f64::NAN),
        omega,
        unbalance,
        graze,
        whirl_error: err / peak,
        ode_peak: peak,
        radius_max,
        friction_total,
        friction_vs_nodes: (friction_total - probe.dissipation).abs()
            / friction_total.abs().max(f64::MIN_POSITIVE),
        return_map: probe.return_map,
        mu_rn_slip: probe.mu_rn_slip,
        friction_error: (probe.return_map - probe.mu_rn_slip).abs()
            / probe.mu_rn_slip.max(f64::MIN_POSITIVE),
        balance: probe.balance / kinetic,
        error: probe.error / kinetic,
        numerical: probe.numerical / kinetic,
        kinetic: probe.kinetic,
        r_disc,
        root_min,
        root_end,
        deepest,
        worst_surface,
        tolerance: 4.0 * p_rotor / eps,
        p_rotor,
        p_disc: probe.pressure.get(disc_pair).copied().unwrap_or(0.0),
        p_max: probe.pressure.iter().copied().fold(0.0, f64::max),
        eps,
        contact_force_max: probe.contact_force_max,
    })
}

impl Measured {
    /// The values the case judges (and those it reports).
    pub fn values(&self) -> Vec<Value> {
        let e = super::error;
        vec![
            e(NAMES[0], self.whirl_error),
            e(NAMES[1], self.friction_vs_nodes),
            e(NAMES[2], self.friction_error),
            e(NAMES[3], self.error),
            e(
                NAMES[4],
                if self.tolerance > 0.0 {
                    self.deepest / self.tolerance
                } else {
                    // the released blade never pressed on the rotor
                    f64::INFINITY
                },
            ),
            e(NAMES[5], self.tolerance),
            e(NAMES[6], (self.r_disc - self.root_min).max(0.0)),
            e(NAMES[7], self.radius_max),
            e(NAMES[8], self.friction_total),
            e(NAMES[9], self.balance),
            e(NAMES[10], self.numerical),
            e(NAMES[11], self.kinetic),
            e(NAMES[12], 1e3 * self.first_rub_time),
            e(NAMES[13], self.contact_force_max),
        ]
    }

    /// One line of figures (the cargo test prints it).
    pub fn line(&self) -> String {
        format!(
            "{} increments, {} Newton iterations, {} cutbacks; m_b {:.4e} r_b {:.2} m_rotor {:.4e}; \
             release at increment {}, first rub at {} (contact force on the rotor before it {:.3e}, \
             unbalance force {:.3e}); whirl vs ODE {:.2e} (peak {:.3e}); max orbit radius {:.3e}; \
             friction work {:.4e} (the return map's {:.4e}) vs sum mu R_N slip {:.4e} ({:.1e}); \
             balance {:.2e} of max K {:.4e} (numerical dissipation {:.2e}, error {:.2e}); \
             released blade: root mean radius min {:.3} (disc {:.1}), at the end {:.3}; deepest \
             penetration into the rotor {:.3e} ({}); max pressure blade/disc {:.4e}, all pairs \
             {:.4e} (4 p / eps at the rotor pairs {:.3e})",
            self.increments,
            self.iterations,
            self.cutbacks,
            self.m_b,
            self.r_b,
            self.m_rotor,
            self.release_increment,
            self.first_rub,
            self.graze,
            self.unbalance,
            self.whirl_error,
            self.ode_peak,
            self.radius_max,
            self.friction_total,
            self.return_map,
            self.mu_rn_slip,
            self.friction_error,
            self.balance,
            self.kinetic,
            self.numerical,
            self.error,
            self.root_min,
            self.r_disc,
            self.root_end,
            self.deepest,
            self.worst_surface,
            self.p_disc,
            self.p_max,
            self.tolerance,
        )
    }
}

/// The report's figures of a run: the shaft's orbit (radius against
/// time, and its path) and the energy audit (kinetic energy, balance and
/// error against time), from `(time, centre)` and the energy rows.
pub fn figures(orbit: &[(f64, [f64; 2])], energy: &[[f64; 4]]) -> Vec<Figure> {
    let curve = |label: &str, points: Vec<(f64, f64)>| Curve {
        label: label.into(),
        points,
    };
    let radius = orbit
        .iter()
        .map(|(t, c)| (1e3 * t, c[0].hypot(c[1])))
        .collect();
    let path = orbit.iter().map(|(_, c)| (c[0], c[1])).collect();
    let row = |k: usize| -> Vec<(f64, f64)> { energy.iter().map(|r| (1e3 * r[0], r[k])).collect() };
    vec![
        Figure {
            name: "orbit".into(),
            panels: vec![
                Panel {
                    title: "shaft orbit radius".into(),
                    x_desc: "time (ms)".into(),
                    y_desc: "radius (mm)".into(),
                    curves: vec![curve("orbit radius", radius)],
                },
                Panel {
                    title: "shaft orbit".into(),
                    x_desc: "x (mm)".into(),
                    y_desc: "y (mm)".into(),
                    curves: vec![curve("centre", path)],
                },
            ],
        },
        Figure {
            name: "energy".into(),
            panels: vec![
                Panel {
                    title: "kinetic energy".into(),
                    x_desc: "time (ms)".into(),
                    y_desc: "K (mJ)".into(),
                    curves: vec![curve("K", row(1))],
                },
                Panel {
                    title: "energy audit".into(),
                    x_desc: "time (ms)".into(),
                    y_desc: "mJ".into(),
                    curves: vec![
                        curve("balance (the scheme's dissipation in it)", row(2)),
                        curve("error (balance + numerical dissipation)", row(3)),
                    ],
                },
            ],
        },
    ]
}

/// Runs `model` with `probe` and `also` observing it.
pub fn run_with<const D: usize>(
    model: &Model<D>,
    probe: &mut dyn Observer<D>,
    also: &mut dyn Observer<D>,
) -> Result<RunSummary, String>
where
    nalgebra::Const<D>: ctc_engine::geom::Dimension<D>,
{
    struct Both<'a, const D: usize> {
        a: &'a mut dyn Observer<D>,
        b: &'a mut dyn Observer<D>,
    }
    impl<const D: usize> Observer<D> for Both<'_, D> {
        fn iteration(&mut self, info: &ctc_engine::solve::IterationInfo) {
            self.a.iteration(info);
            self.b.iteration(info);
        }
        fn converged(&mut self, v: &IncrementView<'_, D>) -> Result<(), String> {
            self.a.converged(v)?;
            self.b.converged(v)
        }
        fn cutback(&mut self, reason: &str, new_dt: f64) {
            self.a.cutback(reason, new_dt);
            self.b.cutback(reason, new_dt);
        }
        fn warning(&mut self, message: &str) {
            self.a.warning(message);
            self.b.warning(message);
        }
    }
    let summary =
        ctc_engine::solve::run(model, &mut Both { a: probe, b: also }).map_err(|e| e.message)?;
    if !summary.completed {
        return Err("the run did not complete".into());
    }
    Ok(summary)
}

fn level_run(level: usize) -> Result<ProgramLevel, String> {
    let model = model(level)?;
    let mut probe = probe_of(&model)?;
    let summary = run_with(&model, &mut probe, &mut Quiet)?;
    let m = measure(&model, &probe, &summary)?;
    let mut out = ProgramLevel {
        h: f64::NAN,
        values: m.values(),
        ..ProgramLevel::default()
    };
    let orbit: Vec<(f64, [f64; 2])> = probe
        .time
        .iter()
        .copied()
        .zip(probe.centre.iter().copied())
        .collect();
    out.figures = figures(&orbit, &probe.energy);
    out.add_run(&summary);
    Ok(out)
}

/// An observer that keeps nothing.
pub struct Quiet;

impl<const D: usize> Observer<D> for Quiet {}

/// The registry entry.
pub fn cases() -> Vec<VerifyCase> {
    vec![VerifyCase {
        name: "blade_loss",
        title: "Blade loss in a reduced rotor (examples/blade_loss.ctc), plane strain: a shaft on damped spring bearings (rigid body) spinning a disc with six flexible blades, blade 1 released at 6 ms, the tips rubbing on an elastic casing with Coulomb friction, implicit generalized-alpha with energy control: orbit vs the Jeffcott ODE until the first rub, friction work vs sum mu |R_N| |slip|, energy audit, released blade outside the rotor, orbit bounded",
        source: "Genta, Dynamics of Rotating Systems (2005) section 4.2 (Jeffcott rotor's unbalance response); Coulomb friction's dissipation; the engine's energy audit",
        tags: &["dynamics", "contact", "friction", "rigid_body", "plane_strain", "example"],
        levels: 1,
        checks: vec![
            // a rigid-rotor ODE: the blades' first bending mode (about 780
            // rad/s by beam theory) is near the whirl, so the flexible
            // rotor departs from it; the released blade rebounds from the
            // casing onto the disc 0.175 ms after the release, which ends
            // the window when the orbit is 0.015 mm: 4.0e-1
            Check::new(Quantity::Named(NAMES[0]), &[0.5]),
            Check::new(Quantity::Named(NAMES[1]), &[1e-9]),
            // round-off since R_N is the force's normal part (1.4e-15)
            Check::new(Quantity::Named(NAMES[2]), &[1e-12]),
            // 2.07e-5 to 10 ms, 8.41e-5 to 20 ms (`ctc verify blade_loss
            // --max-level 1 -j 1`, debug)
            Check::new(Quantity::Named(NAMES[3]), &[1e-4, 2e-4]),
            Check::new(Quantity::Named(NAMES[4]), &[1.0]),
            Check::new(Quantity::Named(NAMES[5]), &[0.5]),
            // the root's mean radius is the rim's but for the penalty's
            // penetration and the blade's root cell (1 mm)
            Check::new(Quantity::Named(NAMES[6]), &[1.5]),
            // 0.6 mm clearance: 0.86 mm by 10 ms, 1.83 mm by 20 ms; the
            // run whose contact created energy (no energy_tol) reached
            // 3.4 mm by 14.6 ms
            Check::new(Quantity::Named(NAMES[7]), &[1.5, 2.5]),
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

    /// Inside a unit square: the depth is the distance to the nearest
    /// edge; outside it is 0.
    #[test]
    fn depth_is_the_distance_inside_a_convex_polygon() {
        let at = [[0.0, 0.0], [0.0, 1.0], [1.0, 1.0], [1.0, 0.0]];
        // counter-clockwise: the outward normal to the right of a -> b
        let edges = [[0, 3], [3, 2], [2, 1], [1, 0]];
        assert!((depth([0.25, 0.5], &edges, &at) - 0.25).abs() < 1e-15);
        assert_eq!(depth([1.5, 0.5], &edges, &at), 0.0);
    }

    /// Both levels' decks: the flight's end and increments replaced.
    #[test]
    fn the_levels_edit_the_flight() {
        for (level, (end, n)) in LEVELS.iter().enumerate() {
            let src = deck(level).unwrap();
            assert!(src.text.contains(&format!("let flight_end = {end}\n")));
            assert!(src.text.contains(&format!("let flight_increments = {n}\n")));
        }
        assert!(flight_deck("no_such_deck.ctc", "1", 1, "").is_err());
    }
}
