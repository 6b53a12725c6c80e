//! Equilibrium between body and tool: the total contact force of a pair is
//! minus the force on the tool, and the moments balance. The load on the
//! tool is measured independently, as minus the derivative of the penalty
//! energy with respect to the tool's rigid motion (central differences on
//! `ToolMotion`), so wrong normals, signs or motion transforms fail it.

mod support;

use ctc_engine::contact::{
    evaluate_pair, pair_penalty_energy, pair_total_force, pair_total_moment, ContactStatus,
    PairState,
};
use ctc_engine::model::{AnalysisKind, Model, TimeFunction, ToolGeometry, ToolMotion, ToolSide};
use support::contact::{area, surface_model};

fn strip(n: usize) -> (Vec<[f64; 2]>, Vec<[usize; 2]>) {
    let nodes = (0..n)
        .map(|i| {
            let x = -0.5 + i as f64 / (n - 1) as f64;
            [x, 0.01 * (7.0 * x).sin()]
        })
        .collect();
    // Body below the strip: edges walk right-to-left (body on the left).
    let edges = (0..n - 1).map(|i| [i + 1, i]).collect();
    (nodes, edges)
}

fn energy(model: &Model, motion: ToolMotion, x: &[[f64; 2]]) -> f64 {
    let mut m = model.clone();
    m.tools[0].motion = motion;
    let mut s = PairState::new(&m, 0);
    pair_penalty_energy(&evaluate_pair(&m, 0, x, 0.0, &mut s))
}

fn check(geometry: ToolGeometry, pivot: [f64; 2], label: &str) {
    let (nodes, edges) = strip(41);
    let model = surface_model(
        AnalysisKind::PlaneStrain,
        2.0,
        nodes.clone(),
        edges,
        geometry,
        ToolMotion {
            center: pivot,
            ..ToolMotion::fixed()
        },
        area(1e4),
        Some(0.2),
    );
    let mut state = PairState::new(&model, 0);
    let out = evaluate_pair(&model, 0, &nodes, 0.0, &mut state);
    let closed = out
        .iter()
        .filter(|c| c.status == ContactStatus::Closed)
        .count();
    assert!(closed >= 5, "{label}: only {closed} closed nodes");
    let f = pair_total_force(&out);
    let m = pair_total_moment(&out, &nodes, pivot);
    let base = ToolMotion {
        center: pivot,
        ..ToolMotion::fixed()
    };
    let d = 1e-7;
    let shifted = |ux: f64, uy: f64, rot: f64| ToolMotion {
        ux: TimeFunction::Constant(ux),
        uy: TimeFunction::Constant(uy),
        rotation: TimeFunction::Constant(rot),
        ..base.clone()
    };
    // Load on the tool = -dPi/d(tool motion).
    let tool_fx = -(energy(&model, shifted(d, 0.0, 0.0), &nodes)
        - energy(&model, shifted(-d, 0.0, 0.0), &nodes))
        / (2.0 * d);
    let tool_fy = -(energy(&model, shifted(0.0, d, 0.0), &nodes)
        - energy(&model, shifted(0.0, -d, 0.0), &nodes))
        / (2.0 * d);
    let tool_m = -(energy(&model, shifted(0.0, 0.0, d), &nodes)
        - energy(&model, shifted(0.0, 0.0, -d), &nodes))
        / (2.0 * d);
    let scale = f[0].hypot(f[1]);
    let err_f = (f[0] + tool_fx).hypot(f[1] + tool_fy) / scale;
    let err_m = (m + tool_m).abs() / scale;
    println!(
        "{label}: body force ({:.6e}, {:.6e}), tool force ({tool_fx:.6e}, {tool_fy:.6e}), \
         rel. error {err_f:.1e}; moment about pivot body {m:.6e}, tool {tool_m:.6e}, error {err_m:.1e}",
        f[0], f[1]
    );
    assert!(err_f < 1e-6, "{label}: force balance error {err_f:e}");
    assert!(err_m < 1e-6, "{label}: moment balance error {err_m:e}");
}

#[test]
fn contact_equilibrium_circle_punch_force_and_moment() {
    let c = [0.05, 1.0 - 0.03];
    check(
        ToolGeometry::Circle {
            center: c,
            radius: 1.0,
            side: ToolSide::Outside,
        },
        [0.3, 0.5],
        "circle",
    );
    // Frictionless circle: every force passes through the centre.
    let (nodes, edges) = strip(41);
    let model = surface_model(
        AnalysisKind::PlaneStrain,
        1.0,
        nodes.clone(),
        edges,
        ToolGeometry::Circle {
            center: c,
            radius: 1.0,
            side: ToolSide::Outside,
        },
        ToolMotion::fixed(),
        area(1e4),
        None,
    );
    let out = evaluate_pair(&model, 0, &nodes, 0.0, &mut PairState::new(&model, 0));
    let f = pair_total_force(&out);
    let m = pair_total_moment(&out, &nodes, c);
    assert!(m.abs() < 1e-12 * f[1].abs(), "moment about centre {m:e}");
    assert!(f[1] < 0.0, "the punch pushes the strip down");
}

#[test]
fn contact_equilibrium_polyline_die_rotation_and_translation() {
    check(
        ToolGeometry::Polyline {
            points: vec![[0.6, 0.3], [0.1, -0.02], [-0.2, 0.0], [-0.6, 0.25]],
        },
        [0.2, 0.7],
        "polyline",
    );
}

#[test]
fn contact_equilibrium_nurbs_tool() {
    check(
        ToolGeometry::Nurbs {
            degree: 2,
            control_points: vec![[0.7, 0.4], [0.2, -0.05], [-0.2, -0.03], [-0.7, 0.5]],
            weights: vec![1.0, 0.8, 1.2, 1.0],
            knots: vec![0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0],
        },
        [-0.1, 0.9],
        "nurbs",
    );
}
