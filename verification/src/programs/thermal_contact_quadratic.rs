//! `thermal_contact_tool_quadratic`: thermal contact of quadratic slave
//! faces against a rigid tool (issue 23; `thermal::contact_faces`), tags
//! `quadratic`, `thermal`.
//!
//! Source: VERIFICATION-CASES.md §8 (case 8, series resistance of the
//! block and the interface), as `thermal_contact_tool` /
//! `thermal_contact_tool_3d`: a block of conductivity `k = 2`, length
//! `L = 2`, pressed onto a rigid floor at `T_cold = 20` by a uniform push of
//! its top (held at `T_hot = 100`), the conductance `h = 3 + 0.5 sqrt(p)`;
//! steady (rho c = 0). Closed form: `q = (T_hot - T_cold) / (L / k + 1 /
//! h(p))`, interface temperature `T_i = T_cold + q / h(p)`, at the two
//! strokes of the linear case (p 2 and 20 per unit area).
//!
//! ```text
//!   T_hot ───────────
//!   │ block k, L     │   quadratic cells: corners and midside nodes
//!   │                │   on the contact faces; the conductance is
//!   ─── h(p) ─────────   integrated at the faces' points
//!   ///// T_cold /////
//! ```
//!
//! The decks of the linear cases with `order = 2`: quad8 and tri6 (plane
//! strain, and axisymmetric: the block a solid cylinder r <= 1, contact
//! area pi), hex20 and tet10 (the 1 x 0.5 x 2 brick, area 0.5); and quad9
//! (plane strain, axisymmetric) / hex27, which no deck key makes: the same
//! models built by the test kit on the elevated meshes ([`built`]). All
//! with the decks' area penalty; quad8 (plane strain) and tet10 also with
//! Lagrange multipliers (the nodal pressures of the dual basis of
//! `contact::face_integrated`).
//! The pressure is uniform and the temperature linear in the height, both
//! in the cells' spaces, so flux and interface temperatures are exact to
//! round-off; the interface temperature is judged at every slave node,
//! corners and midsides (with nodal areas, a tri6 corner would exchange
//! nothing and a quad8 corner heat against the difference).

use super::{error, read_case_deck};
use crate::case::{Check, Quantity};
use crate::registry::{CaseKind, ProgramCase, ProgramLevel, VerifyCase};
use ctc_engine::geom::Dimension;
use ctc_engine::mesh::CellKind;
use ctc_engine::model::{AnyModel, Model};
use ctc_engine::solve::{run, IncrementView, Observer};
use nalgebra::Const;

/// Flux and interface temperatures are exact to round-off (measured: see
/// `cases`).
const EXACT: f64 = 1e-9;

/// A run: (flux name, T_i name, p name, cell kind, deck, deck edits,
/// contact area); the deck [`BUILT`] is the test-kit model of [`built`]
/// (edits: [`AXI`] for the axisymmetric one).
type Run = (
    &'static str,
    &'static str,
    &'static str,
    CellKind,
    &'static str,
    &'static [(&'static str, &'static str)],
    f64,
);

const PLANAR: &str = "thermal_contact_tool.ctc";
const BUILT: &str = "(test kit)";
const SOLID: &str = "thermal_contact_tool_3d.ctc";
const QUAD8: (&str, &str) = ("element = quad4", "element = quad4  order = 2");
const TRI6: (&str, &str) = ("element = quad4", "element = tri3  order = 2");
const AXI: (&str, &str) = ("plane_strain", "axisymmetric");
const HEX20: (&str, &str) = (
    "divisions = (4, 2, 8)",
    "divisions = (4, 2, 8)  element = hex8  order = 2",
);
const LAGRANGE: (&str, &str) = (
    "method = penalty { kind = area  stiffness = 1e7 }",
    "method = lagrange { }",
);
const TET10: (&str, &str) = (
    "divisions = (4, 2, 8)",
    "divisions = (4, 2, 8)  element = tet4  order = 2",
);

