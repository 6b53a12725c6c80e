//! Coulomb friction on a node-to-segment element (deformable master): the
//! regularized law of [`super::friction`] with the slip measured on the
//! master segment.
//!
//! The stick point is a material point of the master surface, stored by
//! its **reference** coordinates `X_a` (undeformed configuration). On the
//! current segment `x_1 -> x_2` (reference `X_1 -> X_2`) it has the
//! parameter `xi_a = (X_a - X_1) . (X_2 - X_1) / |X_2 - X_1|^2` (outside
//! `[0, 1]` when the stick point lies on a neighbouring segment: the line
//! is extended), so the tangential gap is the slip along the current
//! segment, `g_T = (xi - xi_a) L = (x_s - x_1) . t - xi_a L`.
//!
//! Forces over `[x_s, x_1, x_2]`: `R_T [t, -(1 - xi) t, -xi t]` (the
//! reaction acts at the projection point; forces balance, the moment is
//! `g R_T`, of the order of the penalty penetration). The normal force is
//! `R_N(x) = lambda* - alpha_N g` (penalty: `lambda* = 0`) or the Lagrange
//! multiplier (constant). The exact 6x6 tangent `-d f / d x` (stick and
//! slip, with the rotation and stretching of the segment and the motion of
//! the projection point) is obtained with forward-mode dual numbers
//! ([`crate::material::dual`]); it is not symmetric. In the increment of
//! a first impact the stick point's parameter depends on `x`
//! (`anchor_rate`, its derivative), which the tangent includes.
//!
//! Under `smoothing = nodal` ([`respond_smoothed`], [`apply_smoothed`])
//! the basis is the smoothed normal's tangent at the projection and the
//! element has the 10 coordinates of [`super::smoothing`]; the stick point
//! is measured on the chord of the reference segment that holds it (this
//! one or a neighbour), so the slip is continuous when the node passes a
//! master node. A trial force on the cone to round-off slips
//! ([`CONE_TIE`], as node-to-facet and mortar).

use super::friction::{FrictionStatus, NodeFriction};
use super::friction_facet::CONE_TIE;
use super::smoothing;
use crate::material::dual::{Dual, Scalar};

/// Six seeded directions: `[x_s, x_1, x_2]`.
type D6 = Dual<6>;

/// Inputs of the friction law on one element.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SegmentFriction {
    /// Friction coefficient.
    pub mu: f64,
    /// Tangential penalty `alpha_T` (force per unit slip).
    pub alpha_t: f64,
    /// Tangential multiplier shift `lambda_T*` (augmented Lagrangian; 0 for
    /// penalty).
    pub shift: f64,
    /// Normal force law: `R_N = normal_shift - normal_stiffness g` (penalty:
    /// `0 - alpha_N g`; Lagrange: `lambda - 0 g`).
    pub normal_shift: f64,
    /// See `normal_shift`.
    pub normal_stiffness: f64,
}

impl SegmentFriction {
    /// The law of element `e` (its method's tangential penalty, the
    /// augmented shift) with the normal force passed through the current
    /// one: `R_N(x) = R_N + alpha_N (g_now - g)` (penalty and augmented
    /// Lagrangian alike).
    fn of(
        law: &crate::model::Friction,
        method: &crate::model::ContactMethod,
        e: &Element,
        shift: f64,
        alpha_n: f64,
        gap_now: f64,
    ) -> Self {
        SegmentFriction {
            mu: law.mu,
            alpha_t: super::friction::tangential_stiffness(law, method, e.tributary),
            shift,
            normal_shift: e.normal_force + alpha_n * gap_now,
            normal_stiffness: alpha_n,
        }
    }
}

/// Friction contribution of one element.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SegmentResponse {
    /// Status, force, gap, slip increment (along the current `t`) and work.
    pub friction: NodeFriction,
    /// Forces over `[x_s, x_1, x_2]`.
    pub forces: [f64; 6],
    /// `-d forces / d x` (6x6, not symmetric).
    pub tangent: [[f64; 6]; 6],
    /// New stick point (reference coordinates) after the return map.
    pub anchor: [f64; 2],
}

/// The slave node projects on a master vertex, the end of the segment
/// seen as a circle of radius 0 ([`super::segment::SegmentProjection::corner`]):
/// the normal points from the vertex to the node (`side` times), and the
/// friction acts in the tangent of that normal.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Vertex {
    /// The segment's end: 0 (`x_1`) or 1 (`x_2`).
    pub end: usize,
    /// `1`: the node is outside the body (convex kink), `-1`: inside.
    pub side: f64,
}

/// The smallest `t . tau` (cosine between the segment and the vertex's
/// tangent) the stick point's update divides by: 84 degrees, beyond any
/// kink a node slides over (the normal turns by the kink's angle across
/// the vertex's wedge).
const MIN_COSINE: f64 = 0.1;

