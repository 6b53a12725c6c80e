//! Lagrange-multiplier friction (seed slides, "Part III – Lagrange
//! multipliers method"): the friction problem is solved like the contact
//! problem, with a status loop.
//!
//! ```text
//! increments
//!   Newton (saddle-point system: normal rows of the active nodes,
//!           tangential rows g_T = 0 of the sticking nodes)
//!   contact loop: introduce / release normal constraints
//!   friction loop: stick -> slip where |lambda_T| > mu lambda_N
//!                  (sliding direction = sign(lambda_T));
//!                  slip -> stick where the slip runs along the friction
//!                  force (the assumed direction was wrong)
//! ```
//!
//! A slipping node carries the force `mu lambda_N s t` with the current
//! normal multiplier (its derivative with respect to `lambda_N` is not in the
//! saddle-point matrix: within a Newton loop the slip force converges
//! linearly, at the rate `mu`). The rows use `d g_T / d x`
//! ([`super::friction::NodeFriction::gap_gradient`]).

use super::friction::FrictionStatus;
use super::rows::{NodeRows, NodeTerm, RowKind};
use super::{ContactStatus, NodeContact, PairState};
use crate::model::{ContactMethod, Model};

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
            if nc.status != ContactStatus::Closed {
                continue;
            }
            let lambda_n = state.multiplier[i].max(0.0);
            let f = &mut state.friction;
            match nc.friction.status {
                FrictionStatus::Stick => {
                    let lt = f.multiplier[i];
                    if lt.abs() > law.mu * lambda_n * (1.0 + 1e-12) + f64::MIN_POSITIVE {
                        f.sliding[i] = lt.signum();
                        changed.push(nc.node);
                    }
                }
                FrictionStatus::Slip => {
                    // the force opposes the slip; a slip along the force means
                    // the node should stick
                    if nc.friction.slip * f.sliding[i] > threshold {
                        f.sliding[i] = 0.0;
                        f.multiplier[i] = nc.friction.tangential_force;
                        changed.push(nc.node);
                    }
                }
                FrictionStatus::Frictionless => {}
            }
        }
    }
    changed
}

/// The stick/slip statuses of all pairs (for the cycling guard): two flags
/// per slave node (slipping along `+t`, along `-t`).
pub fn status_key(pairs: &[PairState]) -> impl Iterator<Item = bool> + '_ {
    pairs
        .iter()
        .flat_map(|p| p.friction.sliding.iter().flat_map(|s| [*s > 0.0, *s < 0.0]))
}
