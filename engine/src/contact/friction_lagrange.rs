//! Lagrange-multiplier friction (seed slides, "Part III – Lagrange
//! multipliers method"): the friction problem is solved like the contact
//! problem, with a status loop.
//!
//! ```text
//! increments
//!   Newton (saddle-point system: normal rows of the active nodes,
//!           tangential rows g_T = 0 of the sticking nodes)
//!   status loop, both on the same converged solution:
//!     contact: introduce / release normal constraints
//!     friction (nodes that stay closed): stick -> slip where
//!                  |lambda_T| > mu lambda_N (sliding direction =
//!                  sign(lambda_T)); slip -> stick where the slip runs
//!                  along the friction force (the assumed direction was
//!                  wrong)
//! ```
//!
//! The two loops decide together: were the friction statuses only updated
//! once the active set had settled, the increment where the nodes start to
//! slide would solve the contact loop with every node stuck, its stick
//! forces many times the Coulomb limit (up to 29x in
//! `friction_curved_path_3d`); their moment puts the trailing nodes in
//! tension, released, they penetrate, are introduced sticking, and the
//! active set cycles (the cutbacks of `friction_block_3d` and
//! `friction_curved_path_3d` before these rules: 3 and 6). For the same
//! reason a node that the contact loop releases and introduces again in
//! the same increment (3D, [`reintroduce_slipping`]) comes back slipping,
//! its force against its way from the stick point it had at the start of
//! the increment, instead of sticking there: the body has slid on, and the
//! stick rows would pull the node back by the whole slide; the friction
//! loop sticks it again if its slip runs along that force.
//!
//! A slipping node carries the force `mu lambda_N s t` with the current
//! normal multiplier (its derivative with respect to `lambda_N` is not in the
//! saddle-point matrix: within a Newton loop the slip force converges
//! linearly, at the rate `mu`). The rows use `d g_T / d x`
//! ([`super::friction::NodeFriction::gap_gradient`]).
//!
//! 3D (surface tools, [`super::friction_surface`]): the same loop on the
//! Coulomb disc. A sticking node has two rows `t_k . g_T = 0` along a basis
//! of the tangent plane ([`surface_stick_rows`]) and a tangential
//! multiplier vector; a slipping node carries `mu lambda_N` against its
//! slip once it slides against the direction `e` the loop keeps (so the
//! slip direction rotates with the path inside the Newton loop), along `e`
//! before: stick -> slip along `lambda_T / |lambda_T|`, slip -> stick on a
//! slip along `e`, and `e` follows the slip of the converged loop (the
//! predictor of the next increment; by [`TURN_TOLERANCE`]). One
//! decision function, [`decide`], serves both dimensions.

use super::friction::{FrictionState, FrictionStatus};
use super::rows::{NodeRows, NodeTerm, RowKind};
use super::surface::SurfacePair;
use super::{ContactStatus, NodeContact, PairState};
use crate::model::{ContactMethod, Model};
use ctc_geom::{Placement, Vec3};

/// Whether pair `cp` uses Lagrange-multiplier friction.
pub fn is_lagrange_friction(cp: &crate::model::ContactPair) -> bool {
    cp.friction.is_some() && matches!(cp.method, ContactMethod::Lagrange { .. })
}

/// Appends one tangential constraint row `d g_T / d x` per sticking node
/// of every Lagrange pair with friction to `rows` (kind
/// [`RowKind::Stick`]).
pub fn stick_rows(model: &Model, contact: &[Vec<NodeContact>], rows: &mut NodeRows) {
    for (pi, cp) in model.contacts.iter().enumerate() {
        if !is_lagrange_friction(cp) {
            continue;
        }
        for nc in &contact[pi] {
            if nc.status != ContactStatus::Closed || nc.friction.status != FrictionStatus::Stick {
                continue;
            }
            let Ok(i) = cp.nodes.binary_search(&nc.node) else {
                continue;
            };
            rows.push(
                RowKind::Stick,
                (pi, i),
                nc.friction.tangential_gap,
                nc.friction
                    .gap_gradient
                    .iter()
                    .enumerate()
                    .map(|(component, &coefficient)| NodeTerm {
                        node: nc.node,
                        component,
                        coefficient,
                    }),
            );
        }
    }
}