/// Friction on the element `x_s` against `x_1 -> x_2` (current positions;
/// `reference` = `[X_1, X_2]`), stick point `anchor` (reference frame).
///
/// The tangent `tau` is the one of the normal that gives the gap ("one
/// geometry everywhere"): the segment's `t` when the node projects inside
/// the segment, and at a vertex projection (`vertex`) the perpendicular to
/// the vertex's normal, so the friction force is orthogonal to the normal
/// force (along the segment it was off by the normal's turn, 3.5 degrees
/// on examples/blade_loss.ctc's casing). The tangential gap is `g_T =
/// (x_s - x_a) . tau`, `x_a` the stick point on the segment's line, and
/// the reaction `-R_T tau` acts at the projection point (the vertex).
#[allow(clippy::too_many_arguments)]
pub fn respond(
    law: &SegmentFriction,
    xs: [f64; 2],
    x1: [f64; 2],
    x2: [f64; 2],
    reference: [[f64; 2]; 2],
    anchor: [f64; 2],
    anchor_rate: Option<[f64; 6]>,
    vertex: Option<Vertex>,
) -> Option<SegmentResponse> {
    let v = |x: [f64; 2], k: usize| [D6::var(x[0], k), D6::var(x[1], k + 1)];
    let (s, p1, p2) = (v(xs, 0), v(x1, 2), v(x2, 4));
    let a = [p2[0] - p1[0], p2[1] - p1[1]];
    let len = (a[0] * a[0] + a[1] * a[1]).sqrt();
    if !(len.re() > 0.0 && len.re().is_finite()) {
        return None;
    }
    let t = [a[0] / len, a[1] / len];
    let d = [s[0] - p1[0], s[1] - p1[1]];
    // the normal, its tangent (`tau = (-n_y, n_x)`, `t` on the segment),
    // the gap and the projection's parameter
    let (tau, gap, xi) = match vertex {
        None => {
            let n = [t[1], -t[0]];
            let along = d[0] * t[0] + d[1] * t[1];
            (t, d[0] * n[0] + d[1] * n[1], along / len)
        }
        Some(vx) => {
            let xv = if vx.end == 0 { p1 } else { p2 };
            let r = [s[0] - xv[0], s[1] - xv[1]];
            let dist = (r[0] * r[0] + r[1] * r[1]).sqrt();
            if dist.re().is_nan() || dist.re() <= 0.0 {
                return None;
            }
            let n = [r[0] * vx.side / dist, r[1] * vx.side / dist];
            ([n[1] * -1.0, n[0]], dist * vx.side, D6::cst(vx.end as f64))
        }
    };
    // stick point parameter on the current segment (reference geometry)
    let [r1, r2] = reference;
    let ar = [r2[0] - r1[0], r2[1] - r1[1]];
    let lr2 = ar[0] * ar[0] + ar[1] * ar[1];
    if lr2 <= 0.0 {
        return None;
    }
    let xi_a_value = ((anchor[0] - r1[0]) * ar[0] + (anchor[1] - r1[1]) * ar[1]) / lr2;
    // in the increment of a first impact the stick point depends on x
    let xi_a = match anchor_rate {
        Some(d) => D6 { v: xi_a_value, d },
        None => D6::cst(xi_a_value),
    };
    // g_T = (x_s - x_a) . tau, x_a = x_1 + xi_a (x_2 - x_1)
    let gt = (d[0] - a[0] * xi_a) * tau[0] + (d[1] - a[1] * xi_a) * tau[1];
    let xi_a = xi_a_value;
    let rn = (gap * -law.normal_stiffness) + law.normal_shift;
    let rn = if rn.re() > 0.0 { rn } else { D6::cst(0.0) };
    let limit = rn * law.mu;
    let trial = (gt * -law.alpha_t) + law.shift;
    // a trial within `CONE_TIE` below the cone slips (node-to-facet's tie
    // rule: a node that slipped starts the next increment on the cone to
    // round-off, and its tangent must not depend on the last bits)
    let (rt, status) = if trial.re().abs() <= limit.re() * (1.0 - CONE_TIE) && limit.re() > 0.0 {
        (trial, FrictionStatus::Stick)
    } else {
        (limit * trial.re().signum(), FrictionStatus::Slip)
    };
    let ds = if law.alpha_t > 0.0 {
        (rt.re() - trial.re()) / law.alpha_t
    } else {
        0.0
    };
    let w = [D6::cst(1.0), (xi * -1.0) + 1.0, xi];
    let sign = [1.0, -1.0, -1.0];
    let mut forces = [0.0; 6];
    let mut tangent = [[0.0; 6]; 6];
    for node in 0..3 {
        for c in 0..2 {
            let f = rt * w[node] * tau[c] * sign[node];
            forces[2 * node + c] = f.re();
            for (j, dj) in f.d.iter().enumerate() {
                tangent[2 * node + c][j] = -dj;
            }
        }
    }
    // the stick point moves along the segment's line so that `g_T` drops
    // by the slip: by `ds / (t . tau)` (1 inside the segment)
    let cosine = (t[0].re() * tau[0].re() + t[1].re() * tau[1].re()).max(MIN_COSINE);
    let xi_new = xi_a + ds / (len.re() * cosine);
    Some(SegmentResponse {
        friction: NodeFriction {
            status,
            tangential_force: rt.re(),
            tangential_gap: gt.re(),
            slip: ds,
            gap_gradient: [tau[0].re(), tau[1].re()],
            dissipation: -rt.re() * ds,
            traction: [rt.re() * tau[0].re(), rt.re() * tau[1].re()],
            slip_vector: [ds * tau[0].re(), ds * tau[1].re()],
        },
        forces,
        tangent,
        anchor: [r1[0] + xi_new * ar[0], r1[1] + xi_new * ar[1]],
    })
}

/// A closed node-to-segment element as seen by the friction law.
#[derive(Debug, Clone, Copy)]
pub struct Element {
    /// Slave index in the pair's per-slave vectors.
    pub slave: usize,
    /// Current slave position.
    pub xs: [f64; 2],
    /// Master segment nodes `m1 -> m2`.
    pub nodes: [usize; 2],
    /// Projection parameter of the slave node on the segment.
    pub xi: f64,
    /// Normal force `R_N >= 0` of the element.
    pub normal_force: f64,
    /// Open or closed.
    pub status: super::ContactStatus,
    /// Tributary area of the slave node.
    pub tributary: f64,
    /// The projection is the segment's end (`None`: inside the segment).
    pub vertex: Option<Vertex>,
}

