//! The search benchmark of issue 5 (not a test): cost of the contact
//! search against the number of contact nodes, `n = 10^2 .. 10^5`.
//!
//! Scene (synthetic, no solve): a wavy master surface of `m = n` segments
//! over `[0, 10]`, `y = 0.3 sin(2x) + 0.05 cos(13x)`, and `n` slave points
//! spread along it at signed distances within `±h/2` (`h` the segment
//! length), window `prof = h`. Per size:
//!
//! 1. *cold*: [`SurfaceSearch::update`] (boxes + broad-phase rebuild) and a
//!    search of every point without memory;
//! 2. *moved*: the surface slides by `0.3 h` and its wave changes a little,
//!    the points move with it; rebuild and search with each point's
//!    memory (its segment at step 1), Metafor's test;
//! 3. *circle*: the moved configuration with Cast3M's circle test;
//! 4. *rigid tool*: the same surface as a rigid polyline tool searched by
//!    `contact::search` (per-node memory, box pruning, broad phase built
//!    once in the tool's frame);
//! 5. *brute force*: every point projected on every segment (`n m`
//!    projections), up to `n = 10^4` (`brute_max`): the reference the
//!    searches are checked against (mismatches are counted and must be 0).
//!
//! Times are the best of a few repetitions. The fitted exponent is the
//! least-squares slope of `log(time per evaluation)` against `log(n)`:
//! about 1 means `O(n)` per evaluation (`O(1)` per search), 2 is brute
//! force.

use ctc_engine::contact::geometry::ToolShape;
use ctc_engine::contact::search::{self, ToolGrid};
use ctc_engine::contact::segment_search::SurfaceSearch;
use ctc_engine::model::{LocalSearch, ToolGeometry};
use std::fmt;
use std::time::Instant;

/// Benchmark settings.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct SearchBenchOptions {
    /// Numbers of contact nodes (each with a surface of as many segments).
    pub sizes: Vec<usize>,
    /// Largest `n` for which brute force is run.
    pub brute_max: usize,
}

impl Default for SearchBenchOptions {
    fn default() -> Self {
        SearchBenchOptions {
            sizes: vec![100, 1_000, 10_000, 100_000],
            brute_max: 10_000,
        }
    }
}

/// One search variant at one size.
#[derive(Debug, Clone, Copy, Default, PartialEq, serde::Serialize)]
pub struct Phase {
    /// Projection tests in the whole evaluation.
    pub projection_tests: u64,
    /// Projection tests per contact node.
    pub tests_per_node: f64,
    /// Broad-phase (re)build time, seconds (0 when nothing is rebuilt).
    pub build_time: f64,
    /// Mean time of one node's search, seconds.
    pub time_per_search: f64,
    /// Whole evaluation (build + all searches), seconds.
    pub total_time: f64,
    /// Results different from brute force (when it was run); must be 0.
    pub mismatches: usize,
    /// Points that found a segment.
    pub found: usize,
}

/// Measurements at one size.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct SizeResult {
    /// Contact (slave) nodes.
    pub nodes: usize,
    /// Master segments.
    pub segments: usize,
    /// Cold search (no memory, memory test).
    pub cold: Phase,
    /// Moved configuration searched with memory (Metafor).
    pub memory: Phase,
    /// Moved configuration, Cast3M circle test.
    pub circle: Phase,
    /// Moved configuration against the rigid polyline tool search.
    pub rigid: Phase,
    /// Brute force on the moved configuration, if run.
    pub brute: Option<Phase>,
}

/// The whole benchmark.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct SearchBenchReport {
    /// One entry per size.
    pub sizes: Vec<SizeResult>,
    /// Fitted exponent of the total time per evaluation against `n`:
    /// cold, memory, circle, rigid, brute force.
    pub exponents: Exponents,
}

/// Least-squares slopes of `log(total time)` against `log(n)`.
#[derive(Debug, Clone, Copy, Default, PartialEq, serde::Serialize)]
pub struct Exponents {
    /// Cold search.
    pub cold: f64,
    /// Memory search.
    pub memory: f64,
    /// Circle test.
    pub circle: f64,
    /// Rigid tool search.
    pub rigid: f64,
    /// Brute force (over the sizes where it ran).
    pub brute: f64,
}

