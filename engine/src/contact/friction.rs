//! Coulomb friction (seed slides, "Part III - Friction").
//!
//! The normal force `R_N >= 0` of a closed node is known from the pair's
//! normal method; the tangential force `R_T` follows Coulomb's law
//! `|R_T| <= mu R_N` (stick: no slip; slip: `|R_T| = mu R_N`, opposite to the
//! slip). Tangential quantities are scalars along the unit tangent
//! `t = (n_y, -n_x)` of the master at the projection (the force on the node
//! is `R_T t`).
//!
//! Tangential gap: each closed node has a stick point, a material point of
//! the master (stored in the tool's reference frame, so a moving or rotating
//! tool carries it along and drags stuck nodes); `g_T = t . (x - x_a)`, `x_a`
//! the stick point's current position. The stick point is committed only
//! with a converged increment ([`FrictionState::commit`]).
//!
//! Penalty (regularized Coulomb, Metafor): trial force
//! `R_T* = lambda_T* - alpha_T g_T` (`lambda_T* = 0`; the augmented
//! Lagrangian keeps a tangential multiplier shift `lambda_T*`, updated with
//! the normal one, Uzawa), then the return to the cone:
//! - stick, `|R_T*| <= mu R_N`: `R_T = R_T*`;
//! - slip: `R_T = mu R_N sign(R_T*)`; the stick point moves along `t` by the
//!   slip increment `ds = (R_T - R_T*) / alpha_T` (so that the elastic part
//!   `lambda_T* - alpha_T (g_T - ds) = R_T`); the dissipated work of the
//!   increment is `-R_T ds = mu R_N |ds|`.
//!
//! Consistent tangent `K = -d f / d x` (`f = R_T t`, `d n / d x = h t ⊗ t`,
//! `d t / d x = -h n ⊗ t`, `d g_T / d x = (1 - h d.n) t` with `d = x - x_a`):
//! - stick: `K = alpha_T (1 - h d.n) t ⊗ t + R_T h n ⊗ t`;
//! - slip: `K = mu sign(R_T*) alpha_N t ⊗ n + R_T h n ⊗ t` (`alpha_N =
//!   -d R_N / d g`),
//!
//! not symmetric: a model with friction is solved with LU.
//!
//! Lagrange multipliers: a sticking node carries a tangential multiplier
//! `lambda_T` (constraint `g_T = 0`, rows built by
//! [`super::friction_lagrange`]); a slipping node carries `mu lambda_N s`,
//! `s = ±1` its force direction; the stick/slip status loop is
//! [`super::friction_lagrange::update_status`].

use super::geometry::{Projection, ToolShape};
use super::motion::Placement;
use super::penalty::{self, Response};
use super::vec2::{add, dot, outer, scale, sub};
use super::{impact, ContactStatus};
use crate::model::{ContactMethod, FirstImpact, Friction, PenaltyKind};

/// Friction status of a slave node (ordered: frictionless, stick, slip).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Default, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum FrictionStatus {
    /// No tangential force: frictionless pair, open node, or a node in the
    /// increment of its first impact with `first_impact = frictionless`.
    #[default]
    Frictionless,
    /// `|R_T| < mu R_N`: the node sticks to the master.
    Stick,
    /// `|R_T| = mu R_N`: the node slides.
    Slip,
}