/// Adds the friction forces and tangent of a node-to-segment element to
/// its normal part (`forces`, `tangent` over `[x_s, x_1, x_2]`) and updates
/// the trial friction state. In the increment in which a node first
/// touches, with `first_impact = intersect` (the default) the stick point
/// is where the node met the segment: the node and the segment's ends move
/// at constant velocity from their converged positions `committed` to `x`
/// ([`super::impact::segment_intersection`]; a node that already touched
/// or penetrated at the start sticks where it was), and friction acts on
/// the rest of the increment; with `first_impact = frictionless` that
/// increment has no tangential force and the stick point is where the node
/// is at its end. The stick point is held fixed within a Newton iteration
/// (its dependence on `x` is left out of the tangent, in that increment
/// only). Lagrange multipliers: no friction (rejected by the deck
/// validation).
#[allow(clippy::too_many_arguments)]
pub fn apply(
    law: &crate::model::Friction,
    method: &crate::model::ContactMethod,
    reference: &[[f64; 2]],
    x: &[[f64; 2]],
    committed: &[[f64; 2]],
    e: &Element,
    state: &mut super::friction::FrictionState,
    forces: &mut [f64; 6],
    tangent: &mut [[f64; 6]; 6],
) -> NodeFriction {
    let i = e.slave;
    let Some(Start {
        anchor,
        rate: anchor_rate,
        shift,
        alpha_n,
        r: [r1, r2],
        x: [x1, x2],
    }) = start(law, method, reference, x, committed, e, state)
    else {
        return NodeFriction::default();
    };
    // R_N(x) = R_N + alpha_N (g_now - g): pass the law through the current
    // force (penalty and augmented Lagrangian alike)
    // (the vertex's gap at a vertex projection)
    let gap_now = match e.vertex {
        None => {
            let a = [x2[0] - x1[0], x2[1] - x1[1]];
            let l = a[0].hypot(a[1]);
            let n = [a[1] / l, -a[0] / l];
            (e.xs[0] - x1[0]) * n[0] + (e.xs[1] - x1[1]) * n[1]
        }
        Some(v) => {
            let xv = if v.end == 0 { x1 } else { x2 };
            v.side * (e.xs[0] - xv[0]).hypot(e.xs[1] - xv[1])
        }
    };
    let seg = SegmentFriction::of(law, method, e, shift, alpha_n, gap_now);
    let Some(r) = respond(&seg, e.xs, x1, x2, [r1, r2], anchor, anchor_rate, e.vertex) else {
        return NodeFriction::default();
    };
    add_element(forces, tangent, &r.forces, &r.tangent);
    state.anchor[i] = Some(r.anchor);
    state.position[i] = e.xs;
    r.friction
}

/// Adds an element's friction forces and tangent (`N` coordinates) to the
/// contact element's.
fn add_element<const N: usize>(
    forces: &mut [f64; N],
    tangent: &mut [[f64; N]; N],
    rf: &[f64; N],
    rt: &[[f64; N]; N],
) {
    for ((f, row), (rf, rrow)) in forces
        .iter_mut()
        .zip(tangent.iter_mut())
        .zip(rf.iter().zip(rt))
    {
        *f += rf;
        for (k, rk) in row.iter_mut().zip(rrow) {
            *k += rk;
        }
    }
}

/// Friction contribution of one smoothed element (`smoothing = nodal`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SmoothedResponse {
    /// Status, force, gap, slip increment (along `tau`) and work.
    pub friction: NodeFriction,
    /// Forces over `[x_s, x_0, x_1, x_2, x_3]`.
    pub forces: [f64; smoothing::N],
    /// `-d forces / d x` (10x10, not symmetric).
    pub tangent: [[f64; smoothing::N]; smoothing::N],
    /// New stick point (reference coordinates) after the return map.
    pub anchor: [f64; 2],
}

/// Where the stick point of reference coordinates `anchor` is on the
/// master around segment `X_1 -> X_2` of `reference = [X_0, X_1, X_2,
/// X_3]`: the segment (`0`), the previous one `X_0 -> X_1` (`-1`, when its
/// parameter on the segment's line is below 0 and `has[0]`) or the next
/// one `X_2 -> X_3` (`1`), and its parameter on that segment (0 at its
/// first node; the line extended past the neighbour, if the node slid
/// further in one increment).
fn stick_segment(reference: [[f64; 2]; 4], has: [bool; 2], anchor: [f64; 2]) -> Option<(i8, f64)> {
    let on = |a: [f64; 2], b: [f64; 2]| {
        let e = [b[0] - a[0], b[1] - a[1]];
        let l2 = e[0] * e[0] + e[1] * e[1];
        (l2 > 0.0).then(|| ((anchor[0] - a[0]) * e[0] + (anchor[1] - a[1]) * e[1]) / l2)
    };
    let [r0, r1, r2, r3] = reference;
    let xi = on(r1, r2)?;
    if xi < 0.0 && has[0] {
        on(r0, r1).map(|q| (-1, q))
    } else if xi > 1.0 && has[1] {
        on(r2, r3).map(|q| (1, q))
    } else {
        Some((0, xi))
    }
}

