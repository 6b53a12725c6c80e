//! Shared models for the Lagrange / augmented-Lagrangian tests: the rigid
//! cylinder on an elastic block (curved tool, examples/cylinder_on_block.ctc
//! coarsened) and the Hertz cylinder on a rigid floor
//! (examples/hertz_cylinder.ctc coarsened), with any contact method, plus an
//! observer recording each converged increment.
#![allow(dead_code)]

use ctc_engine::contact::{pair_total_force, ContactStatus, NodeContact};
use ctc_engine::mesh::generate::{generate, Grading, MeshSpec};
use ctc_engine::mesh::{CellKind, Mesh};
use ctc_engine::model::{
    Analysis, AnalysisKind, Body, ContactMethod, ContactPair, Dirichlet, Formulation,
    LagrangeFormulation, Material, MaterialLaw, Model, MultiplierUpdate, NewtonSettings,
    OutputRequest, PenaltyKind, RigidTool, Step, TimeFunction, ToolGeometry, ToolMotion, ToolSide,
};
use ctc_engine::solve::{run, IncrementView, IterationInfo, Observer, RunSummary};

/// Young's modulus of the block / disc.
pub const E: f64 = 1000.0;
/// Poisson's ratio.
pub const NU: f64 = 0.3;

/// Lagrange multipliers, single (LU) or doubled (LDL^T) formulation.
pub fn lagrange(doubled: bool) -> ContactMethod {
    ContactMethod::Lagrange {
        formulation: if doubled {
            LagrangeFormulation::Doubled
        } else {
            LagrangeFormulation::Single
        },
    }
}

/// Area-weighted augmented Lagrangian.
pub fn augmented(penalty: f64, tolerance: f64, newton: bool) -> ContactMethod {
    ContactMethod::AugmentedLagrange {
        kind: PenaltyKind::Area,
        penalty,
        tolerance,
        update: if newton {
            MultiplierUpdate::Newton
        } else {
            MultiplierUpdate::Converged
        },
    }
}

/// Area-weighted penalty.
pub fn penalty(stiffness: f64) -> ContactMethod {
    ContactMethod::Penalty {
        kind: PenaltyKind::Area,
        stiffness,
    }
}

fn ramp(v1: f64) -> TimeFunction {
    TimeFunction::Ramp {
        t0: 0.0,
        t1: 1.0,
        v0: 0.0,
        v1,
    }
}

fn material(young: f64) -> Material {
    Material {
        name: "soft".into(),
        law: MaterialLaw::LinearElastic { young, poisson: NU },
    }
}

fn step(increments: usize) -> Step {
    Step {
        name: "press".into(),
        t_start: 0.0,
        t_end: 1.0,
        increments,
        min_fraction: 1.0 / 64.0,
        newton: NewtonSettings {
            tol: 1e-10,
            tol_displacement: 1e-10,
            max_iter: 25,
            line_search: true,
        },
    }
}

fn body(mesh: &Mesh) -> Body {
    Body {
        name: "body".into(),
        nodes: 0..mesh.nodes.len(),
        cells: 0..mesh.cells.len(),
        material: 0,
        formulation: Formulation::Full,
        kinematics: Default::default(),
    }
}

fn pair(name: &str, edges: Vec<[usize; 2]>, method: ContactMethod) -> ContactPair {
    let mut nodes: Vec<usize> = edges.iter().flat_map(|e| [e[0], e[1]]).collect();
    nodes.sort_unstable();
    nodes.dedup();
    ContactPair {
        name: name.into(),
        body: 0,
        edges,
        nodes,
        master: ctc_engine::model::ContactMaster::Tool(0),
        strategy: Default::default(),
        search: Default::default(),
        method,
        prof: None,
        friction: None,
    }
}

/// Rigid cylinder of radius 1 (centre (0, 1)) pushed `depth` into the
/// block [-4, 4] x [-4, 0] (`nx` x `ny` quads, refined towards the centre
/// top), bottom clamped, plane strain.
pub fn cylinder_on_block(
    method: ContactMethod,
    nx: usize,
    ny: usize,
    depth: f64,
    increments: usize,
) -> Model {
    let mesh = generate(&MeshSpec::Rectangle {
        origin: [-4.0, -4.0],
        size: [8.0, 4.0],
        divisions: [nx, ny],
        grading: [
            Grading::Center { ratio: 8.0 },
            Grading::Geometric { ratio: 0.125 },
        ],
        kind: CellKind::Quad4,
    })
    .expect("rectangle mesh");
    let top = mesh.edge_sets["top"].clone();
    let bottom = mesh.node_sets["bottom"].clone();
    let fix = |c: usize| Dirichlet {
        label: format!("fix bottom {c}"),
        nodes: bottom.clone(),
        component: c,
        value: TimeFunction::Constant(0.0),
    };
    Model {
        analysis: Analysis {
            kind: AnalysisKind::PlaneStrain,
            thickness: 1.0,
        },
        bodies: vec![body(&mesh)],
        mesh,
        materials: vec![material(E)],
        constraints: vec![fix(0), fix(1)],
        loads: vec![],
        tools: vec![RigidTool {
            name: "punch".into(),
            geometry: ToolGeometry::Circle {
                center: [0.0, 1.0],
                radius: 1.0,
                side: ToolSide::Outside,
            },
            motion: ToolMotion {
                uy: ramp(-depth),
                ..ToolMotion::fixed()
            },
        }],
        contacts: vec![pair("block.top -> punch", top, method)],
        steps: vec![step(increments)],
        output: OutputRequest::default(),
        thermal: None,
    }
}

