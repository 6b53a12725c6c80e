//! Consistent contact tangent `K_c = -d force / d x` against central finite
//! differences of the force, for random penetrating nodes on every tool
//! geometry (fixed, translated and rotated tools). Relative tolerance 1e-6.

mod support;

use ctc_engine::contact::geometry::nurbs::Nurbs;
use ctc_engine::contact::motion::Placement;
use ctc_engine::model::{Model, TimeFunction, ToolGeometry, ToolMotion, ToolSide};
use proptest::prelude::*;
use std::f64::consts::{FRAC_1_SQRT_2, PI, TAU};
use support::contact::{probe, probe_model, tangent_error};

const H: f64 = 1e-6;
const TOL: f64 = 1e-6;

/// The geometries exercised.
#[derive(Debug, Clone, Copy)]
enum Case {
    Plane,
    CircleOutside,
    CircleInside,
    ArcBowl,
    ArcRoller,
    PolylineSegment,
    PolylineConcaveCorner,
    NurbsCubic,
    NurbsCircle,
}

const CASES: [Case; 9] = [
    Case::Plane,
    Case::CircleOutside,
    Case::CircleInside,
    Case::ArcBowl,
    Case::ArcRoller,
    Case::PolylineSegment,
    Case::PolylineConcaveCorner,
    Case::NurbsCubic,
    Case::NurbsCircle,
];

fn zigzag() -> Vec<[f64; 2]> {
    vec![[0.0, 0.0], [1.0, 0.3], [2.0, -0.2], [3.0, 0.1], [4.0, 0.4]]
}

fn cubic() -> (usize, Vec<[f64; 2]>, Vec<f64>, Vec<f64>) {
    (
        3,
        vec![
            [0.0, 0.0],
            [1.0, 0.4],
            [2.0, -0.3],
            [3.0, 0.5],
            [4.0, 0.0],
            [5.0, 0.2],
        ],
        vec![1.0, 1.3, 0.8, 1.0, 1.1, 1.0],
        vec![0.0, 0.0, 0.0, 0.0, 1.0 / 3.0, 2.0 / 3.0, 1.0, 1.0, 1.0, 1.0],
    )
}

/// A tool motion: fixed, or a translation plus a rotation about a point.
fn motion(moving: bool) -> ToolMotion {
    if moving {
        ToolMotion {
            ux: TimeFunction::Constant(0.3),
            uy: TimeFunction::Constant(-0.2),
            rotation: TimeFunction::Constant(0.6),
            center: [0.5, -0.4],
        }
    } else {
        ToolMotion::fixed()
    }
}

