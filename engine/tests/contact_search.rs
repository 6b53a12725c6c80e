//! The memory-first, bounding-box search finds exactly the closest entity a
//! brute-force search finds, with far fewer projections; per-node memory is
//! committed and rolled back with the increment.

mod support;

use ctc_engine::contact::geometry::ToolShape;
use ctc_engine::contact::motion::Placement;
use ctc_engine::contact::search::{
    brute_force, closest, closest_in, closest_with, in_circle, Request, ToolGrid,
};
use ctc_engine::contact::{evaluate_pair, PairState};
use ctc_engine::model::{AnalysisKind, LocalSearch, TimeFunction, ToolGeometry, ToolMotion};
use proptest::prelude::*;
use support::contact::{nodal, surface_model};

fn wavy_die(n: usize) -> ToolGeometry {
    let points = (0..=n)
        .map(|i| {
            let x = 10.0 * i as f64 / n as f64;
            [x, 0.2 * (3.0 * x).sin() + 0.05 * (17.0 * x).cos()]
        })
        .collect();
    ToolGeometry::Polyline { points }
}

fn wavy_nurbs(spans: usize) -> ToolGeometry {
    let n = spans + 3;
    let control_points: Vec<[f64; 2]> = (0..n)
        .map(|i| {
            let x = 10.0 * i as f64 / (n - 1) as f64;
            [x, 0.3 * (2.0 * x).sin()]
        })
        .collect();
    let weights = (0..n).map(|i| 1.0 + 0.3 * ((i % 3) as f64)).collect();
    let mut knots = vec![0.0; 4];
    knots.extend((1..spans).map(|k| k as f64 / spans as f64));
    knots.extend([1.0; 4]);
    ToolGeometry::Nurbs {
        degree: 3,
        control_points,
        weights,
        knots,
    }
}

fn shapes() -> Vec<ToolShape> {
    vec![
        ToolShape::new(&wavy_die(200)).unwrap(),
        ToolShape::new(&wavy_nurbs(40)).unwrap(),
        ToolShape::new(&ToolGeometry::Polyline {
            // Closed star: convex and concave corners.
            points: (0..=16)
                .map(|i| {
                    let th = -(i % 16) as f64 * std::f64::consts::TAU / 16.0;
                    let r = if i % 2 == 0 { 3.0 } else { 1.5 };
                    [5.0 + r * th.cos(), r * th.sin()]
                })
                .collect(),
        })
        .unwrap(),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 256, .. ProptestConfig::default() })]

    #[test]
    fn contact_search_matches_brute_force(
        which in 0usize..3,
        x in -0.5f64..10.5,
        y in -1.5f64..1.5,
        window in 0.01f64..1.0,
        memory in proptest::option::of(0usize..220),
        guess in proptest::option::of(0usize..220),
    ) {
        let shape = &shapes()[which];
        let p = [x, y];
        let (mut nb, mut ns) = (0, 0);
        let b = brute_force(shape, p, &mut nb);
        let s = closest(shape, p, window, memory, guess, &mut ns);
        if let Some(s) = s {
            let b = b.expect("brute force finds what the search finds");
            prop_assert_eq!(s.entity, b.entity);
            prop_assert_eq!(s.projection, b.projection);
        }
        if let Some(b) = b {
            if b.projection.gap.abs() <= window {
                prop_assert!(s.is_some(), "search missed a candidate within the window");
            }
        }
        prop_assert_eq!(nb, shape.entity_count());
    }
}

#[test]
fn contact_search_counts_versus_brute_force_on_a_sliding_surface() {
    // 101 slave nodes along a flat strip pressed onto a 400-segment wavy die
    // translating along x: first call without memory, then increments.
    let n = 101;
    let nodes: Vec<[f64; 2]> = (0..n)
        .map(|i| [1.0 + 8.0 * i as f64 / (n - 1) as f64, 0.1])
        .collect();
    let edges: Vec<[usize; 2]> = (0..n - 1).map(|i| [i + 1, i]).collect();
    let motion = ToolMotion {
        ux: TimeFunction::Ramp {
            t0: 0.0,
            t1: 1.0,
            v0: 0.0,
            v1: 0.5,
        },
        ..ToolMotion::fixed()
    };
    for geometry in [wavy_die(400), wavy_nurbs(80)] {
        let m = surface_model(
            AnalysisKind::PlaneStrain,
            1.0,
            nodes.clone(),
            edges.clone(),
            geometry,
            motion.clone(),
            nodal(1e3),
            Some(0.5),
        );
        let shape = ToolShape::new(&m.tools[0].geometry).unwrap();
        let mut state = PairState::new(&m, 0);
        let mut line = String::new();
        for (k, t) in [0.0, 0.1, 0.2, 0.3].into_iter().enumerate() {
            // The strip sinks a little each increment.
            let x: Vec<[f64; 2]> = nodes.iter().map(|p| [p[0], p[1] - 0.1 * t]).collect();
            let out = evaluate_pair(&m, 0, &x, t, &mut state);
            state.commit();
            // Same result as a brute-force search of every node.
            let pl = Placement::at(&m.tools[0].motion, t);
            let mut brute_tests = 0;
            let mut expected = Vec::new();
            for &node in &m.contacts[0].nodes {
                if let Some(b) = brute_force(&shape, pl.to_reference(x[node]), &mut brute_tests) {
                    if b.projection.gap <= 0.5 {
                        expected.push((node, b.entity, b.projection.gap));
                    }
                }
            }
            let got: Vec<_> = out.iter().map(|c| (c.node, c.entity, c.gap)).collect();
            assert_eq!(got, expected);
            assert_eq!(brute_tests, state.last_brute_force_tests);
            line += &format!(
                " call {k}: {} tests (brute {});",
                state.last_projection_tests, state.last_brute_force_tests
            );
            let limit = if k == 0 { 12 * n } else { 6 * n };
            assert!(
                state.last_projection_tests <= limit,
                "call {k}: {} projections",
                state.last_projection_tests
            );
        }
        println!("{} entities:{line}", shape.entity_count());
    }
}

