//! Coulomb friction with mortar contact in 2D (seg2): the weighted
//! tangential slip of Gitterle, Popp, Gee & Wall (IJNME 84 (2010) 543,
//! "Finite deformation frictional mortar contact using a semi-smooth
//! Newton method with consistent linearization"; Popp, Gee & Wall, IJNME
//! 79 (2009) 1354 for the dual mortar frame), regularized by a tangential
//! penalty (and the augmented Lagrangian's Uzawa shift) as the
//! node-to-segment friction of [`super::super::friction`].
//!
//! **Weighted slip.** The mortar pairing of slave node `j` in the
//! committed (last converged) configuration `x^n` is kept as constant
//! coefficients ([`Pairing`]): per slave segment `e` of `j`'s support, the
//! vector `C^n_je(x) = sum_l M^n_jl x_l - sum_k D^n_jk x_k` (the dual
//! weighted relative position of the material points that faced each
//! other at `x^n`, evaluated at the current positions) and the committed
//! area `A^n_j = sum_k D^n_jk`. In `x^n` the master point facing a slave
//! point lies on the slave segment's normal, so `t_e . C^n_je(x^n) = 0`;
//! the weighted slip since `x^n` is
//!
//! `u~_j(x) = -sum_e t_e(x) . C^n_je(x)`, nodal slip `s_j = u~_j / A^n_j`,
//!
//! the objective form `t . ((M - M^n) x - (D - D^n) x)` of Gitterle et al.
//! with each slave segment's own tangent `t_e` (the current pairing's part
//! `t_e . C_je(x)` vanishes identically): a rigid motion of both bodies
//! gives 0, a slave sliding by `s` along a flat master gives `s`.
//!
//! **Return map** (per slave node, the normal force `R_N` of the mortar
//! row): the stick point is a slip coordinate `a_j` (in the frame of the
//! increment: `s_j = 0` at `x^n`), `g_T = s_j - a_j`, trial
//! `R* = lambda_T* - alpha_T g_T` (`lambda_T* = 0` with the penalty, the Uzawa shift with
//! the augmented Lagrangian), stick `|R*| <= mu R_N`: `R_T = R*`, slip:
//! `R_T = mu R_N sign(R*)`, the stick point moves by `(R_T - R*) /
//! alpha_T`. The history is [`super::super::friction::FrictionState`]
//! (`incremental`: the commit moves the frame's origin to the new
//! converged state, `a <- a - s`), so the restart checkpoint carries it.
//! A node without a committed pairing (it was farther than `prof` at
//! `x^n`) has `s = 0`: no tangential force in the increment it arrives.
//!
//! **Forces** with the current `D`, `M` (those of the normal force):
//! `f = (R_T / T_j) [D_jk t_e on the slave, -M_jl t_e on the master]`
//! (`T_j` the reference tributary area; forces sum to zero, their moment is
//! that of the penetration, as node-to-segment's), tangent `K = -df/dx`
//! exact: `R_T`'s derivative (stick `-alpha_T ds/dx`, slip `mu sign(R*) d
//! R_N / dx`) and the derivative of the current `D`, `M` and `t_e` (the
//! segmentation's, by [`super::ad`]).

use super::integrals::MortarSegment;
use crate::contact::friction::{FrictionStatus, NodeFriction};
use crate::contact::friction_facet::CONE_TIE;

/// Coefficients `(node, c)` of a linear combination of node positions.
pub type Coefficients = Vec<(usize, f64)>;

/// The committed pairing of one slave node (see the module doc).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Pairing {
    /// `A^n_j = sum_k D^n_jk` over the committed pieces.
    pub area: f64,
    /// Per slave segment `[a, b]` of the node's support: the coefficients
    /// `(node, c)` of `C^n_je(x) = sum c x_node` (sorted by node).
    pub segments: Vec<([usize; 2], Coefficients)>,
}

impl Pairing {
    /// Adds the piece of slave segment `[a, b]` against master segment
    /// `[c, d]` (`nodes = [a, b, c, d]`), seen from row `row` (0: `a`).
    pub fn add(&mut self, nodes: [usize; 4], row: usize, seg: &MortarSegment) {
        let j = row;
        self.area += seg.d[j][0].v + seg.d[j][1].v;
        let edge = [nodes[0], nodes[1]];
        let k = match self.segments.iter().position(|(e, _)| *e == edge) {
            Some(k) => k,
            None => {
                self.segments.push((edge, Vec::new()));
                self.segments.len() - 1
            }
        };
        let coefs = &mut self.segments[k].1;
        let terms = [
            (nodes[0], -seg.d[j][0].v),
            (nodes[1], -seg.d[j][1].v),
            (nodes[2], seg.m[j][0].v),
            (nodes[3], seg.m[j][1].v),
        ];
        for (n, c) in terms {
            match coefs.binary_search_by_key(&n, |t| t.0) {
                Ok(p) => coefs[p].1 += c,
                Err(p) => coefs.insert(p, (n, c)),
            }
        }
    }