/// Friction on the smoothed element (`smoothing = nodal`, [`smoothing`]):
/// the slave `x_s` against segment `x_1 -> x_2` with the far nodes `x_0`,
/// `x_3` of its neighbours (`x = [x_s, x_0, x_1, x_2, x_3]`, `has` which
/// neighbours exist, `sym` the coordinates the nodal normals drop),
/// projected at `xi` ([`smoothing::project`]).
///
/// One geometry everywhere: the friction acts along `tau = (-n_y, n_x)`,
/// the tangent of the smoothed normal `n(xi)` at the projection, so it is
/// orthogonal to the normal force and continuous where the node passes a
/// master node. The stick point is a material point of the master: its
/// reference coordinates lie on a reference segment ([`stick_segment`]:
/// this one or a neighbour, which `x_0`, `x_3` carry), `x_a` the same
/// parameter on the current segment (the chord point: on a neighbour when
/// the node slid past the master node, continuous across it). The
/// tangential gap is `g_T = (x_s - x_a) . tau`, the reaction `-R_T tau`
/// acts at the projection point `x(xi)` with weights `1 - xi`, `xi`:
/// forces sum to zero, their moment is `g R_T` (the slave is `g n` off the
/// point). `R_N = normal_shift - normal_stiffness g` with the smoothed
/// gap. The tangent `-d f / d x` over the 10 coordinates is exact (dual
/// numbers through the projection, [`smoothing::dual`]: `tau` depends on
/// `x_0 .. x_3` through the nodal normals and on `xi(x)`). After a slip
/// the new stick point is where `g_T` has dropped by the slip, on the
/// current segment or, past its end, on the neighbour's chord.
/// `anchor_rate`: `d xi_a / d x` of a first impact's stick point on the
/// segment (over the 10 coordinates).
#[allow(clippy::too_many_arguments)]
pub fn respond_smoothed(
    law: &SegmentFriction,
    x: [[f64; 2]; 5],
    has: [bool; 2],
    sym: smoothing::Symmetry,
    xi: f64,
    reference: [[f64; 2]; 4],
    anchor: [f64; 2],
    anchor_rate: Option<[f64; smoothing::N]>,
) -> Option<SmoothedResponse> {
    type A = smoothing::Ad10;
    let p = smoothing::dual(x, has[0], has[1], sym, xi)?;
    let [s, p0, p1, p2, p3] = p.x;
    let n = p.normal;
    let tau = [-n[1], n[0]];
    let (side, q) = stick_segment(reference, has, anchor)?;
    // the stick point on the current chord
    let (a, b) = match side {
        -1 => (p0, p1),
        1 => (p2, p3),
        _ => (p1, p2),
    };
    let q = match (side, anchor_rate) {
        (0, Some(d)) => A { v: q, d },
        _ => A::cst(q),
    };
    let xa = [a[0] + (b[0] - a[0]) * q, a[1] + (b[1] - a[1]) * q];
    let gt = (s[0] - xa[0]) * tau[0] + (s[1] - xa[1]) * tau[1];
    let rn = p.gap * -law.normal_stiffness + law.normal_shift;
    let rn = if rn.v > 0.0 { rn } else { A::cst(0.0) };
    let limit = rn * law.mu;
    let trial = gt * -law.alpha_t + law.shift;
    // the cone tie of `respond`
    let (rt, status) = if trial.v.abs() <= limit.v * (1.0 - CONE_TIE) && limit.v > 0.0 {
        (trial, FrictionStatus::Stick)
    } else {
        (limit * trial.v.signum(), FrictionStatus::Slip)
    };
    let ds = if law.alpha_t > 0.0 {
        (rt.v - trial.v) / law.alpha_t
    } else {
        0.0
    };
    // R_T tau on the slave, -(1 - xi) R_T tau and -xi R_T tau on x_1, x_2
    let w = [A::cst(1.0), A::cst(0.0), -(p.xi + -1.0), p.xi, A::cst(0.0)];
    let sign = [1.0, 0.0, -1.0, -1.0, 0.0];
    let mut forces = [0.0; smoothing::N];
    let mut tangent = [[0.0; smoothing::N]; smoothing::N];
    for node in [0, 2, 3] {
        for c in 0..2 {
            let f = rt * w[node] * tau[c] * sign[node];
            forces[2 * node + c] = f.v;
            for (j, dj) in f.d.iter().enumerate() {
                tangent[2 * node + c][j] = -dj;
            }
        }
    }
    // the new stick point: g_T - ds from the slave along tau, on the chord
    // of this segment, or of the neighbour past its end
    let v = |z: [A; 2]| [z[0].v, z[1].v];
    let (xs, t) = (v(s), v(tau));
    let gt_new = gt.v - ds;
    let param = |a: [f64; 2], b: [f64; 2]| {
        let e = [b[0] - a[0], b[1] - a[1]];
        let l = e[0].hypot(e[1]);
        let along = (e[0] * t[0] + e[1] * t[1]).max(MIN_COSINE * l);
        ((xs[0] - a[0]) * t[0] + (xs[1] - a[1]) * t[1] - gt_new) / along
    };
    let [r0, r1, r2, r3] = reference;
    let on = |ra: [f64; 2], rb: [f64; 2], q: f64| {
        [ra[0] + q * (rb[0] - ra[0]), ra[1] + q * (rb[1] - ra[1])]
    };
    let (x0, x1, x2, x3) = (v(p0), v(p1), v(p2), v(p3));
    let xi_new = param(x1, x2);
    let new_anchor = if xi_new < 0.0 && has[0] {
        on(r0, r1, param(x0, x1))
    } else if xi_new > 1.0 && has[1] {
        on(r2, r3, param(x2, x3))
    } else {
        on(r1, r2, xi_new)
    };
    Some(SmoothedResponse {
        friction: NodeFriction {
            status,
            tangential_force: rt.v,
            tangential_gap: gt.v,
            slip: ds,
            gap_gradient: t,
            dissipation: -rt.v * ds,
            traction: [rt.v * t[0], rt.v * t[1]],
            slip_vector: [ds * t[0], ds * t[1]],
        },
        forces,
        tangent,
        anchor: new_anchor,
    })
}

/// A closed smoothed element: the element of [`apply`] with the far
/// nodes of the neighbouring segments (`x_0`, `x_3`) its normal depends
/// on, and its smoothed gap.
#[derive(Debug, Clone, Copy)]
pub struct SmoothedElement {
    /// The element (`xi` the smoothed projection's, `vertex` `None`).
    pub element: Element,
    /// Far nodes `x_0` (before `m1`) and `x_3` (after `m2`).
    pub far: [Option<usize>; 2],
    /// The coordinates the nodal normals drop at a symmetry line or the
    /// axis ([`smoothing::Symmetry`]).
    pub sym: smoothing::Symmetry,
    /// The smoothed gap.
    pub gap: f64,
}

/// [`apply`] on a smoothed element ([`respond_smoothed`]): adds the
/// friction forces and tangent over `[x_s, x_0, x_1, x_2, x_3]` to
/// `forces`, `tangent` and updates the trial friction state. The first
/// impact is found on the chord `x_1 -> x_2` as in [`apply`].
#[allow(clippy::too_many_arguments)]
pub fn apply_smoothed(
    law: &crate::model::Friction,
    method: &crate::model::ContactMethod,
    reference: &[[f64; 2]],
    x: &[[f64; 2]],
    committed: &[[f64; 2]],
    se: &SmoothedElement,
    state: &mut super::friction::FrictionState,
    forces: &mut [f64; smoothing::N],
    tangent: &mut [[f64; smoothing::N]; smoothing::N],
) -> NodeFriction {
    let e = &se.element;
    let Some(Start {
        anchor,
        rate,
        shift,
        alpha_n,
        r: [r1, r2],
        x: [x1, x2],
    }) = start(law, method, reference, x, committed, e, state)
    else {
        return NodeFriction::default();
    };
    let [m1, m2] = e.nodes;
    let node = |k: Option<usize>, own: usize| k.unwrap_or(own);
    let (n0, n3) = (node(se.far[0], m1), node(se.far[1], m2));
    let (Some(&r0), Some(&r3), Some(&x0), Some(&x3)) =
        (reference.get(n0), reference.get(n3), x.get(n0), x.get(n3))
    else {
        return NodeFriction::default();
    };
    let seg = SegmentFriction::of(law, method, e, shift, alpha_n, se.gap);
    // the first impact's rate over [x_s, x_1, x_2] into the 10 coordinates
    let rate = rate.map(|d| {
        let mut r = [0.0; smoothing::N];
        for (k, &to) in [0usize, 1, 4, 5, 6, 7].iter().enumerate() {
            r[to] = d[k];
        }
        r
    });
    let has = [se.far[0].is_some(), se.far[1].is_some()];
    let Some(r) = respond_smoothed(
        &seg,
        [e.xs, x0, x1, x2, x3],
        has,
        se.sym,
        e.xi,
        [r0, r1, r2, r3],
        anchor,
        rate,
    ) else {
        return NodeFriction::default();
    };
    add_element(forces, tangent, &r.forces, &r.tangent);
    state.anchor[e.slave] = Some(r.anchor);
    state.position[e.slave] = e.xs;
    r.friction
}