/// What the status loop decides for one closed node on the Coulomb disc.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Decision<const K: usize> {
    /// Nothing changes.
    Keep,
    /// Stick -> slip, the friction force along the unit vector given.
    Slip([f64; K]),
    /// Slip -> stick (the node slid along the friction force).
    Stick,
    /// Still slipping, but the slip turned: the friction force goes along
    /// the unit vector given (minus the slip direction).
    Turn([f64; K]),
}

/// Angle (radians) by which the slip of a slipping node may differ from
/// minus its friction force direction before the status loop turns the
/// force (3D; a line has no angle to turn).
pub const TURN_TOLERANCE: f64 = 1e-7;

/// The status decision of one closed node, in `K` tangential components
/// (1 along the tangent of a curve, 3 in the tangent plane of a surface):
///
/// - sticking (`direction = None`): slip when the tangential multiplier
///   `force` leaves the disc, `|force| > limit = mu lambda_N`, along
///   `force / |force|`;
/// - slipping with the friction force along the unit `direction`: stick
///   when the slip `slip` runs along the force (`slip . direction >
///   threshold`: the assumed direction was wrong); else, once the slip is
///   longer than `threshold`, turn the force to `-slip / |slip|` when it
///   differs by more than [`TURN_TOLERANCE`] (on a line it never does).
pub fn decide<const K: usize>(
    direction: Option<[f64; K]>,
    force: [f64; K],
    limit: f64,
    slip: [f64; K],
    threshold: f64,
) -> Decision<K> {
    let dot = |a: &[f64; K], b: &[f64; K]| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>();
    match direction {
        None => {
            let f = dot(&force, &force).sqrt();
            if f > limit * (1.0 + 1e-12) + f64::MIN_POSITIVE {
                Decision::Slip(force.map(|x| x / f))
            } else {
                Decision::Keep
            }
        }
        Some(e) => {
            if dot(&slip, &e) > threshold {
                return Decision::Stick;
            }
            let s = dot(&slip, &slip).sqrt();
            if s <= threshold {
                return Decision::Keep;
            }
            let turned = slip.map(|x| -x / s);
            let change = turned
                .iter()
                .zip(&e)
                .map(|(a, b)| (a - b) * (a - b))
                .sum::<f64>()
                .sqrt();
            if change > TURN_TOLERANCE {
                Decision::Turn(turned)
            } else {
                Decision::Keep
            }
        }
    }
}

/// Stick/slip status update of the Lagrange pairs with friction after a
/// converged Newton loop; returns the nodes whose status changed.
/// `threshold`: round-off length below which a slip reversal is ignored.
pub fn update_status(
    model: &Model,
    pairs: &mut [PairState],
    contact: &[Vec<NodeContact>],
    threshold: f64,
) -> Vec<usize> {
    let mut changed = Vec::new();
    for (pi, cp) in model.contacts.iter().enumerate() {
        let Some(law) = cp.friction.filter(|_| is_lagrange_friction(cp)) else {
            continue;
        };
        let state = &mut pairs[pi];
        for nc in &contact[pi] {
            let Ok(i) = cp.nodes.binary_search(&nc.node) else {
                continue;
            };
            if nc.status != ContactStatus::Closed
                || nc.friction.status == FrictionStatus::Frictionless
                || !state.active[i]
            {
                continue;
            }
            let lambda_n = state.multiplier[i].max(0.0);
            let f = &mut state.friction;
            let direction = (nc.friction.status == FrictionStatus::Slip).then_some([f.sliding[i]]);
            match decide(
                direction,
                [f.multiplier[i]],
                law.mu * lambda_n,
                [nc.friction.slip],
                threshold,
            ) {
                Decision::Slip([s]) => {
                    f.sliding[i] = s.signum();
                    changed.push(nc.node);
                }
                Decision::Stick => {
                    f.sliding[i] = 0.0;
                    f.multiplier[i] = nc.friction.tangential_force;
                    changed.push(nc.node);
                }
                Decision::Keep | Decision::Turn(_) => {}
            }
        }
    }
    changed
}

