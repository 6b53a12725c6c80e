//! Coulomb friction of a solid (3D) slave node against a rigid surface tool
//! ([`super::surface`]): the 3D form of [`super::friction::respond_tool`],
//! on the dimension-generic [`FrictionState`] and [`NodeFriction`].
//!
//! Each closed node has a stick point (anchor) `X_a`, stored in the tool's
//! reference frame, so a moving or rotating tool carries it; its current
//! position is `x_a = Q (X_a - c) + c + u` ([`ctc_geom::Placement`]). With
//! the projection's normal `n` and curvature `W = dn/dx`, `P = I - n ⊗ n`:
//!
//! - tangential gap `g_T = P (x - x_a)` (a vector of the tangent plane);
//! - trial force `t* = P m - k_T g_T`, `k_T` the tangential penalty
//!   ([`super::friction::tangential_stiffness`]: the law's `stiffness`, or
//!   `alpha_N / 10`), `m = Q lambda_T*` the augmented-Lagrangian shift
//!   (kept in the tool frame; 0 for the penalty method);
//! - return map onto the Coulomb disc `|t| <= mu R_N`: stick, `t = t*`, if
//!   `|t*| <= mu R_N`; else slip, `t = mu R_N s`, `s = t* / |t*|`, and the
//!   stick point follows the node by `delta = (t - t*) / k_T` (along `-s`,
//!   so the slip direction may turn in the plane from one increment to the
//!   next); the work dissipated over the increment is `-t . slip >= 0`.
//!
//! Consistent tangent `K = -d t / d x` (not symmetric: the model is solved
//! with LU), exact including the curvature terms, with
//! `G = d g_T / d x = P D - (n . d) W - n ⊗ (W d)`, `d = x - x_a`,
//! `D = d d / d x` (`I`, or `I - d x_a / d x` in the increment of a first
//! impact, where the anchor is on the node's path):
//!
//! - `T = d t* / d x = -(n . m) W - n ⊗ (W m) - k_T G`;
//! - stick: `K = -T` (a plane: `k_T P`);
//! - slip: `K = mu alpha_N s ⊗ n - mu R_N / |t*| (I - s ⊗ s) T` (a plane:
//!   `mu alpha_N s ⊗ n + mu R_N k_T / |t*| (I - n ⊗ n - s ⊗ s)`), the first
//!   term being `-mu s ⊗ d R_N / d x`, `d R_N / d x = -alpha_N n`.
//!
//! First impact (`first_impact = intersect`, the default): a node without a
//! committed stick point that was on the free side at the start of the
//! increment (`g_0 > 0`, tool frame position `X_0`) and penetrates now
//! (`g < 0`) sticks where its straight path met the tool, `X_a = X_0 + tau
//! (X - X_0)`, `tau = g_0 / (g_0 - g)` (exact for a plane, first order for a
//! curved tool; the tangent includes `d tau / d x = tau / (g_0 - g) n`); one
//! that already penetrated sticks at `X_0`. `first_impact = frictionless`:
//! no tangential force in that increment, the stick point is the foot of
//! the node. A node closed at a positive gap (augmented Lagrangian) that
//! has not met the tool yet takes `tau = 1` (no force; continuous with the
//! path rule at `g = 0`). The smallest `tau` of an evaluation is recorded
//! for `cut_at_impact`.

use super::friction::{tangential_stiffness, FrictionState, FrictionStatus, NodeFriction};
use super::friction_facet::CONE_TIE;
use crate::model::{ContactMethod, FirstImpact, Friction};
use ctc_geom::{Mat3, Placement, Projection, Vec3};

/// Slip (relative to the square root of the node's tributary area) below
/// which a slipping Lagrange node takes its friction force direction from
/// the kept multiplier rather than from its slip.
const SLIP_FLOOR: f64 = 1e-9;

/// Relative distance to the Coulomb cone under which a node that slid
/// during the increment is reported as slipping.
const ON_CONE: f64 = 1e-9;