/// Tangential response of one slave node at the evaluated state, in
/// dimension `D` (planar by default). The scalar fields are signed
/// components along the tangent `t` in 2D and magnitudes in 3D, where the
/// tangent plane has no preferred direction; the vector fields carry the
/// directions (3D surface tools; planar rigid tools fill `traction` too).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NodeFriction<const D: usize = 2> {
    /// Stick, slip or frictionless.
    pub status: FrictionStatus,
    /// Tangential force `R_T` along `t = (n_y, -n_x)` (axisymmetric: total
    /// over 2*pi); it is included in `NodeContact::force`. 3D: `|R_T|`.
    pub tangential_force: f64,
    /// Tangential gap `g_T = t . (x - x_a)` from the committed stick point
    /// (3D: `|g_T|`, `g_T = (I - n ⊗ n)(x - x_a)`).
    pub tangential_gap: f64,
    /// Slip increment `ds` along `t` since the last converged increment
    /// (0 while sticking; 3D: the length of `slip_vector`).
    pub slip: f64,
    /// Tangential force vector on the node (current frame; 2D: `R_T t`).
    pub traction: [f64; D],
    /// Slip increment vector of the node relative to the tool since the
    /// last converged increment (current frame; 2D: `slip t`).
    pub slip_vector: [f64; D],
    /// `d g_T / d x` at the slave node (the Lagrange stick row; planar).
    pub gap_gradient: [f64; D],
    /// Frictional work dissipated at this node over the increment,
    /// `-R_T ds = mu R_N |ds|` (>= 0 once the status loop has settled;
    /// axisymmetric: over 2*pi). This is the heat source of frictional
    /// heating. `R_N` is the normal part of `NodeContact::force`, `(force -
    /// traction) . normal`: against a deformable master the friction acts
    /// along the segment, and where the node projects on a vertex (the
    /// dead zone of a kink: `normal` points to the vertex) `force .
    /// normal` also holds `R_T t . n` (examples/blade_loss.ctc: 1.2e-4 of
    /// the friction work to 12 ms, one node on a casing vertex). The
    /// force is the one at the end of the increment (backward Euler, like
    /// plastic dissipation): when the normal force varies within the
    /// increments of a dynamic step this is not the trapezoidal work of
    /// the friction forces that the energy audit's `contact_work` holds
    /// (a block sliding to rest under generalized-alpha: 0.96 of its
    /// kinetic energy, 0.77 with the rocking unresolved, while the
    /// contact work is 0.9996; `ctc verify
    /// energy_audit_generalized_alpha`).
    pub dissipation: f64,
}

impl<const D: usize> Default for NodeFriction<D> {
    fn default() -> Self {
        NodeFriction {
            status: FrictionStatus::Frictionless,
            tangential_force: 0.0,
            tangential_gap: 0.0,
            slip: 0.0,
            traction: [0.0; D],
            slip_vector: [0.0; D],
            gap_gradient: [0.0; D],
            dissipation: 0.0,
        }
    }
}

/// Per-pair friction history (one entry per slave node, `ContactPair::nodes`
/// order): trial values of the latest evaluation and their committed
/// counterparts, in dimension `D` (points in the tool's reference frame).
#[derive(Debug, Clone, Default)]
pub struct FrictionState<const D: usize = 2> {
    /// Stick point in the tool's reference frame (trial, after the return
    /// map); `None`: the node is not in contact.
    pub anchor: Vec<Option<[f64; D]>>,
    /// Stick point at the last converged increment.
    pub committed_anchor: Vec<Option<[f64; D]>>,
    /// Stick point the trial force is measured from: the committed one,
    /// or, after an augmented-Lagrangian (Uzawa) update, the trial stick
    /// point of that update (it goes with the multiplier shift).
    pub base: Vec<Option<[f64; D]>>,
    /// Tangential multiplier: `lambda_T` (Lagrange) or the shift
    /// `lambda_T*` (augmented Lagrangian), force units, along `t` (planar).
    pub multiplier: Vec<f64>,
    /// Tangential multiplier at the last converged increment.
    pub committed_multiplier: Vec<f64>,
    /// 3D: the augmented-Lagrangian tangential shift `lambda_T*` as a
    /// vector in the tool's reference frame (so it turns with the tool);
    /// unused in 2D, where `multiplier` is its component along `t`.
    pub shift: Vec<[f64; D]>,
    /// Shift at the last converged increment.
    pub committed_shift: Vec<[f64; D]>,
    /// Lagrange status: 0 stick (constraint row), `±1` slip with the force
    /// along `±t`.
    pub sliding: Vec<f64>,
    /// Lagrange status at the last converged increment.
    pub committed_sliding: Vec<f64>,
    /// Node position in the tool's reference frame at the latest evaluation.
    pub position: Vec<[f64; D]>,
    /// Position at the last converged increment (start of the path of the
    /// constant-velocity intersection).
    pub committed_position: Vec<[f64; D]>,
    /// Smallest fraction of the increment at which a node touched for the
    /// first time, at the latest evaluation (`None`: no first impact).
    pub impact: Option<f64>,
    /// Mortar friction ([`super::mortar::friction`]): the positions and
    /// stick points are slip coordinates measured from the committed
    /// configuration (the node's weighted slip since the last converged
    /// increment, and the stick point's), so [`FrictionState::commit`]
    /// moves their origin to the new converged state (stick point minus
    /// position, positions 0).
    pub incremental: bool,
}

