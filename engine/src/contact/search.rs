//! Contact search: which tool entity is closest to a slave node.
//!
//! Strategy (Metafor style, seed slides "Part I - Geometrical aspects"):
//! 1. the entity the node touched last (per-node memory, committed with the
//!    increment) is projected first, unconditionally, so a node that
//!    penetrated deeper than `prof` during an increment is still found;
//! 2. then that entity's neighbours, then a guess (the entity found for the
//!    previous slave node along the surface) and its neighbours;
//! 3. then every other entity, skipping those whose bounding box (tool
//!    reference frame, i.e. boxes that move with the tool) is farther than
//!    the search radius. The radius is `window` (`prof`) until a candidate
//!    is found, then the best `|gap|` found so far. [`closest_in`] (used
//!    by the solver) asks the tool's broad phase ([`ToolGrid`], built once
//!    in the reference frame) for the entities within the radius instead
//!    of looping over all of them: same result, `O(1)` per node.
//!
//! Guarantee (tested against [`brute_force`]): a returned candidate is the
//! closest candidate of the whole tool (smallest `|gap|`, ties: lowest
//! entity index). `None` is returned only when no entity has a candidate
//! within `window` and the memory entity gave none.
//!
//! Cast3M's circle test ([`LocalSearch::Circle`], [`closest_with`]): a
//! polyline segment is projected only if the node lies in the circle
//! centred on the segment's midpoint with radius `sqrt((L/2)^2 +
//! window^2)` (it holds every point whose foot is inside the segment with
//! `|gap| <= window`); the memory is then only an ordering hint. The result
//! is the closest among the segments passing the test; a node in the fan of
//! a kink may pass none, and a node deeper than the window is lost (no
//! unconditional memory). Other tool shapes (arcs, circles, NURBS spans,
//! planes) have no segment circle: the test is the memory one for them.

use super::broad::BroadPhase;
use super::geometry::{Projection, ToolShape};
use super::vec2::{dot, sub};
use crate::model::LocalSearch;

/// The closest entity of the tool to a node and the projection on it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Found {
    /// Entity index.
    pub entity: usize,
    /// Projection on that entity (tool reference frame).
    pub projection: Projection,
}

/// Whether candidate (`p`, `e`) beats the current best (smaller `|gap|`,
/// then lower index).
fn better(p: &Projection, e: usize, best: &Option<Found>) -> bool {
    match best {
        None => true,
        Some(b) => {
            let (a, c) = (p.gap.abs(), b.projection.gap.abs());
            a < c || (a == c && e < b.entity)
        }
    }
}

/// Search state for one node.
struct Scan<'a> {
    /// The tool.
    shape: &'a ToolShape,
    /// Query point, tool reference frame.
    x: [f64; 2],
    /// Search window `prof` (radius until a candidate is found).
    window: f64,
    /// Closest candidate so far.
    best: Option<Found>,
    /// Projections computed.
    tests: usize,
    /// Whether the Cast3M circle test filters polyline segments.
    circle: bool,
}

impl Scan<'_> {
    fn radius(&self) -> f64 {
        self.best
            .map(|b| b.projection.gap.abs())
            .unwrap_or(self.window)
    }

    /// Projects on `e` unless its box is beyond the radius; returns whether
    /// the entity was projected. The box test keeps a relative margin of
    /// 1e-12 so that rounding never prunes an entity tying with the best
    /// (two segments sharing the closest corner).
    fn consider(&mut self, e: usize, unconditional: bool) -> bool {
        let r = self.radius();
        if !unconditional && self.shape.bounding_box(e).distance(self.x) > r + 1e-12 * r {
            return false;
        }
        if self.circle && !in_circle(self.shape, e, self.x, self.window) {
            return false;
        }
        self.tests += 1;
        if let Some(p) = self.shape.project(e, self.x) {
            if better(&p, e, &self.best) {
                self.best = Some(Found {
                    entity: e,
                    projection: p,
                });
            }
        }
        true
    }
}

/// Cast3M circle test: whether `x` lies in the circle centred on polyline
/// segment `e`'s midpoint with radius `sqrt((L/2)^2 + window^2)`; true for
/// entities of other shapes (no segment circle).
pub fn in_circle(shape: &ToolShape, e: usize, x: [f64; 2], window: f64) -> bool {
    let ToolShape::Polyline(p) = shape else {
        return true;
    };
    let (Some(&a), Some(&l)) = (p.points.get(e), p.lengths.get(e)) else {
        return false;
    };
    let b = p.points[(e + 1) % p.points.len()];
    let mid = [0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])];
    let d = sub(x, mid);
    dot(d, d) <= 0.25 * l * l + window * window
}

