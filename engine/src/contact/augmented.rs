//! Augmented-Lagrangian enforcement of the normal contact constraint (seed
//! slides, "Variants – Augmented Lagrangian"): a small penalty `alpha` plus a
//! multiplier shift `lambda*`,
//!
//! `R_N = max(0, lambda* - alpha g)`,
//!
//! `lambda*` being known during a Newton loop and updated afterwards
//! (`lambda* <- R_N`, Uzawa) until the largest penetration is below
//! `gmax*`. With `lambda* = 0` this is the penalty method.
//!
//! Force on the node `f = R_N n`; tangent (with `d g / d x = n` and
//! `d n / d x = h t ⊗ t`):
//!
//! `K_c = -d f / d x = alpha n ⊗ n - R_N h t ⊗ t`
//!
//! which for `lambda* = 0` is the penalty tangent `alpha (n ⊗ n + g h t ⊗ t)`.
//! Multipliers are stored in force units (per node, axisymmetric: total
//! over 2*pi).

use super::penalty::{self, Response};
use super::vec2::outer;
use super::{friction, ContactStatus, NodeContact, PairState};
use crate::model::{ContactMethod, Model, MultiplierUpdate};

/// Normal force `R_N = max(0, lambda* - alpha g)` of a node.
pub fn normal_force(alpha: f64, lambda_star: f64, gap: f64) -> f64 {
    (lambda_star - alpha * gap).max(0.0)
}

/// Response of a node of penalty coefficient `alpha` (force per unit gap,
/// see [`super::penalty::effective_stiffness`]), multiplier `lambda_star`,
/// gap `gap`, unit normal `normal`, normal rate `normal_rate` and tributary
/// area `tributary`.
pub fn respond(
    alpha: f64,
    lambda_star: f64,
    tributary: f64,
    gap: f64,
    normal: [f64; 2],
    normal_rate: f64,
) -> Response {
    let rn = normal_force(alpha, lambda_star, gap);
    if rn <= 0.0 {
        return Response {
            force: [0.0; 2],
            stiffness: [[0.0; 2]; 2],
            pressure: 0.0,
            status: ContactStatus::Open,
        };
    }
    normal_response(alpha, rn, tributary, normal, normal_rate)
}

/// Force `rn n`, tangent `alpha n ⊗ n - rn h t ⊗ t`, pressure
/// `rn / tributary` and status closed; shared with the Lagrange method
/// (`alpha = 0`, `rn = lambda`).
pub fn normal_response(
    alpha: f64,
    rn: f64,
    tributary: f64,
    normal: [f64; 2],
    normal_rate: f64,
) -> Response {
    let n = normal;
    let t = [n[1], -n[0]];
    let nn = outer(n, n);
    let tt = outer(t, t);
    let mut k = [[0.0; 2]; 2];
    for i in 0..2 {
        for j in 0..2 {
            k[i][j] = alpha * nn[i][j] - rn * normal_rate * tt[i][j];
        }
    }
    Response {
        force: [rn * n[0], rn * n[1]],
        stiffness: k,
        pressure: if tributary > 0.0 { rn / tributary } else { 0.0 },
        status: ContactStatus::Closed,
    }
}

/// Uzawa update of the augmented-Lagrangian pairs whose update mode is
/// `mode`: for a pair whose largest penetration exceeds its tolerance,
/// `lambda* <- max(0, lambda* - alpha g)` at every evaluated node (0 at
/// nodes out of the search window). Returns whether any pair was updated.
pub fn uzawa_update(
    model: &Model,
    pairs: &mut [PairState],
    contact: &[Vec<NodeContact>],
    mode: MultiplierUpdate,
) -> bool {
    let mut updated = false;
    for (pi, cp) in model.contacts.iter().enumerate() {
        let ContactMethod::AugmentedLagrange {
            tolerance, update, ..
        } = cp.method
        else {
            continue;
        };
        // quadratic faces: the multipliers and the test at the points
        // (friction: the points' stick gaps and tangential shifts)
        let state = &mut pairs[pi];
        if let Some(fp) = &mut state.facets {
            let stick = if cp.friction.is_some() {
                friction::stick_violation(&state.point_contact)
            } else {
                0.0
            };
            if update == mode && fp.violation().max(stick) > tolerance {
                fp.uzawa_update();
                if cp.friction.is_some() {
                    let points: Vec<usize> = (0..fp.rule.points.len()).collect();
                    friction::uzawa_update(&points, &state.point_contact, &mut state.friction);
                }
                updated = true;
            }
            continue;
        }
        let violation = constraint_violation(&contact[pi]).max(if cp.friction.is_some() {
            friction::stick_violation(&contact[pi])
        } else {
            0.0
        });
        if update != mode || violation <= tolerance {
            continue;
        }
        let state = &mut pairs[pi];
        let mut next = vec![0.0; state.slaves.len()];
        for nc in &contact[pi] {
            let Some(i) = state.slave_index(nc.node) else {
                continue;
            };
            let alpha = penalty::effective_stiffness(&cp.method_at(nc.node), state.tributary[i]);
            next[i] = normal_force(alpha, state.multiplier[i], nc.gap);
        }
        state.multiplier = next;
        if cp.friction.is_some() {
            friction::uzawa_update(&state.slaves, &contact[pi], &mut state.friction);
        }
        updated = true;
    }
    updated
}