    /// Every node the slip depends on.
    pub fn nodes(&self) -> impl Iterator<Item = usize> + '_ {
        self.segments
            .iter()
            .flat_map(|(e, c)| e.iter().copied().chain(c.iter().map(|t| t.0)))
    }

    /// The nodal slip `s = -sum_e t_e . C^n_e(x) / A^n` since the
    /// committed configuration and its gradient over `nodes` (sorted, 2
    /// components per node); `(0, 0)` without a committed pairing.
    pub fn slip(&self, x: &[[f64; 2]], nodes: &[usize]) -> (f64, Vec<f64>) {
        let mut grad = vec![0.0; 2 * nodes.len()];
        if self.area.is_nan() || self.area <= 0.0 || self.segments.is_empty() {
            return (0.0, grad);
        }
        let pos = |n: usize| nodes.binary_search(&n).ok();
        let mut s = 0.0;
        for ([a, b], coefs) in &self.segments {
            let (Some(&xa), Some(&xb)) = (x.get(*a), x.get(*b)) else {
                continue;
            };
            let e = [xb[0] - xa[0], xb[1] - xa[1]];
            let len = e[0].hypot(e[1]);
            if len.is_nan() || len <= 0.0 {
                continue;
            }
            let t = [e[0] / len, e[1] / len];
            let mut c = [0.0; 2];
            for &(n, k) in coefs {
                let xn = x.get(n).copied().unwrap_or([0.0; 2]);
                c[0] += k * xn[0];
                c[1] += k * xn[1];
                if let Some(p) = pos(n) {
                    grad[2 * p] += k * t[0];
                    grad[2 * p + 1] += k * t[1];
                }
            }
            let tc = t[0] * c[0] + t[1] * c[1];
            s += tc;
            // d t / d x_b = (I - t t^T) / L = -d t / d x_a
            let r = [(c[0] - tc * t[0]) / len, (c[1] - tc * t[1]) / len];
            if let (Some(pa), Some(pb)) = (pos(*a), pos(*b)) {
                for q in 0..2 {
                    grad[2 * pb + q] += r[q];
                    grad[2 * pa + q] -= r[q];
                }
            }
        }
        let f = -1.0 / self.area;
        grad.iter_mut().for_each(|g| *g *= f);
        (s * f, grad)
    }
}

/// The pairings of every slave node in the committed configuration, and
/// the converged-increment count they were computed for.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct CommittedPairing {
    /// `SurfacePair::increments` when computed (a rollback keeps it: the
    /// committed configuration is the same).
    pub key: usize,
    /// Per slave index (`PairState::slaves`).
    pub rows: Vec<Pairing>,
}

/// The friction law of one node row.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Law {
    /// Friction coefficient.
    pub mu: f64,
    /// Tangential penalty `alpha_T` (force per unit slip).
    pub alpha_t: f64,
    /// Tangential multiplier shift `lambda_T*` (augmented Lagrangian).
    pub shift: f64,
    /// Normal penalty `alpha_N = -d R_N / d g` while `R_N > 0`.
    pub alpha_n: f64,
    /// Normal force `R_N >= 0`.
    pub normal_force: f64,
    /// Reference tributary area `T_j` of the node.
    pub support: f64,
    /// Covered current area `A_j = sum_k D_jk` of the node's row.
    pub area: f64,
    /// Stick point (slip coordinate) the trial force is measured from.
    pub anchor: f64,
}

/// The friction part of one node row.
#[derive(Debug, Clone, PartialEq)]
pub struct Response {
    /// Output (status, `R_T`, `g_T`, slip increment, dissipation `-R_T
    /// ds`; `traction`: `R_T A / T` along the slave node's friction force,
    /// the convention of the reported pressure `R_N A / T^2` times `T`).
    pub friction: NodeFriction,
    /// Forces over the row's nodes (2 per node).
    pub force: Vec<f64>,
    /// `-d force / d x`, row-major.
    pub tangent: Vec<f64>,
    /// The node's slip coordinate `s` (its position in the increment's
    /// frame).
    pub position: f64,
    /// The stick point after the return map.
    pub anchor: f64,
}