/// Surface height at abscissa `x` for a deformation parameter `s`.
fn height(x: f64, s: f64) -> f64 {
    0.3 * (2.0 * x + s).sin() + 0.05 * (13.0 * x).cos() * (1.0 + s)
}

/// Surface nodes for `m` segments, slid by `shift` along x.
fn surface(m: usize, shift: f64, s: f64) -> Vec<[f64; 2]> {
    (0..=m)
        .map(|i| {
            let x = 10.0 * i as f64 / m as f64 + shift;
            [x, height(x, s)]
        })
        .collect()
}

/// `n` slave points near the surface of `m` segments: abscissa and signed
/// offset from a deterministic low-discrepancy sequence.
fn points(n: usize, h: f64, shift: f64, s: f64) -> Vec<[f64; 2]> {
    (0..n)
        .map(|k| {
            let u = (k as f64 + 0.5) / n as f64;
            let v = (k as f64 * 0.618_033_988_749_894_9).fract() - 0.5;
            let x = 10.0 * u + shift;
            // offset along y: within ±h/2 of the surface height
            [x, height(x, s) + v * h]
        })
        .collect()
}

/// Best wall time of `f` over at least `reps` runs, continued until the
/// runs add up to [`BUDGET`] seconds (at most 1000 runs): the minimum is the
/// run least disturbed by other processes. Returns it and the last result.
fn timed<T>(reps: usize, mut f: impl FnMut() -> T) -> (f64, T) {
    let mut best = f64::INFINITY;
    let mut total = 0.0;
    let mut runs = 0;
    let mut last = None;
    while runs < reps.max(1) || (total < BUDGET && runs < 1000) {
        let t = Instant::now();
        let r = f();
        let dt = t.elapsed().as_secs_f64();
        best = best.min(dt);
        total += dt;
        runs += 1;
        last = Some(r);
    }
    (best, last.expect("at least one run"))
}

/// Time spent repeating one measurement, seconds.
const BUDGET: f64 = 0.25;

/// Minimum repetitions for size `n`.
fn reps(n: usize) -> usize {
    (20_000 / n.max(1)).clamp(3, 200)
}

/// Searches every point on a surface search; returns the segment found per
/// point and the phase figures (build excluded).
fn search_all(
    s: &SurfaceSearch,
    pts: &[[f64; 2]],
    memory: Option<&[Option<usize>]>,
    scratch: &mut Vec<usize>,
) -> Vec<Option<usize>> {
    pts.iter()
        .enumerate()
        .map(|(k, &p)| {
            let mem = memory.and_then(|m| m[k]);
            s.nearest(p, mem, &[], scratch).map(|h| h.segment)
        })
        .collect()
}

/// Phase figures from counters and times.
fn phase(tests: u64, n: usize, build: f64, search: f64, found: &[Option<usize>]) -> Phase {
    Phase {
        projection_tests: tests,
        tests_per_node: tests as f64 / n as f64,
        build_time: build,
        time_per_search: search / n as f64,
        total_time: build + search,
        mismatches: 0,
        found: found.iter().filter(|f| f.is_some()).count(),
    }
}