/// The stick point a closed element's trial is measured from, with the
/// method's data; `None` when the element has no friction in this
/// evaluation (open, Lagrange, the frictionless first impact: the state is
/// updated for those).
struct Start {
    anchor: [f64; 2],
    rate: Option<[f64; 6]>,
    shift: f64,
    alpha_n: f64,
    r: [[f64; 2]; 2],
    x: [[f64; 2]; 2],
}

fn start(
    law: &crate::model::Friction,
    method: &crate::model::ContactMethod,
    reference: &[[f64; 2]],
    x: &[[f64; 2]],
    committed: &[[f64; 2]],
    e: &Element,
    state: &mut super::friction::FrictionState,
) -> Option<Start> {
    use crate::model::ContactMethod;
    let i = e.slave;
    if e.status != super::ContactStatus::Closed || i >= state.anchor.len() {
        state.open(i, e.xs);
        return None;
    }
    let [m1, m2] = e.nodes;
    let (Some(&r1), Some(&r2), Some(&x1), Some(&x2)) =
        (reference.get(m1), reference.get(m2), x.get(m1), x.get(m2))
    else {
        return None;
    };
    let mut anchor_rate = None;
    let start = match state.committed_anchor[i] {
        Some(a) => a,
        None => {
            let s0 = state.committed_position[i];
            let ends = (committed.get(m1), committed.get(m2));
            let hit = first_impact(s0, e.xs, ends, (x1, x2));
            if let Some((tau, _)) = hit {
                state.record_impact(tau);
            }
            match (law.first_impact, hit) {
                (crate::model::FirstImpact::Intersect, Some((tau, xi))) => {
                    if tau > 0.0 {
                        anchor_rate = Some(impact_rate(s0, ends, [e.xs, x1, x2], xi));
                    }
                    reference_point([r1, r2], xi)
                }
                _ => {
                    // frictionless in this increment
                    state.anchor[i] = Some(reference_point([r1, r2], e.xi));
                    state.position[i] = e.xs;
                    return None;
                }
            }
        }
    };
    let anchor = state.base[i].unwrap_or(start);
    let alpha_n = super::penalty::effective_stiffness(method, e.tributary);
    let shift = match method {
        ContactMethod::Penalty { .. } => 0.0,
        ContactMethod::AugmentedLagrange { .. } => state.multiplier[i],
        ContactMethod::Lagrange { .. } => return None,
    };
    // the Uzawa base (augmented Lagrangian) is a fixed stick point
    let rate = anchor_rate.filter(|_| state.base[i].is_none());
    Some(Start {
        anchor,
        rate,
        shift,
        alpha_n,
        r: [r1, r2],
        x: [x1, x2],
    })
}

/// Where, in the increment, a slave node going `s0 -> s1` met the segment
/// whose ends go `a0 -> a1`, `b0 -> b1` (all at constant velocity): the
/// fraction `tau` and the segment parameter there. A node already on or
/// behind the segment's line at the start (gap <= 0, projection on the
/// segment) met it at `tau = 0` where it was. `None` when the ends' start
/// positions are unknown or the node never crossed the segment.
fn first_impact(
    s0: [f64; 2],
    s1: [f64; 2],
    start: (Option<&[f64; 2]>, Option<&[f64; 2]>),
    end: ([f64; 2], [f64; 2]),
) -> Option<(f64, f64)> {
    let (Some(&a0), Some(&b0)) = start else {
        return None;
    };
    let (a1, b1) = end;
    let e = [b0[0] - a0[0], b0[1] - a0[1]];
    let l2 = e[0] * e[0] + e[1] * e[1];
    if l2 > 0.0 {
        let d = [s0[0] - a0[0], s0[1] - a0[1]];
        let xi = (d[0] * e[0] + d[1] * e[1]) / l2;
        // body on the left of a -> b: gap = d . (e_y, -e_x) / |e|
        let gap = (d[0] * e[1] - d[1] * e[0]) / l2.sqrt();
        if gap <= 0.0 && (0.0..=1.0).contains(&xi) {
            return Some((0.0, xi));
        }
    }
    super::impact::segment_intersection([s0, s1], [a0, a1], [b0, b1])
}

/// `d xi / d [x_s, x_1, x_2]` of the segment parameter where the node met
/// the segment ([`first_impact`]) by central differences (step `1e-7`
/// of the segment's length; one-sided where the path leaves the segment,
/// 0 where it is undefined): the stick point of a first impact moves with
/// the end positions, and Newton needs that rate to converge quadratically.
fn impact_rate(
    s0: [f64; 2],
    ends: (Option<&[f64; 2]>, Option<&[f64; 2]>),
    x: [[f64; 2]; 3],
    xi: f64,
) -> [f64; 6] {
    let len = (x[2][0] - x[1][0]).hypot(x[2][1] - x[1][1]);
    let h = 1e-7 * len.max(f64::MIN_POSITIVE);
    let at = |j: usize, dh: f64| {
        let mut y = x;
        y[j / 2][j % 2] += dh;
        first_impact(s0, y[0], ends, (y[1], y[2])).map(|(_, xi)| xi)
    };
    std::array::from_fn(|j| match (at(j, h), at(j, -h)) {
        (Some(p), Some(m)) => (p - m) / (2.0 * h),
        (Some(p), None) => (p - xi) / h,
        (None, Some(m)) => (xi - m) / h,
        (None, None) => 0.0,
    })
}

