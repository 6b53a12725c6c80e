//! Penalty enforcement of the normal contact constraint (seed slides,
//! "Penalty method"): `R_N = -alpha g` for `g < 0`, 0 otherwise.
//!
//! Force on the node: `f = -alpha_eff g n` for `g < 0` (pushes the node back
//! to the free side). It derives from the potential `alpha_eff g^2 / 2`, so
//! the consistent tangent is symmetric:
//!
//! `K_c = -d f / d x = alpha_eff (n ⊗ n + g h t ⊗ t)`
//!
//! using `d g / d x = n` and `d n / d x = h t ⊗ t` (see
//! [`crate::contact::geometry::Projection::normal_rate`]). For a plane
//! `h = 0`; for a circle seen from outside `h = 1 / |x - c|`; at a corner
//! `g h = 1` and `K_c = alpha_eff I`.

use crate::contact::vec2::outer;
use crate::contact::ContactStatus;
use crate::model::{ContactMethod, PenaltyKind};

/// Penalty coefficient of a node in force per unit gap: the nodal
/// stiffness itself, or the pressure-per-gap stiffness times the node's
/// tributary area.
pub fn effective_stiffness(method: &ContactMethod, tributary: f64) -> f64 {
    match method {
        ContactMethod::Penalty { kind, stiffness }
        | ContactMethod::AugmentedLagrange {
            kind,
            penalty: stiffness,
            ..
        } => match kind {
            PenaltyKind::Nodal => *stiffness,
            PenaltyKind::Area => *stiffness * tributary,
        },
        ContactMethod::Lagrange { .. } => 0.0,
    }
}

/// Force, tangent, pressure and status of one node.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Response {
    /// Force exerted by the tool on the node.
    pub force: [f64; 2],
    /// `K_c = -d force / d x`.
    pub stiffness: [[f64; 2]; 2],
    /// Normal force / tributary area (>= 0).
    pub pressure: f64,
    /// Open (`g >= 0`) or closed (`g < 0`).
    pub status: ContactStatus,
}

/// Penalty response of a node with gap `gap`, unit normal `normal` (current
/// frame) and normal rate `normal_rate`, for a node of tributary area
/// `tributary`.
pub fn respond(
    method: &ContactMethod,
    tributary: f64,
    gap: f64,
    normal: [f64; 2],
    normal_rate: f64,
) -> Response {
    if gap >= 0.0 {
        return Response {
            force: [0.0; 2],
            stiffness: [[0.0; 2]; 2],
            pressure: 0.0,
            status: ContactStatus::Open,
        };
    }
    let alpha = effective_stiffness(method, tributary);
    let n = normal;
    let t = [n[1], -n[0]];
    let nn = outer(n, n);
    let tt = outer(t, t);
    let geo = gap * normal_rate;
    let mut k = [[0.0; 2]; 2];
    for i in 0..2 {
        for j in 0..2 {
            k[i][j] = alpha * (nn[i][j] + geo * tt[i][j]);
        }
    }
    let pressure = match method {
        ContactMethod::Penalty {
            kind: PenaltyKind::Area,
            stiffness,
        } => stiffness * -gap,
        _ if tributary > 0.0 => alpha * -gap / tributary,
        _ => 0.0,
    };
    Response {
        force: [-alpha * gap * n[0], -alpha * gap * n[1]],
        stiffness: k,
        pressure,
        status: ContactStatus::Closed,
    }
}

/// Fraction of the smallest slave edge of a pair within which a slave
/// node counts as touching its master at the start of the analysis
/// ([`touching`], `crate::contact::PairState::touching`).
pub const TOUCH_FRACTION: f64 = 1e-3;

/// Closed-gap start: a node of penalty coefficient `alpha` whose gap lies
/// in `[0, touching]` is closed with zero force and the tangent
/// `alpha n ⊗ n` (the curvature term vanishes with the force), so that the
/// first tangent holds a body that only this contact can hold; `None`
/// otherwise (and always when `touching <= 0`).
pub fn touching(
    alpha: f64,
    gap: f64,
    touching: f64,
    tributary: f64,
    normal: [f64; 2],
    normal_rate: f64,
) -> Option<Response> {
    (touching > 0.0 && (0.0..=touching).contains(&gap) && alpha > 0.0)
        .then(|| super::augmented::normal_response(alpha, 0.0, tributary, normal, normal_rate))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn penalty_force_pushes_back_and_open_is_free() {
        let m = ContactMethod::Penalty {
            kind: PenaltyKind::Area,
            stiffness: 100.0,
        };
        let r = respond(&m, 0.5, -0.01, [0.0, 1.0], 0.0);
        assert_eq!(r.status, ContactStatus::Closed);
        assert!((r.force[1] - 0.5).abs() < 1e-15 && r.force[0] == 0.0);
        assert_eq!(r.stiffness, [[0.0, 0.0], [0.0, 50.0]]);
        assert!((r.pressure - 1.0).abs() < 1e-15);
        let o = respond(&m, 0.5, 0.01, [0.0, 1.0], 0.0);
        assert_eq!(
            (o.status, o.force, o.pressure),
            (ContactStatus::Open, [0.0; 2], 0.0)
        );
        let nodal = ContactMethod::Penalty {
            kind: PenaltyKind::Nodal,
            stiffness: 100.0,
        };
        let r = respond(&nodal, 0.5, -0.01, [1.0, 0.0], 0.0);
        assert!((r.force[0] - 1.0).abs() < 1e-15);
        assert!((r.pressure - 2.0).abs() < 1e-15);
    }

    #[test]
    fn a_touching_node_is_closed_with_zero_force_and_the_normal_stiffness() {
        let r = touching(50.0, 1e-6, 1e-5, 0.5, [0.0, 1.0], 2.0).expect("touching");
        assert_eq!(r.status, ContactStatus::Closed);
        assert_eq!((r.force, r.pressure), ([0.0; 2], 0.0));
        assert_eq!(r.stiffness, [[0.0, 0.0], [0.0, 50.0]]);
        assert!(touching(50.0, 2e-5, 1e-5, 0.5, [0.0, 1.0], 0.0).is_none());
        assert!(touching(50.0, -1e-6, 1e-5, 0.5, [0.0, 1.0], 0.0).is_none());
        assert!(touching(50.0, 0.0, 0.0, 0.5, [0.0, 1.0], 0.0).is_none());
    }

    #[test]
    fn corner_tangent_is_isotropic() {
        let m = ContactMethod::Penalty {
            kind: PenaltyKind::Nodal,
            stiffness: 3.0,
        };
        // Corner: normal_rate = 1 / gap, so g h = 1 and K = alpha I.
        let r = respond(&m, 1.0, -0.2, [0.6, 0.8], 1.0 / -0.2);
        for i in 0..2 {
            for j in 0..2 {
                let e = if i == j { 3.0 } else { 0.0 };
                assert!((r.stiffness[i][j] - e).abs() < 1e-14);
            }
        }
    }
}