/// A node of a Lagrange surface pair with friction that the contact loop
/// introduces at current position `x` (tool normal `normal`, tool at
/// `placement`) while it began the increment in contact (it was released
/// in between; see the module doc): it slips, its friction force against
/// its tangential way from the stick point it had at the start of the
/// increment (`shift` the unit direction, tool frame). Whether it was set
/// (not for a first contact, where the first-impact rule applies, nor for
/// a node at its stick point).
pub fn reintroduce_slipping(
    state: &mut FrictionState<3>,
    i: usize,
    x: Vec3,
    normal: Vec3,
    placement: &Placement,
) -> bool {
    let Some(anchor) = state.committed_anchor[i] else {
        return false;
    };
    let d = x - placement.apply(&Vec3::from(anchor));
    let way = d - normal * normal.dot(&d);
    let Some(s) = way.try_normalize(f64::MIN_POSITIVE) else {
        return false;
    };
    state.sliding[i] = 1.0;
    state.shift[i] = (placement.rotation.inverse() * -s).into();
    true
}

/// What the status loop changed in the surface (3D) pairs.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct SurfaceStatusChange {
    /// Nodes that went from stick to slip or back.
    pub switched: Vec<usize>,
    /// Slipping nodes whose kept friction force direction was turned to
    /// their slip (the force already followed it: not a change of the
    /// solution, no further Newton loop).
    pub turned: usize,
}

/// Appends the two tangential rows of every sticking node of the Lagrange
/// surface pairs with friction ([`super::friction_surface::StickRows`]) to
/// `rows`, and the direction of each row (tool frame) to `directions`.
pub fn surface_stick_rows(
    model: &Model<3>,
    pairs: &[SurfacePair],
    contact: &[Vec<NodeContact<3>>],
    rows: &mut NodeRows,
    directions: &mut Vec<[f64; 3]>,
) {
    for (pi, cp) in model.contacts.iter().enumerate() {
        if !is_lagrange_friction(cp) {
            continue;
        }
        let state = &pairs[pi];
        for nc in &contact[pi] {
            if nc.status != ContactStatus::Closed || nc.friction.status != FrictionStatus::Stick {
                continue;
            }
            let Some(i) = state.slave_index(nc.node) else {
                continue;
            };
            let Some(r) = state.stick[i] else { continue };
            for k in 0..2 {
                rows.push(
                    RowKind::Stick,
                    (pi, i),
                    r.gaps[k],
                    (0..3).map(|component| NodeTerm {
                        node: nc.node,
                        component,
                        coefficient: r.gradients[k][component],
                    }),
                );
                directions.push(r.directions[k].into());
            }
        }
    }
}

/// Stick/slip status update of the Lagrange surface pairs with friction
/// after a converged Newton loop, by [`decide`] on the tangent plane: the
/// tangential multiplier ([`FrictionState::shift`], tool frame) keeps the
/// stick force, or the friction force direction of a slipping node
/// (`sliding = 1`). `placement`: each pair's tool placement at the
/// evaluated time (`None` for pairs without a tool).
pub fn update_surface_status(
    model: &Model<3>,
    pairs: &mut [SurfacePair],
    contact: &[Vec<NodeContact<3>>],
    placement: &[Option<Placement>],
    threshold: f64,
) -> SurfaceStatusChange {
    let mut change = SurfaceStatusChange::default();
    for (pi, cp) in model.contacts.iter().enumerate() {
        let Some(law) = cp.friction.filter(|_| is_lagrange_friction(cp)) else {
            continue;
        };
        let Some(Some(p)) = placement.get(pi) else {
            continue;
        };
        let qt = p.rotation.inverse();
        let state = &mut pairs[pi];
        for nc in &contact[pi] {
            let Some(i) = state.slave_index(nc.node) else {
                continue;
            };
            if nc.status != ContactStatus::Closed
                || nc.friction.status == FrictionStatus::Frictionless
                || !state.active[i]
            {
                continue;
            }
            let t = Vec3::from(nc.friction.traction);
            let limit = law.mu * state.multiplier[i].max(0.0);
            let direction = match nc.friction.status {
                FrictionStatus::Slip => {
                    Some(t.try_normalize(0.0).unwrap_or_else(Vec3::zeros).into())
                }
                _ => None,
            };
            let f = &mut state.friction;
            match decide(
                direction,
                t.into(),
                limit,
                nc.friction.slip_vector,
                threshold,
            ) {
                Decision::Slip(e) => {
                    f.sliding[i] = 1.0;
                    f.shift[i] = (qt * Vec3::from(e) * limit).into();
                    change.switched.push(nc.node);
                }
                Decision::Stick => {
                    f.sliding[i] = 0.0;
                    f.shift[i] = (qt * t).into();
                    change.switched.push(nc.node);
                }
                Decision::Turn(e) => {
                    // the force already turned with the slip: keep it
                    f.shift[i] = (qt * Vec3::from(e) * limit.max(f64::MIN_POSITIVE)).into();
                    change.turned += 1;
                }
                Decision::Keep => {}
            }
        }
    }
    change
}

