//! Heat conduction and thermo-mechanics in 3D (issue 15, tags `thermal`
//! and `3d`), on the one dimension-generic thermal code path:
//!
//! - `thermal_steady_3d`: steady conduction through a 2 x 1 x 1 brick,
//!   `T = 100` prescribed on `x = 0`, convection `h = 5`, `T_inf = 20` on
//!   `x = 2`, the other faces insulated, `k = 3`. Closed form (series
//!   resistances, Incropera & DeWitt, Fundamentals of Heat and Mass
//!   Transfer, §3.1): `q = (T_inf - T_0) / (L / k + 1 / h)`,
//!   `T(x) = T_0 + q x / k`; linear, so tet4 and a distorted hex8 mesh
//!   reproduce it to round-off.
//! - `thermal_transient_3d`: a slab `0 <= x <= 1` at `T = 0`, its face
//!   `x = 0` brought to `T = 1` at `t = 0`, `x = 1` insulated, diffusivity
//!   `k / (rho c) = 1`, judged at `t = 0.1` against the series solution of
//!   the finite slab (Carslaw & Jaeger, Conduction of Heat in Solids,
//!   §3.3): `T = 1 - sum 4 / ((2n+1) pi) sin((2n+1) pi x / 2)
//!   exp(-((2n+1) pi / 2)^2 t)`. Hex8, 4 / 8 / 16 cells across with
//!   `dt ~ h^2` (backward Euler, lumped capacity): the total error, the
//!   time-step error (against the same mesh with 16 x smaller steps) and
//!   the mesh error (that run against the series) are reported.
//! - `thermal_expansion_3d`: a 1 x 1 x 1 brick heated uniformly from 20 to
//!   120 (`alpha = 1e-5`, `E = 200e3`, `nu = 0.3`): free (symmetry planes
//!   only) it strains by `alpha dT` with no stress; held on every face it
//!   carries `sigma = -E alpha dT / (1 - 2 nu)` in every direction
//!   (Timoshenko & Goodier, Theory of Elasticity, §150). Tet4 and hex8,
//!   J2 in its elastic range (the stress of the integration points) and
//!   linear elastic (strain from the displacements, stress from the
//!   reactions). The held brick is one cell thick (every node held): with
//!   interior nodes, whose exact displacement is 0, Newton's relative
//!   correction test `||du|| / ||u||` compares round-off with round-off
//!   and the increment never converges (a limitation of the convergence
//!   test, not of the thermal strains).
//! - `thermal_contact_tool_3d`: `cases/thermal_contact_tool_3d.ctc`, the
//!   block of `thermal_contact_tool` rebuilt in 3D (plane strain by
//!   `uy = 0` on both depth faces) on a rigid plane surface tool at two
//!   pressures: flux and interface temperature against the series
//!   resistance `q = (T_hot - T_cold) / (L / k + 1 / h(p))` and against the
//!   planar run of the same deck.
//! - `adiabatic_heating_3d`: the J2 cylinder of `adiabatic_heating`
//!   rebuilt as a 1/8 cube (symmetry planes, homogeneous uniaxial stress,
//!   5 % compression in 10 increments, Taylor-Quinney 0.9): heat against
//!   `beta W` and the temperature rise against the axisymmetric run.
//!
//! ```text
//!   steady                    transient            expansion
//!   T=100 +--------+ h, T_inf T=1 +----------+ q=0  +-----+  T: 20 -> 120
//!         |  k = 3 |              |  k/rho c=1|      |     |  free: eps = alpha dT
//!         +--------+              +----------+      +-----+  held: sigma = -E alpha dT/(1-2nu)
//!         x=0    x=2              x=0      x=1
//! ```

use super::{error, value};
use crate::case::{Check, Quantity};
use crate::registry::{CaseKind, ProgramCase, ProgramLevel, VerifyCase};
use ctc_engine::mesh::generate::{solid, Grading};
use ctc_engine::mesh::{CellKind, Mesh};
use ctc_engine::model::thermal::{
    Convection, CouplingScheme, MaterialThermal, PrescribedTemperature, ThermalScene,
};
use ctc_engine::model::{Hardening, MaterialLaw, Model, TimeFunction};
use ctc_engine::solve::{run, IncrementView, Observer};
use ctc_engine::testkit::ModelBuilder;
use std::f64::consts::PI;