impl<const D: usize> FrictionState<D> {
    /// State of `n` slave nodes at reference-frame positions `positions`.
    pub fn new(positions: Vec<[f64; D]>) -> Self {
        let n = positions.len();
        FrictionState {
            anchor: vec![None; n],
            committed_anchor: vec![None; n],
            base: vec![None; n],
            multiplier: vec![0.0; n],
            committed_multiplier: vec![0.0; n],
            shift: vec![[0.0; D]; n],
            committed_shift: vec![[0.0; D]; n],
            sliding: vec![0.0; n],
            committed_sliding: vec![0.0; n],
            position: positions.clone(),
            committed_position: positions,
            impact: None,
            incremental: false,
        }
    }

    /// Commits the trial state (converged increment).
    pub fn commit(&mut self) {
        if self.incremental {
            for (a, p) in self.anchor.iter_mut().zip(&mut self.position) {
                if let Some(a) = a {
                    for (ac, pc) in a.iter_mut().zip(p.iter()) {
                        *ac -= pc;
                    }
                }
                *p = [0.0; D];
            }
        }
        self.committed_anchor.clone_from(&self.anchor);
        self.base.clone_from(&self.anchor);
        self.committed_multiplier.clone_from(&self.multiplier);
        self.committed_shift.clone_from(&self.shift);
        self.committed_sliding.clone_from(&self.sliding);
        self.committed_position.clone_from(&self.position);
        self.impact = None;
    }

    /// Restores the committed state (cutback).
    pub fn rollback(&mut self) {
        self.anchor.clone_from(&self.committed_anchor);
        self.base.clone_from(&self.committed_anchor);
        self.multiplier.clone_from(&self.committed_multiplier);
        self.shift.clone_from(&self.committed_shift);
        self.sliding.clone_from(&self.committed_sliding);
        self.position.clone_from(&self.committed_position);
        self.impact = None;
    }

    /// Numbers per node in [`FrictionState::committed_values`]: 7 in 2D,
    /// 12 in 3D (where the shift vector follows).
    fn values_per_node() -> usize {
        if D == 2 {
            3 + 2 * D
        } else {
            3 + 3 * D
        }
    }

    /// The committed state as numbers (restart files): per node the stick
    /// point flag and coordinates, the multiplier, the Lagrange status and
    /// the reference-frame position (7 values in 2D), then in 3D the shift
    /// vector (12 values).
    pub fn committed_values(&self) -> Vec<f64> {
        let mut v = Vec::with_capacity(Self::values_per_node() * self.committed_anchor.len());
        for i in 0..self.committed_anchor.len() {
            let a = self.committed_anchor[i];
            v.push(if a.is_some() { 1.0 } else { 0.0 });
            v.extend(a.unwrap_or([0.0; D]));
            v.push(self.committed_multiplier[i]);
            v.push(self.committed_sliding[i]);
            v.extend(self.committed_position[i]);
            if D != 2 {
                v.extend(self.committed_shift[i]);
            }
        }
        v
    }

    /// Restores the committed state from [`FrictionState::committed_values`]
    /// (call `rollback` afterwards to make it the trial state too).
    pub fn restore_committed(&mut self, v: &[f64]) -> Result<(), String> {
        let n = self.committed_anchor.len();
        let k = Self::values_per_node();
        if v.len() != k * n {
            return Err("the restart point does not match the model (friction state)".into());
        }
        let point = |c: &[f64]| -> [f64; D] { std::array::from_fn(|j| c[j]) };
        for (i, c) in v.chunks_exact(k).enumerate() {
            self.committed_anchor[i] = (c[0] != 0.0).then(|| point(&c[1..]));
            self.committed_multiplier[i] = c[1 + D];
            self.committed_sliding[i] = c[2 + D];
            self.committed_position[i] = point(&c[3 + D..]);
            if D != 2 {
                self.committed_shift[i] = point(&c[3 + 2 * D..]);
            }
        }
        Ok(())
    }

