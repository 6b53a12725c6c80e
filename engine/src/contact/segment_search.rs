//! Search of the master segments of a deformable surface for slave points
//! (node-to-segment contact; seed slides "Part I - Geometrical aspects").
//!
//! The master surface is a list of segments `[a, b]` (global node numbers,
//! body on the left of `a -> b`). At every evaluation the caller gives the
//! current coordinates ([`SurfaceSearch::update`]): the segment boxes are
//! recomputed and the broad phase ([`BroadPhase`], a hashed bucket grid) is
//! rebuilt in `O(m)` without allocating. A slave point then asks for its
//! candidate segments ([`SurfaceSearch::candidates`]), in the order they
//! should be projected, with one of the seed's two local tests:
//!
//! - [`LocalSearch::Memory`] (Metafor): the segment the point touched last
//!   first, then its neighbours along the surface (segments sharing a
//!   node), both unconditionally, so a point that went deeper than `prof`
//!   during an increment is still found; then the other segments whose box
//!   inflated by `prof` contains the point (broad phase).
//! - [`LocalSearch::Circle`] (Cast3M): the segments from the broad phase
//!   whose circle contains the point. The circle is centred on the
//!   segment's midpoint with radius `sqrt((L/2)^2 + prof^2)`: the circle
//!   through the corners of the rectangle `segment x [-prof, prof]`, so it
//!   keeps every point whose foot lies inside the segment with `|gap| <=
//!   prof`, and drops most points whose closest point would be an end of
//!   the segment (those are the neighbour's). The price, seed "projection
//!   problems": a point in the fan of a kink (foot at the vertex for both
//!   segments) can be outside both circles. No memory either: a point
//!   deeper than `prof` is lost. The memory segment, if it passes the
//!   test, is still listed first.
//!
//! Cost: a query is `O(1)` (a few grid cells) plus its candidates, so `n`
//! slave points against `m` segments cost `O(m + n)` per evaluation
//! instead of `O(n m)` (measured by `ctc bench --search`).
//!
//! [`SurfaceSearch::nearest`] completes the search with the closest-point
//! projection on the candidates and returns the exact closest segment
//! (tested against [`SurfaceSearch::nearest_brute_force`]).

use super::broad::BroadPhase;
use super::vec2::{dot, sub};
use crate::geom::Aabb;
use crate::model::LocalSearch;
use std::cell::Cell;

/// Work done by the searches since the last [`SurfaceSearch::reset_counters`].
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, serde::Serialize)]
pub struct SearchCounters {
    /// Calls to [`SurfaceSearch::candidates`] (one per slave point).
    pub queries: u64,
    /// Candidate segments returned (each is one projection test when the
    /// caller projects every candidate).
    pub candidates: u64,
    /// Closest-point projections computed by [`SurfaceSearch::nearest`].
    pub projections: u64,
    /// Projections a brute-force search would have made (queries x
    /// segments).
    pub brute_force: u64,
}

/// Closest point of a master segment to a slave point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SegmentHit {
    /// Segment index (into the `edges` given to [`SurfaceSearch::new`]).
    pub segment: usize,
    /// Parameter of the closest point, in `[0, 1]` (0 at the first node).
    pub xi: f64,
    /// Closest point.
    pub point: [f64; 2],
    /// Distance from the slave point to the closest point (>= 0).
    pub distance: f64,
    /// Signed gap: `distance`, negative when the slave point is on the
    /// body's side of the segment's line (left of `a -> b`).
    pub gap: f64,
}

/// Search structure over the master segments of one surface.
#[derive(Debug, Clone)]
pub struct SurfaceSearch {
    /// Master segments `[a, b]` (global node numbers).
    edges: Vec<[usize; 2]>,
    /// Local test.
    test: LocalSearch,
    /// Neighbours of each segment (segments sharing a node), CSR offsets.
    neighbour_start: Vec<usize>,
    /// Neighbour lists: those sharing the first node, then the second,
    /// ascending within each, no duplicates.
    neighbours: Vec<usize>,
    /// `(node, segment)` pairs sorted by node: the segments of a node.
    node_segments: Vec<(usize, usize)>,
    /// Segment boxes at the current coordinates.
    boxes: Vec<Aabb<2>>,
    /// Segment midpoints and half lengths (circle test).
    circles: Vec<([f64; 2], f64)>,
    /// Current segment end coordinates.
    ends: Vec<[[f64; 2]; 2]>,
    /// Broad phase over `boxes`.
    grid: BroadPhase,
    /// Search window (largest gap of interest), >= 0.
    prof: f64,
    /// Work counters.
    counters: Cell<SearchCounters>,
}