/// The registry entries.
pub fn cases() -> Vec<VerifyCase> {
    vec![
        VerifyCase {
            name: "thermal_steady_3d",
            title: "Steady conduction 3D: brick, prescribed T and convection, tet4 and distorted hex8",
            source: "Incropera & DeWitt, Fundamentals of Heat and Mass Transfer §3.1 (plane wall)",
            tags: &["thermal", "3d", "closed_form", "exact"],
            levels: 1,
            checks: vec![
                Check::new(Quantity::Named("T tet4"), &[1e-10]),
                Check::new(Quantity::Named("T hex8 distorted"), &[1e-10]),
                Check::new(Quantity::Named("T(x = L) hex8"), &[1e-10]),
            ],
            kind: CaseKind::Program(ProgramCase {
                max_levels: 1,
                run: |_| steady(),
            }),
        },
        VerifyCase {
            name: "thermal_transient_3d",
            title: "Transient conduction 3D: slab suddenly heated, series solution, dt ~ h^2",
            source: "Carslaw & Jaeger, Conduction of Heat in Solids §3.3 (finite slab)",
            tags: &["thermal", "3d", "transient", "closed_form", "convergence"],
            levels: 3,
            checks: vec![
                Check::new(Quantity::Named("T error"), &[4e-2, 1e-2, 2.5e-3]).with_min_rate(1.8),
                Check::new(Quantity::Named("T error (time step)"), &[3.5e-2, 9e-3, 2.5e-3]),
                Check::new(Quantity::Named("T error (mesh)"), &[2e-2, 5e-3, 1.3e-3]),
            ],
            kind: CaseKind::Program(ProgramCase {
                max_levels: 3,
                run: transient,
            }),
        },
        VerifyCase {
            name: "thermal_expansion_3d",
            title: "Thermal expansion 3D: free and fully held brick heated uniformly, tet4 and hex8",
            source: "Timoshenko & Goodier, Theory of Elasticity §150",
            tags: &["thermal", "3d", "expansion", "closed_form", "exact"],
            levels: 1,
            checks: expansion_checks(),
            kind: CaseKind::Program(ProgramCase {
                max_levels: 1,
                run: |_| expansion(),
            }),
        },
        VerifyCase {
            name: "thermal_contact_tool_3d",
            title: "Thermal contact 3D: block on a cold rigid surface tool, h(p), vs closed form and 2D",
            source: "VERIFICATION-CASES.md §8 (series resistance l/k + 1/h); thermal_contact_tool",
            tags: &[
                "thermal",
                "3d",
                "contact",
                "penalty",
                "closed_form",
                "cross_check",
                "exact",
            ],
            levels: 1,
            checks: vec![
                Check::new(Quantity::Named("flux (low p)"), &[1e-9]),
                Check::new(Quantity::Named("T_i (low p)"), &[1e-9]),
                Check::new(Quantity::Named("flux (high p)"), &[1e-9]),
                Check::new(Quantity::Named("T_i (high p)"), &[1e-9]),
                Check::new(Quantity::Named("p uniform"), &[1e-9]),
                Check::new(Quantity::Named("flux 3d vs 2d"), &[1e-9]),
                Check::new(Quantity::Named("p 3d vs 2d"), &[1e-9]),
                Check::new(Quantity::Named("node heat = h A (T_tool - T)"), &[1e-12]),
            ],
            kind: CaseKind::Program(ProgramCase {
                max_levels: 1,
                run: |_| contact_tool(),
            }),
        },
        VerifyCase {
            name: "adiabatic_heating_3d",
            title: "Adiabatic heating 3D: J2 cube compressed, heat = beta x plastic work, vs axi",
            source: "VERIFICATION-CASES.md §8; Simo & Hughes, Computational Inelasticity §2.3; adiabatic_heating",
            tags: &[
                "thermal",
                "3d",
                "plasticity",
                "energy",
                "closed_form",
                "cross_check",
            ],
            levels: 1,
            checks: vec![
                Check::new(Quantity::Named("heat / beta W"), &[1e-9]),
                Check::new(Quantity::Named("T rise"), &[1e-9]),
                Check::new(Quantity::Named("T rise 3d vs axi"), &[1e-9]),
            ],
            kind: CaseKind::Program(ProgramCase {
                max_levels: 1,
                run: |_| adiabatic(),
            }),
        },
    ]
}

