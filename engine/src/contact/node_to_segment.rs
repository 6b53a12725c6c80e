//! Contact between deformable bodies and self contact: node-to-segment
//! elements (seed slides, "Contact between two deformable bodies / self
//! contact", "Three usual strategies", "Part I - Geometrical aspects").
//!
//! A pair has two surfaces: side 0 (the deck's left of `->`) and side 1
//! (the master surface, right of `->`). Each slave node is projected on
//! the candidate segments of the opposite side (bucket-grid broad phase
//! inflated by `prof`, plus its memory: the segment of the last
//! evaluation, its neighbours and the segments walked from it towards the
//! node's foot, [`memory_walk`], so a node that penetrated deeper than
//! `prof` is not lost);
//! the kept projection gives a 3-node element (slave, `m1`, `m2`) with the
//! kinematics of [`super::segment`].
//!
//! Strategies ([`ContactStrategy`]):
//! - single pass: side-0 nodes against side-1 segments;
//! - double pass: the roles are swapped at every converged increment
//!   (even increments: side 0 is slave; odd: side 1);
//! - modified double pass: both directions at every evaluation. Each node
//!   then carries **half** its tributary area, so that with the penalty
//!   method a uniform pressure still gives the gap `p / k` and the
//!   reported pressure (slave force / weighted area) is the contact
//!   pressure; with Lagrange multipliers the constraints of the two passes
//!   are redundant (over-constrained system, see the patch test).
//!
//! Self contact (same body and same surface on both sides): the surface's
//! nodes against its own segments, excluding the segments that contain the
//! node and the segments adjacent to those. Every node is slave and master
//! at once, so the strategy is irrelevant (it is the modified double pass
//! by construction, with full areas: two facing parts of the surface each
//! push on the other with their own nodes).
//!
//! Choice of the projection (several projections, projection outside all
//! segments while inside the body):
//! 1. among the candidates whose projection falls inside the segment
//!    (`0 <= xi <= 1`, with a round-off tolerance), the one with the
//!    smallest `|g|` (the closest point), ties to the lower segment index;
//! 2. otherwise (the node lies in the wedge in front of a kink, e.g. inside
//!    the body at a concave corner where every projection falls outside),
//!    the kink's vertex: the signed distance to it
//!    ([`SegmentProjection::corner`], the vertex as a circle of radius 0,
//!    like the corners of rigid tools), whose normal turns continuously
//!    from one segment's normal to the other's across the wedge. (Keeping
//!    the nearer segment's line instead made the normal jump at the
//!    wedge's bisector: a slave node exactly above an interior master node
//!    of a flat interface, pressed into a valley, switched segments at
//!    every iteration, a 2-cycle of the force direction, issue 14 item
//!    5.) The vertex is used only when the node is in the kink's wedge
//!    (beyond the neighbour's near end as well). At a free end of the
//!    surface the segment is **extended** past its end (`g` and `xi` of the
//!    segment line) only by [`FREE_END_XI`] segment lengths;
//! 3. penetrations deeper than `max(prof, L)` are ignored (a node of the
//!    far side of a thin body is not in contact with this face), except
//!    on the node's memory ([`memory_walk`]): a node that had a
//!    projection on this surface at the last evaluation (in contact, or
//!    open within the window) and is now deeper crossed the face during
//!    one Newton step; it is not on the far side. (Dropping it left it
//!    inside the master for good: the 2D ironing slide at slab cells
//!    1/2, 1/4, where a Newton step from an open predictor put a slab
//!    node 0.54 inside the die, past `max(prof, L) = 0.5`, issue 18.)
//!
//! The gap that decides contact is the one that gives the force and the
//! reported pressure.

use super::broad::BroadPhase;
use super::segment::SegmentProjection;
use super::segment_search;
use super::smoothing;
use super::{augmented, lagrange, penalty, ContactStatus, MasterSegment, NodeContact, PairState};
use crate::geom::Aabb;
use crate::model::{
    ContactMaster, ContactMethod, ContactPair, ContactStrategy, LocalSearch, Model, NormalSmoothing,
};

/// Relative tolerance on `xi` for "inside the segment".
const XI_TOL: f64 = 1e-10;

/// How far (in segment lengths) a slave node may pass the free end of the
/// master surface and keep the extended segment: iterates wobble around a
/// node that sits exactly at the end (patch test corners).
const FREE_END_XI: f64 = 0.02;

/// One surface of a deformable pair.
#[derive(Debug, Clone, Default)]
pub struct Surface {
    /// Segments `[a, b]` (body on the left).
    pub edges: Vec<[usize; 2]>,
    /// Per segment: the segment ending at its first node (previous one).
    pub prev: Vec<Option<usize>>,
    /// Per segment: the segment starting at its second node (next one).
    pub next: Vec<Option<usize>>,
    /// Per segment: the coordinates its free ends' smoothed nodal normals
    /// drop (a symmetry line or the axis, [`super::symmetry`]; set by
    /// [`prepare`], none by [`Surface::new`]).
    pub sym: Vec<smoothing::Symmetry>,
    /// Broad phase over the segment boxes at the current coordinates.
    pub(crate) grid: Option<BroadPhase>,
    /// Scratch: segment boxes.
    boxes: Vec<Aabb<2>>,
}

impl Surface {
    pub(crate) fn new(edges: &[[usize; 2]]) -> Self {
        let mut prev = vec![None; edges.len()];
        let mut next = vec![None; edges.len()];
        // sorted (node, segment) lists: deterministic, no hash map
        let mut starts: Vec<(usize, usize)> =
            edges.iter().enumerate().map(|(e, s)| (s[0], e)).collect();
        starts.sort_unstable();
        for (e, s) in edges.iter().enumerate() {
            let k = starts.partition_point(|&(n, _)| n < s[1]);
            if let Some(&(n, f)) = starts.get(k) {
                if n == s[1] && f != e {
                    next[e] = Some(f);
                    prev[f] = Some(e);
                }
            }
        }
        Surface {
            edges: edges.to_vec(),
            prev,
            next,
            sym: vec![smoothing::NO_SYMMETRY; edges.len()],
            grid: None,
            boxes: Vec::with_capacity(edges.len()),
        }
    }

