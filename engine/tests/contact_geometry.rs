//! Projection, gap and normal of each rigid tool geometry through the
//! public `evaluate_pair`, against hand-computed values; moving and rotating
//! tools; nodes on segment ends, at kinks and outside every entity.

mod support;

use ctc_engine::contact::ContactStatus;
use ctc_engine::model::{TimeFunction, ToolGeometry, ToolMotion, ToolSide};
use std::f64::consts::{FRAC_1_SQRT_2, FRAC_PI_2, PI};
use support::contact::{probe, probe_model};

fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol
}

fn assert_vec(a: [f64; 2], b: [f64; 2], tol: f64) {
    assert!(
        close(a[0], b[0], tol) && close(a[1], b[1], tol),
        "{a:?} vs {b:?}"
    );
}

fn plane() -> ToolGeometry {
    ToolGeometry::Plane {
        point: [0.0, 0.0],
        normal: [0.0, 1.0],
    }
}

#[test]
fn contact_plane_fixed_gap_force_and_status() {
    let m = probe_model(plane(), ToolMotion::fixed(), 0.5);
    let c = probe(&m, [0.3, -0.02], 0.0).unwrap();
    assert_eq!(c.status, ContactStatus::Closed);
    assert!(close(c.gap, -0.02, 1e-15));
    assert_vec(c.normal, [0.0, 1.0], 0.0);
    // Nodal penalty 1e3: force = -alpha g n = (0, 20).
    assert_vec(c.force, [0.0, 20.0], 1e-12);
    assert_eq!(c.stiffness, [[0.0, 0.0], [0.0, 1.0e3]]);
    let o = probe(&m, [0.3, 0.4], 0.0).unwrap();
    assert_eq!((o.status, o.force), (ContactStatus::Open, [0.0; 2]));
    // Beyond prof: no contact element.
    assert!(probe(&m, [0.3, 0.6], 0.0).is_none());
}

#[test]
fn contact_plane_translating_with_time() {
    let motion = ToolMotion {
        uy: TimeFunction::Ramp {
            t0: 0.0,
            t1: 1.0,
            v0: 0.0,
            v1: -0.1,
        },
        ..ToolMotion::fixed()
    };
    let m = probe_model(plane(), motion, 0.5);
    // At t = 0.5 the plane is at y = -0.05.
    let c = probe(&m, [0.3, -0.08], 0.5).unwrap();
    assert!(close(c.gap, -0.03, 1e-15), "gap {}", c.gap);
    let c = probe(&m, [0.3, -0.08], 1.0).unwrap();
    assert!(close(c.gap, 0.02, 1e-15));
}

#[test]
fn contact_plane_rotated_quarter_turn_about_origin() {
    let motion = ToolMotion {
        rotation: TimeFunction::Constant(FRAC_PI_2),
        center: [0.0, 0.0],
        ..ToolMotion::fixed()
    };
    let m = probe_model(plane(), motion, 0.5);
    // Normal (0,1) rotated by +90 degrees: (-1, 0); the line is x = 0.
    let c = probe(&m, [0.2, 5.0], 0.0).unwrap();
    assert!(close(c.gap, -0.2, 1e-15));
    assert_vec(c.normal, [-1.0, 0.0], 1e-15);
    assert_vec(c.force, [-200.0, 0.0], 1e-10);
    let k = c.stiffness;
    assert!(close(k[0][0], 1e3, 1e-10) && close(k[1][1], 0.0, 1e-10));
}

#[test]
fn contact_circle_punch_moving_and_rotating() {
    let geometry = ToolGeometry::Circle {
        center: [0.0, 1.0],
        radius: 1.0,
        side: ToolSide::Outside,
    };
    let motion = ToolMotion {
        uy: TimeFunction::Constant(-0.1),
        rotation: TimeFunction::Constant(0.7),
        center: [0.0, 1.0],
        ..ToolMotion::fixed()
    };
    let m = probe_model(geometry, motion, 0.5);
    // Centre now at (0, 0.9): node (0, -0.05) is 0.05 inside.
    let c = probe(&m, [0.0, -0.05], 0.0).unwrap();
    assert!(close(c.gap, -0.05, 1e-14));
    assert_vec(c.normal, [0.0, -1.0], 1e-14);
    // Off-axis node: gap = |x - c| - R.
    let x = [0.3, 0.0];
    let d = (0.09f64 + 0.81).sqrt();
    let c = probe(&m, x, 0.0).unwrap();
    assert!(close(c.gap, d - 1.0, 1e-14));
    assert_vec(c.normal, [0.3 / d, -0.9 / d], 1e-14);
}