fn runs() -> Vec<Run> {
    use std::f64::consts::PI;
    vec![
        (
            "flux quad8 plane strain",
            "T_i quad8 plane strain",
            "p uniform quad8 plane strain",
            CellKind::Quad8,
            PLANAR,
            &[QUAD8],
            1.0,
        ),
        (
            "flux tri6 plane strain",
            "T_i tri6 plane strain",
            "p uniform tri6 plane strain",
            CellKind::Tri6,
            PLANAR,
            &[TRI6],
            1.0,
        ),
        (
            "flux quad8 axisymmetric",
            "T_i quad8 axisymmetric",
            "p uniform quad8 axisymmetric",
            CellKind::Quad8,
            PLANAR,
            &[QUAD8, AXI],
            PI,
        ),
        (
            "flux tri6 axisymmetric",
            "T_i tri6 axisymmetric",
            "p uniform tri6 axisymmetric",
            CellKind::Tri6,
            PLANAR,
            &[TRI6, AXI],
            PI,
        ),
        (
            "flux quad9 plane strain",
            "T_i quad9 plane strain",
            "p uniform quad9 plane strain",
            CellKind::Quad9,
            BUILT,
            &[],
            1.0,
        ),
        (
            "flux quad9 axisymmetric",
            "T_i quad9 axisymmetric",
            "p uniform quad9 axisymmetric",
            CellKind::Quad9,
            BUILT,
            &[AXI],
            PI,
        ),
        (
            "flux hex27",
            "T_i hex27",
            "p uniform hex27",
            CellKind::Hex27,
            BUILT,
            &[],
            0.5,
        ),
        (
            "flux hex20",
            "T_i hex20",
            "p uniform hex20",
            CellKind::Hex20,
            SOLID,
            &[HEX20],
            0.5,
        ),
        (
            "flux tet10",
            "T_i tet10",
            "p uniform tet10",
            CellKind::Tet10,
            SOLID,
            &[TET10],
            0.5,
        ),
        (
            "flux quad8 plane strain lagrange",
            "T_i quad8 plane strain lagrange",
            "p uniform quad8 plane strain lagrange",
            CellKind::Quad8,
            PLANAR,
            &[QUAD8, LAGRANGE],
            1.0,
        ),
        (
            "flux tet10 lagrange",
            "T_i tet10 lagrange",
            "p uniform tet10 lagrange",
            CellKind::Tet10,
            SOLID,
            &[TET10, LAGRANGE],
            0.5,
        ),
    ]
}

/// The registry entry.
pub fn cases() -> Vec<VerifyCase> {
    let checks = runs()
        .iter()
        .flat_map(|r| {
            [
                Check::new(Quantity::Named(r.0), &[EXACT]),
                Check::new(Quantity::Named(r.1), &[EXACT]),
                Check::new(Quantity::Named(r.2), &[EXACT]),
            ]
        })
        .collect();
    vec![VerifyCase {
        name: "thermal_contact_tool_quadratic",
        title:
            "Thermal contact on quadratic faces against a cold rigid tool, h(p), two pressures: \
                quad8/quad9/tri6 (plane strain, axisymmetric), hex27/hex20/tet10",
        source: "VERIFICATION-CASES.md §8 (series resistance l/k + 1/h); thermal_contact_tool",
        tags: &[
            "quadratic",
            "thermal",
            "contact",
            "penalty",
            "3d",
            "axisymmetric",
            "closed_form",
            "exact",
        ],
        levels: 1,
        checks,
        kind: CaseKind::Program(ProgramCase {
            max_levels: 1,
            run: |_| level(),
        }),
    }]
}

/// The interface at the last converged increment.
#[derive(Default)]
struct Interface {
    /// Pressure of every reported node of pair 0.
    pressure: Vec<f64>,
    /// Total normal contact force of pair 0 (along the last axis).
    force: f64,
    /// Temperature of every reported node of pair 0.
    slave_temperature: Vec<f64>,
    /// Heat power into the slave side of pair 0.
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
        Ok(())
    }
}