/// Model and current node position for unit-interval parameters `a`, `b`
/// (position along the tool and penetration depth).
fn node(case: Case, a: f64, b: f64, moving: bool) -> (Model, [f64; 2]) {
    let depth = 0.005 + 0.1 * b;
    let (geometry, xref) = match case {
        Case::Plane => (
            ToolGeometry::Plane {
                point: [0.0, 0.0],
                normal: [0.3, 1.0],
            },
            {
                let n = [0.3 / 1.09f64.sqrt(), 1.0 / 1.09f64.sqrt()];
                let s = 4.0 * a - 2.0;
                [s * n[1] - depth * n[0], -s * n[0] - depth * n[1]]
            },
        ),
        Case::CircleOutside => {
            let th = TAU * a;
            let r = 1.0 - 3.0 * depth;
            (
                ToolGeometry::Circle {
                    center: [0.0, 0.0],
                    radius: 1.0,
                    side: ToolSide::Outside,
                },
                [r * th.cos(), r * th.sin()],
            )
        }
        Case::CircleInside => {
            let th = TAU * a;
            let r = 1.0 + 3.0 * depth;
            (
                ToolGeometry::Circle {
                    center: [0.0, 0.0],
                    radius: 1.0,
                    side: ToolSide::Inside,
                },
                [r * th.cos(), r * th.sin()],
            )
        }
        Case::ArcBowl => {
            let th = PI + 0.1 + (PI - 0.2) * a;
            let r = 1.0 + depth;
            (
                ToolGeometry::Arc {
                    center: [0.0, 0.0],
                    radius: 1.0,
                    start_angle: PI,
                    end_angle: TAU,
                },
                [r * th.cos(), r * th.sin()],
            )
        }
        Case::ArcRoller => {
            let th = 0.1 + (PI - 0.2) * a;
            let r = 1.0 - depth;
            (
                ToolGeometry::Arc {
                    center: [0.0, 0.0],
                    radius: 1.0,
                    start_angle: PI,
                    end_angle: 0.0,
                },
                [r * th.cos(), r * th.sin()],
            )
        }
        Case::PolylineSegment => {
            let pts = zigzag();
            let s = 4.0 * a;
            let i = (s as usize).min(3);
            let xi = 0.2 + 0.6 * (s - i as f64);
            let (p, q) = (pts[i], pts[i + 1]);
            let d = [q[0] - p[0], q[1] - p[1]];
            let l = d[0].hypot(d[1]);
            let n = [-d[1] / l, d[0] / l];
            let foot = [p[0] + xi * d[0], p[1] + xi * d[1]];
            (
                ToolGeometry::Polyline { points: pts },
                [foot[0] - 0.5 * depth * n[0], foot[1] - 0.5 * depth * n[1]],
            )
        }
        Case::PolylineConcaveCorner => {
            // Valley at (1, 0): walk (0,0) -> (1,0) -> (2,1); a node behind
            // both segments in the corner's fan: x = v - s n1 - u n2.
            let n1 = [0.0, 1.0];
            let n2 = [-FRAC_1_SQRT_2, FRAC_1_SQRT_2];
            let (s, u) = (0.01 + 0.1 * a, depth);
            (
                ToolGeometry::Polyline {
                    points: vec![[0.0, 0.0], [1.0, 0.0], [2.0, 1.0]],
                },
                [1.0 - s * n1[0] - u * n2[0], -s * n1[1] - u * n2[1]],
            )
        }
        Case::NurbsCubic | Case::NurbsCircle => {
            let (degree, control_points, weights, knots) = if let Case::NurbsCubic = case {
                cubic()
            } else {
                (
                    2,
                    vec![[1.0, 0.0], [1.0, 1.0], [0.0, 1.0]],
                    vec![1.0, FRAC_1_SQRT_2, 1.0],
                    vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
                )
            };
            let curve = Nurbs::new(degree, &control_points, &weights, &knots).unwrap();
            let u = 0.03 + 0.94 * a;
            let s = (0..curve.span_count())
                .find(|&s| curve.span_range(s).1 >= u)
                .unwrap();
            let (c, n, _) = curve.frame(s, u).unwrap();
            let depth = 0.3 * depth;
            (
                ToolGeometry::Nurbs {
                    degree,
                    control_points,
                    weights,
                    knots,
                },
                [c[0] - depth * n[0], c[1] - depth * n[1]],
            )
        }
    };
    let m = probe_model(geometry, motion(moving), 1.0);
    let x = Placement::at(&m.tools[0].motion, 0.0).to_current(xref);
    (m, x)
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, .. ProptestConfig::default() })]

    #[test]
    fn contact_tangent_matches_central_differences(
        which in 0usize..CASES.len(),
        a in 0.0f64..1.0,
        b in 0.0f64..1.0,
        moving in any::<bool>(),
    ) {
        let (m, x) = node(CASES[which], a, b, moving);
        let c = probe(&m, x, 0.0).expect("penetrating node found");
        prop_assert!(c.gap < 0.0, "{:?}: gap {}", CASES[which], c.gap);
        let err = tangent_error(&m, x, 0.0, H).unwrap();
        prop_assert!(err <= TOL, "{:?} a={} b={} moving={}: relative error {:e}",
            CASES[which], a, b, moving, err);
        // The tangent derives from a potential: symmetric.
        prop_assert!((c.stiffness[0][1] - c.stiffness[1][0]).abs() <= 1e-12 * c.stiffness[0][0].abs().max(1.0));
    }
}

/// Deterministic sweep printing the worst error per geometry (the numbers
/// quoted in the report), and a control: dropping the curvature term makes
/// the finite-difference check fail on curved tools.
#[test]
fn contact_tangent_error_summary_per_geometry() {
    for case in CASES {
        let mut worst = 0.0f64;
        for i in 0..12 {
            for j in 0..4 {
                for moving in [false, true] {
                    let (m, x) = node(case, (i as f64 + 0.37) / 12.0, j as f64 / 3.0, moving);
                    let e = tangent_error(&m, x, 0.0, H)
                        .unwrap_or_else(|| panic!("{case:?}: no contact at {x:?}"));
                    worst = worst.max(e);
                }
            }
        }
        println!("{case:?}: worst relative FD tangent error {worst:.2e} (96 nodes)");
        assert!(worst <= TOL, "{case:?}: {worst:e}");
    }
    // Control: a circle punch with the tangent reduced to alpha n n.
    let (m, x) = node(Case::CircleOutside, 0.3, 1.0, false);
    let c = probe(&m, x, 0.0).unwrap();
    let n = c.normal;
    let alpha = 1e3;
    let plain = [
        [alpha * n[0] * n[0], alpha * n[0] * n[1]],
        [alpha * n[1] * n[0], alpha * n[1] * n[1]],
    ];
    let diff = (0..2)
        .flat_map(|i| (0..2).map(move |j| (i, j)))
        .map(|(i, j)| (plain[i][j] - c.stiffness[i][j]).abs())
        .fold(0.0f64, f64::max)
        / alpha;
    println!("circle: tangent without the curvature term differs by {diff:.2e} (relative)");
    assert!(diff > 1e-2, "the curvature term must matter: {diff:e}");
}