/// The stick/slip statuses of all pairs (for the cycling guard): two flags
/// per slave node (slipping along `+t`, along `-t`; in 3D the second is
/// never set).
pub fn status_key<'a, const D: usize>(
    states: impl Iterator<Item = &'a FrictionState<D>> + 'a,
) -> impl Iterator<Item = bool> + 'a {
    states.flat_map(|f| f.sliding.iter().flat_map(|s| [*s > 0.0, *s < 0.0]))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn decide_slips_off_the_disc_sticks_on_a_reversal_and_turns_with_the_slip() {
        // inside the disc: keep sticking; outside: slip along the force
        assert_eq!(
            decide(None, [0.3, 0.4, 0.0], 0.6, [0.0; 3], 1e-12),
            Decision::Keep
        );
        assert_eq!(
            decide(None, [0.6, 0.8, 0.0], 0.5, [0.0; 3], 1e-12),
            Decision::Slip([0.6, 0.8, 0.0])
        );
        // slipping along -e: keep; along e: stick
        let e = [1.0, 0.0, 0.0];
        assert_eq!(
            decide(Some(e), [0.0; 3], 1.0, [-0.1, 0.0, 0.0], 1e-12),
            Decision::Keep
        );
        assert_eq!(
            decide(Some(e), [0.0; 3], 1.0, [0.1, 0.0, 0.0], 1e-12),
            Decision::Stick
        );
        // the slip turned by 90 degrees: the force turns with it
        assert_eq!(
            decide(Some(e), [0.0; 3], 1.0, [0.0, -0.1, 0.0], 1e-12),
            Decision::Turn([0.0, 1.0, 0.0])
        );
        // below the threshold: nothing to learn from the slip
        assert_eq!(
            decide(Some(e), [0.0; 3], 1.0, [0.0, 1e-14, 0.0], 1e-12),
            Decision::Keep
        );
        // on a line (2D) a slip against the force never turns it
        assert_eq!(
            decide(Some([-1.0]), [0.0], 1.0, [0.3], 1e-12),
            Decision::Keep
        );
        assert_eq!(
            decide(Some([-1.0]), [0.0], 1.0, [-0.3], 1e-12),
            Decision::Stick
        );
    }

    #[test]
    fn a_reintroduced_node_slips_against_its_way_from_the_stick_point() {
        let placement = Placement::identity();
        let mut state = FrictionState::<3>::new(vec![[0.0; 3]]);
        // first contact (no stick point at the start): the first-impact rule
        assert!(!reintroduce_slipping(
            &mut state,
            0,
            Vec3::new(0.3, 0.4, -0.01),
            Vec3::z(),
            &placement
        ));
        assert_eq!(state.sliding[0], 0.0);
        state.committed_anchor[0] = Some([0.0; 3]);
        // right above its stick point: nothing to slip along
        assert!(!reintroduce_slipping(
            &mut state,
            0,
            Vec3::new(0.0, 0.0, -0.01),
            Vec3::z(),
            &placement
        ));
        assert_eq!(state.sliding[0], 0.0);
        // moved by (0.3, 0.4) in the tangent plane: slips, force along -(0.6, 0.8)
        assert!(reintroduce_slipping(
            &mut state,
            0,
            Vec3::new(0.3, 0.4, -0.01),
            Vec3::z(),
            &placement
        ));
        assert_eq!(state.sliding[0], 1.0);
        let f = state.shift[0];
        assert!((f[0] + 0.6).abs() < 1e-14 && (f[1] + 0.8).abs() < 1e-14 && f[2] == 0.0);
    }

    #[test]
    fn tangent_basis_is_orthonormal_and_normal_to_n() {
        use super::super::friction_surface::tangent_basis;
        for n in [Vec3::z(), Vec3::new(0.3, -0.2, 0.9).normalize(), -Vec3::x()] {
            let [a, b] = tangent_basis(&n);
            for (u, v) in [(a, b), (a, n), (b, n)] {
                assert!(u.dot(&v).abs() < 1e-15);
            }
            assert!((a.norm() - 1.0).abs() < 1e-15 && (b.norm() - 1.0).abs() < 1e-15);
            assert!((a.cross(&b) - n).norm() < 1e-15);
        }
    }
}