    /// Node `i` is out of contact at reference-frame position `reference`.
    pub fn open(&mut self, i: usize, reference: [f64; D]) {
        if let Some(p) = self.position.get_mut(i) {
            *p = reference;
            self.release(i);
        }
    }

    /// Forgets node `i`'s contact history (it is open).
    pub(crate) fn release(&mut self, i: usize) {
        self.anchor[i] = None;
        self.base[i] = None;
        self.multiplier[i] = 0.0;
        self.shift[i] = [0.0; D];
        self.sliding[i] = 0.0;
    }

    /// Records a first impact at fraction `tau`.
    pub(crate) fn record_impact(&mut self, tau: f64) {
        self.impact = Some(self.impact.map_or(tau, |t| t.min(tau)));
    }
}

/// Tangential penalty `alpha_T` of a node (force per unit slip): the
/// friction stiffness scaled like the normal penalty (nodal, or times the
/// tributary area), or `alpha_N / 10` by default. 0 for Lagrange pairs.
pub fn tangential_stiffness(law: &Friction, method: &ContactMethod, tributary: f64) -> f64 {
    let kind = match method {
        ContactMethod::Penalty { kind, .. } | ContactMethod::AugmentedLagrange { kind, .. } => {
            *kind
        }
        ContactMethod::Lagrange { .. } => return 0.0,
    };
    match law.stiffness {
        Some(s) => match kind {
            PenaltyKind::Nodal => s,
            PenaltyKind::Area => s * tributary,
        },
        None => 0.1 * penalty::effective_stiffness(method, tributary),
    }
}

/// A closed node against a rigid tool, as seen by the friction law.
#[derive(Debug, Clone, Copy)]
pub struct ToolContact<'a> {
    /// The tool geometry (reference frame).
    pub shape: &'a ToolShape,
    /// The tool's placement at the evaluated time.
    pub placement: &'a Placement,
    /// Current node position.
    pub x: [f64; 2],
    /// Node position in the tool's reference frame.
    pub reference: [f64; 2],
    /// Projection on the tool (reference frame).
    pub projection: &'a Projection,
    /// Unit outward normal, current frame.
    pub normal: [f64; 2],
    /// Search window (bounds the first-impact search).
    pub window: f64,
}