#[test]
fn contact_memory_commit_and_rollback() {
    let m = surface_model(
        AnalysisKind::PlaneStrain,
        1.0,
        vec![[1.0, 0.1], [2.0, 0.1]],
        vec![[1, 0]],
        wavy_die(50),
        ToolMotion::fixed(),
        nodal(1.0),
        Some(1.0),
    );
    let mut state = PairState::new(&m, 0);
    assert_eq!(state.last_entity, vec![None, None]);
    evaluate_pair(&m, 0, &m.mesh.nodes, 0.0, &mut state);
    let first = state.last_entity.clone();
    assert!(first.iter().all(|e| e.is_some()));
    state.commit();
    let moved = vec![[6.0, 0.1], [7.0, 0.1]];
    evaluate_pair(&m, 0, &moved, 0.0, &mut state);
    assert_ne!(state.last_entity, first);
    state.rollback();
    assert_eq!(state.last_entity, first);
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 256, .. ProptestConfig::default() })]

    /// Cast3M circle test: the result is the closest of the polyline
    /// segments whose circle holds the node, found whenever it is within
    /// the window.
    #[test]
    fn contact_circle_search_matches_filtered_brute_force(
        which in 0usize..3,
        x in -0.5f64..10.5,
        y in -1.5f64..1.5,
        window in 0.01f64..1.0,
        memory in proptest::option::of(0usize..220),
    ) {
        let shape = &shapes()[which];
        let p = [x, y];
        let mut ns = 0;
        let s = closest_with(shape, p, window, memory, None, LocalSearch::Circle, &mut ns);
        let mut best: Option<(usize, f64)> = None;
        for e in 0..shape.entity_count() {
            if !in_circle(shape, e, p, window) {
                continue;
            }
            if let Some(q) = shape.project(e, p) {
                if best.is_none_or(|b| q.gap.abs() < b.1.abs()) {
                    best = Some((e, q.gap));
                }
            }
        }
        if let Some(s) = s {
            let b = best.expect("a circle candidate exists");
            prop_assert_eq!((s.entity, s.projection.gap), b);
        }
        if let Some(b) = best {
            if b.1.abs() <= window {
                prop_assert!(s.is_some(), "circle search missed {:?}", b);
            }
        }
    }
}

#[test]
fn contact_circle_test_skips_segments_the_node_projects_past() {
    // Node past the end of segment 0 above a flat continuation: the memory
    // test projects on both segments, the circle test only on segment 1.
    let shape = ToolShape::new(&ToolGeometry::Polyline {
        points: vec![[0.0, 0.0], [1.0, 0.0], [2.0, 0.0]],
    })
    .unwrap();
    let p = [1.03, 0.01];
    let (mut memory_tests, mut circle_tests) = (0, 0);
    let m = closest(&shape, p, 0.05, None, None, &mut memory_tests).unwrap();
    let c = closest_with(
        &shape,
        p,
        0.05,
        None,
        None,
        LocalSearch::Circle,
        &mut circle_tests,
    )
    .unwrap();
    assert_eq!((m.entity, c.entity), (1, 1));
    assert_eq!((memory_tests, circle_tests), (2, 1));
    // a node deeper than the window: the memory test still finds it
    let deep = [0.5, -0.2];
    let (mut a, mut b) = (0, 0);
    assert!(closest(&shape, deep, 0.05, Some(0), None, &mut a).is_some());
    assert!(closest_with(
        &shape,
        deep,
        0.05,
        Some(0),
        None,
        LocalSearch::Circle,
        &mut b
    )
    .is_none());
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 256, .. ProptestConfig::default() })]

    /// The broad-phase search of a rigid tool returns what the entity loop
    /// returns, for both local tests, with no more projections.
    #[test]
    fn contact_grid_search_matches_entity_loop(
        which in 0usize..3,
        x in -0.5f64..10.5,
        y in -1.5f64..1.5,
        window in 0.01f64..1.0,
        memory in proptest::option::of(0usize..220),
        guess in proptest::option::of(0usize..220),
        circle in any::<bool>(),
    ) {
        let shape = &shapes()[which];
        let grid = ToolGrid::new(shape);
        let test = if circle { LocalSearch::Circle } else { LocalSearch::Memory };
        let (mut nl, mut ng) = (0, 0);
        let looped = closest_with(shape, [x, y], window, memory, guess, test, &mut nl);
        let mut scratch = Vec::new();
        let request = Request { x: [x, y], window, memory, guess, test };
        let gridded = closest_in(shape, &grid, request, &mut scratch, &mut ng);
        prop_assert_eq!(looped, gridded);
        // a priority entity pruned at the window radius is projected by the
        // grid once a deeper candidate widens the radius; the loop visits in
        // index order and may prune differently: a few projections at most
        // more than the loop (six priority entities)
        prop_assert!(ng <= nl + 6, "grid {} projections, loop {}", ng, nl);
    }
}