/// A closed node against a surface tool, as the friction law sees it.
#[derive(Debug, Clone, Copy)]
pub struct SurfaceContact<'a> {
    /// The tool's placement at the evaluated time.
    pub placement: &'a Placement,
    /// Current node position.
    pub x: Vec3,
    /// Node position in the tool's reference frame.
    pub reference: Vec3,
    /// Projection on the tool, current frame.
    pub projection: &'a Projection,
    /// Normal force `R_N > 0`.
    pub normal_force: f64,
    /// `-d R_N / d g` (`alpha_N`).
    pub normal_stiffness: f64,
    /// Tributary area (area penalties).
    pub area: f64,
}

/// Adds the friction force and tangent of slave node `i` to `force` and
/// `stiffness` (`-d force / d x`), updating the trial friction state.
/// `start_gap` gives the gap at a reference-frame point (the start of the
/// increment's path, first impact only).
#[allow(clippy::too_many_arguments)]
pub fn respond(
    law: &Friction,
    method: &ContactMethod,
    i: usize,
    c: &SurfaceContact<'_>,
    start_gap: impl FnOnce(&Vec3) -> Option<f64>,
    state: &mut FrictionState<3>,
    force: &mut [f64; 3],
    stiffness: &mut [[f64; 3]; 3],
    rows: &mut Option<StickRows>,
) -> NodeFriction<3> {
    *rows = None;
    state.position[i] = c.reference.into();
    let pr = c.projection;
    let (n, w) = (pr.normal, pr.curvature);
    let q: Mat3 = *c.placement.rotation.matrix();
    // d x_a / d x (nonzero only on the first-impact path)
    let mut dxa = Mat3::zeros();
    let start = match state.committed_anchor[i] {
        Some(a) => Vec3::from(a),
        None => {
            let x0 = Vec3::from(state.committed_position[i]);
            let g0 = start_gap(&x0);
            if pr.gap < 0.0 {
                let tau = match g0 {
                    Some(g0) if g0 > 0.0 => g0 / (g0 - pr.gap),
                    _ => 0.0,
                };
                state.record_impact(tau);
            }
            match law.first_impact {
                FirstImpact::Frictionless => {
                    let foot = c.placement.to_reference(&pr.point);
                    state.anchor[i] = Some(foot.into());
                    state.shift[i] = [0.0; 3];
                    return NodeFriction::default();
                }
                FirstImpact::Intersect => match g0 {
                    Some(g0) if g0 > 0.0 => {
                        // not there yet at a positive gap (augmented
                        // Lagrangian): tau = 1, the stick point is the node
                        let (tau, rate) = if pr.gap < 0.0 {
                            let tau = g0 / (g0 - pr.gap);
                            (tau, tau / (g0 - pr.gap))
                        } else {
                            (1.0, 0.0)
                        };
                        let path = c.reference - x0;
                        if state.base[i].is_none() {
                            dxa = Mat3::identity() * tau + (q * path) * n.transpose() * rate;
                        }
                        x0 + path * tau
                    }
                    _ => x0,
                },
            }
        }
    };
    if matches!(method, ContactMethod::Lagrange { .. }) {
        let mut k = Mat3::zeros();
        let sliding = (state.sliding[i], state.committed_sliding[i] != 0.0);
        let (f, r) = lagrange(law, c, start, dxa, sliding, state.shift[i], &mut k);
        for a in 0..3 {
            force[a] += f.traction[a];
            for b in 0..3 {
                stiffness[a][b] += k[(a, b)];
            }
        }
        // the slip moves the stick point with the node
        let slip = Vec3::from(f.slip_vector);
        state.anchor[i] = Some((start + q.transpose() * slip).into());
        *rows = r;
        return f;
    }
    let anchor = state.base[i].map_or(start, Vec3::from);
    let xa = c.placement.apply(&anchor);
    let d = c.x - xa;
    let p = Mat3::identity() - n * n.transpose();
    let gt = p * d;
    let kt = tangential_stiffness(law, method, c.area);
    let m = match method {
        ContactMethod::AugmentedLagrange { .. } => q * Vec3::from(state.shift[i]),
        _ => Vec3::zeros(),
    };
    let trial = p * m - gt * kt;
    let g = p * (Mat3::identity() - dxa) - w * n.dot(&d) - n * (w * d).transpose();
    let dtrial = -(w * n.dot(&m)) - n * (w * m).transpose() - g * kt;
    let limit = law.mu * c.normal_force;
    let norm = trial.norm();
    let (status, t, dt, delta) = if kt <= 0.0 {
        // no tangential penalty: no friction force
        (
            FrictionStatus::Stick,
            Vec3::zeros(),
            Mat3::zeros(),
            Vec3::zeros(),
        )
    } else if limit <= 0.0 {
        // mu R_N = 0 slides freely (no stick stiffness from a zero disc)
        (
            FrictionStatus::Slip,
            Vec3::zeros(),
            Mat3::zeros(),
            -trial / kt,
        )
    } else if norm <= limit * (1.0 - CONE_TIE) {
        // a trial within `CONE_TIE` below the cone slips (the tie rule of
        // node-to-facet friction: one tangent for mirror nodes)
        (FrictionStatus::Stick, trial, dtrial, Vec3::zeros())
    } else {
        let s = trial / norm;
        let t = s * limit;
        let dt = s * n.transpose() * (-law.mu * c.normal_stiffness)
            + (Mat3::identity() - s * s.transpose()) * dtrial * (limit / norm);
        (FrictionStatus::Slip, t, dt, (t - trial) / kt)
    };
    let new_anchor = anchor + q.transpose() * delta;
    state.anchor[i] = Some(new_anchor.into());
    // slip over the whole increment (the base may have moved with Uzawa)
    let slip = delta + q * (anchor - start);
    // the augmented Lagrangian slides a node by moving the base of its
    // trial force: it ends on the cone (within `k_T` times the pair's gap
    // tolerance) with a slip, and is reported as slipping (the tangent
    // stays the return map's)
    let near = match method {
        ContactMethod::AugmentedLagrange { tolerance, .. } => kt * tolerance,
        _ => 0.0,
    };
    let status = if status == FrictionStatus::Stick
        && limit > 0.0
        && norm >= limit * (1.0 - ON_CONE) - near
        && slip.norm() > 0.0
    {
        FrictionStatus::Slip
    } else {
        status
    };
    for a in 0..3 {
        force[a] += t[a];
        for b in 0..3 {
            stiffness[a][b] -= dt[(a, b)];
        }
    }
    NodeFriction {
        status,
        tangential_force: t.norm(),
        tangential_gap: gt.norm(),
        slip: slip.norm(),
        traction: t.into(),
        slip_vector: slip.into(),
        gap_gradient: [0.0; 3],
        // + 0: no negative zero in the outputs
        dissipation: -t.dot(&slip) + 0.0,
    }
}