/// Adds the friction force and tangent of slave node `i` to its normal
/// response `r` (rigid tool), updating the trial friction state.
pub fn respond_tool(
    law: &Friction,
    method: &ContactMethod,
    tributary: f64,
    i: usize,
    c: &ToolContact<'_>,
    state: &mut FrictionState,
    r: &mut Response,
) -> NodeFriction {
    state.position[i] = c.reference;
    let mut impact = None;
    if r.status != ContactStatus::Closed {
        state.release(i);
        return NodeFriction::default();
    }
    let start = match state.committed_anchor[i] {
        Some(a) => a,
        None => {
            // first touch within this increment
            let hit = impact::tool_intersection(
                c.shape,
                state.committed_position[i],
                c.reference,
                c.window,
            );
            if let Some(h) = hit {
                state.record_impact(h.fraction);
            }
            match law.first_impact {
                FirstImpact::Frictionless => {
                    state.anchor[i] = Some(c.projection.point);
                    state.multiplier[i] = 0.0;
                    state.sliding[i] = 0.0;
                    return NodeFriction::default();
                }
                FirstImpact::Intersect => {
                    impact = hit;
                    hit.map_or(c.projection.point, |h| h.point)
                }
            }
        }
    };
    let anchor = state.base[i].unwrap_or(start);
    let n = c.normal;
    let t = [n[1], -n[0]];
    let t_ref = c.placement.rotate_back(t);
    let h = c.projection.normal_rate;
    let xa = c.placement.to_current(anchor);
    let d = sub(c.x, xa);
    let coulomb = Coulomb {
        mu: law.mu,
        normal_force: dot(r.force, n).max(0.0),
        normal_stiffness: penalty::effective_stiffness(method, tributary),
        tangential_stiffness: tangential_stiffness(law, method, tributary),
    };
    let tangential = match method {
        ContactMethod::Lagrange { .. } => {
            coulomb.lagrange(dot(t, d), state.multiplier[i], state.sliding[i])
        }
        ContactMethod::AugmentedLagrange { .. } => {
            coulomb.regularized(dot(t, d), state.multiplier[i])
        }
        ContactMethod::Penalty { .. } => coulomb.regularized(dot(t, d), 0.0),
    };
    let mut tangential = tangential;
    let ds = tangential.friction.slip;
    state.anchor[i] = Some(add(anchor, scale(ds, t_ref)));
    let rt = tangential.friction.tangential_force;
    // slip over the whole increment (the base may have moved with Uzawa)
    let slip = ds + dot(t_ref, sub(anchor, start));
    tangential.friction.slip = slip;
    tangential.friction.slip_vector = scale(slip, t);
    tangential.friction.dissipation = -rt * slip;
    // d g_T / d x; in the increment of the first impact the stick point
    // itself depends on x: X_a = X0 + tau (X - X0), with tau = g0 / (g0 - g)
    // (exact for a plane), d tau / d x = tau / (g0 - g) n
    let mut grad = scale(1.0 - h * dot(d, n), t);
    if state.base[i].is_none() {
        if let Some(hit) = impact.filter(|h| h.fraction > 0.0) {
            let tau = hit.fraction;
            let path = c
                .placement
                .rotate(sub(c.reference, state.committed_position[i]));
            let dg = hit.start_gap - c.projection.gap;
            if dg > 0.0 {
                grad = sub(grad, add(scale(tau, t), scale(dot(t, path) * tau / dg, n)));
            }
        }
    }
    tangential.friction.gap_gradient = grad;
    tangential.friction.traction = scale(rt, t);
    let (tg, tn, nt) = (outer(t, grad), outer(t, n), outer(n, t));
    for a in 0..2 {
        r.force[a] += rt * t[a];
        for b in 0..2 {
            r.stiffness[a][b] += tangential.stick_stiffness * tg[a][b]
                + tangential.slip_stiffness * tn[a][b]
                + rt * h * nt[a][b];
        }
    }
    tangential.friction
}

/// Coulomb's law at one node: the data the return map needs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Coulomb {
    /// Friction coefficient.
    pub mu: f64,
    /// Normal force `R_N >= 0`.
    pub normal_force: f64,
    /// `-d R_N / d g` (penalty and augmented Lagrangian: `alpha_N`).
    pub normal_stiffness: f64,
    /// Tangential penalty `alpha_T` (0 for Lagrange multipliers).
    pub tangential_stiffness: f64,
}

/// Result of the return map along the tangent, before the geometric terms.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Tangential {
    /// Status, force, gap, slip increment and dissipation.
    pub friction: NodeFriction,
    /// `d R_T / d g_T` with the sign flipped (`alpha_T` in stick, else 0).
    pub stick_stiffness: f64,
    /// Coefficient of `t ⊗ n` in the tangent (`mu s alpha_N` in slip).
    pub slip_stiffness: f64,
}