/// Runs one size.
fn run_size(n: usize, brute_max: usize) -> SizeResult {
    let m = n;
    let edges: Vec<[usize; 2]> = (0..m).map(|i| [i + 1, i]).collect();
    let h = 10.0 / m as f64;
    let prof = h;
    let reps = reps(n);
    let mut scratch = Vec::with_capacity(64);

    // 1. cold
    let x0 = surface(m, 0.0, 0.0);
    let p0 = points(n, h, 0.0, 0.0);
    let mut s = SurfaceSearch::new(&edges, LocalSearch::Memory);
    s.update(&x0, prof);
    let (build, ()) = timed(reps, || s.update(&x0, prof));
    s.reset_counters();
    let (time, first) = timed(reps, || {
        s.reset_counters();
        search_all(&s, &p0, None, &mut scratch)
    });
    let cold = phase(s.counters().projections, n, build, time, &first);

    // 2. moved, with memory
    let shift = 0.3 * h;
    let x1 = surface(m, shift, 0.01);
    let p1 = points(n, h, shift, 0.01);
    let (build, ()) = timed(reps, || s.update(&x1, prof));
    let (time, moved) = timed(reps, || {
        s.reset_counters();
        search_all(&s, &p1, Some(&first), &mut scratch)
    });
    let mut memory = phase(s.counters().projections, n, build, time, &moved);

    // 3. circle test
    let mut c = SurfaceSearch::new(&edges, LocalSearch::Circle);
    c.update(&x1, prof);
    let (build, ()) = timed(reps, || c.update(&x1, prof));
    let (time, circled) = timed(reps, || {
        c.reset_counters();
        search_all(&c, &p1, Some(&first), &mut scratch)
    });
    let mut circle = phase(c.counters().projections, n, build, time, &circled);

    // 4. rigid polyline tool (reference frame = current frame here)
    let shape = ToolShape::new(&ToolGeometry::Polyline { points: x1.clone() })
        .expect("the benchmark surface is a valid polyline");
    let (build, grid) = timed(reps.min(20), || ToolGrid::new(&shape));
    let rigid_memory: Vec<Option<usize>> = first.clone();
    let (time, (rigid_found, rigid_tests)) = timed(reps, || {
        let mut tests = 0;
        let mut guess = None;
        let found: Vec<Option<usize>> = p1
            .iter()
            .enumerate()
            .map(|(k, &p)| {
                let f = search::closest_in(
                    &shape,
                    &grid,
                    search::Request {
                        x: p,
                        window: prof,
                        memory: rigid_memory[k],
                        guess,
                        test: LocalSearch::Memory,
                    },
                    &mut scratch,
                    &mut tests,
                )
                .map(|f| f.entity);
                guess = f;
                f
            })
            .collect();
        (found, tests)
    });
    // the tool grid is built once per run (rigid): not part of an evaluation
    let mut rigid = phase(rigid_tests as u64, n, 0.0, time, &rigid_found);
    rigid.build_time = build;

    // 5. brute force
    let brute = (n <= brute_max).then(|| {
        let (time, found) = timed(1, || {
            p1.iter()
                .map(|&p| s.nearest_brute_force(p, &[]).map(|h| h.segment))
                .collect::<Vec<_>>()
        });
        // a brute-force hit beyond the window may be missed, nothing else
        memory.mismatches = moved
            .iter()
            .zip(&found)
            .zip(&p1)
            .filter(|((g, b), p)| {
                let within = b
                    .and_then(|e| s.project(e, **p))
                    .is_some_and(|h| h.distance <= prof);
                g != b && (within || g.is_some())
            })
            .count();
        rigid.mismatches = rigid_found
            .iter()
            .zip(&moved)
            .filter(|(a, b)| a != b)
            .count();
        // circle: compare with brute force over the segments its test keeps
        circle.mismatches = p1
            .iter()
            .zip(&circled)
            .filter(|(p, got)| {
                let best = (0..m)
                    .filter(|&e| c.in_circle(e, **p, prof))
                    .filter_map(|e| c.project(e, **p))
                    .filter(|h| {
                        let b = ctc_engine::geom::Aabb::around(&[x1[h.segment + 1], x1[h.segment]]);
                        b.contains_within(**p, prof)
                    })
                    .min_by(|a, b| {
                        a.distance
                            .total_cmp(&b.distance)
                            .then(a.segment.cmp(&b.segment))
                    })
                    .map(|h| h.segment);
                best != **got
            })
            .count();
        phase((n * m) as u64, n, 0.0, time, &found)
    });
    SizeResult {
        nodes: n,
        segments: m,
        cold,
        memory,
        circle,
        rigid,
        brute,
    }
}

/// Least-squares slope of `log y` against `log x`.
fn slope(points: &[(f64, f64)]) -> f64 {
    let pts: Vec<(f64, f64)> = points
        .iter()
        .filter(|(x, y)| *x > 0.0 && *y > 0.0)
        .map(|(x, y)| (x.ln(), y.ln()))
        .collect();
    if pts.len() < 2 {
        return f64::NAN;
    }
    let k = pts.len() as f64;
    let (mx, my) = (
        pts.iter().map(|p| p.0).sum::<f64>() / k,
        pts.iter().map(|p| p.1).sum::<f64>() / k,
    );
    let sxy: f64 = pts.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    let sxx: f64 = pts.iter().map(|p| (p.0 - mx) * (p.0 - mx)).sum();
    sxy / sxx
}