/// Closest entity to `x` (tool reference frame) within `window`, testing
/// `memory` first (unconditionally), then its neighbours, then `guess` and
/// its neighbours, then the rest. Adds the number of projections made to
/// `tests`. Same as [`closest_with`] with the memory test.
pub fn closest(
    shape: &ToolShape,
    x: [f64; 2],
    window: f64,
    memory: Option<usize>,
    guess: Option<usize>,
    tests: &mut usize,
) -> Option<Found> {
    closest_with(shape, x, window, memory, guess, LocalSearch::Memory, tests)
}

/// [`closest`] with the local test `test`: [`LocalSearch::Memory`] as
/// described there, or [`LocalSearch::Circle`] (module documentation).
pub fn closest_with(
    shape: &ToolShape,
    x: [f64; 2],
    window: f64,
    memory: Option<usize>,
    guess: Option<usize>,
    test: LocalSearch,
    tests: &mut usize,
) -> Option<Found> {
    let count = shape.entity_count();
    let circle = test == LocalSearch::Circle;
    let mut scan = Scan {
        shape,
        x,
        window,
        best: None,
        tests: 0,
        circle,
    };
    let (first, nfirst, unconditional) = priority(shape, memory, guess, circle);
    let first = &first[..nfirst];
    let mut skipped_before_any = false;
    for (k, &e) in first.iter().enumerate() {
        let had = scan.best.is_some();
        if !scan.consider(e, k == 0 && unconditional == Some(e)) && !had {
            skipped_before_any = true;
        }
    }
    for e in 0..count {
        if first.contains(&e) {
            continue;
        }
        let had = scan.best.is_some();
        if !scan.consider(e, false) && !had {
            skipped_before_any = true;
        }
    }
    // A candidate farther than the window was found after some entities had
    // been skipped with the window radius: rescan them with the final radius
    // so the result is exactly the closest one.
    // Entities projected in the first pass then include every entity whose
    // box is within the window (the radius never fell below it).
    if skipped_before_any && scan.radius() > window {
        for e in 0..count {
            let done = unconditional == Some(e)
                || shape.bounding_box(e).distance(x) <= window + 1e-12 * window;
            if !done {
                scan.consider(e, false);
            }
        }
    }
    *tests += scan.tests;
    scan.best
}

/// Broad phase over a rigid tool's entity boxes in its reference frame
/// (built once: the tool is rigid and the node is mapped into its frame).
#[derive(Debug, Clone, Default)]
pub struct ToolGrid {
    /// Bucket grid over the entity boxes.
    grid: BroadPhase,
}

impl ToolGrid {
    /// Builds the grid over the entities of `shape`.
    pub fn new(shape: &ToolShape) -> Self {
        let boxes: Vec<_> = (0..shape.entity_count())
            .map(|e| shape.bounding_box(e))
            .collect();
        let mut grid = BroadPhase::default();
        grid.rebuild(&boxes, 0.0);
        ToolGrid { grid }
    }

    /// Number of entities.
    pub fn len(&self) -> usize {
        self.grid.len()
    }

    /// True if the tool has no entity.
    pub fn is_empty(&self) -> bool {
        self.grid.is_empty()
    }
}

/// One node's search request for [`closest_in`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Request {
    /// Query point, tool reference frame.
    pub x: [f64; 2],
    /// Search window `prof`.
    pub window: f64,
    /// Entity the node touched last (per-node memory).
    pub memory: Option<usize>,
    /// Entity found for the previous node along the surface.
    pub guess: Option<usize>,
    /// Local test.
    pub test: LocalSearch,
}

