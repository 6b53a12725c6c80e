//! Parity test of a trimmed face with two holes against a brute-force
//! point-in-polygon test on a fine polygonal approximation.
//!
//! Reference: the even-odd rule (Jordan curve theorem); the brute force is
//! the classic crossing-number test (W. R. Franklin's `pnpoly`) on each
//! loop's polyline (64 points per curve piece: arcs are cut every 10
//! degrees, NURBS spans in 4 (p + 1) pieces, so the polyline is within
//! 2e-7 of the curves).
//!
//! ```text
//!  v
//!  1 |        ___arc___
//!    |   ____/         \____
//!    |  |                   )  <- rational NURBS (bulges right)
//!    |  |      ______       |
//!    |  |     | hole2 )     |    hole 2: line, rational NURBS, line
//!    |  |  O  |_______|     |    hole 1: full circle (one arc of 2 pi)
//!    |  | hole1             |
//!  0 |  |___________________|
//!    +--------------------------- u
//! ```
//! Points are drawn at random, on the curves, at the loops' vertices, on
//! horizontal lines tangent to a hole or through a vertex (the first ray of
//! the test goes to -u, so those rays are tangent / through a vertex / along
//! a line, and the test must restart), and at +-1e-8 across the curves
//! (the switch happens exactly at the curve).

use ctc_geom::nurbs::NurbsCurve;
use ctc_geom::trim::{Boundary, Containment, Loop, TrimCurve};
use ctc_geom::Vec2;
use proptest::prelude::*;
use std::f64::consts::{FRAC_PI_2, FRAC_PI_4, TAU};

fn v(x: f64, y: f64) -> Vec2 {
    Vec2::new(x, y)
}

/// The face of the sketch; the outer loop and both holes are walked
/// counter-clockwise (the face is on the left of the outer loop and on the
/// right of the holes).
fn face() -> Boundary {
    let right = NurbsCurve::new(
        2,
        vec![0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0],
        vec![v(0.95, 0.05), v(1.05, 0.3), v(0.9, 0.7), v(0.95, 0.95)],
        vec![1.0, 0.8, 1.3, 1.0],
    )
    .unwrap();
    let r = (0.45f64 * 0.45 * 2.0).sqrt();
    let outer = Loop::new(
        vec![
            TrimCurve::line(v(0.05, 0.05), v(0.95, 0.05)).unwrap(),
            TrimCurve::Nurbs(right),
            TrimCurve::arc(v(0.5, 0.5), r, FRAC_PI_4, FRAC_PI_2).unwrap(),
            TrimCurve::line(v(0.05, 0.95), v(0.05, 0.05)).unwrap(),
        ],
        1e-12,
    )
    .unwrap();
    let hole1 = Loop::new(
        vec![TrimCurve::arc(v(0.3, 0.375), 0.125, 0.0, TAU).unwrap()],
        1e-12,
    )
    .unwrap();
    let bulge = NurbsCurve::new(
        2,
        vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
        vec![v(0.8, 0.6), v(0.85, 0.8), v(0.6, 0.8)],
        vec![1.0, 0.7, 1.0],
    )
    .unwrap();
    let hole2 = Loop::new(
        vec![
            TrimCurve::line(v(0.6, 0.6), v(0.8, 0.6)).unwrap(),
            TrimCurve::Nurbs(bulge),
            TrimCurve::line(v(0.6, 0.8), v(0.6, 0.6)).unwrap(),
        ],
        1e-12,
    )
    .unwrap();
    Boundary::new(outer, vec![hole1, hole2])
}

/// Polylines of every loop.
fn polygons(b: &Boundary) -> Vec<Vec<Vec2>> {
    std::iter::once(&b.outer)
        .chain(b.holes.iter())
        .map(|l| l.curves.iter().flat_map(|c| c.polyline(64)).collect())
        .collect()
}

/// Crossing-number test over all polygons together (even-odd rule).
fn brute_inside(polys: &[Vec<Vec2>], p: Vec2) -> bool {
    let mut inside = false;
    for poly in polys {
        let n = poly.len();
        for i in 0..n {
            let (a, b) = (poly[i], poly[(i + 1) % n]);
            if (a.y > p.y) != (b.y > p.y) && p.x < (b.x - a.x) * (p.y - a.y) / (b.y - a.y) + a.x {
                inside = !inside;
            }
        }
    }
    inside
}

/// Distance from `p` to the polylines.
fn distance(polys: &[Vec<Vec2>], p: Vec2) -> f64 {
    let mut d = f64::INFINITY;
    for poly in polys {
        let n = poly.len();
        for i in 0..n {
            let (a, b) = (poly[i], poly[(i + 1) % n]);
            let ab = b - a;
            let t = if ab.norm_squared() > 0.0 {
                ((p - a).dot(&ab) / ab.norm_squared()).clamp(0.0, 1.0)
            } else {
                0.0
            };
            d = d.min((a + ab * t - p).norm());
        }
    }
    d
}

fn every_curve(b: &Boundary) -> Vec<(bool, TrimCurve)> {
    b.outer
        .curves
        .iter()
        .map(|c| (true, c.clone()))
        .chain(
            b.holes
                .iter()
                .flat_map(|h| h.curves.iter().map(|c| (false, c.clone()))),
        )
        .collect()
}