/// Runs the benchmark.
pub fn run_search_bench(opts: &SearchBenchOptions) -> SearchBenchReport {
    let sizes: Vec<SizeResult> = opts
        .sizes
        .iter()
        .map(|&n| run_size(n.max(2), opts.brute_max))
        .collect();
    let fit = |f: &dyn Fn(&SizeResult) -> Option<f64>| {
        slope(
            &sizes
                .iter()
                .filter_map(|s| f(s).map(|t| (s.nodes as f64, t)))
                .collect::<Vec<_>>(),
        )
    };
    let exponents = Exponents {
        cold: fit(&|s| Some(s.cold.total_time)),
        memory: fit(&|s| Some(s.memory.total_time)),
        circle: fit(&|s| Some(s.circle.total_time)),
        rigid: fit(&|s| Some(s.rigid.total_time)),
        brute: fit(&|s| s.brute.map(|b| b.total_time)),
    };
    SearchBenchReport { sizes, exponents }
}

impl fmt::Display for SearchBenchReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(
            f,
            "contact search: n slave nodes against a wavy surface of n segments, prof = h"
        )?;
        writeln!(
            f,
            "{:>7} | {:>9} {:>9} {:>9} | {:>9} {:>9} {:>9} | {:>9} {:>9} | {:>9} {:>9} | {:>11} {:>9}",
            "n",
            "build ms",
            "cold t/n",
            "cold us",
            "build ms",
            "mem t/n",
            "mem us",
            "circ t/n",
            "circ us",
            "tool t/n",
            "tool us",
            "brute us",
            "mismatch"
        )?;
        for s in &self.sizes {
            let brute = s
                .brute
                .map(|b| format!("{:>11.3}", b.time_per_search * 1e6))
                .unwrap_or_else(|| format!("{:>11}", "-"));
            let mism = s.memory.mismatches + s.circle.mismatches + s.rigid.mismatches;
            writeln!(
                f,
                "{:>7} | {:>9.3} {:>9.2} {:>9.3} | {:>9.3} {:>9.2} {:>9.3} | {:>9.2} {:>9.3} | {:>9.2} {:>9.3} | {brute} {:>9}",
                s.nodes,
                s.cold.build_time * 1e3,
                s.cold.tests_per_node,
                s.cold.time_per_search * 1e6,
                s.memory.build_time * 1e3,
                s.memory.tests_per_node,
                s.memory.time_per_search * 1e6,
                s.circle.tests_per_node,
                s.circle.time_per_search * 1e6,
                s.rigid.tests_per_node,
                s.rigid.time_per_search * 1e6,
                if s.brute.is_some() { mism.to_string() } else { "-".into() },
            )?;
        }
        let e = self.exponents;
        writeln!(
            f,
            "fitted exponent of time per evaluation vs n: cold {:.2}, memory {:.2}, circle {:.2}, \
             rigid tool {:.2}, brute force {:.2} (1 = O(n), 2 = O(n^2))",
            e.cold, e.memory, e.circle, e.rigid, e.brute
        )?;
        writeln!(
            f,
            "t/n = projection tests per node; us = microseconds per node search; build = boxes + \
             broad-phase rebuild per evaluation"
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn small_search_bench_agrees_with_brute_force() {
        let r = run_search_bench(&SearchBenchOptions {
            sizes: vec![50, 200],
            brute_max: 200,
        });
        for s in &r.sizes {
            let b = s.brute.expect("brute force ran");
            assert_eq!(b.projection_tests, (s.nodes * s.segments) as u64);
            assert_eq!(s.memory.mismatches, 0);
            assert_eq!(s.circle.mismatches, 0);
            assert_eq!(s.rigid.mismatches, 0);
            assert_eq!(s.memory.found, s.nodes, "every point is within prof");
            // memory: about the memory segment, its 2 neighbours and a few
            // broad-phase hits
            assert!(s.memory.tests_per_node < 8.0, "{:?}", s.memory);
            assert!(s.cold.tests_per_node < 6.0, "{:?}", s.cold);
        }
        assert!((slope(&[(1.0, 2.0), (10.0, 200.0)]) - 2.0).abs() < 1e-12);
        let text = r.to_string();
        assert!(text.contains("fitted exponent"), "{text}");
    }
}