impl SurfaceSearch {
    /// Prepares the search over `edges` with local test `test`. Call
    /// [`SurfaceSearch::update`] before the first query.
    pub fn new(edges: &[[usize; 2]], test: LocalSearch) -> Self {
        let m = edges.len();
        let mut node_segments: Vec<(usize, usize)> = edges
            .iter()
            .enumerate()
            .flat_map(|(e, &[a, b])| [(a, e), (b, e)])
            .collect();
        node_segments.sort_unstable();
        node_segments.dedup();
        let mut neighbour_start = Vec::with_capacity(m + 1);
        let mut neighbours = Vec::with_capacity(2 * m);
        neighbour_start.push(0);
        for (e, &[a, b]) in edges.iter().enumerate() {
            let first = neighbours.len();
            for node in [a, b] {
                for &(_, f) in segments_of(&node_segments, node) {
                    if f != e && !neighbours[first..].contains(&f) {
                        neighbours.push(f);
                    }
                }
            }
            neighbour_start.push(neighbours.len());
        }
        let empty = Aabb {
            min: [f64::INFINITY; 2],
            max: [f64::NEG_INFINITY; 2],
        };
        SurfaceSearch {
            edges: edges.to_vec(),
            test,
            neighbour_start,
            neighbours,
            node_segments,
            boxes: vec![empty; m],
            circles: vec![([f64::NAN; 2], 0.0); m],
            ends: vec![[[f64::NAN; 2]; 2]; m],
            grid: BroadPhase::default(),
            prof: 0.0,
            counters: Cell::new(SearchCounters::default()),
        }
    }

    /// Recomputes the segments at coordinates `x` (all nodes, indexed by
    /// global node number) and rebuilds the broad phase for the window
    /// `prof`. Allocates only on the first call (and if the grid grows).
    /// A segment with a node outside `x` or a non-finite coordinate gets an
    /// empty box and is never a candidate.
    pub fn update(&mut self, x: &[[f64; 2]], prof: f64) {
        self.prof = if prof.is_finite() { prof.max(0.0) } else { 0.0 };
        for (e, &[a, b]) in self.edges.iter().enumerate() {
            let ends = match (x.get(a), x.get(b)) {
                (Some(&pa), Some(&pb)) if finite(pa) && finite(pb) => Some([pa, pb]),
                _ => None,
            };
            match ends {
                Some([pa, pb]) => {
                    self.ends[e] = [pa, pb];
                    self.boxes[e] = Aabb::around(&[pa, pb]);
                    let mid = [0.5 * (pa[0] + pb[0]), 0.5 * (pa[1] + pb[1])];
                    let d = sub(pb, pa);
                    self.circles[e] = (mid, 0.5 * dot(d, d).sqrt());
                }
                None => {
                    self.ends[e] = [[f64::NAN; 2]; 2];
                    self.boxes[e] = Aabb {
                        min: [f64::INFINITY; 2],
                        max: [f64::NEG_INFINITY; 2],
                    };
                    self.circles[e] = ([f64::NAN; 2], 0.0);
                }
            }
        }
        self.grid.rebuild(&self.boxes, self.prof);
    }

    /// Candidate segments for a slave point at `point`, in test order,
    /// written to `out` (cleared first): see the module documentation for
    /// the two local tests. `memory` is the segment the point touched last
    /// (ignored if out of range); segments in `exclude` are never returned
    /// (self contact: the segments of the slave node itself, see
    /// [`SurfaceSearch::segments_of_node`]).
    pub fn candidates(
        &self,
        point: [f64; 2],
        memory: Option<usize>,
        exclude: &[usize],
        out: &mut Vec<usize>,
    ) {
        self.candidates_within(point, self.prof, memory, exclude, out);
    }

