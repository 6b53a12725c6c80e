//! The neighbour-first face search of a BREP tool: a node moving over a
//! tool of many faces tests its last face and the neighbours first, so with
//! memory it projects on far fewer faces than without, and finds the same
//! closest point (the counters are the engine's health figures).
//!
//! ```text
//!   z ^        8 x 8 bicubic patches of the wavy sheet
//!     |  ~~~~~~~~~~~~~~~~~~~~~~~~   z = 0.1 sin(2 x) cos(3 y)
//!     |    * -> * -> * ->  nodes sliding along a line above the sheet
//!     +-----------------------> x
//! ```

use ctc_geom::brep::{BrepOptions, BrepTool, Counters, Face, SearchState};
use ctc_geom::nurbs::NurbsSurface;
use ctc_geom::{FootKind, Vec3};

/// The 8 x 8 sheet over [0, 4]^2, each face a bicubic patch interpolating
/// the wave at its control points (faces share their boundary rows).
fn sheet() -> BrepTool {
    let n = 8;
    let h = 4.0 / n as f64;
    let wave = |x: f64, y: f64| 0.1 * (2.0 * x).sin() * (3.0 * y).cos();
    let mut faces = Vec::new();
    for j in 0..n {
        for i in 0..n {
            let mut pts = Vec::new();
            for b in 0..4 {
                for a in 0..4 {
                    let (x, y) = (
                        h * (i as f64 + a as f64 / 3.0),
                        h * (j as f64 + b as f64 / 3.0),
                    );
                    // Boundary rows are shared exactly; interior rows follow the wave.
                    pts.push(Vec3::new(
                        x,
                        y,
                        if a == 0 || a == 3 || b == 0 || b == 3 {
                            0.0
                        } else {
                            wave(x, y)
                        },
                    ));
                }
            }
            let k = vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0];
            let s = NurbsSurface::new([3, 3], [4, 4], [k.clone(), k], pts, vec![1.0; 16]).unwrap();
            faces.push(Face::new(s, None, 1.0));
        }
    }
    BrepTool::new(faces, BrepOptions::default()).unwrap()
}

#[test]
fn memory_makes_the_search_test_few_faces_and_changes_nothing() {
    let tool = sheet();
    // Interior faces have 8 neighbours (4 by edges, 4 by corners).
    assert_eq!(tool.neighbours[9].len(), 8);
    assert_eq!(tool.neighbours[0].len(), 3);
    let path: Vec<Vec3> = (0..400)
        .map(|k| {
            Vec3::new(
                0.05 + 3.9 * k as f64 / 399.0,
                1.3 + 0.2 * (k as f64 * 0.05).sin(),
                0.05,
            )
        })
        .collect();
    let mut warm = Counters::default();
    let mut cold = Counters::default();
    let mut state = SearchState::with_reach(0.5);
    let mut kinds = [0usize; 3];
    for x in &path {
        let a = tool.project(x, &mut state, &mut warm).unwrap();
        let b = tool
            .project(x, &mut SearchState::with_reach(0.5), &mut cold)
            .unwrap();
        assert!(
            (a.gap - b.gap).abs() < 1e-12 && (a.point - b.point).norm() < 1e-10,
            "{x:?}"
        );
        assert_eq!(
            (a.kind, a.normal.dot(&b.normal) > 1.0 - 1e-12),
            (b.kind, true),
            "{x:?}"
        );
        kinds[a.kind as usize] += 1;
    }
    let per = |c: &Counters| c.faces_tested as f64 / c.queries as f64;
    println!(
        "faces tested per query: with memory {:.2}, without {:.2}; projections per query {:.2} / {:.2}; Newton its per query {:.2} / {:.2}",
        per(&warm),
        per(&cold),
        warm.projections_per_query(),
        cold.projections_per_query(),
        warm.newton_iterations as f64 / warm.queries as f64,
        cold.newton_iterations as f64 / cold.queries as f64
    );
    assert!(
        per(&warm) < per(&cold),
        "memory must reduce the faces tested"
    );
    // The path crosses the faces' shared (kinked) edges: both kinds occur.
    assert!(
        kinds[FootKind::Interior as usize] > 100 && kinds[FootKind::Edge as usize] > 0,
        "{kinds:?}"
    );
    assert!(warm.faces_skipped > 0 && warm.not_converged == 0);
}