/// Largest violation of the contact conditions over a pair's evaluated
/// nodes: `|g|` where a force acts (closed: the gap should vanish, a force
/// at a positive gap is an over-correction of `lambda*`), the penetration
/// `max(0, -g)` elsewhere. The augmented-Lagrangian iterations stop when it
/// is below the tolerance `gmax*`.
pub fn constraint_violation<const D: usize>(contact: &[NodeContact<D>]) -> f64 {
    contact
        .iter()
        .map(|c| match c.status {
            ContactStatus::Closed => c.gap.abs(),
            ContactStatus::Open => (-c.gap).max(0.0),
        })
        .fold(0.0, f64::max)
}

/// Largest penetration `max(0, -g)` over a pair's evaluated nodes.
pub fn max_penetration<const D: usize>(contact: &[NodeContact<D>]) -> f64 {
    contact.iter().map(|c| -c.gap).fold(0.0, f64::max)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::penalty;
    use crate::model::{ContactMethod, PenaltyKind};

    #[test]
    fn zero_multiplier_is_the_penalty_method() {
        let m = ContactMethod::Penalty {
            kind: PenaltyKind::Nodal,
            stiffness: 50.0,
        };
        let n = [0.6, 0.8];
        for (gap, h) in [(-0.01, 0.0), (-0.02, 0.5), (0.01, 0.5)] {
            let p = penalty::respond(&m, 1.0, gap, n, h);
            let a = respond(50.0, 0.0, 1.0, gap, n, h);
            assert_eq!(p.status, a.status);
            for i in 0..2 {
                assert!((p.force[i] - a.force[i]).abs() < 1e-14);
                for j in 0..2 {
                    assert!((p.stiffness[i][j] - a.stiffness[i][j]).abs() < 1e-12);
                }
            }
        }
    }

    #[test]
    fn multiplier_shift_holds_the_node_at_zero_gap() {
        // lambda* = 2: at g = 0 the force is 2 along n, at g = 2/alpha it opens
        let r = respond(100.0, 2.0, 0.5, 0.0, [0.0, 1.0], 0.0);
        assert_eq!(r.status, ContactStatus::Closed);
        assert_eq!(r.force, [0.0, 2.0]);
        assert_eq!(r.pressure, 4.0);
        let o = respond(100.0, 2.0, 0.5, 0.03, [0.0, 1.0], 0.0);
        assert_eq!(o.status, ContactStatus::Open);
        assert_eq!(normal_force(100.0, 2.0, 0.01), 1.0);
    }

    #[test]
    fn tangent_is_minus_force_derivative_on_a_circle() {
        // circle of centre 0 radius 1, node outside-penetrating at radius 0.99
        let (alpha, ls) = (30.0, 0.7);
        let force = |x: [f64; 2]| {
            let r = (x[0] * x[0] + x[1] * x[1]).sqrt();
            let n = [x[0] / r, x[1] / r];
            respond(alpha, ls, 1.0, r - 1.0, n, 1.0 / r).force
        };
        let x = [0.3, (0.99f64 * 0.99 - 0.09).sqrt()];
        let r = (x[0] * x[0] + x[1] * x[1]).sqrt();
        let k = respond(alpha, ls, 1.0, r - 1.0, [x[0] / r, x[1] / r], 1.0 / r).stiffness;
        let h = 1e-6;
        for j in 0..2 {
            let mut xp = x;
            let mut xm = x;
            xp[j] += h;
            xm[j] -= h;
            let (fp, fm) = (force(xp), force(xm));
            for i in 0..2 {
                let fd = -(fp[i] - fm[i]) / (2.0 * h);
                assert!((fd - k[i][j]).abs() < 1e-6, "{i}{j}: {fd} vs {}", k[i][j]);
            }
        }
    }
}