/// Radius of the Hertz disc.
pub const HERTZ_R: f64 = 8.0;
/// Young's modulus of the Hertz disc.
pub const HERTZ_E: f64 = 200.0;

/// Elastic lower half disc (R = 8, centre (0, 8)) pressed `depth` onto the
/// rigid floor y = 0 through its flat edge (ux fixed, uy prescribed), as
/// examples/hertz_cylinder.ctc with `radial` x `circumferential` divisions.
pub fn hertz_disc(
    method: ContactMethod,
    radial: usize,
    circumferential: usize,
    depth: f64,
    increments: usize,
) -> Model {
    let mesh = generate(&MeshSpec::HalfDisc {
        center: [0.0, HERTZ_R],
        radius: HERTZ_R,
        radial,
        circumferential,
        radial_grading: Grading::Geometric { ratio: 0.15 },
        circumferential_grading: Grading::Center { ratio: 8.0 },
        upper: false,
        kind: CellKind::Quad4,
    })
    .expect("half disc mesh");
    let arc = mesh.edge_sets["arc"].clone();
    let flat = mesh.node_sets["flat"].clone();
    Model {
        analysis: Analysis {
            kind: AnalysisKind::PlaneStrain,
            thickness: 1.0,
        },
        bodies: vec![body(&mesh)],
        mesh,
        materials: vec![material(HERTZ_E)],
        constraints: vec![
            Dirichlet {
                label: "flat ux".into(),
                nodes: flat.clone(),
                component: 0,
                value: TimeFunction::Constant(0.0),
            },
            Dirichlet {
                label: "flat uy".into(),
                nodes: flat,
                component: 1,
                value: ramp(-depth),
            },
        ],
        loads: vec![],
        tools: vec![RigidTool {
            name: "floor".into(),
            geometry: ToolGeometry::Plane {
                point: [0.0, 0.0],
                normal: [0.0, 1.0],
            },
            motion: ToolMotion::fixed(),
        }],
        contacts: vec![pair("disc.arc -> floor", arc, method)],
        steps: vec![step(increments)],
        output: OutputRequest::default(),
        thermal: None,
    }
}

/// One converged increment as seen by the observer.
#[derive(Debug, Clone)]
pub struct Record {
    /// Time.
    pub time: f64,
    /// Contact evaluation of pair 0.
    pub contact: Vec<NodeContact>,
    /// Total reaction at the constrained dofs.
    pub reaction: [f64; 2],
    /// Displacements.
    pub u: Vec<[f64; 2]>,
    /// Relative residuals.
    pub residuals: Vec<f64>,
}

impl Record {
    /// Total force of the tool on the body.
    pub fn contact_force(&self) -> [f64; 2] {
        pair_total_force(&self.contact)
    }

    /// Largest penetration over the slave nodes.
    pub fn max_penetration(&self) -> f64 {
        self.contact.iter().map(|c| -c.gap).fold(0.0, f64::max)
    }

    /// Closed nodes.
    pub fn closed(&self) -> Vec<&NodeContact> {
        self.contact
            .iter()
            .filter(|c| c.status == ContactStatus::Closed)
            .collect()
    }
}

/// Records every converged increment; prints iterations when `verbose`.
#[derive(Default)]
pub struct Recorder {
    /// Converged increments.
    pub records: Vec<Record>,
    /// Cutback reasons.
    pub cutbacks: Vec<String>,
}

impl Observer for Recorder {
    fn iteration(&mut self, _info: &IterationInfo) {}
    fn converged(&mut self, view: &IncrementView<'_>) -> Result<(), String> {
        let reaction = view
            .reaction
            .iter()
            .fold([0.0; 2], |a, r| [a[0] + r[0], a[1] + r[1]]);
        self.records.push(Record {
            time: view.time,
            contact: view.contact[0].clone(),
            reaction,
            u: view.displacement.to_vec(),
            residuals: view.residuals.to_vec(),
        });
        Ok(())
    }
    fn cutback(&mut self, reason: &str, _new_dt: f64) {
        self.cutbacks.push(reason.to_string());
    }
}

/// Runs `model`, printing the Newton residual sequence of each increment
/// under `label`.
pub fn solve(label: &str, model: &Model) -> (RunSummary, Recorder) {
    let mut rec = Recorder::default();
    let summary = match run(model, &mut rec) {
        Ok(s) => s,
        Err(e) => panic!("{label}: {}", e.message),
    };
    for inc in &summary.increments {
        let r: Vec<String> = inc.residuals.iter().map(|r| format!("{r:.1e}")).collect();
        println!(
            "{label} inc {} t={:.3}: {} Newton its, {} contact its, {} closed, max penetration \
             {:.3e}, residuals [{}]",
            inc.increment,
            inc.time,
            inc.iterations,
            inc.contact_iterations,
            inc.active_contacts,
            inc.max_penetration,
            r.join(", ")
        );
    }
    (summary, rec)
}

/// Hertz p0 from the total contact force `p` (per unit thickness) for a
/// disc of radius `r` and modulus `e` on a rigid flat (plane strain).
pub fn hertz_p0(p: f64, r: f64, e: f64) -> f64 {
    let e_star = e / (1.0 - NU * NU);
    let a = (4.0 * p * r / (std::f64::consts::PI * e_star)).sqrt();
    2.0 * p / (std::f64::consts::PI * a)
}