    /// Sets [`Surface::sym`]: the free ends of the surface (a body's
    /// segments) on a symmetry line or the axis ([`super::symmetry`]).
    pub(crate) fn mirror_free_ends(&mut self, model: &Model, body: usize) {
        let mut ends: Vec<usize> = Vec::new();
        for (e, ed) in self.edges.iter().enumerate() {
            if self.prev[e].is_none() {
                ends.push(ed[0]);
            }
            if self.next[e].is_none() {
                ends.push(ed[1]);
            }
        }
        ends.sort_unstable();
        ends.dedup();
        let masks = super::symmetry::masks(model, body, &ends);
        let mask = |n: usize| ends.binary_search(&n).map_or([false; 2], |i| masks[i]);
        self.sym = self
            .edges
            .iter()
            .enumerate()
            .map(|(e, ed)| {
                [
                    if self.prev[e].is_none() {
                        mask(ed[0])
                    } else {
                        [false; 2]
                    },
                    if self.next[e].is_none() {
                        mask(ed[1])
                    } else {
                        [false; 2]
                    },
                ]
            })
            .collect();
    }

    /// Rebuilds the broad phase at the current coordinates `x` with each
    /// segment's box around its two ends and its midside node
    /// (`midsides`, per segment: seg3 segments).
    pub(crate) fn update_with_midsides(&mut self, x: &[[f64; 2]], midsides: &[usize]) {
        self.boxes.clear();
        for (&[a, b], &m) in self.edges.iter().zip(midsides) {
            self.boxes.push(Aabb::around(&[x[a], x[b], x[m]]));
        }
        self.grid
            .get_or_insert_with(BroadPhase::default)
            .rebuild(&self.boxes, 0.0);
    }

    /// Rebuilds the broad phase at the current coordinates `x`.
    pub(crate) fn update(&mut self, x: &[[f64; 2]]) {
        self.boxes.clear();
        for &[a, b] in &self.edges {
            self.boxes.push(Aabb::around(&[x[a], x[b]]));
        }
        // rebuilt in place: no allocation once the sizes have settled
        self.grid
            .get_or_insert_with(BroadPhase::default)
            .rebuild(&self.boxes, 0.0);
    }
}

/// Prepared data of a pair whose master is a deformable surface.
#[derive(Debug, Clone, Default)]
pub struct SurfacePair {
    /// Side 0 (the deck's slave surface) and side 1 (its master surface).
    pub sides: [Surface; 2],
    /// Per slave index (`PairState::slaves`): the side the node belongs to.
    pub side_of: Vec<u8>,
    /// Self contact (both sides are the same surface).
    pub self_contact: bool,
    /// Per slave index, self contact only: segments excluded for the node
    /// (its own and the adjacent ones), sorted.
    pub excluded: Vec<Vec<usize>>,
    /// Converged increments so far (double pass: parity picks the slave side).
    pub increments: usize,
    /// Converged increments at the last commit (rollback target).
    committed_increments: usize,
    /// Current coordinates of every node at the latest evaluation.
    pub positions: Vec<[f64; 2]>,
    /// Coordinates at the last converged increment (the start of the
    /// constant-velocity path of a first impact,
    /// [`crate::model::FirstImpact::Intersect`]).
    pub committed_positions: Vec<[f64; 2]>,
    /// Mortar friction: the slave nodes' pairings in the committed
    /// configuration (recomputed once per increment from
    /// `committed_positions`).
    pub pairing: Option<super::mortar::friction::CommittedPairing>,
    /// Mortar friction on seg3 faces: the slave nodes' committed pairings
    /// ([`super::mortar::friction_quadratic`], once per increment).
    pub seg3_pairing: Option<super::mortar::friction_quadratic::CommittedPairing2>,
    /// Per side, per segment: its midside node when the side's body has
    /// quadratic cells (seg3 segments `[a, b, m]`, mortar only,
    /// [`super::mortar::seg3`]); empty for a linear side.
    pub midsides: [Vec<usize>; 2],
    /// Scratch: candidate segments of one query.
    pub(crate) candidates: Vec<usize>,
    /// Scratch: the memory segments of one query ([`memory_walk`]).
    memory: Vec<usize>,
}

impl SurfacePair {
    /// Which sides act as slave now: `[side 0 is slave, side 1 is slave]`.
    pub fn slave_sides(&self, strategy: ContactStrategy) -> [bool; 2] {
        if self.self_contact {
            return [true, false];
        }
        strategy.slave_sides(self.increments)
    }

    /// Called when an increment has converged.
    pub fn commit(&mut self) {
        self.increments += 1;
        self.committed_increments = self.increments;
        self.committed_positions.clone_from(&self.positions);
    }

    /// Called when an increment is cut back.
    pub fn rollback(&mut self) {
        self.increments = self.committed_increments;
        self.positions.clone_from(&self.committed_positions);
    }

    /// Restart: `increments` converged increments were done (the restart
    /// checkpoint's count), so the double pass resumes with the right side;
    /// `positions` are the committed coordinates of every node.
    pub fn restore(&mut self, increments: usize, positions: &[[f64; 2]]) {
        self.increments = increments;
        self.committed_increments = increments;
        self.committed_positions = positions.to_vec();
        self.positions = positions.to_vec();
    }
}

/// Slave nodes of a pair (sorted): the deck's slave nodes, plus the master
/// surface's nodes for the double-pass strategies (not for self contact).
pub fn slave_nodes(model: &Model, pair: usize) -> Vec<usize> {
    let Some(cp) = model.contacts.get(pair) else {
        return Vec::new();
    };
    let mut nodes = cp.nodes.clone();
    if let ContactMaster::Surface {
        nodes: master,
        edges,
        ..
    } = &cp.master
    {
        let self_contact = edges == &cp.edges;
        if !self_contact && cp.strategy != ContactStrategy::SinglePass {
            nodes.extend(master);
            nodes.sort_unstable();
            nodes.dedup();
        }
    }
    nodes
}

/// Prepares a deformable pair; `None` if the master is a rigid tool.
pub fn prepare(model: &Model, pair: usize, slaves: &[usize]) -> Option<SurfacePair> {
    let cp = model.contacts.get(pair)?;
    let ContactMaster::Surface {
        edges,
        body: master_body,
        ..
    } = &cp.master
    else {
        return None;
    };
    let master_body = *master_body;
    let self_contact = edges == &cp.edges;
    let mut sides = [Surface::new(&cp.edges), Surface::new(edges)];
    if cp.smoothing == NormalSmoothing::Nodal {
        sides[0].mirror_free_ends(model, cp.body);
        sides[1].mirror_free_ends(model, master_body);
    }
    let side_of = slaves
        .iter()
        .map(|n| u8::from(cp.nodes.binary_search(n).is_err()))
        .collect();
    let excluded = if self_contact {
        let s = &sides[0];
        slaves
            .iter()
            .map(|&node| {
                let mut ex = Vec::new();
                for (e, ed) in s.edges.iter().enumerate() {
                    if ed.contains(&node) {
                        ex.push(e);
                        ex.extend(s.prev[e]);
                        ex.extend(s.next[e]);
                    }
                }
                ex.sort_unstable();
                ex.dedup();
                ex
            })
            .collect()
    } else {
        Vec::new()
    };
    let midsides = [(cp.body, &cp.edges), (master_body, edges)]
        .map(|(b, e)| super::mortar::seg3::edge_midsides(model, b, e).unwrap_or_default());
    Some(SurfacePair {
        sides,
        side_of,
        self_contact,
        excluded,
        midsides,
        positions: model.mesh.nodes.clone(),
        committed_positions: model.mesh.nodes.clone(),
        ..SurfacePair::default()
    })
}