/// [`closest_with`] with the broad phase `grid` of the tool (built by
/// [`ToolGrid::new`] for `shape`): the memory entity, its neighbours, the
/// guess and its neighbours first, then only the entities the grid returns
/// for the current radius (the window, or the best `|gap|` found by the
/// first ones if that is larger) instead of every entity; same result,
/// `O(1)` work per node instead of `O(entities)`. `scratch` holds the grid
/// hits (reused).
pub fn closest_in(
    shape: &ToolShape,
    grid: &ToolGrid,
    req: Request,
    scratch: &mut Vec<usize>,
    tests: &mut usize,
) -> Option<Found> {
    let count = shape.entity_count();
    if grid.len() != count {
        return closest_with(
            shape, req.x, req.window, req.memory, req.guess, req.test, tests,
        );
    }
    let circle = req.test == LocalSearch::Circle;
    let mut scan = Scan {
        shape,
        x: req.x,
        window: req.window,
        best: None,
        tests: 0,
        circle,
    };
    let (first, nfirst, unconditional) = priority(shape, req.memory, req.guess, circle);
    // a priority entity pruned at the first radius may still be the
    // closest once the radius grows: only the ones projected are skipped below
    let mut projected = [usize::MAX; 6];
    let mut nprojected = 0;
    for (k, &e) in first[..nfirst].iter().enumerate() {
        if scan.consider(e, k == 0 && unconditional == Some(e)) {
            projected[nprojected] = e;
            nprojected += 1;
        }
    }
    let first = &projected[..nprojected];
    // every entity not returned has its box beyond the query radius; when
    // the best candidate found is farther than that (the first candidate of
    // a node farther than the window), query again with its distance
    let mut r = scan.radius();
    grid.grid.query(req.x, r + 1e-12 * r, scratch);
    for &e in scratch.iter() {
        if !first.contains(&e) {
            scan.consider(e, false);
        }
    }
    if scan.radius() > r {
        let seen = r + 1e-12 * r;
        r = scan.radius();
        grid.grid.query(req.x, r + 1e-12 * r, scratch);
        for &e in scratch.iter() {
            if !first.contains(&e) && shape.bounding_box(e).distance(req.x) > seen {
                scan.consider(e, false);
            }
        }
    }
    *tests += scan.tests;
    scan.best
}

/// The priority entities (memory, its neighbours, guess, its neighbours;
/// at most 6, no allocation), their count and the entity projected
/// unconditionally (the memory, except with the circle test).
fn priority(
    shape: &ToolShape,
    memory: Option<usize>,
    guess: Option<usize>,
    circle: bool,
) -> ([usize; 6], usize, Option<usize>) {
    let count = shape.entity_count();
    let mut first = [usize::MAX; 6];
    let mut nfirst = 0;
    let mut push = |e: Option<usize>, first: &mut [usize; 6]| {
        if let Some(e) = e {
            if e < count && !first[..nfirst].contains(&e) {
                first[nfirst] = e;
                nfirst += 1;
            }
        }
    };
    let memory = memory.filter(|&e| e < count);
    push(memory, &mut first);
    if let Some(m) = memory {
        let [a, b] = shape.neighbours(m);
        push(a, &mut first);
        push(b, &mut first);
    }
    if let Some(g) = guess.filter(|&g| g < count) {
        push(Some(g), &mut first);
        let [a, b] = shape.neighbours(g);
        push(a, &mut first);
        push(b, &mut first);
    }
    (first, nfirst, memory.filter(|_| !circle))
}

/// Reference search: projects `x` on every entity and returns the closest
/// candidate (smallest `|gap|`, ties: lowest index), with no window.
pub fn brute_force(shape: &ToolShape, x: [f64; 2], tests: &mut usize) -> Option<Found> {
    let mut best = None;
    for e in 0..shape.entity_count() {
        *tests += 1;
        if let Some(p) = shape.project(e, x) {
            if better(&p, e, &best) {
                best = Some(Found {
                    entity: e,
                    projection: p,
                });
            }
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::ToolGeometry;

    fn zigzag(n: usize) -> ToolShape {
        let points: Vec<[f64; 2]> = (0..=n)
            .map(|i| [i as f64 * 0.1, if i % 2 == 0 { 0.0 } else { 0.03 }])
            .collect();
        ToolShape::new(&ToolGeometry::Polyline { points }).unwrap()
    }

    #[test]
    fn memory_first_prunes_other_entities() {
        let shape = zigzag(100);
        let x = [5.04, 0.01];
        let mut brute = 0;
        let b = brute_force(&shape, x, &mut brute).unwrap();
        let mut t = 0;
        let s = closest(&shape, x, 0.2, Some(b.entity), None, &mut t).unwrap();
        assert_eq!((s.entity, s.projection), (b.entity, b.projection));
        assert_eq!(brute, 100);
        assert!(t <= 3, "{t} projections with memory");
        let mut t2 = 0;
        let s2 = closest(&shape, x, 0.2, None, None, &mut t2).unwrap();
        assert_eq!(s2.entity, b.entity);
        assert!(t2 < 10, "{t2} projections without memory");
    }

    #[test]
    fn deep_memory_candidate_beyond_window_is_still_exact() {
        let shape = zigzag(10);
        // Far below the tool (behind it): memory entity 3 finds a candidate
        // with |gap| > window; the result must still be the global closest.
        let x = [0.52, -0.5];
        let mut n = 0;
        let b = brute_force(&shape, x, &mut n).unwrap();
        let s = closest(&shape, x, 0.01, Some(3), None, &mut n).unwrap();
        assert_eq!(s.entity, b.entity);
        assert_eq!(s.projection, b.projection);
        // Without memory nothing is within the window.
        assert!(closest(&shape, x, 0.01, None, None, &mut n).is_none());
    }
}