/// The two tangential stick constraints of a sticking node (Lagrange
/// multipliers): `g_k = t_k . g_T = 0` along an orthonormal basis `t_1,
/// t_2` of the tangent plane, with `d g_k / d x = t_k^T G` (exact where
/// `g_T = 0`, i.e. at the converged stick state: the derivative of the
/// basis multiplies `g_T`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StickRows {
    /// `t_1`, `t_2` in the tool's reference frame (the multiplier
    /// correction of row `k` adds `t_k dlambda` to the tangential
    /// multiplier, kept in that frame).
    pub directions: [Vec3; 2],
    /// `d g_k / d x` (current frame).
    pub gradients: [Vec3; 2],
    /// `g_k`.
    pub gaps: [f64; 2],
}

/// An orthonormal basis of the plane normal to the unit vector `n`
/// (deterministic: the first axis is `n` crossed with the coordinate axis
/// least aligned with it).
pub fn tangent_basis(n: &Vec3) -> [Vec3; 2] {
    let k = (0..3)
        .min_by(|&a, &b| n[a].abs().total_cmp(&n[b].abs()))
        .unwrap_or(0);
    let t1 = n.cross(&Vec3::ith(k, 1.0)).normalize();
    [t1, n.cross(&t1)]
}

/// Lagrange-multiplier friction of a closed node against a surface tool
/// (the 3D form of [`super::friction::Coulomb::lagrange`], status loop in
/// [`super::friction_lagrange`]): the tangential multiplier `lambda_T`
/// is a vector `m` of the tool's reference frame
/// ([`FrictionState::shift`]), `v = P Q m` its current tangential part;
/// the normal force is the normal multiplier `R_N`.
///
/// - stick (`sliding = 0`): force `t = v`, no slip, the constraint rows
///   [`StickRows`] `t_k . g_T = 0`, `g_T = P (x - x_a)`; tangent `-dv/dx =
///   (n . Q m) W + n ⊗ (W Q m)`;
/// - slip (`sliding != 0`): the node slips by `g_T` from its stick point
///   (dissipation `-t . g_T`). Where it was already sliding at the start
///   of the increment and slides against the kept direction `e = v / |v|`
///   (`g_T . e < 0`, `|g_T|` above round-off), the force
///   opposes its slip, `t = -mu R_N s`, `s = g_T / |g_T|`, so the slip
///   direction turns freely within the Newton loop, tangent `mu R_N / |g_T|
///   (I - s ⊗ s) G`; otherwise (the increment of the switch, as in 2D: the
///   slips there are small and their direction ill-conditioned; the first
///   iteration; or a slip along `e`, which the status loop turns into
///   stick) `t = mu R_N e`, tangent `-mu R_N (I - e ⊗ e) / |v| dv/dx`. (`R_N` is an unknown of
///   its own: no `d R_N / d x`.) The status loop keeps `e` along the force
///   (the predictor of the next increment).
///
/// Adds `-d t / d x` to `k`; returns the friction output and the rows of
/// a sticking node.
fn lagrange(
    law: &Friction,
    c: &SurfaceContact<'_>,
    start: Vec3,
    dxa: Mat3,
    (sliding, established): (f64, bool),
    shift: [f64; 3],
    k: &mut Mat3,
) -> (NodeFriction<3>, Option<StickRows>) {
    let pr = c.projection;
    let (n, w) = (pr.normal, pr.curvature);
    let q: Mat3 = *c.placement.rotation.matrix();
    let xa = c.placement.apply(&start);
    let d = c.x - xa;
    let p = Mat3::identity() - n * n.transpose();
    let gt = p * d;
    let m = q * Vec3::from(shift);
    let v = p * m;
    let dv = -(w * n.dot(&m)) - n * (w * m).transpose();
    if sliding == 0.0 {
        *k -= dv;
        let g = p * (Mat3::identity() - dxa) - w * n.dot(&d) - n * (w * d).transpose();
        let t = tangent_basis(&n);
        let qt = q.transpose();
        let rows = StickRows {
            directions: [qt * t[0], qt * t[1]],
            gradients: [g.transpose() * t[0], g.transpose() * t[1]],
            gaps: [t[0].dot(&gt), t[1].dot(&gt)],
        };
        let f = NodeFriction {
            status: FrictionStatus::Stick,
            tangential_force: v.norm(),
            tangential_gap: gt.norm(),
            slip: 0.0,
            traction: v.into(),
            slip_vector: [0.0; 3],
            gap_gradient: [0.0; 3],
            dissipation: 0.0,
        };
        return (f, Some(rows));
    }
    let limit = law.mu * c.normal_force.max(0.0);
    let norm = v.norm();
    let slip = gt.norm();
    let t = if established && slip > SLIP_FLOOR * c.area.sqrt() && gt.dot(&v) < 0.0 {
        // sliding against the kept direction: the force opposes the slip
        // of the increment, its direction turning with it inside Newton
        let s = gt / slip;
        let g = p * (Mat3::identity() - dxa) - w * n.dot(&d) - n * (w * d).transpose();
        *k += (Mat3::identity() - s * s.transpose()) * g * (limit / slip);
        -s * limit
    } else if norm > 0.0 {
        let e = v / norm;
        *k -= (Mat3::identity() - e * e.transpose()) * dv * (limit / norm);
        e * limit
    } else {
        Vec3::zeros()
    };
    let f = NodeFriction {
        status: FrictionStatus::Slip,
        tangential_force: t.norm(),
        tangential_gap: gt.norm(),
        slip: gt.norm(),
        traction: t.into(),
        slip_vector: gt.into(),
        gap_gradient: [0.0; 3],
        // + 0: no negative zero in the outputs
        dissipation: -t.dot(&gt) + 0.0,
    };
    (f, None)
}