/// Tributary area of each slave node: the deck's slave edges for side-0
/// nodes, the master edges for side-1 nodes; halved for the modified
/// double pass and for self contact (both directions carry the load at
/// once, so that a penalty gap is `p / k` with `p` the interface pressure,
/// as in 3D: `node_to_facet::areas`).
pub fn tributary_areas(model: &Model, pair: usize, slaves: &[usize]) -> Vec<f64> {
    let Some(cp) = model.contacts.get(pair) else {
        return Vec::new();
    };
    let ContactMaster::Surface { edges, .. } = &cp.master else {
        return super::tributary::tributary_areas(model, pair);
    };
    let mut area = super::tributary::edge_areas(model, &cp.edges, slaves);
    if edges == &cp.edges {
        for a in &mut area {
            *a *= 0.5;
        }
    } else {
        let side1: Vec<usize> = slaves
            .iter()
            .copied()
            .filter(|n| cp.nodes.binary_search(n).is_err())
            .collect();
        let a1 = super::tributary::edge_areas(model, edges, &side1);
        for (n, a) in side1.iter().zip(a1) {
            if let Ok(i) = slaves.binary_search(n) {
                area[i] = a;
            }
        }
        if cp.strategy == ContactStrategy::ModifiedDoublePass {
            for a in &mut area {
                *a *= 0.5;
            }
        }
    }
    area
}

/// The projection kept for a slave node.
#[derive(Debug, Clone, Copy)]
struct Kept {
    segment: usize,
    projection: SegmentProjection,
}

/// The memory of a slave node at `xs` whose last evaluation kept segment
/// `start` of `surface`, appended to `out` (sorted, without duplicates):
/// `start`, its neighbours, and the segments walked from `start` towards
/// the node's foot (to the previous segment while the projection falls
/// before the segment's start, to the next while it falls past its end;
/// at most once round a closed surface). The segments a node can have
/// reached by crossing the face since the last evaluation, however far it
/// slid along it: exempt from the depth window (rule 3 of the module
/// documentation). `tests` counts projections.
fn memory_walk(
    surface: &Surface,
    x: &[[f64; 2]],
    xs: [f64; 2],
    start: usize,
    tests: &mut usize,
    out: &mut Vec<usize>,
) {
    out.push(start);
    out.extend(surface.prev[start]);
    out.extend(surface.next[start]);
    let mut e = start;
    let mut dir = 0i8;
    for _ in 0..surface.edges.len() {
        let [a, b] = surface.edges[e];
        let Some(p) = SegmentProjection::new(xs, x[a], x[b]) else {
            break;
        };
        *tests += 1;
        let step = if p.xi < -XI_TOL {
            -1
        } else if p.xi > 1.0 + XI_TOL {
            1
        } else {
            0
        };
        // inside the segment, or turned back (a kink's wedge): done
        if step == 0 || (dir != 0 && step != dir) {
            break;
        }
        dir = step;
        let next = if step < 0 {
            surface.prev[e]
        } else {
            surface.next[e]
        };
        match next {
            Some(f) if f != start => {
                out.push(f);
                e = f;
            }
            _ => break,
        }
    }
    out.sort_unstable();
    out.dedup();
}

/// Projects `xs` on the candidates of `surface` and keeps one projection
/// (rules of the module documentation): the segments of `memory` (sorted,
/// [`memory_walk`]) at any depth, the others within `max(depth, L)`;
/// `tests` counts projections.
fn closest(
    surface: &Surface,
    x: &[[f64; 2]],
    xs: [f64; 2],
    candidates: &[usize],
    memory: &[usize],
    depth: f64,
    tests: &mut usize,
) -> Option<Kept> {
    let mut inside: Option<(f64, Kept)> = None;
    let mut outside: Option<(f64, Kept)> = None;
    for &e in candidates {
        let [a, b] = surface.edges[e];
        let Some(p) = SegmentProjection::new(xs, x[a], x[b]) else {
            continue;
        };
        *tests += 1;
        if p.gap < -depth.max(p.length) && memory.binary_search(&e).is_err() {
            continue;
        }
        let k = Kept {
            segment: e,
            projection: p,
        };
        if (-XI_TOL..=1.0 + XI_TOL).contains(&p.xi) {
            if inside.is_none_or(|(d, _)| p.gap.abs() < d) {
                inside = Some((p.gap.abs(), k));
            }
            continue;
        }
        // beyond an end: at a kink only when the node is in the wedge of
        // the kink (beyond the neighbour's near end too); at a free end of
        // the surface only by the small tolerance `FREE_END_XI`
        let neighbour = if p.xi < 0.0 {
            surface.prev[e]
        } else {
            surface.next[e]
        };
        let allowed = match neighbour {
            Some(f) => {
                let [fa, fb] = surface.edges[f];
                SegmentProjection::new(xs, x[fa], x[fb]).is_some_and(|q| {
                    *tests += 1;
                    if p.xi < 0.0 {
                        q.xi > 1.0
                    } else {
                        q.xi < 0.0
                    }
                })
            }
            None => (-FREE_END_XI..=1.0 + FREE_END_XI).contains(&p.xi),
        };
        if !allowed {
            continue;
        }
        let end = if p.xi < 0.0 { x[a] } else { x[b] };
        let dist = (xs[0] - end[0]).hypot(xs[1] - end[1]);
        // in the wedge of a kink the closest point of the surface is the
        // vertex: the distance to it (continuous across the wedge, the
        // same from both segments); a node on the vertex keeps the line
        let k = match neighbour {
            Some(f) => Kept {
                projection: SegmentProjection::corner_on_side(
                    xs,
                    x[a],
                    x[b],
                    p.xi,
                    kink_side(surface, x, e, f, p.xi < 0.0),
                )
                .unwrap_or(p),
                ..k
            },
            None => k,
        };
        if outside.is_none_or(|(d, _)| dist < d) {
            outside = Some((dist, k));
        }
    }
    inside.or(outside).map(|(_, k)| k)
}