/// The reference point of the master surface at parameter `xi` of the
/// reference segment `X_1 -> X_2` (the stick point of a first touch).
pub fn reference_point(reference: [[f64; 2]; 2], xi: f64) -> [f64; 2] {
    let [r1, r2] = reference;
    [r1[0] + xi * (r2[0] - r1[0]), r1[1] + xi * (r2[1] - r1[1])]
}

#[cfg(test)]
mod tests {
    use super::*;

    fn law(mu: f64) -> SegmentFriction {
        SegmentFriction {
            mu,
            alpha_t: 30.0,
            shift: 0.0,
            normal_shift: 0.0,
            normal_stiffness: 100.0,
        }
    }

    /// Forces balance; the tangent is minus the derivative of the forces
    /// (central differences), in stick and in slip.
    /// The element tangent `K = -d f / d x` against central differences of
    /// the forces `eval` at `x0` (6 dofs: slave, segment ends).
    fn tangent_matches_fd(
        eval: impl Fn([f64; 6]) -> [f64; 6],
        x0: [f64; 6],
        tangent: &[[f64; 6]; 6],
        mu: f64,
    ) {
        let h = 1e-7;
        for j in 0..6 {
            let (mut xp, mut xm) = (x0, x0);
            xp[j] += h;
            xm[j] -= h;
            let (fp, fm) = (eval(xp), eval(xm));
            for i in 0..6 {
                let fd = -(fp[i] - fm[i]) / (2.0 * h);
                assert!(
                    (fd - tangent[i][j]).abs() < 1e-6 * (1.0 + fd.abs()),
                    "mu {mu} K[{i}][{j}]: {fd} vs {}",
                    tangent[i][j]
                );
            }
        }
    }

    #[test]
    fn segment_friction_balances_and_tangent_matches_finite_differences() {
        let reference = [[0.0, 0.0], [1.0, 0.0]];
        let (x1, x2) = ([0.01, -0.02], [1.03, 0.05]);
        for (mu, anchor, status) in [
            (0.5, [0.42, 0.0], FrictionStatus::Stick),
            (0.2, [0.2, 0.0], FrictionStatus::Slip),
        ] {
            let xs = [0.45, 0.03];
            let r = respond(&law(mu), xs, x1, x2, reference, anchor, None, None).unwrap();
            assert_eq!(r.friction.status, status, "{:?}", r.friction);
            for c in 0..2 {
                let sum: f64 = (0..3).map(|k| r.forces[2 * k + c]).sum();
                assert!(sum.abs() < 1e-14, "{sum}");
            }
            let x0 = [xs[0], xs[1], x1[0], x1[1], x2[0], x2[1]];
            let eval = |x: [f64; 6]| {
                respond(
                    &law(mu),
                    [x[0], x[1]],
                    [x[2], x[3]],
                    [x[4], x[5]],
                    reference,
                    anchor,
                    None,
                    None,
                )
                .unwrap()
                .forces
            };
            tangent_matches_fd(eval, x0, &r.tangent, mu);
        }
    }

    /// A node pressed into the wedge of a concave kink of the master
    /// projects on the vertex `x_2` (normal from the node to the vertex):
    /// the friction acts in the tangent of that normal, `T . n = 0`, with
    /// `|T| = mu R_N` in slip (along the segment it was off by the angle
    /// between the segment and the vertex's tangent, 45 degrees here);
    /// forces balance; the tangent is minus the derivative of the forces
    /// (central differences), in stick and in slip.
    #[test]
    fn friction_at_a_vertex_is_orthogonal_to_its_normal_and_tangent_matches_finite_differences() {
        let reference = [[0.0, 0.0], [1.0, 0.0]];
        let (x1, x2) = ([0.01, -0.02], [1.03, 0.05]);
        // beyond x_2, on the body's side of the segment's line
        let xs: [f64; 2] = [1.08, 0.09];
        let vertex = Some(Vertex { end: 1, side: -1.0 });
        let r = (xs[0] - x2[0]).hypot(xs[1] - x2[1]);
        let n = [-(xs[0] - x2[0]) / r, -(xs[1] - x2[1]) / r];
        for (mu, anchor, status) in [
            (0.5, [1.05, 0.0], FrictionStatus::Stick),
            (0.05, [0.9, 0.0], FrictionStatus::Slip),
        ] {
            let out = respond(&law(mu), xs, x1, x2, reference, anchor, None, vertex).unwrap();
            assert_eq!(out.friction.status, status, "{:?}", out.friction);
            let t = out.friction.traction;
            let tn = t[0] * n[0] + t[1] * n[1];
            let tl = t[0].hypot(t[1]);
            assert!(
                tl > 0.0 && tn.abs() <= 1e-14 * tl,
                "T . n {tn:e}, |T| {tl:e}"
            );
            // the slave's friction force is the traction; the reaction is at
            // the vertex
            assert_eq!([out.forces[0], out.forces[1]], t);
            assert!(out.forces[2].abs() + out.forces[3].abs() < 1e-15);
            if status == FrictionStatus::Slip {
                // R_N = alpha_N r (the vertex's gap -r)
                let rn = 100.0 * r;
                assert!((tl - mu * rn).abs() <= 1e-13 * tl, "{tl} vs {}", mu * rn);
                let s = out.friction.slip_vector;
                assert!((s[0] * n[0] + s[1] * n[1]).abs() < 1e-15);
            }
            let x0 = [xs[0], xs[1], x1[0], x1[1], x2[0], x2[1]];
            let eval = |x: [f64; 6]| {
                respond(
                    &law(mu),
                    [x[0], x[1]],
                    [x[2], x[3]],
                    [x[4], x[5]],
                    reference,
                    anchor,
                    None,
                    vertex,
                )
                .unwrap()
                .forces
            };
            for c in 0..2 {
                let sum: f64 = (0..3).map(|k| out.forces[2 * k + c]).sum();
                assert!(sum.abs() < 1e-14, "{sum}");
            }
            tangent_matches_fd(eval, x0, &out.tangent, mu);
        }
    }

