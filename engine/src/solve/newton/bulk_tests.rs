//! The assembled bulk tangent of a linear model
//! ([`crate::solve::bulk_tangent`]) against the element loop, in the
//! Newton evaluation and through a whole contact step.
//!
//! ```text
//!        \   rigid circle R = 1, pressed down 0.05   /
//!         `-._______________________________.-'
//!   +--------------------------------------------+ y = 0  top: penalty contact
//!   |  12 x 4 jittered triangles, E = 1e3, 0.3   |
//!   +--------------------------------------------+ y = -1 bottom: clamped
//!  x = -1.5                                    x = 1.5
//! ```

use super::Newton;
use crate::model::{ContactMethod, Model, PenaltyKind, ToolGeometry, ToolMotion, ToolSide};
use crate::solve::Observer;
use crate::testkit::grid::{grid, grid_node};
use crate::testkit::{ramp, ModelBuilder};

const NX: usize = 12;
const NY: usize = 4;

/// The block pressed by the circle (penalty `kind`), one step of
/// `increments`.
fn model(increments: usize) -> Model {
    let mesh = grid(NX, NY, [-1.5, -1.0], [3.0, 1.0], 0.2, 7, true);
    // the top edges walked from +x to -x: the block on their left
    let top: Vec<[usize; 2]> = (0..NX)
        .map(|i| [grid_node(NX, i + 1, NY), grid_node(NX, i, NY)])
        .collect();
    let bottom: Vec<usize> = (0..=NX).map(|i| grid_node(NX, i, 0)).collect();
    ModelBuilder::plane_strain()
        .elastic("e", 1e3, 0.3)
        .body("block", mesh, "e")
        .tool(
            "punch",
            ToolGeometry::Circle {
                center: [0.0, 1.0],
                radius: 1.0,
                side: ToolSide::Outside,
            },
            ToolMotion {
                uy: ramp(0.0, 1.0, -0.05),
                center: [0.0, 1.0],
                ..ToolMotion::fixed()
            },
        )
        .contact_tool(
            "block.top -> punch",
            "block",
            top,
            "punch",
            ContactMethod::Penalty {
                stiffness: 4e4,
                kind: PenaltyKind::Area,
            },
        )
        .fix(bottom.clone(), 0)
        .fix(bottom, 1)
        .step("press", 1.0, increments)
        .build()
}

fn rel_diff(a: &[f64], b: &[f64]) -> f64 {
    let scale = b.iter().fold(0.0f64, |m, v| m.max(v.abs())).max(1e-300);
    a.iter()
        .zip(b)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()))
        / scale
}

struct Quiet;
impl Observer for Quiet {}

#[test]
fn the_bulk_tangent_gives_the_element_loops_residual_and_tangent() {
    let m = model(2);
    let mut cached = Newton::new(&m).unwrap();
    let mut looped = Newton::new(&m).unwrap();
    looped.set_bulk_tangent(false);
    // a state with part of the top surface in contact at t = 1 (the tool
    // 0.05 down): the top nodes pushed down 0.01 under the tool, less than
    // it (the three nodes at |x| <= 0.25 penetrate), the block strained
    let u: Vec<[f64; 2]> = m
        .mesh
        .nodes
        .iter()
        .map(|p| {
            let depth = (p[1] + 1.0) * 0.01 * (1.0 - p[0] * p[0] / 2.25);
            [1e-3 * p[0] * (p[1] + 1.0), -depth]
        })
        .collect();
    let mut reference = None;
    for newton in [&mut looped, &mut cached] {
        newton.u.copy_from_slice(&u);
        let mut tangents = Vec::new();
        // twice: the bulk is assembled at the first, copied at the second
        for _ in 0..2 {
            newton.evaluate(1.0, true).unwrap();
            tangents.push((
                newton.values.clone(),
                newton.r_free.clone(),
                newton.reactions.clone(),
            ));
        }
        assert!(newton.active_contacts() > 2, "the state has contact");
        assert!(newton.active_contacts() < NX + 1, "and open nodes");
        let reference = reference.get_or_insert_with(|| tangents[0].clone());
        for (values, r_free, reactions) in &tangents {
            assert!(rel_diff(values, &reference.0) <= 1e-12);
            assert!(rel_diff(r_free, &reference.1) <= 1e-12);
            assert!(rel_diff(reactions, &reference.2) <= 1e-12);
            // each path gives the same bits at every evaluation (the bulk
            // is a copy of the loop's values; the cached path adds the
            // contact after it, the loop before it, and sums `K u` in
            // another order: round-off between the paths)
            let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
            assert_eq!(bits(values), bits(&tangents[0].0));
            assert_eq!(bits(r_free), bits(&tangents[0].1));
        }
    }
    assert_eq!(
        looped.bulk_counts(),
        (0, 0),
        "the loop assembled every tangent"
    );
    let (reuses, builds) = cached.bulk_counts();
    assert_eq!(builds, 1, "one assembly of the bulk");
    assert_eq!(reuses, 1, "the second tangent from the bulk");
}

#[test]
fn a_contact_step_takes_the_same_iterations_with_the_bulk_tangent() {
    let m = model(3);
    let settings = m.steps[0].newton;
    let mut runs = Vec::new();
    for bulk in [false, true] {
        let mut newton = Newton::new(&m).unwrap();
        newton.set_bulk_tangent(bulk);
        let mut iterations = Vec::new();
        for k in 1..=3 {
            let t = k as f64 / 3.0;
            let c = newton.newton_loop(&settings, t, 0, k, &mut Quiet).unwrap();
            iterations.push(c.iterations);
            newton.commit();
        }
        let (reuses, _) = newton.bulk_counts();
        assert_eq!(reuses > 0, bulk);
        runs.push((
            iterations,
            newton.u.as_flattened().to_vec(),
            newton.active_contacts(),
        ));
    }
    assert_eq!(runs[0].0, runs[1].0, "Newton iterations per increment");
    assert!(runs[1].2 > 2, "the block is in contact");
    assert!(rel_diff(&runs[1].1, &runs[0].1) <= 1e-12);
}
