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

use super::friction::{FrictionStatus, NodeFriction};
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
    let (rt, status) = if trial.re().abs() <= limit.re() && limit.re() > 0.0 {
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
    use crate::model::ContactMethod;
    let i = e.slave;
    if e.status != super::ContactStatus::Closed || i >= state.anchor.len() {
        state.open(i, e.xs);
        return NodeFriction::default();
    }
    let [m1, m2] = e.nodes;
    let (Some(&r1), Some(&r2), Some(&x1), Some(&x2)) =
        (reference.get(m1), reference.get(m2), x.get(m1), x.get(m2))
    else {
        return NodeFriction::default();
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
                    return NodeFriction::default();
                }
            }
        }
    };
    let anchor = state.base[i].unwrap_or(start);
    let alpha_n = super::penalty::effective_stiffness(method, e.tributary);
    let shift = match method {
        ContactMethod::Penalty { .. } => 0.0,
        ContactMethod::AugmentedLagrange { .. } => state.multiplier[i],
        ContactMethod::Lagrange { .. } => return NodeFriction::default(),
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
    let seg = SegmentFriction {
        mu: law.mu,
        alpha_t: super::friction::tangential_stiffness(law, method, e.tributary),
        shift,
        normal_shift: e.normal_force + alpha_n * gap_now,
        normal_stiffness: alpha_n,
    };
    // the Uzawa base (augmented Lagrangian) is a fixed stick point
    let anchor_rate = anchor_rate.filter(|_| state.base[i].is_none());
    let Some(r) = respond(&seg, e.xs, x1, x2, [r1, r2], anchor, anchor_rate, e.vertex) else {
        return NodeFriction::default();
    };
    for ((f, row), (rf, rrow)) in forces
        .iter_mut()
        .zip(tangent.iter_mut())
        .zip(r.forces.iter().zip(&r.tangent))
    {
        *f += rf;
        for (k, rk) in row.iter_mut().zip(rrow) {
            *k += rk;
        }
    }
    state.anchor[i] = Some(r.anchor);
    state.position[i] = e.xs;
    r.friction
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