    /// Like [`SurfaceSearch::candidates`] with the window `radius` instead
    /// of `prof` (a wider rescan after a deep memory hit).
    pub fn candidates_within(
        &self,
        point: [f64; 2],
        radius: f64,
        memory: Option<usize>,
        exclude: &[usize],
        out: &mut Vec<usize>,
    ) {
        out.clear();
        let m = self.edges.len();
        let memory = memory.filter(|&e| e < m);
        let first = match self.test {
            LocalSearch::Memory => {
                if let Some(e) = memory {
                    if !exclude.contains(&e) {
                        out.push(e);
                    }
                    for &f in self.neighbours(e) {
                        if !exclude.contains(&f) {
                            out.push(f);
                        }
                    }
                }
                out.len()
            }
            LocalSearch::Circle => 0,
        };
        self.grid.query_append(point, radius, out);
        // keep the broad-phase hits that pass the local test and are not
        // already listed or excluded
        let mut kept = first;
        for k in first..out.len() {
            let e = out[k];
            let pass = !exclude.contains(&e)
                && !out[..first].contains(&e)
                && match self.test {
                    LocalSearch::Memory => true,
                    LocalSearch::Circle => self.in_circle(e, point, radius),
                };
            if pass {
                out[kept] = e;
                kept += 1;
            }
        }
        out.truncate(kept);
        if self.test == LocalSearch::Circle {
            if let Some(k) = memory.and_then(|e| out.iter().position(|&f| f == e)) {
                out[..=k].rotate_right(1);
            }
        }
        let mut c = self.counters.get();
        c.queries += 1;
        c.candidates += out.len() as u64;
        c.brute_force += m as u64;
        self.counters.set(c);
    }

    /// Cast3M circle test: whether `point` lies in the circle centred on
    /// segment `e`'s midpoint with radius `sqrt((L/2)^2 + window^2)`.
    pub fn in_circle(&self, e: usize, point: [f64; 2], window: f64) -> bool {
        let Some(&(c, h)) = self.circles.get(e) else {
            return false;
        };
        let d = sub(point, c);
        dot(d, d) <= h * h + window * window
    }

    /// The exact closest segment to `point` (smallest distance, ties: lowest
    /// index) among the candidates of the local test, excluded segments left
    /// out (memory test: among all segments within the window).
    /// Projects the candidates of [`SurfaceSearch::candidates`]; memory test:
    /// when the best one is farther than `prof` (a deep point found through
    /// its memory), the window is widened to that distance and searched
    /// again, so the result is the closest of the whole surface. `None` when no
    /// segment is within `prof` and the memory gave nothing. `scratch` holds
    /// the candidate list (reused, no allocation once grown).
    pub fn nearest(
        &self,
        point: [f64; 2],
        memory: Option<usize>,
        exclude: &[usize],
        scratch: &mut Vec<usize>,
    ) -> Option<SegmentHit> {
        self.candidates(point, memory, exclude, scratch);
        let mut best = self.closest_of(point, scratch);
        if let Some(b) = best {
            if self.test == LocalSearch::Memory && b.distance > self.prof {
                let r = b.distance * (1.0 + 1e-12);
                self.candidates_within(point, r, None, exclude, scratch);
                // the widened window holds the first best: keep it if tied
                if let Some(w) = self.closest_of(point, scratch) {
                    if better(&w, &b) {
                        best = Some(w);
                    }
                }
            }
        }
        best
    }

    /// Closest segment among `list`, counting the projections.
    fn closest_of(&self, point: [f64; 2], list: &[usize]) -> Option<SegmentHit> {
        let mut best: Option<SegmentHit> = None;
        let mut tests = 0;
        for &e in list {
            // a box farther than the best distance cannot hold a closer point
            if best
                .as_ref()
                .is_some_and(|b| self.boxes[e].distance(point) > b.distance)
            {
                continue;
            }
            tests += 1;
            if let Some(h) = self.project(e, point) {
                if best.as_ref().is_none_or(|b| better(&h, b)) {
                    best = Some(h);
                }
            }
        }
        let mut c = self.counters.get();
        c.projections += tests;
        self.counters.set(c);
        best
    }