/// The side of the wedge of the kink between segment `e` and its
/// neighbour `f` (`f` before `e` when `before`): `+1` (outside the body)
/// at a convex vertex (the walk, body on its left, turns left), `-1`
/// (inside) at a concave one, `None` when the segments are collinear (the
/// wedge is empty; the line's side is kept). Every point of a convex
/// kink's wedge is in front of one of the two faces, and every point of
/// a concave kink's wedge behind one of them, whatever the angle.
fn kink_side(surface: &Surface, x: &[[f64; 2]], e: usize, f: usize, before: bool) -> Option<f64> {
    let dir = |s: usize| {
        let [a, b] = surface.edges[s];
        [x[b][0] - x[a][0], x[b][1] - x[a][1]]
    };
    let (din, dout) = if before {
        (dir(f), dir(e))
    } else {
        (dir(e), dir(f))
    };
    let cross = din[0] * dout[1] - din[1] * dout[0];
    let scale = din[0].hypot(din[1]) * dout[0].hypot(dout[1]);
    if cross > 1e-12 * scale {
        Some(1.0)
    } else if cross < -1e-12 * scale {
        Some(-1.0)
    } else {
        None
    }
}

/// A smoothed projection (`smoothing = nodal`) and the far nodes of the
/// neighbouring segments its nodal normals depend on.
#[derive(Debug, Clone, Copy)]
struct SmoothKept {
    segment: usize,
    far: [Option<usize>; 2],
    sym: smoothing::Symmetry,
    d: smoothing::Smoothed,
}

/// The coordinates `[x_s, x_0, x_1, x_2, x_3]` of segment `e` of `surface`
/// and the far nodes `x_0`, `x_3` (if the neighbours exist); the
/// segment's symmetry is `surface.sym[e]`.
fn patch_points(
    surface: &Surface,
    x: &[[f64; 2]],
    xs: [f64; 2],
    e: usize,
) -> ([[f64; 2]; 5], [Option<usize>; 2]) {
    let [a, b] = surface.edges[e];
    let far0 = surface.prev[e].map(|f| surface.edges[f][0]);
    let far3 = surface.next[e].map(|f| surface.edges[f][1]);
    let pts = [
        xs,
        far0.map_or(x[a], |n| x[n]),
        x[a],
        x[b],
        far3.map_or(x[b], |n| x[n]),
    ];
    (pts, [far0, far3])
}

/// Relative tolerance (of the segment's length) within which the smoothed
/// `|g|` of two segments is a tie: at a master vertex both segments give
/// the same point, gap and normal, and round-off decided.
const VERTEX_TIE: f64 = 1e-9;

/// Smoothed projection of `xs` on the candidates (the nodal normal field
/// of [`smoothing`]): among the projections inside their segment (past a
/// free end only by [`FREE_END_XI`]), the smallest `|g|`, ties to the
/// lower segment index; but the segment `last` of the last evaluation is
/// kept while its `|g|` is within [`VERTEX_TIE`] of its length of the
/// smallest (a node on a master vertex projects on both segments with the
/// same gap to round-off: choosing by the last bits made it switch at
/// every iteration, 308 times on the sliding cylinder with the vertex
/// under its pole); `None` when no projection falls inside (the caller
/// then keeps the faceted projection).
#[allow(clippy::too_many_arguments)]
fn closest_smoothed(
    surface: &Surface,
    x: &[[f64; 2]],
    xs: [f64; 2],
    candidates: &[usize],
    memory: &[usize],
    last: Option<usize>,
    depth: f64,
    tests: &mut usize,
) -> Option<SmoothKept> {
    let mut best: Option<(f64, usize, f64)> = None;
    let mut kept: Option<(f64, usize, f64, f64)> = None;
    for &e in candidates {
        let (pts, far) = patch_points(surface, x, xs, e);
        let Some(line) = SegmentProjection::new(xs, pts[2], pts[3]) else {
            continue;
        };
        let sym = surface
            .sym
            .get(e)
            .copied()
            .unwrap_or(smoothing::NO_SYMMETRY);
        let Some(p) = smoothing::Patch::new(pts, far[0].is_some(), far[1].is_some(), sym) else {
            continue;
        };
        *tests += 1;
        let Some(xi) = smoothing::project(&p, line.xi.clamp(0.0, 1.0)) else {
            continue;
        };
        let lo = if far[0].is_some() {
            -XI_TOL
        } else {
            -FREE_END_XI
        };
        let hi = if far[1].is_some() {
            1.0 + XI_TOL
        } else {
            1.0 + FREE_END_XI
        };
        if !(lo..=hi).contains(&xi) {
            continue;
        }
        let gap = p.gap(xi).0;
        if gap < -depth.max(line.length) && memory.binary_search(&e).is_err() {
            continue;
        }
        if best.is_none_or(|(d, _, _)| gap.abs() < d) {
            best = Some((gap.abs(), e, xi));
        }
        if last == Some(e) {
            kept = Some((gap.abs(), e, xi, line.length));
        }
    }
    let (d, e, xi) = best?;
    let (_, e, xi) = match kept {
        Some((dk, ek, xik, length)) if dk <= d + VERTEX_TIE * length => (dk, ek, xik),
        _ => (d, e, xi),
    };
    let (pts, far) = patch_points(surface, x, xs, e);
    let sym = surface
        .sym
        .get(e)
        .copied()
        .unwrap_or(smoothing::NO_SYMMETRY);
    let d = smoothing::differentiate(pts, far[0].is_some(), far[1].is_some(), sym, xi)?;
    Some(SmoothKept {
        segment: e,
        far,
        sym,
        d,
    })
}