fn solve<const D: usize>(
    model: &Model<D>,
    kind: CellKind,
    level: &mut ProgramLevel,
) -> Result<Interface, String>
where
    Const<D>: Dimension<D>,
{
    if model.mesh.cells.kind(0) != kind {
        return Err(format!(
            "the deck made {} cells, not {}",
            model.mesh.cells.kind(0).name(),
            kind.name()
        ));
    }
    let mut probe = Interface::default();
    let s = run(model, &mut probe).map_err(|e| e.message)?;
    level.add_run(&s);
    Ok(probe)
}

/// Runs `deck` with `edits` and its push replaced by `stroke`.
fn pushed(
    deck: &str,
    edits: &[(&str, &str)],
    stroke: f64,
    kind: CellKind,
    level: &mut ProgramLevel,
) -> Result<Interface, String> {
    let (path, mut text) = read_case_deck(deck)?;
    let push = "ramp(0, -0.004)";
    for &(from, to) in edits.iter().chain([(push, "PUSH")].iter()) {
        if !text.contains(from) {
            return Err(format!("{deck} has no `{from}` to replace"));
        }
        text = text.replace(from, to);
    }
    let text = text.replace("PUSH", &format!("ramp(0, {})", -stroke));
    let src = ctc_lang::Source::new(&path, &text);
    match ctc_lang::compile_any(&src).map_err(|d| d.render(&src))? {
        AnyModel::D2(m) => solve(&m, kind, level),
        AnyModel::D3(m) => solve(&m, kind, level),
    }
}

fn level() -> Result<ProgramLevel, String> {
    let mut level = ProgramLevel {
        h: f64::NAN,
        ..ProgramLevel::default()
    };
    let (k, l, t_hot, t_cold) = (2.0, 2.0, 100.0, 20.0);
    for (flux, t_i, uniform, kind, deck, edits, area) in runs() {
        let (mut e_flux, mut e_t, mut spread) = (0.0f64, 0.0f64, 0.0f64);
        let mut pressures = Vec::new();
        for stroke in [0.004, 0.04] {
            let probe = if deck == BUILT {
                built(kind, !edits.is_empty(), stroke, &mut level)?
            } else {
                pushed(deck, edits, stroke, kind, &mut level)?
            };
            let p = probe.force / area;
            let h = 3.0 + 0.5 * p.sqrt();
            let q = (t_hot - t_cold) / (l / k + 1.0 / h);
            let ti = t_cold + q / h;
            // heat leaves through the slave side: power into the slave < 0
            e_flux = e_flux.max((-probe.power / area - q).abs() / q);
            e_t = probe
                .slave_temperature
                .iter()
                .map(|t| (t - ti).abs() / (t_hot - t_cold))
                .fold(e_t, f64::max);
            spread = probe
                .pressure
                .iter()
                .map(|pi| (pi - p).abs() / p)
                .fold(spread, f64::max);
            if probe.slave_temperature.is_empty() {
                return Err(format!("{}: no slave node reported", kind.name()));
            }
            pressures.push(p);
        }
        if pressures[1] <= 5.0 * pressures[0] {
            return Err(format!(
                "{}: the two pressures {pressures:?} are too close to test h(p)",
                kind.name()
            ));
        }
        level.values.push(error(flux, e_flux));
        level.values.push(error(t_i, e_t));
        level.values.push(error(uniform, spread));
    }
    Ok(level)
}