/// Uzawa update of the tangential shifts of an augmented-Lagrangian pair
/// evaluated with the tool at `placement`: `lambda_T* <- Q^T t` at every
/// node with friction, 0 elsewhere; the trial force is measured from the
/// current trial stick point from then on (as in 2D,
/// [`super::friction::uzawa_update`]).
pub fn uzawa_update(
    nodes: &[usize],
    contact: &[super::NodeContact<3>],
    placement: &Placement,
    state: &mut FrictionState<3>,
) {
    state.shift.iter_mut().for_each(|m| *m = [0.0; 3]);
    let qt = placement.rotation.inverse();
    for c in contact {
        if c.friction.status == FrictionStatus::Frictionless {
            continue;
        }
        if let Ok(i) = nodes.binary_search(&c.node) {
            state.shift[i] = (qt * Vec3::from(c.friction.traction)).into();
            state.base[i] = state.anchor[i];
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::PenaltyKind;

    /// The tie rule of `friction_facet::CONE_TIE` on a rigid surface tool:
    /// a node that slipped starts the next increment with its stick point
    /// where the return map left it, its trial force on the disc's rim to
    /// round-off. Plane tool `z = 0`, node 0.01 below it, normal force 10,
    /// mu 0.3, `k_T` 40: the stick point at the origin and the node at
    /// `mu R_N / k_T = 0.075 (+-1e-13)` along x (two mirror nodes'
    /// round-off) must get one status and one tangent, the slip's (no
    /// tangential stiffness along the slip). Before the tie the node a
    /// hair inside stuck with `K_xx = k_T`.
    #[test]
    fn a_trial_on_the_disc_rim_to_round_off_slips_whatever_the_round_off() {
        let law = Friction {
            mu: 0.3,
            stiffness: Some(40.0),
            first_impact: FirstImpact::Intersect,
            cut_at_impact: false,
        };
        let method = ContactMethod::Penalty {
            kind: PenaltyKind::Nodal,
            stiffness: 1000.0,
        };
        let placement = Placement::identity();
        // the node at `(x, 0, -0.01)`, its stick point at the origin
        let eval = |x: f64| {
            let x = Vec3::new(x, 0.0, -0.01);
            let projection = Projection::closed_form(
                Vec3::new(x.x, 0.0, 0.0),
                -0.01,
                Vec3::new(0.0, 0.0, 1.0),
                Mat3::zeros(),
            );
            let c = SurfaceContact {
                placement: &placement,
                x,
                reference: x,
                projection: &projection,
                normal_force: 10.0,
                normal_stiffness: 1000.0,
                area: 1.0,
            };
            let mut state = FrictionState::<3>::new(vec![[0.0; 3]]);
            state.committed_anchor[0] = Some([0.0; 3]);
            let (mut force, mut stiffness) = ([0.0; 3], [[0.0; 3]; 3]);
            let f = respond(
                &law,
                &method,
                0,
                &c,
                |_| None,
                &mut state,
                &mut force,
                &mut stiffness,
                &mut None,
            );
            (f.status, force[0], stiffness[0][0])
        };
        for dx in [-1e-13, 0.0, 1e-13] {
            let (status, fx, kxx) = eval(0.075 + dx);
            assert_eq!(status, FrictionStatus::Slip, "dx {dx:e}");
            assert!((fx + 3.0).abs() < 1e-9, "{fx}");
            // the slip's tangent: no stiffness along the slip
            assert!(kxx.abs() < 1e-9, "dx {dx:e}: {kxx}");
        }
        // well inside the disc it still sticks
        let (status, _, kxx) = eval(0.07);
        assert_eq!(status, FrictionStatus::Stick);
        assert!((kxx - 40.0).abs() < 1e-9);
    }
}