impl Coulomb {
    /// Penalty return map with the multiplier shift `shift` (0 for the
    /// penalty method): trial `R_T* = shift - alpha_T g_T`.
    pub fn regularized(&self, gap: f64, shift: f64) -> Tangential {
        let alpha = self.tangential_stiffness;
        let limit = self.mu * self.normal_force;
        let trial = shift - alpha * gap;
        // mu R_N = 0 slides freely (no stick stiffness from a zero cone).
        // No `friction_facet::CONE_TIE` here (3D tools have it): measured,
        // a trial within 1e-9 below the cone slipping cut the 2D
        // catalogue's iterations (friction_quadratic 528 -> 291,
        // friction_inclined_plane 475 -> 381, blankholder level 0 1626 ->
        // 1285) but `blankholder` level 1 (mu 0.05, free rollers) stalled
        // at t = 0.70 (relative residual 1.95e-7 for 23 iterations, line
        // search steps 0.016-0.06, two closed nodes on roller A) and
        // stopped; its level-0 moment balance went 1.4e-11 -> 3.3e-10
        if (trial.abs() <= limit && limit > 0.0) || alpha <= 0.0 {
            return Tangential {
                friction: NodeFriction {
                    status: FrictionStatus::Stick,
                    tangential_force: if alpha > 0.0 { trial } else { 0.0 },
                    tangential_gap: gap,
                    slip: 0.0,
                    dissipation: 0.0,
                    ..NodeFriction::default()
                },
                stick_stiffness: alpha,
                slip_stiffness: 0.0,
            };
        }
        let s = trial.signum();
        let rt = limit * s;
        let slip = (rt - trial) / alpha;
        Tangential {
            friction: NodeFriction {
                status: FrictionStatus::Slip,
                tangential_force: rt,
                tangential_gap: gap,
                slip,
                dissipation: -rt * slip,
                ..NodeFriction::default()
            },
            stick_stiffness: 0.0,
            slip_stiffness: self.mu * s * self.normal_stiffness,
        }
    }

    /// Lagrange multipliers: stick (`sliding = 0`) carries the multiplier
    /// `lambda_T` and no slip; slip carries `mu R_N sliding` and slips by
    /// the whole tangential gap.
    pub fn lagrange(&self, gap: f64, lambda: f64, sliding: f64) -> Tangential {
        let friction = if sliding == 0.0 {
            NodeFriction {
                status: FrictionStatus::Stick,
                tangential_force: lambda,
                tangential_gap: gap,
                slip: 0.0,
                dissipation: 0.0,
                ..NodeFriction::default()
            }
        } else {
            let rt = self.mu * self.normal_force * sliding;
            NodeFriction {
                status: FrictionStatus::Slip,
                tangential_force: rt,
                tangential_gap: gap,
                slip: gap,
                dissipation: -rt * gap,
                ..NodeFriction::default()
            }
        };
        Tangential {
            friction,
            stick_stiffness: 0.0,
            slip_stiffness: 0.0,
        }
    }
}

/// Largest tangential gap `|g_T|` of a sticking node (the augmented
/// Lagrangian iterates until it is below the pair's tolerance).
pub fn stick_violation<const D: usize>(contact: &[super::NodeContact<D>]) -> f64 {
    contact
        .iter()
        .filter(|c| c.friction.status == FrictionStatus::Stick)
        .map(|c| c.friction.tangential_gap.abs())
        .fold(0.0, f64::max)
}

/// Uzawa update of the tangential multiplier shifts of an augmented
/// Lagrangian pair: `lambda_T* <- R_T` at every closed node, 0 elsewhere;
/// the trial force is measured from the current trial stick point from
/// then on (the shift carries the force accumulated up to it).
pub fn uzawa_update(nodes: &[usize], contact: &[super::NodeContact], state: &mut FrictionState) {
    state.multiplier.iter_mut().for_each(|m| *m = 0.0);
    for c in contact {
        if c.friction.status == FrictionStatus::Frictionless {
            continue;
        }
        if let Ok(i) = nodes.binary_search(&c.node) {
            state.multiplier[i] = c.friction.tangential_force;
            state.base[i] = state.anchor[i];
        }
    }
}

/// Per-node friction fields for output (nodes not in a frictional contact:
/// zeros and status 0). A node in several pairs sums forces, slips and
/// dissipations and keeps the highest status.
#[derive(Debug, Clone, PartialEq)]
pub struct NodalFriction {
    /// Tangential force (3D: its magnitude).
    pub force: Vec<f64>,
    /// Tangential force vector, 3 components (3D; planar: in-plane, z = 0).
    pub traction: Vec<[f64; 3]>,
    /// Slip increment.
    pub slip: Vec<f64>,
    /// 0 frictionless, 1 stick, 2 slip.
    pub status: Vec<i32>,
    /// Work dissipated over the increment.
    pub dissipation: Vec<f64>,
}