/// Evaluates deformable pair `pair` at current coordinates `x`: one entry
/// per slave node within `prof` of the opposite surface (or penetrating).
pub fn evaluate(
    model: &Model,
    pair: usize,
    x: &[[f64; 2]],
    state: &mut PairState,
) -> Vec<NodeContact> {
    let mut out = Vec::new();
    let Some(cp) = model.contacts.get(pair) else {
        return out;
    };
    let Some(mut sp) = state.surface.take() else {
        return out;
    };
    let active_sides = sp.slave_sides(cp.strategy);
    let master_of = |side: u8| {
        if sp.self_contact {
            0
        } else {
            1 - side as usize
        }
    };
    for s in 0..2 {
        if (s == 0 && (active_sides[1] || sp.self_contact)) || (s == 1 && active_sides[0]) {
            sp.sides[s].update(x);
        }
    }
    let prof = state.prof;
    let mut tests = 0usize;
    let mut brute = 0usize;
    let mut candidates = std::mem::take(&mut sp.candidates);
    let mut memory = std::mem::take(&mut sp.memory);
    let smooth = cp.smoothing == NormalSmoothing::Nodal;
    let mut couplings = state.couplings.take();
    if let Some(c) = &mut couplings {
        c.clear();
    }
    sp.positions.clear();
    sp.positions.extend_from_slice(x);
    state.friction.impact = None;
    for (i, &node) in state.slaves.iter().enumerate() {
        let side = sp.side_of[i];
        if !active_sides[side as usize] {
            continue;
        }
        let Some(&xs) = x.get(node) else {
            continue;
        };
        let m = master_of(side);
        let surface = &sp.sides[m];
        brute += surface.edges.len();
        candidates.clear();
        if let Some(grid) = &surface.grid {
            grid.query(xs, prof, &mut candidates);
        }
        // memory: the last segment, its neighbours and the walk from it
        // towards the node's foot are always tested, at any depth
        memory.clear();
        if let Some(e) = state.last_entity[i].filter(|&e| e < surface.edges.len()) {
            memory_walk(surface, x, xs, e, &mut tests, &mut memory);
            candidates.extend_from_slice(&memory);
        }
        candidates.sort_unstable();
        candidates.dedup();
        if sp.self_contact {
            let ex = &sp.excluded[i];
            candidates.retain(|e| ex.binary_search(e).is_err());
        }
        // Cast3M's local test (`search = circle`): only the segments whose
        // circle holds the node, memory included (see `segment_search`)
        if cp.search == LocalSearch::Circle {
            candidates.retain(|&e| {
                let [a, b] = surface.edges[e];
                segment_search::in_segment_circle(x[a], x[b], xs, prof)
            });
        }
        let smoothed = if smooth {
            let last = state.last_entity[i];
            closest_smoothed(surface, x, xs, &candidates, &memory, last, prof, &mut tests)
        } else {
            None
        };
        let kept = match &smoothed {
            Some(s) => {
                let [a, b] = surface.edges[s.segment];
                SegmentProjection::new(xs, x[a], x[b]).map(|projection| Kept {
                    segment: s.segment,
                    projection,
                })
            }
            None => closest(surface, x, xs, &candidates, &memory, prof, &mut tests),
        };
        let Some(k) = kept else {
            state.last_entity[i] = None;
            state.friction.open(i, xs);
            continue;
        };
        state.last_entity[i] = Some(k.segment);
        let p = k.projection;
        let (gap, n) = match &smoothed {
            Some(s) => (s.d.gap.v, s.d.normal),
            None => (p.gap, p.normal),
        };
        if gap > prof {
            state.friction.open(i, xs);
            continue;
        }
        let [m1, m2] = surface.edges[k.segment];
        let tributary = state.tributary.get(i).copied().unwrap_or(0.0);
        let lambda = state.multiplier.get(i).copied().unwrap_or(0.0);
        let method = cp.method_at(node);
        let (resp, dr_dg) = match &method {
            ContactMethod::Penalty { .. } => {
                let alpha = penalty::effective_stiffness(&method, tributary);
                let resp = penalty::respond(&method, tributary, gap, n, 0.0);
                let resp = penalty::touching(alpha, gap, state.touching, tributary, n, 0.0)
                    .filter(|_| resp.status == ContactStatus::Open)
                    .unwrap_or(resp);
                let closed = resp.status == ContactStatus::Closed;
                (resp, if closed { -alpha } else { 0.0 })
            }
            ContactMethod::Lagrange { .. } => {
                let active = state.active.get(i).copied().unwrap_or(false);
                (lagrange::respond(active, lambda, tributary, n, 0.0), 0.0)
            }
            ContactMethod::AugmentedLagrange { .. } => {
                let alpha = penalty::effective_stiffness(&method, tributary);
                let resp = augmented::respond(alpha, lambda, tributary, gap, n, 0.0);
                let resp = penalty::touching(alpha, gap, state.touching, tributary, n, 0.0)
                    .filter(|_| resp.status == ContactStatus::Open)
                    .unwrap_or(resp);
                let closed = resp.status == ContactStatus::Closed;
                (resp, if closed { -alpha } else { 0.0 })
            }
        };
        let rn = resp.force[0] * n[0] + resp.force[1] * n[1];
        let (mut f, mut kt) = match &smoothed {
            // the 6-dof blocks are filled from the smoothed element below
            Some(_) => ([0.0; 6], [[0.0; 6]; 6]),
            None => p.element(rn, dr_dg),
        };
        // the smoothed element's friction over [x_s, x_0, x_1, x_2, x_3]
        let mut f10 = [0.0; smoothing::N];
        let mut k10 = [[0.0; smoothing::N]; smoothing::N];
        let element = super::friction_segment::Element {
            slave: i,
            xs,
            nodes: [m1, m2],
            xi: smoothed.as_ref().map_or(p.xi, |s| s.d.xi),
            normal_force: rn,
            status: resp.status,
            tributary,
            // a vertex projection: the friction in the tangent of the
            // vertex's normal
            vertex: (smoothed.is_none() && p.corner).then(|| super::friction_segment::Vertex {
                end: usize::from(p.xi > 0.5),
                side: if p.gap < 0.0 { -1.0 } else { 1.0 },
            }),
        };
        let friction = match (&cp.friction, &smoothed) {
            (Some(law), Some(s)) => super::friction_segment::apply_smoothed(
                law,
                &method,
                &model.mesh.nodes,
                x,
                &sp.committed_positions,
                &super::friction_segment::SmoothedElement {
                    element,
                    far: s.far,
                    sym: s.sym,
                    gap: s.d.gap.v,
                },
                &mut state.friction,
                &mut f10,
                &mut k10,
            ),
            (Some(law), None) => super::friction_segment::apply(
                law,
                &method,
                &model.mesh.nodes,
                x,
                &sp.committed_positions,
                &element,
                &mut state.friction,
                &mut f,
                &mut kt,
            ),
            (None, _) => Default::default(),
        };
        let mut gap_gradient = p.gap_gradient();
        if let (Some(s), Some(rows)) = (&smoothed, couplings.as_mut()) {
            // f = R B + friction, K = -dR/dg B (dg/dx)^T - R dB/dx + friction
            // over [x_s, x_0, x_1, x_2, x_3]; the friction blocks sit at the
            // slave and the segment ends
            let far = s.far;
            let local = [Some(node), far[0], Some(m1), Some(m2), far[1]];
            let mut nodes: Vec<usize> = local.iter().flatten().copied().collect();
            nodes.sort_unstable();
            nodes.dedup();
            let pos = |k: usize| local[k].and_then(|n| nodes.binary_search(&n).ok());
            let nd = 2 * nodes.len();
            let mut force = vec![0.0; nd];
            let mut tangent = vec![0.0; nd * nd];
            let mut row = vec![0.0; nd];
            let g = &s.d.gap;
            for a in 0..smoothing::N {
                let Some(pa) = pos(a / 2) else { continue };
                let ra = 2 * pa + a % 2;
                force[ra] += rn * s.d.b[a].v;
                row[ra] += s.d.b[a].v;
                for c in 0..smoothing::N {
                    let Some(pc) = pos(c / 2) else { continue };
                    let rc = 2 * pc + c % 2;
                    tangent[ra * nd + rc] += -dr_dg * s.d.b[a].v * g.d[c] - rn * s.d.b[a].d[c];
                }
            }
            // friction (over the same 10 coordinates)
            for a in 0..smoothing::N {
                let Some(pa) = pos(a / 2) else { continue };
                let ra = 2 * pa + a % 2;
                force[ra] += f10[a];
                for c in 0..smoothing::N {
                    let Some(pc) = pos(c / 2) else { continue };
                    tangent[ra * nd + 2 * pc + c % 2] += k10[a][c];
                }
            }
            // the 6-dof view (slave, m1, m2 = local 0, 2, 3), for output
            // and the search (the full element is the coupling)
            let six = [0usize, 1, 4, 5, 6, 7];
            for (a6, &a) in six.iter().enumerate() {
                f[a6] += rn * s.d.b[a].v + f10[a];
                gap_gradient[a6] = s.d.b[a].v;
                for (c6, &c) in six.iter().enumerate() {
                    kt[a6][c6] += -dr_dg * s.d.b[a].v * g.d[c] - rn * s.d.b[a].d[c] + k10[a][c];
                }
            }
            if resp.status == ContactStatus::Closed {
                rows.push(super::mortar::Coupling {
                    nodes,
                    force,
                    tangent,
                    slave: node,
                    gap_gradient: row,
                    force_direction: Vec::new(),
                });
            }
        }
        out.push(NodeContact {
            node,
            gap,
            normal: n,
            force: [f[0], f[1]],
            stiffness: [[kt[0][0], kt[0][1]], [kt[1][0], kt[1][1]]],
            pressure: resp.pressure,
            status: resp.status,
            entity: k.segment,
            master: Some(MasterSegment {
                nodes: [m1, m2],
                xi: smoothed.as_ref().map_or(p.xi, |s| s.d.xi),
                forces: [[f[2], f[3]], [f[4], f[5]]],
                tangent: kt,
                gap_gradient,
            }),
            friction,
        });
    }
    sp.candidates = candidates;
    sp.memory = memory;
    if cp.strategy == ContactStrategy::ModifiedDoublePass || sp.self_contact {
        // both passes at once (self contact: both directions): report the
        // interface pressure (`super::interface_pressures`)
        let plain: Vec<([usize; 3], [f64; 6], [f64; 6])> = out
            .iter()
            .filter(|c| c.status == ContactStatus::Closed)
            .filter_map(|c| {
                let m = c.master.as_ref()?;
                let f = [
                    c.force[0],
                    c.force[1],
                    m.forces[0][0],
                    m.forces[0][1],
                    m.forces[1][0],
                    m.forces[1][1],
                ];
                Some(([c.node, m.nodes[0], m.nodes[1]], f, m.gap_gradient))
            })
            .collect();
        let elements: Vec<super::ElementForces<'_>> = match &couplings {
            Some(rows) => rows.iter().map(super::ElementForces::of_coupling).collect(),
            None => plain
                .iter()
                .map(|(nodes, force, grad)| super::ElementForces {
                    slave: nodes[0],
                    nodes,
                    force,
                    gap_gradient: grad,
                })
                .collect(),
        };
        let (slaves, areas) = (&state.slaves, &state.tributary);
        super::interface_pressures(&mut out, &elements, |n| {
            slaves
                .binary_search(&n)
                .ok()
                .and_then(|i| areas.get(i).copied())
        });
    }
    state.couplings = couplings;
    if super::log::debug_enabled() {
        for c in &out {
            if let Some(ms) = &c.master {
                eprintln!(
                    "[ctc contact] pair '{}': node {} -> segment {} {:?} xi {:.4} gap {:.4e} force {:?}",
                    cp.name, c.node, c.entity, ms.nodes, ms.xi, c.gap, c.force
                );
            }
        }
    }
    state.last_projection_tests = tests;
    state.last_brute_force_tests = brute;
    state.total_projection_tests += tests as u64;
    state.surface = Some(sp);
    out
}