    /// Reference search: projects `point` on every segment not excluded.
    pub fn nearest_brute_force(&self, point: [f64; 2], exclude: &[usize]) -> Option<SegmentHit> {
        let mut best: Option<SegmentHit> = None;
        for e in 0..self.edges.len() {
            if exclude.contains(&e) {
                continue;
            }
            if let Some(h) = self.project(e, point) {
                if best.as_ref().is_none_or(|b| better(&h, b)) {
                    best = Some(h);
                }
            }
        }
        best
    }

    /// Closest point of segment `e` (current coordinates) to `point`;
    /// `None` for a segment with invalid coordinates or zero length.
    pub fn project(&self, e: usize, point: [f64; 2]) -> Option<SegmentHit> {
        let [a, b] = *self.ends.get(e)?;
        let d = sub(b, a);
        let l2 = dot(d, d);
        if !(l2 > 0.0 && l2.is_finite() && finite(point)) {
            return None;
        }
        let xi = (dot(sub(point, a), d) / l2).clamp(0.0, 1.0);
        let foot = [a[0] + xi * d[0], a[1] + xi * d[1]];
        let r = sub(point, foot);
        let distance = dot(r, r).sqrt();
        // outward normal (dy, -dx): the body is on the left of a -> b
        let side = r[0] * d[1] - r[1] * d[0];
        Some(SegmentHit {
            segment: e,
            xi,
            point: foot,
            distance,
            gap: if side < 0.0 { -distance } else { distance },
        })
    }

    /// Segments sharing a node with segment `e` (those at its first node,
    /// then at its second).
    pub fn neighbours(&self, e: usize) -> &[usize] {
        match (self.neighbour_start.get(e), self.neighbour_start.get(e + 1)) {
            (Some(&s), Some(&t)) => &self.neighbours[s..t],
            _ => &[],
        }
    }

    /// The segments having `node` as an end, ascending (self contact: the
    /// segments a slave node must not be tested against).
    pub fn segments_of_node(&self, node: usize) -> impl Iterator<Item = usize> + '_ {
        segments_of(&self.node_segments, node).iter().map(|p| p.1)
    }

    /// Number of segments.
    pub fn len(&self) -> usize {
        self.edges.len()
    }

    /// True if the surface has no segment.
    pub fn is_empty(&self) -> bool {
        self.edges.is_empty()
    }

    /// The segments `[a, b]`.
    pub fn edges(&self) -> &[[usize; 2]] {
        &self.edges
    }

    /// The local test in use.
    pub fn test(&self) -> LocalSearch {
        self.test
    }

    /// The window given to the last [`SurfaceSearch::update`].
    pub fn prof(&self) -> f64 {
        self.prof
    }

    /// Work done since the last reset.
    pub fn counters(&self) -> SearchCounters {
        self.counters.get()
    }

    /// Sets the work counters to zero.
    pub fn reset_counters(&self) {
        self.counters.set(SearchCounters::default());
    }
}

/// The `(node, segment)` pairs of `node` in a list sorted by node.
fn segments_of(pairs: &[(usize, usize)], node: usize) -> &[(usize, usize)] {
    let lo = pairs.partition_point(|p| p.0 < node);
    let hi = pairs.partition_point(|p| p.0 <= node);
    &pairs[lo..hi]
}

/// Cast3M circle test for a segment `a -> b`: whether `point` lies in the
/// circle centred on the midpoint with radius `sqrt((L/2)^2 + window^2)`
/// (every point whose foot is inside the segment with `|gap| <= window`
/// passes). Same test as [`SurfaceSearch::in_circle`].
pub fn in_segment_circle(a: [f64; 2], b: [f64; 2], point: [f64; 2], window: f64) -> bool {
    let mid = [0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])];
    let (d, l) = (sub(point, mid), sub(b, a));
    dot(d, d) <= 0.25 * dot(l, l) + window * window
}