/// Collects the friction fields of all pair evaluations on `nn` nodes.
pub fn nodal_fields<const D: usize>(
    nn: usize,
    contact: &[Vec<super::NodeContact<D>>],
) -> NodalFriction {
    let mut out = NodalFriction {
        force: vec![0.0; nn],
        traction: vec![[0.0; 3]; nn],
        slip: vec![0.0; nn],
        status: vec![0; nn],
        dissipation: vec![0.0; nn],
    };
    for c in contact.iter().flatten() {
        if c.node >= nn {
            continue;
        }
        out.force[c.node] += c.friction.tangential_force;
        for (k, t) in c.friction.traction.iter().enumerate().take(3) {
            out.traction[c.node][k] += t;
        }
        out.slip[c.node] += c.friction.slip;
        out.dissipation[c.node] += c.friction.dissipation;
        out.status[c.node] = out.status[c.node].max(status_code(c.friction.status));
    }
    out
}

/// Output code of a status: 0 frictionless, 1 stick, 2 slip.
pub fn status_code(s: FrictionStatus) -> i32 {
    match s {
        FrictionStatus::Frictionless => 0,
        FrictionStatus::Stick => 1,
        FrictionStatus::Slip => 2,
    }
}

/// Frictional work dissipated over the increment by the nodes of one pair
/// evaluation (axisymmetric: over 2*pi).
pub fn pair_dissipation<const D: usize>(contact: &[super::NodeContact<D>]) -> f64 {
    contact.iter().map(|c| c.friction.dissipation).sum()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::{ToolGeometry, ToolMotion};

    fn law(mu: f64) -> Friction {
        Friction {
            mu,
            stiffness: Some(40.0),
            first_impact: FirstImpact::Intersect,
            cut_at_impact: false,
        }
    }

    #[test]
    fn return_map_sticks_inside_the_cone_and_slides_on_it() {
        let c = Coulomb {
            mu: 0.3,
            normal_force: 10.0,
            normal_stiffness: 100.0,
            tangential_stiffness: 50.0,
        };
        let s = c.regularized(0.02, 0.0);
        assert_eq!(s.friction.status, FrictionStatus::Stick);
        assert_eq!(s.friction.tangential_force, -1.0);
        let p = c.regularized(0.1, 0.0);
        assert_eq!(p.friction.status, FrictionStatus::Slip);
        assert!((p.friction.tangential_force + 3.0).abs() < 1e-14);
        // elastic part g_T - ds = mu R_N / alpha_T = 0.06, slip 0.04
        assert!((p.friction.slip - 0.04).abs() < 1e-14);
        assert!((p.friction.dissipation - 0.12).abs() < 1e-14);
        // augmented shift: trial 2 - 50 g
        let a = c.regularized(0.02, 2.0);
        assert!((a.friction.tangential_force - 1.0).abs() < 1e-14);
    }

    /// The tangent is minus the derivative of the friction + normal force
    /// with the stick point fixed, on a circle tool (curvature terms), in
    /// stick and in slip.
    #[test]
    fn friction_tangent_matches_finite_differences_on_a_circle() {
        let geometry = ToolGeometry::Circle {
            center: [0.0, 0.0],
            radius: 1.0,
            side: crate::model::ToolSide::Outside,
        };
        let shape = ToolShape::new(&geometry).unwrap();
        let placement = Placement::at(&ToolMotion::fixed(), 0.0);
        let method = ContactMethod::Penalty {
            kind: PenaltyKind::Nodal,
            stiffness: 100.0,
        };
        for (mu, anchor, expected) in [
            (0.5, [0.249, 0.962], FrictionStatus::Stick),
            (0.2, [0.1, 0.99], FrictionStatus::Slip),
        ] {
            let eval = |x: [f64; 2]| {
                let p = shape.project(0, x).unwrap();
                let mut r = penalty::respond(&method, 1.0, p.gap, p.normal, p.normal_rate);
                let mut st = FrictionState::new(vec![x]);
                st.committed_anchor[0] = Some(anchor);
                let c = ToolContact {
                    shape: &shape,
                    placement: &placement,
                    x,
                    reference: x,
                    projection: &p,
                    normal: p.normal,
                    window: 1.0,
                };
                let f = respond_tool(&law(mu), &method, 1.0, 0, &c, &mut st, &mut r);
                (r, f)
            };
            let x = [0.25, 0.96];
            let f0 = eval(x).1;
            assert_eq!(f0.status, expected, "mu = {mu}: {f0:?}");
            assert_tangent_matches_fd(|x| eval(x).0, x, &format!("mu {mu}"));
        }
    }

    /// A plane tool through the origin with outward normal `normal`, at
    /// rest, and a nodal penalty of 100.
    fn plane_with_nodal_penalty(normal: [f64; 2]) -> (ToolShape, Placement, ContactMethod) {
        let shape = ToolShape::new(&ToolGeometry::Plane {
            point: [0.0, 0.0],
            normal,
        })
        .unwrap();
        let method = ContactMethod::Penalty {
            kind: PenaltyKind::Nodal,
            stiffness: 100.0,
        };
        (shape, Placement::identity(), method)
    }

    /// `K = -d force / d x` of `eval` at `x` against central differences.
    fn assert_tangent_matches_fd(
        eval: impl Fn([f64; 2]) -> penalty::Response,
        x: [f64; 2],
        label: &str,
    ) {
        let k = eval(x).stiffness;
        let h = 1e-7;
        for j in 0..2 {
            let (mut xp, mut xm) = (x, x);
            xp[j] += h;
            xm[j] -= h;
            let (fp, fm) = (eval(xp).force, eval(xm).force);
            for i in 0..2 {
                let fd = -(fp[i] - fm[i]) / (2.0 * h);
                assert!(
                    (fd - k[i][j]).abs() < 1e-5 * (1.0 + fd.abs()),
                    "{label} K[{i}][{j}]: fd {fd} vs {}",
                    k[i][j]
                );
            }
        }
    }

    /// In the increment of the first impact the stick point moves with the
    /// node (constant-velocity intersection): the tangent includes it.
    #[test]
    fn first_impact_tangent_matches_finite_differences() {
        let (shape, placement, method) = plane_with_nodal_penalty([0.3, 1.0]);
        let eval = |x: [f64; 2]| {
            let p = shape.project(0, x).unwrap();
            let mut r = penalty::respond(&method, 1.0, p.gap, p.normal, p.normal_rate);
            let mut st = FrictionState::new(vec![[0.0, 0.2]]);
            let c = ToolContact {
                shape: &shape,
                placement: &placement,
                x,
                reference: x,
                projection: &p,
                normal: p.normal,
                window: 1.0,
            };
            let f = respond_tool(&law(10.0), &method, 1.0, 0, &c, &mut st, &mut r);
            (r, f)
        };
        let x = [0.08, -0.05];
        assert_eq!(eval(x).1.status, FrictionStatus::Stick);
        assert_tangent_matches_fd(|x| eval(x).0, x, "first impact");
    }

    #[test]
    fn first_impact_sets_the_stick_point_where_the_node_met_the_tool() {
        let (shape, placement, method) = plane_with_nodal_penalty([0.0, 1.0]);
        // node from (0, 0.1) to (0.4, -0.1): meets the plane at x = 0.2
        let x = [0.4, -0.1];
        let p = shape.project(0, x).unwrap();
        for (first, rt) in [
            (FirstImpact::Intersect, -0.2 * 40.0f64),
            (FirstImpact::Frictionless, 0.0),
        ] {
            let mut st = FrictionState::new(vec![[0.0, 0.1]]);
            let mut r = penalty::respond(&method, 1.0, p.gap, p.normal, p.normal_rate);
            let c = ToolContact {
                shape: &shape,
                placement: &placement,
                x,
                reference: x,
                projection: &p,
                normal: p.normal,
                window: 1.0,
            };
            let lw = Friction {
                first_impact: first,
                ..law(10.0)
            };
            let f = respond_tool(&lw, &method, 1.0, 0, &c, &mut st, &mut r);
            // t = (n_y, -n_x) = (1, 0): g_T = 0.2, R_T = -alpha_T g_T
            assert!((f.tangential_force - rt).abs() < 1e-9, "{first:?}: {f:?}");
            assert!((st.impact.unwrap() - 0.5).abs() < 1e-9);
        }
    }
}