/// Drops the redundant Lagrange rows of a two-way pair (modified double
/// pass, self contact; [`super::redundancy`]), after the evaluation and
/// the closed-gap start, before the forces are assembled: the active
/// nodes' rows in slave order (smoothed: the coupling's row; faceted: the
/// element's `d g / d x`) over the free coordinates (`free(node,
/// component)`: a row that differs from another only in prescribed
/// components is the same constraint on the unknowns). A redundant node
/// keeps its place in the active set but loses its multiplier, its force
/// and its row (its coupling). Other pairs: nothing.
pub fn drop_redundant(
    cp: &ContactPair,
    state: &mut PairState,
    out: &mut [NodeContact],
    free: &dyn Fn(usize, usize) -> bool,
) {
    let self_contact = state.surface.as_ref().is_some_and(|sp| sp.self_contact);
    if !matches!(cp.method, ContactMethod::Lagrange { .. })
        || !(cp.strategy == ContactStrategy::ModifiedDoublePass || self_contact)
    {
        return;
    }
    let mut couplings = state.couplings.take();
    let n = state.slaves.len();
    state.redundant.clear();
    state.redundant.resize(n, false);
    let mut owners = Vec::new();
    let mut rows: Vec<Vec<super::rows::NodeTerm>> = Vec::new();
    for (k, nc) in out.iter().enumerate() {
        let Some(i) = state.slave_index(nc.node) else {
            continue;
        };
        if !state.active.get(i).copied().unwrap_or(false) {
            continue;
        }
        let terms =
            |nodes: &[usize], grad: &[f64]| super::redundancy::free_row(nodes, grad, 2, free);
        let row = match couplings.as_deref() {
            Some(list) => match list.binary_search_by_key(&nc.node, |c| c.slave) {
                Ok(j) => terms(&list[j].nodes, &list[j].gap_gradient),
                Err(_) => continue,
            },
            None => match &nc.master {
                Some(ms) => terms(&[nc.node, ms.nodes[0], ms.nodes[1]], &ms.gap_gradient),
                None => continue,
            },
        };
        owners.push((k, i));
        rows.push(row);
    }
    let drop = super::redundancy::redundant_rows_of(&cp.name, &rows);
    for (&(k, i), _) in owners.iter().zip(&drop).filter(|(_, &d)| d) {
        state.redundant[i] = true;
        state.multiplier[i] = 0.0;
        let nc = &mut out[k];
        nc.force = [0.0; 2];
        nc.stiffness = [[0.0; 2]; 2];
        if let Some(ms) = &mut nc.master {
            ms.forces = [[0.0; 2]; 2];
            ms.tangent = [[0.0; 6]; 6];
        }
        if let Some(list) = couplings.as_mut() {
            if let Ok(j) = list.binary_search_by_key(&nc.node, |c| c.slave) {
                list.remove(j);
            }
        }
    }
    state.couplings = couplings;
}