    #[test]
    fn first_impact_is_where_the_node_met_the_segment_or_where_it_touched() {
        // segment (0,0) -> (-2,0): body below, free side above; the node
        // falls from y = 0.3 to -0.1 while moving from x = -1 to -0.6:
        // it crosses y = 0 at tau = 0.75, x = -0.7, xi = 0.35
        let (tau, xi) = first_impact(
            [-1.0, 0.3],
            [-0.6, -0.1],
            (Some(&[0.0, 0.0]), Some(&[-2.0, 0.0])),
            ([0.0, 0.0], [-2.0, 0.0]),
        )
        .unwrap();
        assert!((tau - 0.75).abs() < 1e-14 && (xi - 0.35).abs() < 1e-14);
        // a node touching at the start sticks where it was
        let (tau, xi) = first_impact(
            [-0.5, 0.0],
            [-0.3, -0.01],
            (Some(&[0.0, 0.0]), Some(&[-2.0, 0.0])),
            ([0.0, 0.0], [-2.0, 0.0]),
        )
        .unwrap();
        assert_eq!((tau, xi), (0.0, 0.25));
        // unknown start positions: no impact point
        assert!(first_impact([0.0; 2], [0.0; 2], (None, None), ([0.0; 2], [1.0, 0.0])).is_none());
        // the rate of xi with the node's end x is tau-independent here:
        // x_hit = x0 + tau (x1 - x0), tau fixed by y: d xi / d x1 = -tau / 2
        let r = impact_rate(
            [-1.0, 0.3],
            (Some(&[0.0, 0.0]), Some(&[-2.0, 0.0])),
            [[-0.6, -0.1], [0.0, 0.0], [-2.0, 0.0]],
            0.35,
        );
        assert!((r[0] + 0.375).abs() < 1e-6, "{r:?}");
    }

    /// A trial force on the cone to round-off (`1e-12` of it below) slips
    /// ([`CONE_TIE`]): the force is the cone's and the tangent the slip's
    /// (no tangential stiffness `alpha_T` on the slave's own x); without
    /// the tie it stuck, its tangent decided by the last bits.
    #[test]
    fn a_trial_on_the_cone_to_round_off_slips() {
        let reference = [[0.0, 0.0], [2.0, 0.0]];
        // R_N = 100 * 0.01 = 1, limit 0.1; trial -30 g_T = -0.1 (1 - 1e-12)
        let gt = 0.1 / 30.0 * (1.0 - 1e-12);
        let xs = [1.1, 0.01];
        let r = respond(
            &law(0.1),
            xs,
            [0.0, 0.0],
            [2.0, 0.0],
            reference,
            [xs[0] - gt, 0.0],
            None,
            None,
        )
        .unwrap();
        assert_eq!(r.friction.status, FrictionStatus::Slip, "{:?}", r.friction);
        assert!((r.friction.tangential_force + 0.1).abs() < 1e-14);
        // slip: the force does not depend on the slave's tangential x
        assert!(r.tangent[0][0].abs() < 1e-12, "{}", r.tangent[0][0]);
    }

    /// A wavy master walked `-x` (body below), nodes `x_0 .. x_3` at `x =
    /// 2, 1, 0, -1`; its reference is the same polyline with other waves
    /// (the master deformed); `w` the waves, `[x_s]` near segment `x_1 ->
    /// x_2` at `xi`, gap `g`.
    fn wavy(w: &[f64], xi: f64, g: f64) -> ([[f64; 2]; 5], [[f64; 2]; 4]) {
        let base = [2.0, 1.0, 0.0, -1.0];
        let mut x = [[0.0; 2]; 5];
        let mut r = [[0.0; 2]; 4];
        for k in 0..4 {
            x[k + 1] = [base[k] + w[2 * k], w[2 * k + 1]];
            r[k] = [base[k] + 0.5 * w[8 + k], 0.5 * w[12 + k]];
        }
        // `g` below the chord (penetrating: R_N > 0)
        let chord = (1.0 - xi) * x[2][1] + xi * x[3][1];
        x[0] = [1.0 - xi + w[16], chord + g];
        (x, r)
    }

    /// The smoothed element's forces at `x` (projection solved from the
    /// faceted one), with its projection's `xi` and gap.
    fn smoothed_at(
        law: &SegmentFriction,
        x: [[f64; 2]; 5],
        has: [bool; 2],
        sym: smoothing::Symmetry,
        r: [[f64; 2]; 4],
        anchor: [f64; 2],
    ) -> Option<(SmoothedResponse, f64, f64, [f64; 2])> {
        let p = smoothing::Patch::new(x, has[0], has[1], sym)?;
        let xi = smoothing::project(&p, 0.5)?;
        let (g, n) = p.gap(xi);
        let out = respond_smoothed(law, x, has, sym, xi, r, anchor, None)?;
        Some((out, xi, g, n))
    }