proptest! {
    // `tangent_and_vertex_rays_restart_and_agree` rejects about 1 case in 6
    // (points on the outer bottom edge), more than the default reject cap
    // allows at large PROPTEST_CASES.
    #![proptest_config(ProptestConfig { cases: 4000, max_global_rejects: 1 << 20, ..ProptestConfig::default() })]

    #[test]
    fn random_points_agree_with_brute_force(x in -0.05f64..1.1, y in -0.05f64..1.2) {
        let b = face();
        let polys = polygons(&b);
        let p = v(x, y);
        prop_assume!(distance(&polys, p) > 1e-6);
        let (c, _) = b.classify(p);
        prop_assert_eq!(c.is_in(), brute_inside(&polys, p), "{:?} -> {:?}", p, c);
        prop_assert!(c != Containment::Boundary);
    }

    #[test]
    fn points_on_the_curves_are_on_the_boundary(k in 0usize..7, t in 0.0f64..=1.0) {
        let b = face();
        let curves = every_curve(&b);
        let c = &curves[k].1;
        let [t0, t1] = c.domain();
        let p = c.eval(t0 + (t1 - t0) * t).p;
        prop_assert_eq!(b.classify(p).0, Containment::Boundary, "{:?}", p);
    }

    #[test]
    fn the_switch_is_exactly_at_the_curve(k in 0usize..7, t in 0.001f64..0.999) {
        // Across curve k at its parameter t: left (+1e-8) and right (-1e-8).
        let b = face();
        let curves = every_curve(&b);
        let (outer, c) = &curves[k];
        let [t0, t1] = c.domain();
        let d = c.eval(t0 + (t1 - t0) * t);
        let left = v(-d.d1.y, d.d1.x).normalize();
        // Left of the outer loop and right of a hole is inside the face.
        let inside_on_left = *outer;
        let pl = d.p + left * 1e-8;
        let pr = d.p - left * 1e-8;
        prop_assert_eq!(b.classify(pl).0 == Containment::Inside, inside_on_left, "left of {:?}", d.p);
        prop_assert_eq!(b.classify(pr).0 == Containment::Inside, !inside_on_left, "right of {:?}", d.p);
    }

    #[test]
    fn tangent_and_vertex_rays_restart_and_agree(x in 0.42f64..0.58, which in 0usize..5) {
        // The first ray goes to -u along the line v = y.
        let y = [0.5, 0.25, 0.6, 0.8, 0.05][which]; // tangent to hole 1 (top, bottom), along hole 2's edge, through hole 2's corner, along the outer bottom
        let b = face();
        let polys = polygons(&b);
        let x = if which >= 2 { x + 0.4 } else { x };
        let p = v(x, y);
        prop_assume!(distance(&polys, p) > 1e-6);
        let (c, rays) = b.classify(p);
        prop_assert!(rays > 1, "{:?}: the horizontal ray is degenerate and must restart", p);
        prop_assert_eq!(c.is_in(), brute_inside(&polys, p), "{:?}", p);
    }
}

#[test]
fn vertices_are_on_the_boundary_and_holes_are_outside() {
    let b = face();
    for p in [
        v(0.05, 0.05),
        v(0.95, 0.05),
        v(0.95, 0.95),
        v(0.05, 0.95),
        v(0.6, 0.6),
        v(0.8, 0.6),
        v(0.6, 0.8),
        v(0.425, 0.375),
    ] {
        assert_eq!(b.classify(p).0, Containment::Boundary, "{p:?}");
    }
    assert_eq!(b.classify(v(0.3, 0.375)).0, Containment::Outside);
    assert_eq!(b.classify(v(0.68, 0.68)).0, Containment::Outside);
    assert_eq!(b.classify(v(0.5, 0.2)).0, Containment::Inside);
    assert_eq!(b.classify(v(0.5, 1.1)).0, Containment::Inside);
    assert_eq!(b.classify(v(0.5, 1.2)).0, Containment::Outside);
}

/// Points on a curve near its ends, where the first ray (-u) meets hole 2's
/// rational bulge at a shallow angle (its end tangent is horizontal): the
/// bisected crossing is exact across the ray but off along it by
/// `eps / sine`, which once classified a point 1e-16 from the bulge as
/// Inside (proptest seed in the regressions file: curve 6, t = 0.99991).
#[test]
fn points_near_curve_ends_at_shallow_crossings_are_on_the_boundary() {
    let b = face();
    let curves = every_curve(&b);
    let mut wrong = Vec::new();
    for (k, (_, c)) in curves.iter().enumerate() {
        let [t0, t1] = c.domain();
        for i in 0..=2000 {
            let s = 1e-3 * i as f64 / 2000.0;
            for t in [s, 1.0 - s] {
                let p = c.eval(t0 + (t1 - t0) * t).p;
                let got = b.classify(p).0;
                if got != Containment::Boundary {
                    wrong.push((k, t, p, got));
                }
            }
        }
    }
    assert!(
        wrong.is_empty(),
        "{} points off the boundary, first {:?}",
        wrong.len(),
        &wrong[..wrong.len().min(5)]
    );
}