/// Nodes of the master surface near segment `segment` of the side opposite
/// to the slave `slave` (the segment, its neighbours and theirs): the
/// solver couples the slave to all of them when it grows the sparsity
/// pattern, so that sliding to a neighbouring segment does not grow it
/// again.
pub fn neighbourhood(state: &PairState, slave: usize, segment: usize, out: &mut Vec<usize>) {
    let Some(sp) = &state.surface else {
        return;
    };
    let Ok(i) = state.slaves.binary_search(&slave) else {
        return;
    };
    let side = sp.side_of[i];
    let m = if sp.self_contact {
        0
    } else {
        1 - side as usize
    };
    let s = &sp.sides[m];
    let mut segs = vec![segment];
    for _ in 0..2 {
        let mut more = Vec::new();
        for &e in &segs {
            more.extend(s.prev.get(e).copied().flatten());
            more.extend(s.next.get(e).copied().flatten());
        }
        segs.extend(more);
        segs.sort_unstable();
        segs.dedup();
    }
    for e in segs {
        if let Some(ed) = s.edges.get(e) {
            out.extend_from_slice(ed);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Master surface with a kink at node 1: segments 0 -> 1 -> 2 (body on
    /// the left), the two segments at right angles.
    fn kinked(concave: bool) -> (Surface, Vec<[f64; 2]>) {
        // concave (re-entrant corner of the body): the body occupies
        // x < 0 or y < 0; walk (1, 0) -> (0, 0) -> (0, 1)
        // convex: the body occupies x < 0 and y < 0; walk (0, -1) -> (0, 0) -> (-1, 0)
        let x = if concave {
            vec![[1.0, 0.0], [0.0, 0.0], [0.0, 1.0], [0.0; 2]]
        } else {
            vec![[0.0, -1.0], [0.0, 0.0], [-1.0, 0.0], [0.0; 2]]
        };
        (Surface::new(&[[0, 1], [1, 2]]), x)
    }

    #[test]
    fn surface_neighbours_follow_the_walk() {
        let s = Surface::new(&[[0, 1], [1, 2], [5, 6]]);
        assert_eq!(s.prev, vec![None, Some(0), None]);
        assert_eq!(s.next, vec![Some(1), None, None]);
    }

    #[test]
    fn node_inside_a_concave_corner_is_not_lost() {
        // projections on both segments fall outside them (the dead zone of
        // the kink): the extended nearest segment keeps the contact
        let (s, x) = kinked(true);
        let mut tests = 0;
        let k = closest(&s, &x, [-0.05, -0.03], &[0, 1], &[], 0.5, &mut tests)
            .expect("contact kept in the dead zone");
        assert!(k.projection.gap < 0.0, "{k:?}");
        // the vertex: gap = minus the distance to it, normal towards it
        assert!(k.projection.corner, "{k:?}");
        let r = 0.05f64.hypot(0.03);
        assert!((k.projection.gap + r).abs() < 1e-15, "{k:?}");
        let n = k.projection.normal;
        assert!((n[0] - 0.05 / r).abs() < 1e-15 && (n[1] - 0.03 / r).abs() < 1e-15);
        // the same answer from either segment (continuous across the wedge)
        let k1 = closest(&s, &x, [-0.05, -0.03], &[1, 0], &[], 0.5, &mut tests).unwrap();
        assert_eq!(k1.projection.gap, k.projection.gap);
        assert_eq!(k1.projection.normal, k.projection.normal);
    }

    #[test]
    fn several_projections_keep_the_closest_and_convex_wedge_is_open() {
        let (s, x) = kinked(false);
        let mut tests = 0;
        // inside the body near a convex corner: both projections inside
        // their segments, the nearer face wins
        let k = closest(&s, &x, [-0.1, -0.05], &[0, 1], &[], 0.5, &mut tests).unwrap();
        assert_eq!(k.segment, 1);
        assert!((k.projection.gap + 0.05).abs() < 1e-15);
        // outside, beyond the corner: extended lines give positive gaps
        let k = closest(&s, &x, [0.1, 0.1], &[0, 1], &[], 0.5, &mut tests).unwrap();
        assert!(k.projection.gap > 0.0);
        // outside, in front of one face: no false contact from the other
        // face's extension
        let k = closest(&s, &x, [0.05, -0.01], &[0, 1], &[], 0.5, &mut tests).unwrap();
        assert_eq!(k.segment, 0);
        assert!((k.projection.gap - 0.05).abs() < 1e-15);
    }

    /// A slave node on a master vertex (to round-off) projects on both
    /// segments with the same smoothed gap: `closest_smoothed` keeps the
    /// segment of the last evaluation, whichever it is, instead of letting
    /// round-off choose (the sliding cylinder's pole switched 308 times);
    /// without a last segment the smaller `|g|` and the lower index win.
    #[test]
    fn smoothed_projection_on_a_vertex_keeps_the_last_segment() {
        // walked -x, a 9-degree kink at (0, 0), body below
        let k = 9f64.to_radians();
        let x = vec![
            [2.0, 0.0],
            [1.0, 0.0],
            [0.0, 0.0],
            [-k.cos(), -k.sin()],
            [-2.0 * k.cos(), -2.0 * k.sin()],
        ];
        let s = Surface::new(&[[0, 1], [1, 2], [2, 3], [3, 4]]);
        // on the vertex's nodal normal, 1e-3 inside, a few ulps off
        let nv = smoothing::Patch::new(
            [x[2], x[0], x[1], x[2], x[3]],
            true,
            true,
            smoothing::NO_SYMMETRY,
        )
        .unwrap()
        .nu[1];
        let xs = [-1e-3 * nv[0] + 1e-17, -1e-3 * nv[1]];
        let mut tests = 0;
        let run = |last: Option<usize>, tests: &mut usize| {
            closest_smoothed(&s, &x, xs, &[0, 1, 2, 3], &[], last, 0.5, tests)
                .unwrap()
                .segment
        };
        assert_eq!(run(Some(1), &mut tests), 1);
        assert_eq!(run(Some(2), &mut tests), 2);
        // a clear choice is not overridden by the last segment
        let far = [0.5, -1e-3];
        let k = closest_smoothed(&s, &x, far, &[0, 1, 2, 3], &[], Some(2), 0.5, &mut tests);
        assert_eq!(k.unwrap().segment, 1);
    }

    #[test]
    fn wedge_of_a_kink_that_is_not_a_right_angle_has_the_kink_side() {
        // a convex corner of 88 degrees (the walk turns left by 92 degrees
        // at the vertex (0, 0)): segment 0 (0, -1) -> (0, 0), normal
        // (1, 0); segment 1 towards (-cos 2deg.., -sin 2deg..). A node in
        // the corner's wedge near segment 0's normal is in front of
        // segment 0 but behind segment 1's extended line: both segments
        // must give it the same positive distance to the vertex (issue
        // 19: the released blade's corner on another blade's tip corner
        // got -7.4e-3 from one face and +2.8e-3 from the other and
        // cycled between them to the smallest cutback)
        let turn = 92f64.to_radians();
        let dout = [-turn.sin(), turn.cos()];
        let x = vec![[0.0, -1.0], [0.0, 0.0], dout];
        let s = Surface::new(&[[0, 1], [1, 2]]);
        let xs: [f64; 2] = [0.01, 1e-4];
        let r = xs[0].hypot(xs[1]);
        let mut tests = 0;
        for order in [[0, 1], [1, 0]] {
            let k = closest(&s, &x, xs, &order, &[], 0.5, &mut tests).unwrap();
            assert!(k.projection.corner, "{k:?}");
            assert!((k.projection.gap - r).abs() < 1e-15, "{order:?}: {k:?}");
        }
        // the concave counterpart (the walk reversed): the wedge is inside
        // (the same point is in its wedge, now behind segment 1 and in
        // front of segment 0's extension: the vertex, inside the body)
        let x = vec![dout, [0.0, 0.0], [0.0, -1.0]];
        for order in [[0, 1], [1, 0]] {
            let k = closest(&s, &x, xs, &order, &[], 0.5, &mut tests).unwrap();
            assert!(k.projection.corner, "{k:?}");
            assert!((k.projection.gap + r).abs() < 1e-15, "{order:?}: {k:?}");
        }
    }

    /// A node deep inside a convex sliding master keeps its segment (issue
    /// 18, the 2D ironing slide): the die's arc (radius 3, 200..340
    /// degrees in 28 segments of 5 degrees, body on the left: the walk is
    /// counterclockwise), a slab node touching segment 14 (272.5 deg);
    /// then the die slides 0.6 along x (2.3 segment lengths) and a Newton
    /// step puts the node 0.56 inside it, past `max(prof, L) = 0.5`.
    /// Searched from its memory it keeps the segment under it, at its
    /// depth; a node without memory there is not taken (rule 3: the far
    /// side of a thin body), nor was it from the last segment and its
    /// neighbours alone (the search before the walk: the node was lost
    /// and stayed inside the die).
    #[test]
    fn node_deep_inside_a_convex_sliding_master_keeps_its_segment() {
        let (r, prof) = (3.0f64, 0.5);
        let arc = |c: [f64; 2]| -> Vec<[f64; 2]> {
            (0..=28)
                .map(|k| {
                    let t = (200.0 + 5.0 * k as f64).to_radians();
                    [c[0] + r * t.cos(), c[1] + r * t.sin()]
                })
                .collect()
        };
        let edges: Vec<[usize; 2]> = (0..28).map(|k| [k, k + 1]).collect();
        let s = Surface::new(&edges);
        let mut tests = 0;
        // touching: a node just inside the chord of segment 14
        let t = 272.5f64.to_radians();
        let c0 = [0.0, 3.0];
        let chord = r * 2.5f64.to_radians().cos();
        let xs = [
            c0[0] + (chord - 1e-3) * t.cos(),
            c0[1] + (chord - 1e-3) * t.sin(),
        ];
        let x = arc(c0);
        let k = closest(&s, &x, xs, &[13, 14, 15], &[], prof, &mut tests).unwrap();
        assert_eq!(k.segment, 14);
        assert!((k.projection.gap + 1e-3).abs() < 1e-12, "{k:?}");
        // the die slides 0.6 along x, the node is 0.56 inside it
        let c1 = [0.6, 3.0];
        let x = arc(c1);
        let xs = [xs[0], xs[1] + 0.6];
        let (dx, dy) = (xs[0] - c1[0], xs[1] - c1[1]);
        let angle = dy.atan2(dx).to_degrees().rem_euclid(360.0);
        let under = ((angle - 200.0) / 5.0).floor() as usize;
        assert!(under + 2 <= 14, "the foot is 2+ segments away: {under}");
        let half = 2.5f64.to_radians();
        let mid = (200.0 + 5.0 * under as f64 + 2.5).to_radians();
        // depth below the chord of segment `under`
        let depth = r * half.cos() - (dx * mid.cos() + dy * mid.sin());
        assert!(depth > prof && depth > k.projection.length, "{depth}");
        // the last segment and its neighbours alone: lost
        assert!(closest(&s, &x, xs, &[13, 14, 15], &[], prof, &mut tests).is_none());
        // no memory, every segment a candidate: not taken (too deep)
        let all: Vec<usize> = (0..28).collect();
        assert!(closest(&s, &x, xs, &all, &[], prof, &mut tests).is_none());
        // from its memory: the walk reaches the segment under it
        let mut memory = Vec::new();
        memory_walk(&s, &x, xs, 14, &mut tests, &mut memory);
        assert!(memory.contains(&under), "{memory:?} lacks {under}");
        assert!(memory.windows(2).all(|w| w[0] < w[1]), "{memory:?}");
        let k = closest(&s, &x, xs, &memory, &memory, prof, &mut tests).expect("kept");
        assert_eq!(k.segment, under);
        assert!((k.projection.gap + depth).abs() < 1e-12, "{k:?} vs {depth}");
        // memory exempts from the depth window only its own segments
        assert!(closest(&s, &x, xs, &all, &[14], prof, &mut tests).is_none());
    }

    #[test]
    fn free_end_extends_only_by_the_tolerance() {
        let s = Surface::new(&[[0, 1]]);
        let x = vec![[1.0, 0.0], [0.0, 0.0]];
        let mut tests = 0;
        assert!(closest(&s, &x, [-0.01, -0.001], &[0], &[], 0.5, &mut tests).is_some());
        assert!(closest(&s, &x, [-0.1, -0.001], &[0], &[], 0.5, &mut tests).is_none());
    }

    #[test]
    fn double_pass_swaps_sides_at_each_commit_and_rolls_back() {
        let mut sp = SurfacePair::default();
        let d = ContactStrategy::DoublePass;
        assert_eq!(sp.slave_sides(d), [true, false]);
        sp.commit();
        assert_eq!(sp.slave_sides(d), [false, true]);
        sp.increments += 1;
        sp.rollback();
        assert_eq!(sp.slave_sides(d), [false, true]);
        assert_eq!(
            sp.slave_sides(ContactStrategy::ModifiedDoublePass),
            [true, true]
        );
        assert_eq!(sp.slave_sides(ContactStrategy::SinglePass), [true, false]);
    }
}