/// The friction forces and tangent of the row of slave `node` over
/// `nodes` (sorted): `slip` and its gradient from [`Pairing::slip`],
/// `dgap` the gradient of the nodal gap, `bt`, `dbt` the tangential row
/// `[-D_jk t_e, M_jl t_e]` and its derivative (row-major `nd x nd`).
pub fn respond(
    law: &Law,
    node_at: usize,
    slip: (f64, &[f64]),
    dgap: &[f64],
    bt: &[f64],
    dbt: &[f64],
) -> Response {
    let nd = bt.len();
    let (s, ds_dx) = slip;
    let g_t = s - law.anchor;
    let trial = law.shift - law.alpha_t * g_t;
    let limit = law.mu * law.normal_force;
    // a trial within `CONE_TIE` below the cone slips (node-to-facet's tie
    // rule: a node that slipped starts the next increment on the cone to
    // round-off, and its tangent must not depend on the last bits)
    let inside = trial.abs() <= limit * (1.0 - CONE_TIE) && limit > 0.0;
    let (rt, drt, status): (f64, Vec<f64>, _) = if inside {
        let d = ds_dx.iter().map(|v| -law.alpha_t * v).collect();
        (trial, d, FrictionStatus::Stick)
    } else {
        let sign = trial.signum();
        let d = if law.normal_force > 0.0 {
            dgap.iter()
                .map(|v| -law.mu * sign * law.alpha_n * v)
                .collect()
        } else {
            vec![0.0; nd]
        };
        (limit * sign, d, FrictionStatus::Slip)
    };
    let ds = if law.alpha_t > 0.0 {
        (rt - trial) / law.alpha_t
    } else {
        0.0
    };
    let q = rt / law.support;
    // f = -(R_T / T) bt: the slave gets (R_T / T) D t
    let force: Vec<f64> = bt.iter().map(|b| -q * b).collect();
    let mut tangent = vec![0.0; nd * nd];
    for r in 0..nd {
        for c in 0..nd {
            tangent[r * nd + c] = (bt[r] * drt[c] / law.support) + q * dbt[r * nd + c];
        }
    }
    // reported as the pressure is (the slave force of a fully covered
    // node, `R_T A / T`, along the slave node's friction force)
    let at = 2 * node_at;
    let own = [force[at], force[at + 1]];
    let ol = own[0].hypot(own[1]);
    let tl = rt.abs() * law.area / law.support;
    let traction = if ol > 0.0 {
        [own[0] / ol * tl, own[1] / ol * tl]
    } else {
        [0.0; 2]
    };
    Response {
        friction: NodeFriction {
            status,
            tangential_force: rt,
            tangential_gap: g_t,
            slip: ds,
            traction,
            slip_vector: [0.0; 2],
            gap_gradient: if tl > 0.0 {
                [
                    traction[0] / tl * rt.signum(),
                    traction[1] / tl * rt.signum(),
                ]
            } else {
                [0.0; 2]
            },
            dissipation: -rt * ds,
        },
        force,
        tangent,
        position: s,
        anchor: law.anchor + ds,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The 2D twin of `friction3d`'s tie test: a node that slipped starts
    /// the next increment with its trial force on the cone `mu R_N` to
    /// round-off; moved by +-1e-13 of that slip it must get one status and
    /// one tangent, the slip's (`d R_T / d x` along the slip 0). One slave
    /// node over a row of 2 coordinates, `R_N = 1`, mu = 0.3, `alpha_T =
    /// 40`, the tangential row `bt = [1, 0]`.
    #[test]
    fn a_node_on_the_cone_to_round_off_slips_whatever_the_last_bits() {
        let law = Law {
            mu: 0.3,
            alpha_t: 40.0,
            shift: 0.0,
            alpha_n: 100.0,
            normal_force: 1.0,
            support: 1.0,
            area: 1.0,
            anchor: 0.0,
        };
        let (ds, dgap, bt, dbt) = ([1.0, 0.0], [0.0, 1.0], [1.0, 0.0], [0.0; 4]);
        let cone = 0.3 / 40.0;
        for rel in [-1e-13, 0.0, 1e-13] {
            let r = respond(&law, 0, (-cone * (1.0 + rel), &ds), &dgap, &bt, &dbt);
            assert_eq!(r.friction.status, FrictionStatus::Slip, "rel {rel:e}");
            assert!((r.friction.tangential_force - 0.3).abs() < 1e-9);
            assert!(
                r.tangent[0].abs() < 1e-9,
                "rel {rel:e}: K_xx {}",
                r.tangent[0]
            );
        }
        let r = respond(&law, 0, (-0.5 * cone, &ds), &dgap, &bt, &dbt);
        assert_eq!(r.friction.status, FrictionStatus::Stick);
    }
}