/// The models of the decks built by the test kit on elevated meshes (the
/// decks' generators make quad8 / hex20 only): `kind` quad9 (plane strain,
/// or axisymmetric when `axi`) or hex27, the push `stroke`.
fn built(
    kind: CellKind,
    axi: bool,
    stroke: f64,
    level: &mut ProgramLevel,
) -> Result<Interface, String> {
    use ctc_engine::mesh::elevate::elevate;
    use ctc_engine::mesh::generate::{generate, solid, Grading, MeshSpec};
    use ctc_engine::model::thermal::{
        Conductance, ContactThermal, CouplingScheme, MaterialThermal, PrescribedTemperature,
        ThermalScene,
    };
    use ctc_engine::model::{AnalysisKind, ContactMethod, PenaltyKind, TimeFunction};
    use ctc_engine::testkit::{ramp, ModelBuilder};
    // the decks' block, floor, conductance and temperatures
    let penalty = ContactMethod::Penalty {
        kind: PenaltyKind::Area,
        stiffness: 1e7,
    };
    let scene = |hot: Vec<usize>| ThermalScene {
        materials: vec![Some(MaterialThermal {
            conductivity: 2.0,
            capacity: 0.0,
            density: 0.0,
            expansion: 0.0,
            reference: 0.0,
            taylor_quinney: 0.0,
            young_factor: None,
            yield_factor: None,
        })],
        initial: vec![0.0],
        temperatures: vec![PrescribedTemperature {
            label: "temperature block.top".into(),
            nodes: hot,
            value: TimeFunction::Constant(100.0),
        }],
        fluxes: Vec::new(),
        convection: Vec::new(),
        contacts: vec![Some(ContactThermal {
            conductance: Conductance::Power {
                h0: 3.0,
                h1: 0.5,
                n: 0.5,
            },
            gap_conductivity: 0.0,
            gap_min: 1e-6,
            friction_split: 0.5,
            tool_temperature: Some(TimeFunction::Constant(20.0)),
        })],
        scheme: CouplingScheme::Staggered,
    };
    let push = ramp(0.0, 1.0, -stroke);
    if kind == CellKind::Hex27 {
        use ctc_engine::model::SurfaceMotion;
        use ctc_geom::analytic::{Analytic, Plane};
        use ctc_geom::{Side, Vec3};
        let mesh = solid::brick(
            [0.0; 3],
            [1.0, 0.5, 2.0],
            [4, 2, 8],
            [Grading::Uniform; 3],
            CellKind::Hex8,
        )
        .and_then(|m| elevate(&m, kind))
        .map_err(|e| e.message)?;
        let mut b = ModelBuilder::solid()
            .elastic("metal", 1000.0, 0.3)
            .body("block", mesh, "metal");
        for (set, c) in [("xmin", 0), ("ymin", 1), ("ymax", 1)] {
            let nodes = b.node_set(&format!("block.{set}"));
            b = b.fix(nodes, c);
        }
        let top = b.node_set("block.zmax");
        let faces = b.face_set("block.zmin");
        let floor = Plane::new(Vec3::zeros(), Vec3::z(), Side::Outside)?;
        let model = b
            .displace(top.clone(), 2, push)
            .surface("floor", Analytic::Plane(floor), SurfaceMotion::fixed())
            .contact_faces("block.zmin -> floor", "block", faces, "floor", penalty)
            .step("press", 1.0, 1)
            .tol(1e-12)
            .thermal(scene(top))
            .build();
        return solve(&model, kind, level);
    }
    let mesh = generate(&MeshSpec::Rectangle {
        origin: [0.0, 0.0],
        size: [1.0, 2.0],
        divisions: [4, 8],
        grading: [Grading::Uniform; 2],
        kind: CellKind::Quad4,
    })
    .and_then(|m| elevate(&m, kind))
    .map_err(|e| e.message)?;
    let analysis = if axi {
        AnalysisKind::Axisymmetric
    } else {
        AnalysisKind::PlaneStrain
    };
    let b = ModelBuilder::new(analysis)
        .elastic("metal", 1000.0, 0.3)
        .body("block", mesh, "metal");
    let (left, top) = (b.node_set("block.left"), b.node_set("block.top"));
    let bottom = b.edge_set("block.bottom");
    let model = b
        .fix(left, 0)
        .displace(top.clone(), 1, push)
        .tool(
            "floor",
            ctc_engine::model::ToolGeometry::Plane {
                point: [0.0, 0.0],
                normal: [0.0, 1.0],
            },
            ctc_engine::model::ToolMotion::fixed(),
        )
        .contact_tool("block.bottom -> floor", "block", bottom, "floor", penalty)
        .step("press", 1.0, 1)
        .tol(1e-12)
        .thermal(scene(top))
        .build();
    solve(&model, kind, level)
}