#[test]
fn contact_circle_container_inside() {
    let geometry = ToolGeometry::Circle {
        center: [0.0, 0.0],
        radius: 2.0,
        side: ToolSide::Inside,
    };
    let m = probe_model(geometry, ToolMotion::fixed(), 0.5);
    let c = probe(&m, [0.0, -2.1], 0.0).unwrap();
    assert!(close(c.gap, -0.1, 1e-14));
    assert_vec(c.normal, [0.0, 1.0], 1e-15);
    assert!(probe(&m, [0.0, 0.0], 0.0).is_none());
}

fn die() -> ToolGeometry {
    // Walk (0,0) -> (1,0) -> (2,1): a left turn, so seen from the free side
    // (above) the kink at (1,0) is a concave valley.
    ToolGeometry::Polyline {
        points: vec![[0.0, 0.0], [1.0, 0.0], [2.0, 1.0]],
    }
}

#[test]
fn contact_polyline_node_exactly_on_kink_and_segment_ends() {
    let m = probe_model(die(), ToolMotion::fixed(), 0.5);
    let c = probe(&m, [1.0, 0.0], 0.0).unwrap();
    assert_eq!((c.gap, c.entity), (0.0, 0));
    assert_eq!(c.status, ContactStatus::Open);
    let c = probe(&m, [2.0, 1.0], 0.0).unwrap();
    assert_eq!((c.gap, c.entity), (0.0, 1));
    let c = probe(&m, [0.0, -0.01], 0.0).unwrap();
    assert!(close(c.gap, -0.01, 1e-15) && c.entity == 0);
}

#[test]
fn contact_polyline_concave_kink_nearer_segment_and_corner_fan() {
    let m = probe_model(die(), ToolMotion::fixed(), 0.5);
    // Penetrates segment 1 (gap (-0.1 + 0.05)/sqrt2); its foot on segment 0
    // would lie beyond the kink.
    let c = probe(&m, [1.1, 0.05], 0.0).unwrap();
    assert_eq!(c.entity, 1);
    assert!(close(c.gap, -0.05 * FRAC_1_SQRT_2, 1e-15));
    assert_vec(c.normal, [-FRAC_1_SQRT_2, FRAC_1_SQRT_2], 1e-15);
    // In the valley above the kink, nearer to segment 0.
    let c = probe(&m, [0.9, 0.05], 0.0).unwrap();
    assert_eq!(c.entity, 0);
    assert!(close(c.gap, 0.05, 1e-15));
    // Below and right of the kink, behind both segments: the closest free
    // point is the kink itself (radius-0 circle), gap = -distance.
    let c = probe(&m, [1.05, -0.1], 0.0).unwrap();
    let d = (0.05f64 * 0.05 + 0.01).sqrt();
    assert!(close(c.gap, -d, 1e-15));
    assert_vec(c.normal, [-0.05 / d, 0.1 / d], 1e-15);
    // The force is the spring -alpha (x - kink), tangent alpha I.
    assert_vec(c.force, [-50.0, 100.0], 1e-10);
    assert!(close(c.stiffness[0][0], 1e3, 1e-9) && close(c.stiffness[0][1], 0.0, 1e-9));
}

#[test]
fn contact_polyline_convex_corner_projects_on_vertex() {
    // A punch edge: (0,0) -> (1,0) -> (1,-1) turns right: convex corner.
    let g = ToolGeometry::Polyline {
        points: vec![[0.0, 0.0], [1.0, 0.0], [1.0, -1.0]],
    };
    let m = probe_model(g, ToolMotion::fixed(), 0.5);
    let c = probe(&m, [1.3, 0.4], 0.0).unwrap();
    assert!(close(c.gap, 0.5, 1e-15));
    assert_vec(c.normal, [0.6, 0.8], 1e-15);
    // Penetrating near the corner: least penetrated segment.
    let c = probe(&m, [0.95, -0.02], 0.0).unwrap();
    assert_eq!(c.entity, 0);
    assert!(close(c.gap, -0.02, 1e-15));
    let c = probe(&m, [0.98, -0.3], 0.0).unwrap();
    assert_eq!(c.entity, 1);
    assert!(close(c.gap, -0.02, 1e-15));
}

