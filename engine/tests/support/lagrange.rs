//! The rigid cylinder on an elastic block (curved tool,
//! examples/cylinder_on_block.ctc coarsened) and the Hertz cylinder on a
//! rigid floor (examples/hertz_cylinder.ctc coarsened), with any contact
//! method, for the Lagrange / augmented-Lagrangian tests.

use super::{ramp, ModelBuilder, Recorder};
use ctc_engine::mesh::generate::{generate, Grading, MeshSpec};
use ctc_engine::mesh::CellKind;
use ctc_engine::model::{
    ContactMethod, LagrangeFormulation, Model, MultiplierUpdate, NewtonSettings, PenaltyKind,
    TimeFunction, ToolGeometry, ToolMotion, ToolSide,
};
use ctc_engine::solve::{run, RunSummary};

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

/// One step "press" over `0 .. 1` (tolerances 1e-10, min increment 1/64).
fn press(b: ModelBuilder, increments: usize) -> ModelBuilder {
    b.step("press", 1.0, increments)
        .min_fraction(1.0 / 64.0)
        .newton(NewtonSettings {
            tol: 1e-10,
            tol_displacement: 1e-10,
            max_iter: 25,
            line_search: true,
            predictor: true,
            stabilize: None,
        })
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
    let b = ModelBuilder::plane_strain()
        .elastic("soft", E, NU)
        .body("body", mesh, "soft")
        .fix(bottom.clone(), 0)
        .fix(bottom, 1)
        .tool(
            "punch",
            ToolGeometry::Circle {
                center: [0.0, 1.0],
                radius: 1.0,
                side: ToolSide::Outside,
            },
            ToolMotion {
                uy: ramp(0.0, 1.0, -depth),
                ..ToolMotion::fixed()
            },
        )
        .contact_tool("block.top -> punch", "body", top, "punch", method);
    press(b, increments).build()
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
    let b = ModelBuilder::plane_strain()
        .elastic("soft", HERTZ_E, NU)
        .body("body", mesh, "soft")
        .displace(flat.clone(), 0, TimeFunction::Constant(0.0))
        .displace(flat, 1, ramp(0.0, 1.0, -depth))
        .tool(
            "floor",
            ToolGeometry::Plane {
                point: [0.0, 0.0],
                normal: [0.0, 1.0],
            },
            ToolMotion::fixed(),
        )
        .contact_tool("disc.arc -> floor", "body", arc, "floor", method);
    press(b, increments).build()
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