    /// A point of the reference polyline `r` at arclength-like parameter
    /// `q` from `X_1` towards `X_2` (`q < 0`: on `X_0 -> X_1`, `q > 1`: on
    /// `X_2 -> X_3`, where they exist; else the segment's line).
    fn on_reference(r: [[f64; 2]; 4], has: [bool; 2], q: f64) -> [f64; 2] {
        let at =
            |a: [f64; 2], b: [f64; 2], t: f64| [a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])];
        if q < 0.0 && has[0] {
            at(r[1], r[0], -q)
        } else if q > 1.0 && has[1] {
            at(r[2], r[3], q - 1.0)
        } else {
            at(r[1], r[2], q)
        }
    }

    proptest::proptest! {
        /// Smoothed friction (`smoothing = nodal`), stick and slip, inside a
        /// segment and next to a master node (the stick point on this
        /// segment or a neighbour), with and without the far nodes and a
        /// symmetry line `x = const` at a free end (`s0`, `s3`): the
        /// force on the slave is orthogonal to the smoothed normal; forces
        /// sum to zero and their moment is `g R_T`; the 10x10 tangent is
        /// minus the derivative of the forces (central differences, the
        /// projection solved again at each perturbed point).
        #[test]
        fn smoothed_friction_is_orthogonal_balanced_and_its_tangent_matches_finite_differences(
            w in proptest::collection::vec(-0.12f64..0.12, 17),
            xi in -0.1f64..1.1,
            g in -0.03f64..-0.001,
            q in -0.6f64..1.6,
            mu in 0.02f64..1.0,
            h0 in proptest::bool::ANY,
            h3 in proptest::bool::ANY,
            s0 in proptest::bool::ANY,
            s3 in proptest::bool::ANY,
        ) {
            let has = [h0, h3];
            let sym = [[s0 && !h0, false], [s3 && !h3, false]];
            let (x, r) = wavy(&w, xi, g);
            let law = law(mu);
            let anchor = on_reference(r, has, q);
            let Some((out, xi, g, n)) = smoothed_at(&law, x, has, sym, r, anchor) else {
                return Ok(());
            };
            proptest::prop_assume!((-0.3..1.3).contains(&xi));
            let t = out.friction.traction;
            let tl = t[0].hypot(t[1]);
            proptest::prop_assert!((t[0] * n[0] + t[1] * n[1]).abs() <= 1e-14 * tl);
            for c in 0..2 {
                let sum: f64 = (0..5).map(|k| out.forces[2 * k + c]).sum();
                proptest::prop_assert!(sum.abs() < 1e-13 * (1.0 + tl), "sum {sum}");
            }
            let moment: f64 = (0..5)
                .map(|k| x[k][0] * out.forces[2 * k + 1] - x[k][1] * out.forces[2 * k])
                .sum();
            let expected = g * out.friction.tangential_force;
            proptest::prop_assert!((moment - expected).abs() < 1e-12 * (1.0 + tl),
                "moment {moment} vs g R_T {expected}");
            let h = 1e-6;
            for j in 0..smoothing::N {
                let (mut xp, mut xm) = (x, x);
                xp[j / 2][j % 2] += h;
                xm[j / 2][j % 2] -= h;
                let (Some(fp), Some(fm)) = (
                    smoothed_at(&law, xp, has, sym, r, anchor),
                    smoothed_at(&law, xm, has, sym, r, anchor),
                ) else {
                    continue;
                };
                // the stick / slip boundary is a kink of the force
                if fp.0.friction.status != out.friction.status
                    || fm.0.friction.status != out.friction.status
                {
                    continue;
                }
                for i in 0..smoothing::N {
                    let fd = -(fp.0.forces[i] - fm.0.forces[i]) / (2.0 * h);
                    let k = out.tangent[i][j];
                    proptest::prop_assert!((fd - k).abs() < 1e-5 * (1.0 + fd.abs()),
                        "{:?} K[{i}][{j}]: {fd} vs {k}", out.friction.status);
                }
            }
        }
    }

    /// The slave on a master vertex's nodal normal: the element of the
    /// segment before the vertex (at `xi = 1`) and the one after it (at
    /// `xi = 0`) give the same friction force on the slave and on the
    /// vertex (continuous where the node passes a master node), in stick
    /// and in slip, and the same new stick point; the faceted tangents of
    /// the two segments differ by the kink's 11 degrees.
    #[test]
    fn smoothed_friction_is_the_same_from_both_segments_of_a_vertex() {
        // master nodes walked -x, a kink at (0, 0)
        let m = [[2.0, 0.1], [1.0, 0.0], [0.0, 0.0], [-1.0, 0.2], [-2.0, 0.3]];
        let rf = [[2.0, 0.0], [1.0, 0.0], [0.0, 0.0], [-1.0, 0.0], [-2.0, 0.0]];
        let nv = smoothing::Patch::new(
            [m[2], m[0], m[1], m[2], m[3]],
            true,
            true,
            smoothing::NO_SYMMETRY,
        )
        .unwrap()
        .nu[1];
        let xs = [-0.01 * nv[0], -0.01 * nv[1]];
        for (mu, anchor, status) in [
            (0.5, [0.01, 0.0], FrictionStatus::Stick),
            (0.1, [-0.3, 0.0], FrictionStatus::Slip),
        ] {
            let before = respond_smoothed(
                &law(mu),
                [xs, m[0], m[1], m[2], m[3]],
                [true, true],
                smoothing::NO_SYMMETRY,
                1.0,
                [rf[0], rf[1], rf[2], rf[3]],
                anchor,
                None,
            )
            .unwrap();
            let after = respond_smoothed(
                &law(mu),
                [xs, m[1], m[2], m[3], m[4]],
                [true, true],
                smoothing::NO_SYMMETRY,
                0.0,
                [rf[1], rf[2], rf[3], rf[4]],
                anchor,
                None,
            )
            .unwrap();
            assert_eq!(before.friction.status, status);
            assert_eq!(after.friction.status, status);
            let (tb, ta) = (before.friction.traction, after.friction.traction);
            let tl = tb[0].hypot(tb[1]);
            assert!(tl > 0.0);
            for c in 0..2 {
                assert!((tb[c] - ta[c]).abs() < 1e-12 * tl, "{tb:?} {ta:?}");
                // the vertex: x_2 before, x_1 after
                assert!((before.forces[6 + c] - after.forces[4 + c]).abs() < 1e-12 * tl);
                assert!((before.anchor[c] - after.anchor[c]).abs() < 1e-12);
            }
        }
    }

    #[test]
    fn slip_moves_the_stick_point_along_the_master() {
        let reference = [[0.0, 0.0], [2.0, 0.0]];
        // undeformed master (free side y < 0), node 0.1 past its stick point,
        // penetration 0.01
        let r = respond(
            &law(0.1),
            [1.1, 0.01],
            [0.0, 0.0],
            [2.0, 0.0],
            reference,
            [1.0, 0.0],
            None,
            None,
        )
        .unwrap();
        // R_N = 1, limit 0.1: slip, elastic part 0.1 / 30
        assert_eq!(r.friction.status, FrictionStatus::Slip);
        assert!((r.friction.tangential_force + 0.1).abs() < 1e-14);
        let elastic = 0.1 / 30.0;
        assert!((r.friction.slip - (0.1 - elastic)).abs() < 1e-14);
        assert!((r.anchor[0] - (1.1 - elastic)).abs() < 1e-14);
    }
}