/// Whether `a` beats `b`: smaller distance, then lower segment index.
fn better(a: &SegmentHit, b: &SegmentHit) -> bool {
    a.distance < b.distance || (a.distance == b.distance && a.segment < b.segment)
}

/// Whether both coordinates are finite.
fn finite(p: [f64; 2]) -> bool {
    p[0].is_finite() && p[1].is_finite()
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// A wavy open surface of `m` segments over [0, 1], nodes 0..=m, the
    /// body below (walk from right to left so the body is on the left).
    fn wavy(m: usize, phase: f64) -> (Vec<[usize; 2]>, Vec<[f64; 2]>) {
        let x: Vec<[f64; 2]> = (0..=m)
            .map(|i| {
                let s = i as f64 / m as f64;
                [s, 0.05 * (9.0 * s + phase).sin()]
            })
            .collect();
        let edges = (0..m).map(|i| [i + 1, i]).collect();
        (edges, x)
    }

    #[test]
    fn neighbours_follow_shared_nodes() {
        let (edges, _) = wavy(4, 0.0);
        let s = SurfaceSearch::new(&edges, LocalSearch::Memory);
        // edge e = [e+1, e]: first node shared with e+1, second with e-1
        assert_eq!(s.neighbours(0), &[1]);
        assert_eq!(s.neighbours(2), &[3, 1]);
        assert_eq!(s.neighbours(3), &[2]);
        assert_eq!(s.segments_of_node(2).collect::<Vec<_>>(), vec![1, 2]);
        assert!(s.neighbours(9).is_empty());
    }

    #[test]
    fn memory_first_then_neighbours_then_broad_phase() {
        let (edges, x) = wavy(100, 0.0);
        let mut s = SurfaceSearch::new(&edges, LocalSearch::Memory);
        s.update(&x, 0.02);
        let mut out = Vec::new();
        // far from segment 90 but with memory 90: 90, 91, 89 come first
        let p = [0.505, 0.05 * (9.0f64 * 0.505).sin() + 0.001];
        s.candidates(p, Some(90), &[], &mut out);
        assert_eq!(&out[..3], &[90, 91, 89]);
        let rest = out[3..].to_vec();
        assert!(rest.contains(&50) && rest.windows(2).all(|w| w[0] < w[1]));
        assert!(rest.len() < 10, "{rest:?}");
        // without memory: only the broad-phase hits, ascending
        s.candidates(p, None, &[], &mut out);
        assert_eq!(out, rest);
        // exclusion
        s.candidates(p, Some(90), &[91, 50], &mut out);
        assert_eq!(&out[..2], &[90, 89]);
        assert!(!out.contains(&50));
        let c = s.counters();
        assert_eq!((c.queries, c.brute_force), (3, 300));
    }

    #[test]
    fn circle_test_drops_segments_projecting_on_their_end() {
        let x = vec![[0.0, 0.0], [1.0, 0.0], [2.0, 0.5]];
        let edges = vec![[0, 1], [1, 2]];
        let mut circle = SurfaceSearch::new(&edges, LocalSearch::Circle);
        let mut memory = SurfaceSearch::new(&edges, LocalSearch::Memory);
        circle.update(&x, 0.01);
        memory.update(&x, 0.01);
        let mut out = Vec::new();
        // past the end of segment 0, inside segment 1: both boxes hold it,
        // only the circle of segment 1 does
        memory.candidates([1.005, 0.005], None, &[], &mut out);
        assert_eq!(out, vec![0, 1]);
        circle.candidates([1.005, 0.005], None, &[], &mut out);
        assert_eq!(out, vec![1]);
        // above the shared node both circles hold it; memory 1 goes first
        circle.candidates([1.0, 0.001], Some(1), &[], &mut out);
        assert_eq!(out, vec![1, 0]);
        // a memoryless test loses a point deeper than prof
        circle.candidates([1.2, -0.3], Some(0), &[], &mut out);
        assert!(out.is_empty());
        memory.candidates([1.2, -0.3], Some(0), &[], &mut out);
        assert_eq!(out, vec![0, 1]);
    }

    #[test]
    fn deep_point_found_through_memory_is_exact() {
        let (edges, x) = wavy(50, 0.3);
        let mut s = SurfaceSearch::new(&edges, LocalSearch::Memory);
        s.update(&x, 0.001);
        let mut scratch = Vec::new();
        let p = [0.41, -0.2];
        // nothing within prof without memory
        assert!(s.nearest(p, None, &[], &mut scratch).is_none());
        // memory on a far segment: the widened rescan finds the true closest
        let hit = s.nearest(p, Some(3), &[], &mut scratch).unwrap();
        assert_eq!(Some(hit), s.nearest_brute_force(p, &[]));
        assert!(hit.gap < 0.0, "below the surface = inside the body");
    }

    #[test]
    fn update_does_not_allocate_after_the_first_call() {
        let (edges, x) = wavy(400, 0.0);
        let mut s = SurfaceSearch::new(&edges, LocalSearch::Memory);
        s.update(&x, 0.01);
        let ptrs = (s.boxes.as_ptr(), s.ends.as_ptr(), s.circles.as_ptr());
        let (_, moved) = wavy(400, 0.05);
        s.update(&moved, 0.01);
        assert_eq!(
            (s.boxes.as_ptr(), s.ends.as_ptr(), s.circles.as_ptr()),
            ptrs
        );
    }

    #[test]
    fn invalid_coordinates_give_no_candidate() {
        let edges = vec![[0, 1], [1, 5]];
        let mut s = SurfaceSearch::new(&edges, LocalSearch::Memory);
        s.update(&[[0.0, 0.0], [1.0, 0.0]], 0.1);
        let mut out = Vec::new();
        s.candidates([1.5, 0.0], None, &[], &mut out);
        assert!(out.is_empty());
        assert!(s.project(1, [1.5, 0.0]).is_none());
        s.candidates([f64::NAN, 0.0], None, &[], &mut out);
        assert!(out.is_empty());
    }

    proptest! {
        #[test]
        fn nearest_matches_brute_force(
            m in 1usize..60,
            phase in 0.0f64..6.0,
            prof in 0.0f64..0.2,
            circle in any::<bool>(),
            points in proptest::collection::vec((-0.2f64..1.2, -0.3f64..0.3, 0usize..80), 1..30),
        ) {
            let (edges, x) = wavy(m, phase);
            let test = if circle { LocalSearch::Circle } else { LocalSearch::Memory };
            let mut s = SurfaceSearch::new(&edges, test);
            s.update(&x, prof);
            let mut scratch = Vec::new();
            for &(px, py, mem) in &points {
                let p = [px, py];
                let memory = Some(mem); // may be out of range
                // the circle test only ever sees the segments passing it
                let outside: Vec<usize> = (0..m)
                    .filter(|&e| circle && !(s.in_circle(e, p, prof) && s.boxes[e].contains_within(p, prof)))
                    .collect();
                let brute = s.nearest_brute_force(p, &outside);
                let found = s.nearest(p, memory, &[], &mut scratch);
                match (brute, found) {
                    (Some(b), Some(f)) => prop_assert_eq!(b, f),
                    (Some(b), None) => {
                        // missed only if the closest is beyond the window
                        // and the memory did not reach it
                        prop_assert!(b.distance > prof, "{:?}", b);
                    }
                    (None, f) => prop_assert!(f.is_none()),
                }
                // memory test: every segment within prof is a candidate;
                // circle test: exactly those in the box and the circle
                s.candidates(p, None, &[], &mut scratch);
                for e in 0..m {
                    let h = s.project(e, p).unwrap();
                    let expected = if circle {
                        s.in_circle(e, p, prof) && s.boxes[e].contains_within(p, prof)
                    } else {
                        h.distance <= prof
                    };
                    if expected {
                        prop_assert!(scratch.contains(&e), "segment {} at {}", e, h.distance);
                    } else if circle {
                        prop_assert!(!scratch.contains(&e), "segment {}", e);
                    }
                }
            }
        }
    }
}