#[test]
fn contact_node_outside_all_entities() {
    let m = probe_model(die(), ToolMotion::fixed(), 0.5);
    // Far above: beyond prof of every segment box.
    assert!(probe(&m, [0.5, 3.0], 0.0).is_none());
    // Behind the free start of the die, within prof: past the tool's end,
    // open with the distance to the end as gap.
    let c = probe(&m, [-0.3, -0.4], 0.0).unwrap();
    assert_eq!(c.status, ContactStatus::Open);
    assert!(close(c.gap, 0.5, 1e-15));
}

#[test]
fn contact_arc_bowl_and_roller() {
    // Lower half circle walked counter-clockwise: a bowl, free inside.
    let bowl = ToolGeometry::Arc {
        center: [0.0, 0.0],
        radius: 1.0,
        start_angle: PI,
        end_angle: 2.0 * PI,
    };
    let m = probe_model(bowl, ToolMotion::fixed(), 0.5);
    let c = probe(&m, [0.0, -1.02], 0.0).unwrap();
    assert!(close(c.gap, -0.02, 1e-15));
    assert_vec(c.normal, [0.0, 1.0], 1e-15);
    // Beyond the end (1, 0), above it: rounded end.
    let c = probe(&m, [1.0, 0.3], 0.0).unwrap();
    assert!(close(c.gap, 0.3, 1e-15));
    // Upper quarter walked clockwise: a roller, free outside.
    let roller = ToolGeometry::Arc {
        center: [0.0, 0.0],
        radius: 1.0,
        start_angle: PI,
        end_angle: 0.0,
    };
    let m = probe_model(roller, ToolMotion::fixed(), 0.5);
    let c = probe(&m, [0.0, 0.97], 0.0).unwrap();
    assert!(close(c.gap, -0.03, 1e-15));
    assert_vec(c.normal, [0.0, 1.0], 1e-15);
}

#[test]
fn contact_nurbs_quarter_circle_equals_arc_through_evaluate_pair() {
    let nurbs = ToolGeometry::Nurbs {
        degree: 2,
        control_points: vec![[1.0, 0.0], [1.0, 1.0], [0.0, 1.0]],
        weights: vec![1.0, FRAC_1_SQRT_2, 1.0],
        knots: vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
    };
    let arc = ToolGeometry::Arc {
        center: [0.0, 0.0],
        radius: 1.0,
        start_angle: 0.0,
        end_angle: FRAC_PI_2,
    };
    let motion = ToolMotion {
        ux: TimeFunction::Constant(0.25),
        rotation: TimeFunction::Constant(-0.4),
        center: [0.5, 0.5],
        ..ToolMotion::fixed()
    };
    let mn = probe_model(nurbs, motion.clone(), 0.5);
    let ma = probe_model(arc, motion, 0.5);
    let mut worst = 0.0f64;
    for i in 0..50 {
        for j in 0..7 {
            let theta = 0.02 + 1.53 * i as f64 / 49.0;
            let r = 0.8 + 0.05 * j as f64;
            let reference = [r * theta.cos(), r * theta.sin()];
            // Place the probe where the moved tool's reference point is.
            let p = ctc_engine::contact::motion::Placement::at(&mn.tools[0].motion, 0.0);
            let x = p.to_current(reference);
            let (a, b) = (probe(&ma, x, 0.0).unwrap(), probe(&mn, x, 0.0).unwrap());
            worst = worst
                .max((a.gap - b.gap).abs())
                .max((a.normal[0] - b.normal[0]).abs())
                .max((a.normal[1] - b.normal[1]).abs())
                .max((a.force[0] - b.force[0]).abs() / 1e3)
                .max((a.force[1] - b.force[1]).abs() / 1e3);
        }
    }
    println!("nurbs vs arc: worst gap/normal difference {worst:.3e}");
    assert!(worst <= 1e-12, "worst {worst:e}");
}

#[test]
fn contact_invalid_tool_is_reported_not_panicking() {
    let bad = ToolGeometry::Polyline {
        points: vec![[0.0, 0.0], [0.0, 0.0]],
    };
    let m = probe_model(bad, ToolMotion::fixed(), 0.5);
    let err = ctc_engine::contact::PairState::try_new(&m, 0).unwrap_err();
    assert!(err.contains("coincide"), "{err}");
    assert!(probe(&m, [0.0, 0.0], 0.0).is_none());
}