/// Thermal properties with conductivity `k` and volumetric capacity `rho_c`.
fn thermal(k: f64, rho_c: f64, expansion: f64, reference: f64) -> MaterialThermal {
    MaterialThermal {
        conductivity: k,
        capacity: rho_c,
        density: 1.0,
        expansion,
        reference,
        taylor_quinney: 0.9,
        young_factor: None,
        yield_factor: None,
    }
}

/// A scene with one thermal material and body at `initial`.
fn scene(m: MaterialThermal, initial: f64) -> ThermalScene {
    ThermalScene {
        materials: vec![Some(m)],
        initial: vec![initial],
        temperatures: Vec::new(),
        fluxes: Vec::new(),
        convection: Vec::new(),
        contacts: Vec::new(),
        scheme: CouplingScheme::Staggered,
    }
}

/// The nodal temperatures and integration points of the last increment.
#[derive(Default)]
struct Last {
    temperature: Vec<f64>,
    displacement: Vec<[f64; 3]>,
    reaction: Vec<[f64; 3]>,
    stress: Vec<[f64; 6]>,
    plastic: f64,
}

impl Observer<3> for Last {
    fn converged(&mut self, v: &IncrementView<'_, 3>) -> Result<(), String> {
        self.temperature = v.temperature.ok_or("no thermal scene")?.to_vec();
        self.displacement = v.displacement.to_vec();
        self.reaction = v.reaction.to_vec();
        self.stress = v
            .points
            .iter()
            .flatten()
            .map(|p| std::array::from_fn(|k| p.state.stress[k]))
            .collect();
        self.plastic += v.thermal.ok_or("no heat report")?.plastic;
        Ok(())
    }
}

/// Runs `model`; the last increment and the level's counts.
fn solve(model: &Model<3>, level: &mut ProgramLevel) -> Result<Last, String> {
    let mut last = Last::default();
    let s = run(model, &mut last).map_err(|e| e.message)?;
    level.add_run(&s);
    Ok(last)
}

/// Moves every interior node of `mesh` (not on the faces of its bounding
/// box) by up to `amount` times the cell size `h`, deterministically.
fn distort(mesh: &mut Mesh<3>, h: f64, amount: f64) {
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for p in &mesh.nodes {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    let eps = 1e-9 * h;
    for (i, p) in mesh.nodes.iter_mut().enumerate() {
        if (0..3).any(|k| (p[k] - lo[k]).abs() < eps || (p[k] - hi[k]).abs() < eps) {
            continue;
        }
        for (k, x) in p.iter_mut().enumerate() {
            *x += amount * h * ((1.7 * i as f64 + 2.3 * k as f64).sin());
        }
    }
}

/// Every node held: the mechanics is trivial, only heat is solved.
fn held(mut b: ModelBuilder<3>) -> ModelBuilder<3> {
    let all = b.node_set("slab.all");
    for c in 0..3 {
        b = b.fix(all.clone(), c);
    }
    b
}

/// A body `slab` of `mesh`, linear elastic, with the node set `all`.
fn slab(mut mesh: Mesh<3>) -> ModelBuilder<3> {
    mesh.node_sets
        .insert("all".into(), (0..mesh.nodes.len()).collect());
    ModelBuilder::solid()
        .elastic("steel", 200e3, 0.3)
        .body("slab", mesh, "steel")
}

fn steady() -> Result<ProgramLevel, String> {
    let (l, k, h, t0, t_inf) = (2.0, 3.0, 5.0, 100.0, 20.0);
    let q = (t_inf - t0) / (l / k + 1.0 / h);
    let exact = |x: f64| t0 + q * x / k;
    let mut level = ProgramLevel {
        h: f64::NAN,
        ..ProgramLevel::default()
    };
    let mut at_end = 0.0f64;
    for (kind, name) in [
        (CellKind::Tet4, "T tet4"),
        (CellKind::Hex8, "T hex8 distorted"),
    ] {
        let g = [Grading::Uniform; 3];
        let mut mesh =
            solid::brick([0.0; 3], [l, 1.0, 1.0], [6, 3, 3], g, kind).map_err(|e| e.message)?;
        if kind == CellKind::Hex8 {
            distort(&mut mesh, 1.0 / 3.0, 0.15);
        }
        let b = held(slab(mesh));
        let mut s = scene(thermal(k, 0.0, 0.0, 0.0), 0.0);
        s.temperatures.push(PrescribedTemperature {
            label: "temperature slab.xmin".into(),
            nodes: b.node_set("slab.xmin"),
            value: TimeFunction::Constant(t0),
        });
        s.convection.push(Convection {
            label: "convection slab.xmax".into(),
            facets: b.face_set("slab.xmax"),
            film: h,
            ambient: TimeFunction::Constant(t_inf),
        });
        let model = b.thermal(s).step("heat", 1.0, 1).build();
        let last = solve(&model, &mut level)?;
        let worst = model
            .mesh
            .nodes
            .iter()
            .zip(&last.temperature)
            .map(|(p, t)| (t - exact(p[0])).abs() / (t0 - t_inf))
            .fold(0.0, f64::max);
        level.values.push(error(name, worst));
        if kind == CellKind::Hex8 {
            let end = model.mesh.node_sets["slab.xmax"].clone();
            at_end = end.iter().map(|&n| last.temperature[n]).sum::<f64>() / end.len() as f64;
        }
    }
    level.values.push(value("T(x = L) hex8", at_end, exact(l)));
    Ok(level)
}

/// The finite-slab series solution at `x`, `t` (unit diffusivity and
/// thickness, `T = 1` at `x = 0`, insulated at `x = 1`).
fn slab_series(x: f64, t: f64) -> f64 {
    let mut sum = 0.0;
    for n in 0..200 {
        let m = (2 * n + 1) as f64 * PI / 2.0;
        sum += 2.0 / m * (m * x).sin() * (-m * m * t).exp();
    }
    1.0 - sum
}

/// The slab of `thermal_transient_3d` with `nx` cells across, run to
/// `t = 0.1` in `increments`.
fn slab_run(
    nx: usize,
    increments: usize,
    level: &mut ProgramLevel,
) -> Result<(Vec<f64>, Vec<f64>), String> {
    let g = [Grading::Uniform; 3];
    let mesh = solid::brick([0.0; 3], [1.0, 0.25, 0.25], [nx, 1, 1], g, CellKind::Hex8)
        .map_err(|e| e.message)?;
    let b = held(slab(mesh));
    let mut s = scene(thermal(1.0, 1.0, 0.0, 0.0), 0.0);
    s.temperatures.push(PrescribedTemperature {
        label: "temperature slab.xmin".into(),
        nodes: b.node_set("slab.xmin"),
        value: TimeFunction::Constant(1.0),
    });
    let model = b.thermal(s).step("heat", 0.1, increments).build();
    let last = solve(&model, level)?;
    let x = model.mesh.nodes.iter().map(|p| p[0]).collect();
    Ok((x, last.temperature))
}

fn transient(level_index: usize) -> Result<ProgramLevel, String> {
    let nx = 4 << level_index;
    let increments = 4 << (2 * level_index);
    let mut level = ProgramLevel {
        h: 1.0 / nx as f64,
        ..ProgramLevel::default()
    };
    let (x, t) = slab_run(nx, increments, &mut level)?;
    let (_, fine) = slab_run(nx, 16 * increments, &mut level)?;
    let max = |it: &mut dyn Iterator<Item = f64>| it.fold(0.0, f64::max);
    let total = max(&mut x
        .iter()
        .zip(&t)
        .map(|(x, t)| (t - slab_series(*x, 0.1)).abs()));
    let step = max(&mut t.iter().zip(&fine).map(|(a, b)| (a - b).abs()));
    let mesh = max(&mut x
        .iter()
        .zip(&fine)
        .map(|(x, t)| (t - slab_series(*x, 0.1)).abs()));
    level.values.push(error("T error", total));
    level.values.push(error("T error (time step)", step));
    level.values.push(error("T error (mesh)", mesh));
    Ok(level)
}

fn expansion_checks() -> Vec<Check> {
    [
        "free strain tet4",
        "free stress tet4",
        "held stress tet4",
        "free strain hex8",
        "free stress hex8",
        "held stress hex8",
        "free strain tet4 (linear elastic)",
        "held reaction stress tet4 (linear elastic)",
        "free strain hex8 (linear elastic)",
        "held reaction stress hex8 (linear elastic)",
    ]
    .into_iter()
    .map(|q| Check::new(Quantity::Named(q), &[1e-10]))
    .collect()
}

fn expansion() -> Result<ProgramLevel, String> {
    let (young, nu, alpha, t0, t1) = (200e3, 0.3, 1e-5, 20.0, 120.0);
    let dt = t1 - t0;
    let sigma = -young * alpha * dt / (1.0 - 2.0 * nu);
    let mut level = ProgramLevel {
        h: f64::NAN,
        ..ProgramLevel::default()
    };
    let names = [
        [
            "free strain tet4",
            "free stress tet4",
            "held stress tet4",
            "free strain tet4 (linear elastic)",
            "held reaction stress tet4 (linear elastic)",
        ],
        [
            "free strain hex8",
            "free stress hex8",
            "held stress hex8",
            "free strain hex8 (linear elastic)",
            "held reaction stress hex8 (linear elastic)",
        ],
    ];
    for (kind, names) in [CellKind::Tet4, CellKind::Hex8].into_iter().zip(names) {
        for plastic in [true, false] {
            for free in [true, false] {
                let g = [Grading::Uniform; 3];
                // held: one cell layer, every node on a held face (an
                // interior node whose exact displacement is 0 stalls the
                // relative correction test: see the module doc)
                let n = if free { 2 } else { 1 };
                let mut mesh =
                    solid::brick([0.0; 3], [1.0; 3], [n; 3], g, kind).map_err(|e| e.message)?;
                mesh.node_sets
                    .insert("all".into(), (0..mesh.nodes.len()).collect());
                let law = if plastic {
                    MaterialLaw::ElastoPlastic {
                        young,
                        poisson: nu,
                        hardening: Hardening::Linear {
                            yield_stress: 1e9,
                            modulus: 0.0,
                        },
                        viscosity: None,
                    }
                } else {
                    MaterialLaw::LinearElastic { young, poisson: nu }
                };
                let mut b = ModelBuilder::solid()
                    .material("steel", law)
                    .body("brick", mesh, "steel");
                for (c, face) in ["xmin", "ymin", "zmin"].iter().enumerate() {
                    let nodes = b.node_set(&format!("brick.{face}"));
                    b = b.fix(nodes, c);
                }
                if !free {
                    for (c, face) in ["xmax", "ymax", "zmax"].iter().enumerate() {
                        let nodes = b.node_set(&format!("brick.{face}"));
                        b = b.fix(nodes, c);
                    }
                }
                let mut s = scene(thermal(1.0, 0.0, alpha, t0), t0);
                s.temperatures.push(PrescribedTemperature {
                    label: "temperature brick.all".into(),
                    nodes: b.node_set("brick.all"),
                    value: TimeFunction::Constant(t1),
                });
                // the first increment heats the brick, the second one
                // loads the mechanics with the heated state (staggered)
                let model = b.thermal(s).step("heat", 1.0, 2).tol(1e-12).build();
                let held = if free { "free" } else { "held" };
                let last = solve(&model, &mut level)
                    .map_err(|e| format!("{held} {} brick: {e}", kind.name()))?;
                let strain = model
                    .mesh
                    .nodes
                    .iter()
                    .zip(&last.displacement)
                    .flat_map(|(p, u)| (0..3).map(move |k| (p[k], u[k])))
                    .map(|(x, u)| (u - alpha * dt * x).abs() / (alpha * dt))
                    .fold(0.0, f64::max);
                let scale = sigma.abs();
                match (plastic, free) {
                    (true, true) => {
                        level.values.push(error(names[0], strain));
                        let worst = last
                            .stress
                            .iter()
                            .flatten()
                            .map(|s| s.abs() / scale)
                            .fold(0.0, f64::max);
                        level.values.push(error(names[1], worst));
                    }
                    (true, false) => {
                        let worst = last
                            .stress
                            .iter()
                            .flat_map(|s| {
                                (0..6).map(move |k| {
                                    let exact = if k < 3 { sigma } else { 0.0 };
                                    (s[k] - exact).abs() / scale
                                })
                            })
                            .fold(0.0, f64::max);
                        level.values.push(error(names[2], worst));
                    }
                    (false, true) => level.values.push(error(names[3], strain)),
                    (false, false) => {
                        // the reaction on x = 1 (outward normal +x) over the
                        // face's area is the traction sigma_xx
                        let face = &model.mesh.node_sets["brick.xmax"];
                        let fx: f64 = face.iter().map(|&n| last.reaction[n][0]).sum();
                        level
                            .values
                            .push(error(names[4], (fx - sigma).abs() / scale));
                    }
                }
            }
        }
    }
    Ok(level)
}

/// The interface data of the last increment of a thermal contact run.
#[derive(Default)]
struct Interface {
    pressure: Vec<f64>,
    force: f64,
    slave_temperature: Vec<f64>,
    /// `h A (T_tool - T)` of every closed node against its reported power.
    balance: f64,
    power: f64,
}

impl<const D: usize> Observer<D> for Interface {
    fn converged(&mut self, v: &IncrementView<'_, D>) -> Result<(), String> {
        let t = v.temperature.ok_or("no thermal scene")?;
        let pair = v.contact.first().ok_or("no contact pair")?;
        self.pressure = pair.iter().map(|c| c.pressure).collect();
        self.force = pair.iter().map(|c| c.force[D - 1]).sum();
        self.slave_temperature = pair.iter().map(|c| t[c.node]).collect();
        self.power = v.thermal.ok_or("no heat report")?.contact_power[0];
        // the heat of each node from its own h(p), tributary area and
        // temperature, summed, against the solver's contact power
        let model = v.model;
        let scene = model.thermal.as_ref().ok_or("no thermal scene")?;
        let settings = scene.contacts[0].as_ref().ok_or("no thermal pair")?;
        let t_tool = settings
            .tool_temperature
            .as_ref()
            .ok_or("no tool temperature")?
            .eval(v.time);
        let areas = ctc_engine::thermal::coupling::pair_areas(model, 0);
        let cp = &model.contacts[0];
        let mut sum = 0.0;
        for c in pair {
            let i = cp.nodes.binary_search(&c.node).map_err(|_| "not a slave")?;
            let h = ctc_engine::thermal::contact::node_conductance(settings, c);
            sum += h * areas[i] * (t_tool - t[c.node]);
        }
        self.balance = (sum - self.power).abs() / self.power.abs();
        Ok(())
    }
}

/// Runs `cases/<deck>` (planar or solid) with its push `ramp` replaced by
/// `stroke`.
fn pushed(
    deck: &str,
    ramp: &str,
    stroke: f64,
    level: &mut ProgramLevel,
) -> Result<Interface, String> {
    let (path, text) = super::read_case_deck(deck)?;
    if !text.contains(ramp) {
        return Err(format!("{deck} has no `{ramp}` to replace"));
    }
    let text = text.replace(ramp, &format!("ramp(0, {})", -stroke));
    let src = ctc_lang::Source::new(&path, &text);
    let any = ctc_lang::compile_any(&src).map_err(|d| d.render(&src))?;
    let mut probe = Interface::default();
    let s = match any {
        ctc_engine::model::AnyModel::D2(m) => run(&m, &mut probe),
        ctc_engine::model::AnyModel::D3(m) => run(&m, &mut probe),
    }
    .map_err(|e| e.message)?;
    level.add_run(&s);
    Ok(probe)
}

fn contact_tool() -> Result<ProgramLevel, String> {
    let mut level = ProgramLevel {
        h: f64::NAN,
        ..ProgramLevel::default()
    };
    let (k1, l1, t_hot, t_cold) = (2.0, 2.0, 100.0, 20.0);
    // 3D contact area 1 x 0.5; the planar block is 1 wide, thickness 1
    let (area3, area2) = (0.5, 1.0);
    let names = [
        ("flux (low p)", "T_i (low p)"),
        ("flux (high p)", "T_i (high p)"),
    ];
    let (mut spread, mut flux_2d, mut p_2d, mut balance) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
    for (stroke, (flux, t_i)) in [0.004, 0.04].into_iter().zip(names) {
        let p3 = pushed(
            "thermal_contact_tool_3d.ctc",
            "ramp(0, -0.004)",
            stroke,
            &mut level,
        )?;
        let p2 = pushed(
            "thermal_contact_tool.ctc",
            "ramp(0, -0.004)",
            stroke,
            &mut level,
        )?;
        let p = p3.force / area3;
        let h = 3.0 + 0.5 * p.sqrt();
        let q = (t_hot - t_cold) / (l1 / k1 + 1.0 / h);
        let ti = t_cold + q / h;
        let t_error = p3
            .slave_temperature
            .iter()
            .map(|t| (t - ti).abs() / (t_hot - t_cold))
            .fold(0.0, f64::max);
        level.values.push(value(flux, -p3.power / area3, q));
        level.values.push(error(t_i, t_error));
        spread = p3
            .pressure
            .iter()
            .map(|pi| (pi - p).abs() / p)
            .fold(spread, f64::max);
        let q2 = -p2.power / area2;
        flux_2d = flux_2d.max((-p3.power / area3 - q2).abs() / q2.abs());
        p_2d = p_2d.max((p - p2.force / area2).abs() / p);
        balance = balance.max(p3.balance);
    }
    level.values.push(error("p uniform", spread));
    level.values.push(error("flux 3d vs 2d", flux_2d));
    level.values.push(error("p 3d vs 2d", p_2d));
    level
        .values
        .push(error("node heat = h A (T_tool - T)", balance));
    Ok(level)
}

fn adiabatic() -> Result<ProgramLevel, String> {
    // the closed form of `adiabatic_heating`
    let (e, sy, hm, beta, rho_c) = (1000.0, 2.0, 100.0, 0.9, 1.0);
    let mut ep_old: f64 = 0.0;
    let mut work = 0.0;
    for n in 1..=10 {
        let eps = 0.05 * n as f64 / 10.0;
        let ep = ((eps - sy / e) / (1.0 + hm / e)).max(0.0);
        work += (sy + hm * ep) * (ep - ep_old);
        ep_old = ep;
    }
    let mut level = ProgramLevel {
        h: f64::NAN,
        ..ProgramLevel::default()
    };
    // 1/8 model: the unit cube, symmetry planes, top pushed down 5 %
    let g = [Grading::Uniform; 3];
    let mesh =
        solid::brick([0.0; 3], [1.0; 3], [2, 2, 2], g, CellKind::Hex8).map_err(|e| e.message)?;
    let mut b = ModelBuilder::solid()
        .material(
            "j2",
            MaterialLaw::ElastoPlastic {
                young: e,
                poisson: 0.3,
                hardening: Hardening::Linear {
                    yield_stress: sy,
                    modulus: hm,
                },
                viscosity: None,
            },
        )
        .body("cube", mesh, "j2");
    for (c, face) in ["xmin", "ymin", "zmin"].iter().enumerate() {
        let nodes = b.node_set(&format!("cube.{face}"));
        b = b.fix(nodes, c);
    }
    let top = b.node_set("cube.zmax");
    let volume = 1.0;
    let model = b
        .displace(top, 2, ctc_engine::testkit::ramp(0.0, 1.0, -0.05))
        .thermal(scene(thermal(1.0, rho_c, 0.0, 0.0), 0.0))
        .step("press", 1.0, 10)
        .tol(1e-12)
        .build();
    let last = solve(&model, &mut level)?;
    let heat = beta * work * volume;
    let rise = heat / (rho_c * volume);
    level
        .values
        .push(value("heat / beta W", last.plastic, heat));
    let worst = last
        .temperature
        .iter()
        .map(|t| (t - rise).abs() / rise)
        .fold(0.0, f64::max);
    level.values.push(error("T rise", worst));
    // the axisymmetric run of `adiabatic_heating`
    let (path, text) = super::read_case_deck("adiabatic_heating.ctc")?;
    let axi = super::compile(&path, &text)?;
    #[derive(Default)]
    struct Axi(Vec<f64>);
    impl Observer for Axi {
        fn converged(&mut self, v: &IncrementView<'_>) -> Result<(), String> {
            self.0 = v.temperature.ok_or("no thermal scene")?.to_vec();
            Ok(())
        }
    }
    let mut probe = Axi::default();
    let s = run(&axi, &mut probe).map_err(|e| e.message)?;
    level.add_run(&s);
    // the planar deck starts at 20
    let mean2 = probe.0.iter().sum::<f64>() / probe.0.len() as f64 - 20.0;
    let mean3 = last.temperature.iter().sum::<f64>() / last.temperature.len() as f64;
    level.values.push(value("T rise 3d vs axi", mean3, mean2));
    Ok(level)
}
