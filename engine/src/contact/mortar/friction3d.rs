//! Coulomb friction with mortar contact in 3D (tri3 / quad4 facets,
//! [`super::facets`]): the weighted tangential slip of Gitterle, Popp,
//! Gee & Wall (IJNME 84 (2010) 543) as a vector of the slave node's
//! tangent plane, the 3D form of [`super::friction`].
//!
//! **Weighted slip.** The mortar pairing of slave node `j` in the
//! committed configuration `x^n` is kept as constant coefficients
//! ([`Pairing`]): per slave facet `e` of `j`'s support, `C^n_je(x) =
//! sum_l M^n_jl x_l - sum_k D^n_jk x_k` (summed over `e`'s facet pairs),
//! and `A^n_j = sum_k D^n_jk`. In `x^n` every master point faces its slave
//! point along the normal `n_e` of `e`'s auxiliary plane, so `C^n_je(x^n)`
//! is parallel to `n_e`. The weighted slip since `x^n` is the vector
//!
//! `u~_j(x) = -sum_e P_e(x) C^n_je(x)`, `P_e = I - n_e ⊗ n_e`, nodal slip
//! `s_j = u~_j / A^n_j`,
//!
//! each facet's part projected on **that facet's own tangent plane** (as
//! the 2D code takes each segment's own tangent): a rigid motion of both
//! bodies rotates `C` and `n_e` together and gives `s = 0` exactly; a
//! slave sliding by `v` along a flat master gives `C = C^n - D^n_e v`,
//! so `s = v` exactly.
//!
//! **Return map** in the slave node's tangent plane: its normal `nu` is
//! the direction of the node's own normal row (`-sum_e D_jj n_e`, the
//! normal reported), `P = I - nu ⊗ nu`. The stick point is a slip vector
//! `a_j` of the increment's frame ([`crate::contact::friction::FrictionState`]
//! with `incremental`: the commit rebases `a <- a - s`, so the restart
//! checkpoint carries it), `g_T = P (s_j - a_j)`, the trial force
//! `t* = P (m - alpha_T (s_j - a_j))` (`m` the augmented Lagrangian's
//! tangential shift, a vector of the current frame; 0 for the penalty),
//! and the return to the circular cone `|t| <= mu R_N`: stick `t = t*`;
//! slip `t = mu R_N t* / |t*|`, the stick point moving by `(t - t*) /
//! alpha_T` (a trial force of a round-off slip sticks, and a node
//! pressed by a round-off gap is open: [`ROUND_OFF`]). A node without a
//! committed pairing (farther than `prof` at `x^n`) has `s = 0`: no
//! tangential force in the increment it arrives.
//! The stick vector `a_j` is held in the global frame (projected on the
//! current tangent plane): a node sticking with an elastic offset while
//! the interface turns by a finite angle within one increment is not
//! objective at first order in that angle (the slip `s` itself is).
//!
//! **Forces** through the current `D`, `M` (those of the normal force):
//! `f = (t / T_j) [D_jk on the slave, -M_jl on the master]` (`T_j` the
//! reference tributary area; the forces sum to zero, the slave node's own
//! friction force is along `t`, orthogonal to its normal force), tangent
//! `K = -df/dx` exact: the derivative of `t` (the slip through `n_e(x)`,
//! the tangent plane through `nu(x)`, `R_N` in slip) and of the current
//! `D`, `M` (the segmentation's, by [`super::ad`]).

use super::facets::FacetSegment;
use super::UNUSED;
use crate::contact::friction::{FrictionState, FrictionStatus, NodeFriction};
use crate::contact::friction_facet::CONE_TIE;
use crate::contact::mortar::ad::Ad;
use crate::contact::node_to_facet::{cross, dot, sub};
use crate::contact::NodeContact;

/// Coefficients `(node, c)` of a linear combination of node positions.
pub type Coefficients = Vec<(usize, f64)>;

/// The committed pairing of one slave node (see the module doc).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Pairing {
    /// `A^n_j = sum_k D^n_jk` over the committed facet pairs.
    pub area: f64,
    /// Per slave facet of the node's support: its nodes (a tri3's fourth
    /// [`UNUSED`]) and the coefficients `(node, c)` of `C^n_je(x) = sum c
    /// x_node` (sorted by node).
    pub facets: Vec<([usize; 4], Coefficients)>,
}

impl Pairing {
    /// Adds facet pair `seg` (variables `vars`: slave facet nodes in slots
    /// 0..4, master ones in 4..8) seen from the slave facet's node `j`.
    pub fn add(&mut self, vars: &[usize; 8], j: usize, seg: &FacetSegment) {
        let (d, m) = (seg.d[j].map(|v| v.v), seg.m[j].map(|v| v.v));
        self.add_row(vars, seg.ns, seg.nm, d, m);
    }

    /// [`Pairing::add`] from the values of row `j`: `D_jk` (`ns` slave
    /// nodes) and `M_jl` (`nm` master nodes).
    pub fn add_row(&mut self, vars: &[usize; 8], ns: usize, nm: usize, d: [f64; 4], m: [f64; 4]) {
        self.area += d[..ns].iter().sum::<f64>();
        let facet = [vars[0], vars[1], vars[2], vars[3]];
        let k = match self.facets.iter().position(|(f, _)| *f == facet) {
            Some(k) => k,
            None => {
                self.facets.push((facet, Vec::new()));
                self.facets.len() - 1
            }
        };
        let coefs = &mut self.facets[k].1;
        let terms = (0..ns)
            .map(|k| (vars[k], -d[k]))
            .chain((0..nm).map(|l| (vars[4 + l], m[l])));
        for (n, c) in terms {
            match coefs.binary_search_by_key(&n, |t| t.0) {
                Ok(p) => coefs[p].1 += c,
                Err(p) => coefs.insert(p, (n, c)),
            }
        }
    }

    /// The nodal gap `sum_e n_e . C^n_je(x) / A^n` at `x`: in the
    /// committed configuration (where `C^n_je` is parallel to `n_e`) the
    /// node's committed nodal gap `g~ / A` (positive open). 0 without a
    /// committed pairing.
    pub fn normal_gap(&self, x: &[[f64; 3]]) -> f64 {
        if self.area.is_nan() || self.area <= 0.0 {
            return 0.0;
        }
        let mut g = 0.0;
        for (facet, coefs) in &self.facets {
            let Some(n) = facet_normal(facet, x) else {
                continue;
            };
            for &(m, k) in coefs {
                let xm = x.get(m).copied().unwrap_or([0.0; 3]);
                g += k * (n[0].v * xm[0] + n[1].v * xm[1] + n[2].v * xm[2]);
            }
        }
        g / self.area
    }

    /// Every node the slip depends on.
    pub fn nodes(&self) -> impl Iterator<Item = usize> + '_ {
        self.facets.iter().flat_map(|(f, c)| {
            f.iter()
                .copied()
                .filter(|&n| n != UNUSED)
                .chain(c.iter().map(|t| t.0))
        })
    }

    /// The nodal slip vector `s = -sum_e P_e C^n_e(x) / A^n` since the
    /// committed configuration and its gradient over `nodes` (sorted, 3
    /// components per node): `grad[c]` is `d s_c / d x`. Zero without a
    /// committed pairing.
    pub fn slip(&self, x: &[[f64; 3]], nodes: &[usize]) -> ([f64; 3], [Vec<f64>; 3]) {
        let nd = 3 * nodes.len();
        let mut grad = [vec![0.0; nd], vec![0.0; nd], vec![0.0; nd]];
        if self.area.is_nan() || self.area <= 0.0 || self.facets.is_empty() {
            return ([0.0; 3], grad);
        }
        let pos = |n: usize| nodes.binary_search(&n).ok();
        let mut s = [0.0; 3];
        for (facet, coefs) in &self.facets {
            let Some(n) = facet_normal(facet, x) else {
                continue;
            };
            let nv = n.map(|v| v.v);
            let mut c = [0.0; 3];
            for &(m, k) in coefs {
                let xm = x.get(m).copied().unwrap_or([0.0; 3]);
                for q in 0..3 {
                    c[q] += k * xm[q];
                }
            }
            let nc = nv[0] * c[0] + nv[1] * c[1] + nv[2] * c[2];
            for q in 0..3 {
                s[q] += c[q] - nv[q] * nc;
            }
            // through C (constant coefficients): k (I - n n^T)
            for &(m, k) in coefs {
                let Some(p) = pos(m) else { continue };
                for (q, g) in grad.iter_mut().enumerate() {
                    for r in 0..3 {
                        let delta = if q == r { 1.0 } else { 0.0 };
                        g[3 * p + r] += k * (delta - nv[q] * nv[r]);
                    }
                }
            }
            // through n: -(dn (n . C) + n (dn . C))
            for (a, &m) in facet.iter().enumerate() {
                let Some(p) = pos(m).filter(|_| m != UNUSED) else {
                    continue;
                };
                for r in 0..3 {
                    let v = 3 * a + r;
                    let dn = [n[0].d[v], n[1].d[v], n[2].d[v]];
                    let dnc = dn[0] * c[0] + dn[1] * c[1] + dn[2] * c[2];
                    for (q, g) in grad.iter_mut().enumerate() {
                        g[3 * p + r] -= dn[q] * nc + nv[q] * dnc;
                    }
                }
            }
        }
        let f = -1.0 / self.area;
        for g in &mut grad {
            g.iter_mut().for_each(|v| *v *= f);
        }
        (s.map(|v| v * f), grad)
    }
}

/// The unit normal of slave facet `facet` (its auxiliary plane's,
/// [`super::facets`]: tri3 `(x_2 - x_1) x (x_3 - x_1)`, quad4 the
/// diagonals' product) in dual numbers over its 12 coordinates (`3 a +
/// c`); `None` for a degenerate facet or a node outside `x`.
fn facet_normal(facet: &[usize; 4], x: &[[f64; 3]]) -> Option<[Ad<12>; 3]> {
    let ns = facet.iter().filter(|&&n| n != UNUSED).count();
    let mut p = [[Ad::<12>::cst(0.0); 3]; 4];
    for (a, &m) in facet.iter().enumerate().take(ns) {
        let xm = x.get(m)?;
        p[a] = std::array::from_fn(|c| Ad::var(xm[c], 3 * a + c));
    }
    let raw = match ns {
        3 => cross(sub(p[1], p[0]), sub(p[2], p[0])),
        4 => cross(sub(p[2], p[0]), sub(p[3], p[1])),
        _ => return None,
    };
    let len = dot(raw, raw).sqrt();
    if len.v.is_nan() || len.v <= 0.0 {
        return None;
    }
    Some(raw.map(|v| v / len))
}

/// The pairings of every slave node in the committed configuration, and
/// the converged-increment count they were computed for.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct CommittedPairing {
    /// `DeformablePair::increments` when computed (a rollback keeps it).
    pub key: usize,
    /// Per slave index.
    pub rows: Vec<Pairing>,
}

/// The friction law of one node row.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Law {
    /// Friction coefficient.
    pub mu: f64,
    /// Tangential penalty `alpha_T` (force per unit slip).
    pub alpha_t: f64,
    /// Tangential shift `m` (augmented Lagrangian; 0 for the penalty),
    /// current frame.
    pub shift: [f64; 3],
    /// Normal penalty `alpha_N = -d R_N / d g` while `R_N > 0`.
    pub alpha_n: f64,
    /// Normal force `R_N >= 0`.
    pub normal_force: f64,
    /// Reference tributary area `T_j` of the node.
    pub support: f64,
    /// Covered current area `A_j = sum_k D_jk` of the node's row.
    pub area: f64,
    /// Stick point (slip vector) the trial force is measured from.
    pub anchor: [f64; 3],
    /// First touch in this increment (the node open in the committed
    /// state): `[g0, g]`, its nodal gap in the committed configuration
    /// (`> 0`) and the current one. The stick point is then where the
    /// straight path from the committed configuration crosses the master,
    /// `a = anchor + tau (s - anchor)`, `tau = g0 / (g0 - g)` (1 at `g >=
    /// 0`), a function of the current state (see [`Law::offset`]).
    pub impact: Option<[f64; 2]>,
}

impl Law {
    /// The slip from the stick point, `e = s - a`, and its gradient over
    /// the row's coordinates (`ds` the slip's, `dgap` the nodal gap's).
    /// Without a first touch the stick point is fixed: `e = s - anchor`.
    /// At a first touch `a = anchor + tau (s - anchor)`: `e = (1 - tau)
    /// (s - anchor)`, `de = (1 - tau) ds - (s - anchor) dtau`, `dtau =
    /// tau / (g0 - g) dg` (0 at `g >= 0`). The tangential force of a node that
    /// closes vanishes with its gap, as its normal force does: no slip of
    /// the approach (the relative motion of the two surfaces before they
    /// touch) is charged to the stick point. Before this rule the stick
    /// point of a node closing in the increment was its committed
    /// position: the approach counted as slip, the node slipped where it
    /// sticks, and Newton cycled (`ironing_3d`'s mortar mu = 0.3 press:
    /// its flank nodes 9 <-> 3 closed at level 0).
    pub fn offset(
        &self,
        s: &[f64; 3],
        ds: &[Vec<f64>; 3],
        dgap: &[f64],
    ) -> ([f64; 3], [Vec<f64>; 3]) {
        let mut e: [f64; 3] = std::array::from_fn(|c| s[c] - self.anchor[c]);
        let mut de = ds.clone();
        if let Some([g0, g]) = self.impact.filter(|i| i[0] > 0.0) {
            let (tau, k) = if g < 0.0 {
                let tau = g0 / (g0 - g);
                (tau, tau / (g0 - g))
            } else {
                (1.0, 0.0)
            };
            for c in 0..3 {
                let full = e[c];
                e[c] = (1.0 - tau) * full;
                for (v, dg) in de[c].iter_mut().zip(dgap) {
                    *v = (1.0 - tau) * *v - full * k * dg;
                }
            }
        }
        (e, de)
    }
}

/// The scalar mortar row of one slave node over its nodes: `-D_jk` on the
/// slave nodes, `M_jl` on the master ones (summed over the facet pairs)
/// and their gradient (row-major `nodes x 3 nodes`).
pub struct CoefficientRow {
    /// Per node of the row.
    pub coef: Vec<f64>,
    /// `d coef / d x`, row-major `nodes x nd`.
    pub dcoef: Vec<f64>,
}

/// The slave node's own normal row: `sn = -sum_e D_jj n_e` and its
/// gradient (3 rows of `nd`), from which the node's unit normal `nu =
/// -sn / |sn|` and its tangent plane follow.
pub struct OwnNormal<'a> {
    /// `sn`.
    pub sn: [f64; 3],
    /// `d sn / d x`, rows of `nd`.
    pub dsn: [&'a [f64]; 3],
}

/// The friction part of one node row.
#[derive(Debug, Clone, PartialEq)]
pub struct Response {
    /// Output (status, `|t|`, `|g_T|`, slip of the return map and its
    /// vector, dissipation `-t . slip`; `traction`: `t A / T`, the
    /// convention of the reported pressure `R_N A / T^2` times `T`).
    pub friction: NodeFriction<3>,
    /// Forces over the row's nodes (3 per node).
    pub force: Vec<f64>,
    /// `-d force / d x`, row-major.
    pub tangent: Vec<f64>,
    /// The tangential force `t` of the node (force units; the augmented
    /// Lagrangian's next shift).
    pub traction: [f64; 3],
    /// The node's slip vector `s` (its position in the increment's frame).
    pub position: [f64; 3],
    /// The stick point after the return map.
    pub anchor: [f64; 3],
}

/// Gaps and tangential gaps up to this fraction of a node's length scale
/// `sqrt(T_j)` are round-off. Two meshed blocks that touch on a flat
/// interface have nodal gaps of round-off (either sign) at the start: a
/// frictional node whose normal force is that of such a penetration is
/// left open (see `Row::close_with_friction_3d`), and a node whose trial
/// force is within `alpha_T` times a round-off slip sticks even where `mu
/// R_N` is smaller. Without the first, half the interface nodes of the 3D
/// patch test closed with an `R_N` of round-off in the first Newton
/// iteration and stuck there: the top block tilted on them, slid sideways
/// by 3e-4, and Newton did not converge in 30 iterations (with it: 2, as
/// with a gap of 1e-9 at the start). Without the second, such a node
/// slipped in a direction of noise, its tangent `mu t*/|t*| ⊗ dR_N/dx`
/// coupling the full normal stiffness into that direction.
pub const ROUND_OFF: f64 = 1e-12;

fn dot3(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// The friction forces and tangent of a node row over `nd = 3 nodes`
/// coordinates: `own` its normal row, `slip` and its gradient from
/// [`Pairing::slip`], `dgap` the gradient of the nodal gap, `row` the
/// distribution of the forces.
pub fn respond(
    law: &Law,
    own: &OwnNormal,
    slip: &([f64; 3], [Vec<f64>; 3]),
    dgap: &[f64],
    row: &CoefficientRow,
) -> Response {
    let nd = dgap.len();
    let (s, ds) = slip;
    // the node's tangent plane
    let sl = dot3(own.sn, own.sn).sqrt();
    let nu = if sl > 0.0 {
        own.sn.map(|v| -v / sl)
    } else {
        [0.0; 3]
    };
    let mut dnu = [vec![0.0; nd], vec![0.0; nd], vec![0.0; nd]];
    if sl > 0.0 {
        for (c, d) in dnu.iter_mut().enumerate() {
            for (col, v) in d.iter_mut().enumerate() {
                let mut acc = 0.0;
                for q in 0..3 {
                    let delta = if c == q { 1.0 } else { 0.0 };
                    acc += (delta - nu[c] * nu[q]) * own.dsn[q][col];
                }
                *v = -acc / sl;
            }
        }
    }
    let (e, de) = law.offset(s, ds, dgap);
    let ne = dot3(nu, e);
    let g_t: [f64; 3] = std::array::from_fn(|c| e[c] - nu[c] * ne);
    // trial t* = P w, w = m - alpha_T (s - a)
    let w: [f64; 3] = std::array::from_fn(|c| law.shift[c] - law.alpha_t * e[c]);
    let nw = dot3(nu, w);
    let trial: [f64; 3] = std::array::from_fn(|c| w[c] - nu[c] * nw);
    // d t* = dw - dnu (nu . w) - nu (dnu . w + nu . dw), dw = -alpha_T de
    let mut dtrial = [vec![0.0; nd], vec![0.0; nd], vec![0.0; nd]];
    for col in 0..nd {
        let dw: [f64; 3] = std::array::from_fn(|c| -law.alpha_t * de[c][col]);
        let dn: [f64; 3] = std::array::from_fn(|c| dnu[c][col]);
        let dnw = dot3(dn, w) + dot3(nu, dw);
        for c in 0..3 {
            dtrial[c][col] = dw[c] - dn[c] * nw - nu[c] * dnw;
        }
    }
    let limit = law.mu * law.normal_force;
    let norm = dot3(trial, trial).sqrt();
    let drn: Vec<f64> = if law.normal_force > 0.0 {
        dgap.iter().map(|v| -law.alpha_n * v).collect()
    } else {
        vec![0.0; nd]
    };
    // a trial force of a round-off slip sticks whatever `mu R_N` (a node
    // closed by a gap of round-off carries an `R_N` of round-off, and the
    // direction of a slip there would be noise); a trial within
    // `CONE_TIE` below the cone slips (node-to-facet's tie rule: a node
    // that slipped starts the next increment on the cone to round-off)
    let noise = law.alpha_t * ROUND_OFF * law.support.max(0.0).sqrt();
    let inside = norm <= limit * (1.0 - CONE_TIE) && limit > 0.0;
    let (t, dt, status) = if inside || norm <= noise {
        (trial, dtrial, FrictionStatus::Stick)
    } else if norm > 0.0 {
        let u = trial.map(|v| v / norm);
        let k = limit / norm;
        let mut dt = [vec![0.0; nd], vec![0.0; nd], vec![0.0; nd]];
        for col in 0..nd {
            let ud = u[0] * dtrial[0][col] + u[1] * dtrial[1][col] + u[2] * dtrial[2][col];
            for c in 0..3 {
                dt[c][col] = law.mu * drn[col] * u[c] + k * (dtrial[c][col] - u[c] * ud);
            }
        }
        (u.map(|v| v * limit), dt, FrictionStatus::Slip)
    } else {
        let zero = [vec![0.0; nd], vec![0.0; nd], vec![0.0; nd]];
        ([0.0; 3], zero, FrictionStatus::Slip)
    };
    let delta: [f64; 3] = if law.alpha_t > 0.0 {
        std::array::from_fn(|c| (t[c] - trial[c]) / law.alpha_t)
    } else {
        [0.0; 3]
    };
    // f = -(t / T) coef: the slave gets (D / T) t, the master -(M / T) t
    let inv = 1.0 / law.support;
    let nodes = row.coef.len();
    let mut force = vec![0.0; nd];
    let mut tangent = vec![0.0; nd * nd];
    for p in 0..nodes {
        let cp = row.coef[p];
        let dcp = &row.dcoef[p * nd..(p + 1) * nd];
        for c in 0..3 {
            let r = 3 * p + c;
            force[r] = -inv * t[c] * cp;
            let out = &mut tangent[r * nd..(r + 1) * nd];
            for (col, o) in out.iter_mut().enumerate() {
                *o = inv * (cp * dt[c][col] + t[c] * dcp[col]);
            }
        }
    }
    let norm3 = |v: [f64; 3]| dot3(v, v).sqrt();
    let scale = law.area / law.support;
    Response {
        friction: NodeFriction {
            status,
            tangential_force: norm3(t),
            tangential_gap: norm3(g_t),
            slip: norm3(delta),
            traction: t.map(|v| v * scale),
            slip_vector: delta,
            gap_gradient: [0.0; 3],
            dissipation: -dot3(t, delta) + 0.0,
        },
        force,
        tangent,
        traction: t,
        position: *s,
        anchor: std::array::from_fn(|c| s[c] - e[c] + delta[c]),
    }
}

/// Uzawa update of the tangential shifts of an augmented-Lagrangian
/// mortar pair: `m <- t` (the node's tangential force `forces[i]` of the
/// latest evaluation) at every node with friction in `contact`, 0
/// elsewhere; the trial force is measured from the current trial stick
/// point from then on (the shift carries the force accumulated up to it).
pub fn uzawa_update(
    slaves: &[usize],
    contact: &[NodeContact<3>],
    forces: &[[f64; 3]],
    state: &mut FrictionState<3>,
) {
    state.shift.iter_mut().for_each(|m| *m = [0.0; 3]);
    for c in contact {
        if c.friction.status == FrictionStatus::Frictionless {
            continue;
        }
        if let Ok(i) = slaves.binary_search(&c.node) {
            state.shift[i] = forces.get(i).copied().unwrap_or([0.0; 3]);
            state.base[i] = state.anchor[i];
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::{facets, row_3d, Basis, FacetPiece, FrictionInputs3, UNUSED};
    use super::*;

    /// Slave: 2 x 2 quads on `z = 0` over `[0, 2]^2` (nodes 0..9, `3 j +
    /// i`, outward `+z`; node 4 in the middle); master: 2 x 2 quads over
    /// `[-0.2, 2.3]^2` at `z = -0.01` (nodes 9..18, facing `-z`).
    fn reference() -> Vec<[f64; 3]> {
        let mut x = Vec::new();
        for j in 0..3 {
            for i in 0..3 {
                x.push([i as f64, j as f64, 0.0]);
            }
        }
        for j in 0..3 {
            for i in 0..3 {
                x.push([-0.2 + 1.25 * i as f64, -0.2 + 1.25 * j as f64, -0.01]);
            }
        }
        x
    }

    fn faces(base: usize, facing_up: bool) -> Vec<[usize; 4]> {
        let n = |i: usize, j: usize| base + 3 * j + i;
        let mut f = Vec::new();
        for j in 0..2 {
            for i in 0..2 {
                f.push(if facing_up {
                    [n(i, j), n(i + 1, j), n(i + 1, j + 1), n(i, j + 1)]
                } else {
                    [n(i, j), n(i, j + 1), n(i + 1, j + 1), n(i + 1, j)]
                });
            }
        }
        f
    }

    /// The facet pairs at `x` and the `(piece, row)` list of the middle
    /// slave node.
    fn pieces(x: &[[f64; 3]]) -> (Vec<FacetPiece>, Vec<(usize, usize)>) {
        let (mut out, mut list) = (Vec::new(), Vec::new());
        for s in faces(0, true) {
            let sx: Vec<[f64; 3]> = s.iter().map(|&n| x[n]).collect();
            for (m, mf) in faces(9, false).into_iter().enumerate() {
                let mx: Vec<[f64; 3]> = mf.iter().map(|&n| x[n]).collect();
                let Some(seg) = facets::facet_pair(&sx, &mx, Basis::Dual) else {
                    continue;
                };
                let mut vars = [UNUSED; 8];
                vars[..4].copy_from_slice(&s);
                vars[4..].copy_from_slice(&mf);
                if let Some(j) = s.iter().position(|&n| n == 4) {
                    list.push((out.len(), j));
                }
                out.push(FacetPiece {
                    vars,
                    master: m,
                    seg,
                    covered: None,
                });
            }
        }
        (out, list)
    }

    fn pairing_at(xn: &[[f64; 3]]) -> Pairing {
        let (p, list) = pieces(xn);
        let mut out = Pairing::default();
        for (k, j) in list {
            out.add(&p[k].vars, j, &p[k].seg);
        }
        out
    }

    /// The middle node's frictional row at `x` with its committed pairing:
    /// `(nodes, masters and clip sizes, entry, coupling)`.
    #[allow(clippy::type_complexity)]
    fn middle_row(
        x: &[[f64; 3]],
        pairing: &Pairing,
        mu: f64,
        anchor: [f64; 3],
        shift: ([f64; 3], f64),
        start_gap: Option<f64>,
    ) -> Option<(
        Vec<usize>,
        Vec<(usize, usize)>,
        NodeContact<3>,
        crate::contact::mortar::Coupling,
    )> {
        let (p, list) = pieces(x);
        let mut nodes: Vec<usize> = list
            .iter()
            .flat_map(|&(k, _)| p[k].vars)
            .chain(pairing.nodes())
            .collect();
        nodes.sort_unstable();
        nodes.dedup();
        let (row, scalar) = row_3d(&p, &list, &nodes, true);
        let inputs = FrictionInputs3 {
            mu,
            alpha_t: 40.0,
            shift: shift.0,
            anchor,
            slip: pairing.slip(x, &nodes),
            start_gap,
        };
        let (nc, c, _) =
            row.close_with_friction_3d(&scalar.unwrap(), 4, 1.0, 100.0, shift.1, 1.0, 0, &inputs)?;
        let shape = list
            .iter()
            .map(|&(k, _)| (p[k].master, p[k].seg.polygon.len()))
            .collect();
        Some((nodes, shape, nc, c?))
    }

    /// The law of a node that slipped in the last increment: its stick
    /// point is where the return map put it, so at the next increment's
    /// start its trial force lies on the cone `mu R_N` to round-off. Flat
    /// tangent plane (`nu = +z`), `R_N = 1`, mu = 0.3, `alpha_T = 40`: the
    /// node moved by +-1e-13 of the cone's slip along x (two mirror nodes'
    /// round-off) must get one status and one tangent, the slip's (its
    /// `d t_x / d x` is 0): before the tie rule (`CONE_TIE`) the trial
    /// just inside the cone stuck, with `alpha_T` = 40 there.
    #[test]
    fn a_node_on_the_cone_to_round_off_slips_whatever_the_last_bits() {
        let nd = 3;
        let ds: [Vec<f64>; 3] =
            std::array::from_fn(|c| (0..nd).map(|k| if k == c { 1.0 } else { 0.0 }).collect());
        let zero = vec![0.0; nd];
        let own = OwnNormal {
            sn: [0.0, 0.0, -1.0],
            dsn: [&zero, &zero, &zero],
        };
        let law = |anchor: [f64; 3]| Law {
            mu: 0.3,
            alpha_t: 40.0,
            shift: [0.0; 3],
            alpha_n: 100.0,
            normal_force: 1.0,
            support: 1.0,
            area: 1.0,
            anchor,
            impact: None,
        };
        let row = CoefficientRow {
            coef: vec![1.0],
            dcoef: vec![0.0; nd],
        };
        let dgap = [0.0, 0.0, 1.0];
        // the slip that puts the trial force on the cone
        let cone = 0.3 / 40.0;
        for rel in [-1e-13, 0.0, 1e-13] {
            let s = [cone * (1.0 + rel), 0.0, 0.0];
            let r = respond(&law([0.0; 3]), &own, &(s, ds.clone()), &dgap, &row);
            assert_eq!(r.friction.status, FrictionStatus::Slip, "rel {rel:e}");
            assert!((r.friction.tangential_force - 0.3).abs() < 1e-9);
            // tangent row-major nd x nd: d f_x / d x_x
            assert!(
                r.tangent[0].abs() < 1e-9,
                "rel {rel:e}: K_xx {}",
                r.tangent[0]
            );
        }
        // a trial clearly inside the cone still sticks
        let r = respond(
            &law([0.0; 3]),
            &own,
            &([0.5 * cone, 0.0, 0.0], ds),
            &dgap,
            &row,
        );
        assert_eq!(r.friction.status, FrictionStatus::Stick);
    }

    /// A xorshift stream in `[-1, 1)`.
    fn stream(mut seed: u64) -> impl FnMut() -> f64 {
        move || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
        }
    }

    /// `x` jittered: in-plane by `inplane`, across by `across`.
    fn jittered(
        x: &[[f64; 3]],
        rnd: &mut impl FnMut() -> f64,
        inplane: f64,
        across: f64,
    ) -> Vec<[f64; 3]> {
        x.iter()
            .map(|q| {
                [
                    q[0] + inplane * rnd(),
                    q[1] + inplane * rnd(),
                    q[2] + across * rnd(),
                ]
            })
            .collect()
    }

    #[test]
    fn slip_is_zero_for_a_rigid_motion_and_the_slide_along_a_flat_master() {
        let mut rnd = stream(11);
        let nodes: Vec<usize> = (0..18).collect();
        // a warped pair: both surfaces jittered out of plane
        let xn = jittered(&reference(), &mut rnd, 0.05, 0.004);
        let p = pairing_at(&xn);
        assert_eq!(p.facets.len(), 4);
        assert!((p.area - 1.0).abs() < 0.2, "{}", p.area);
        let (s0, _) = p.slip(&xn, &nodes);
        // rigid rotation (about an oblique axis) and translation
        let (a, b) = (0.4f64, -0.3f64);
        let (ca, sa, cb, sb) = (a.cos(), a.sin(), b.cos(), b.sin());
        let rot = |q: [f64; 3]| {
            let r = [ca * q[0] - sa * q[1], sa * q[0] + ca * q[1], q[2]];
            [r[0], cb * r[1] - sb * r[2], sb * r[1] + cb * r[2]]
        };
        let moved: Vec<[f64; 3]> = xn
            .iter()
            .map(|&q| {
                let r = rot(q);
                [r[0] + 0.7, r[1] - 0.2, r[2] + 1.3]
            })
            .collect();
        let (s, _) = p.slip(&moved, &nodes);
        let worst = s0.iter().chain(&s).fold(0.0f64, |m, v| m.max(v.abs()));
        println!("rigid motion: |s| = {worst:.1e}");
        assert!(worst < 1e-13, "{s0:?} {s:?}");
        // the slave slides by v along a flat master
        let flat = reference();
        let p = pairing_at(&flat);
        let v = [0.03, -0.02, 0.0];
        let slid: Vec<[f64; 3]> = flat
            .iter()
            .enumerate()
            .map(|(k, q)| {
                if k < 9 {
                    [q[0] + v[0], q[1] + v[1], q[2]]
                } else {
                    *q
                }
            })
            .collect();
        let (s, _) = p.slip(&slid, &nodes);
        for c in 0..3 {
            assert!((s[c] - v[c]).abs() < 1e-14, "{s:?}");
        }
        // the slave slides as a whole: the slip of a rigid motion of the
        // slave alone is its translation in the plane
        let (s, _) = p.slip(
            &flat
                .iter()
                .enumerate()
                .map(|(k, q)| {
                    if k < 9 {
                        [q[0], q[1], q[2] + 0.004]
                    } else {
                        *q
                    }
                })
                .collect::<Vec<_>>(),
            &nodes,
        );
        assert!(s.iter().all(|v| v.abs() < 1e-14), "{s:?}");
    }

    #[test]
    fn slip_gradient_matches_finite_differences() {
        let mut rnd = stream(5);
        let nodes: Vec<usize> = (0..18).collect();
        let xn = jittered(&reference(), &mut rnd, 0.05, 0.004);
        let p = pairing_at(&xn);
        let x = jittered(&xn, &mut rnd, 0.03, 0.003);
        let (_, grad) = p.slip(&x, &nodes);
        let h = 1e-7;
        let mut worst = 0.0f64;
        for k in 0..18 {
            for c in 0..3 {
                let at = |d: f64| {
                    let mut y = x.clone();
                    y[k][c] += d;
                    p.slip(&y, &nodes).0
                };
                let (sp, sm) = (at(h), at(-h));
                for q in 0..3 {
                    let fd = (sp[q] - sm[q]) / (2.0 * h);
                    worst = worst.max((fd - grad[q][3 * k + c]).abs());
                }
            }
        }
        assert!(worst < 1e-7, "{worst}");
    }

    /// The largest `|K - K_fd|` of the middle row relative to the largest
    /// `|K|` (central differences) and its friction status; `None` when
    /// the node is open or a perturbation changes the clip polygons or
    /// the status.
    fn fd_error(
        x: &[[f64; 3]],
        xn: &[[f64; 3]],
        mu: f64,
        anchor: [f64; 3],
        shift: ([f64; 3], f64),
        start_gap: Option<f64>,
    ) -> Option<(FrictionStatus, f64)> {
        let pairing = pairing_at(xn);
        let (nodes, shape, nc, c) = middle_row(x, &pairing, mu, anchor, shift, start_gap)?;
        let h = 1e-7;
        let scale = c.tangent.iter().fold(1.0f64, |m, v| m.max(v.abs()));
        let nd = 3 * nodes.len();
        let mut worst = 0.0f64;
        for (k, &node) in nodes.iter().enumerate() {
            for comp in 0..3 {
                let at = |dh: f64| {
                    let mut y = x.to_vec();
                    y[node][comp] += dh;
                    middle_row(&y, &pairing, mu, anchor, shift, start_gap)
                        .filter(|r| r.0 == nodes && r.1 == shape)
                        .filter(|r| r.2.friction.status == nc.friction.status)
                };
                let (p, m) = at(h).zip(at(-h))?;
                let col = 3 * k + comp;
                for r in 0..nd {
                    let fd = -(p.3.force[r] - m.3.force[r]) / (2.0 * h);
                    worst = worst.max((fd - c.tangent[r * nd + col]).abs() / scale);
                }
            }
        }
        Some((nc.friction.status, worst))
    }

    #[test]
    fn frictional_row_tangent_matches_finite_differences_in_stick_and_slip() {
        let mut rnd = stream(0x9e37_79b9_7f4a_7c15);
        let (mut stick, mut slip) = ((0, 0.0f64), (0, 0.0f64));
        for k in 0..8 {
            let xn = jittered(&reference(), &mut rnd, 0.05, 0.003);
            // the slave slid by about 0.02 since the committed state
            let x: Vec<[f64; 3]> = jittered(&xn, &mut rnd, 0.004, 0.002)
                .iter()
                .enumerate()
                .map(|(n, q)| {
                    if n < 9 {
                        [q[0] + 0.02, q[1] - 0.01, q[2]]
                    } else {
                        *q
                    }
                })
                .collect();
            let mu = if k % 2 == 0 { 0.9 } else { 0.1 };
            let anchor = [0.003 * rnd(), 0.003 * rnd(), 0.001 * rnd()];
            // penalty, and augmented Lagrangian shifts on odd pairs of runs
            let shift = if k % 4 < 2 {
                ([0.0; 3], 0.0)
            } else {
                ([0.2 * rnd(), 0.2 * rnd(), 0.05 * rnd()], 0.5 + 0.3 * rnd())
            };
            let Some((status, worst)) = fd_error(&x, &xn, mu, anchor, shift, None) else {
                continue;
            };
            let slot = if status == FrictionStatus::Stick {
                &mut stick
            } else {
                &mut slip
            };
            slot.0 += 1;
            slot.1 = slot.1.max(worst);
        }
        println!(
            "3D mortar friction row, K vs central differences: stick {} rows, max {:.1e}; slip {} rows, max {:.1e}",
            stick.0, stick.1, slip.0, slip.1
        );
        assert!(stick.0 >= 2 && slip.0 >= 2, "{stick:?} {slip:?}");
        assert!(stick.1 < 1e-6 && slip.1 < 1e-6, "{stick:?} {slip:?}");
    }

    #[test]
    fn friction_forces_balance_oppose_the_slide_and_slip_on_the_cone() {
        let xn = reference();
        let x: Vec<[f64; 3]> = xn
            .iter()
            .enumerate()
            .map(|(n, q)| {
                if n < 9 {
                    [q[0] + 0.02, q[1] + 0.01, q[2]]
                } else {
                    *q
                }
            })
            .collect();
        for (mu, status) in [(0.9, FrictionStatus::Stick), (0.1, FrictionStatus::Slip)] {
            let (nodes, _, nc, c) =
                middle_row(&x, &pairing_at(&xn), mu, [0.0; 3], ([0.0; 3], 0.0), None).unwrap();
            assert_eq!(nc.friction.status, status);
            for comp in 0..3 {
                let sum: f64 = (0..nodes.len()).map(|k| c.force[3 * k + comp]).sum();
                assert!(sum.abs() < 1e-13, "{sum}");
            }
            let rn = -100.0 * nc.gap;
            let t = nc.friction.tangential_force;
            if status == FrictionStatus::Slip {
                assert!((t - mu * rn).abs() < 1e-14 * rn, "{t} {rn}");
            } else {
                // stick: t = -alpha_T s, s = (0.02, 0.01, 0)
                assert!((t - 40.0 * 0.02f64.hypot(0.01)).abs() < 1e-12, "{t}");
            }
            // along (-2, -1, 0): against the slide, in the plane
            let tr = nc.friction.traction;
            assert!(
                tr[2].abs() < 1e-15 && (tr[0] - 2.0 * tr[1]).abs() < 1e-14,
                "{tr:?}"
            );
            assert!(tr[0] < 0.0, "{tr:?}");
        }
    }

    /// A node open in the committed state that touches in the increment
    /// (`Law::impact`): its committed nodal gap is the pairing's normal
    /// gap there; its stick point is where its path crosses the master,
    /// so its trial force is `(1 - tau)` times the one from the committed
    /// stick point and vanishes with its gap; the tangent (with the
    /// stick point's motion, `dtau`) matches central differences in
    /// stick and slip.
    #[test]
    fn a_node_touching_in_the_increment_sticks_where_it_touched() {
        // the committed configuration: the master 0.01 below the slave,
        // then 0.03 above it (open, g0 = 0.02)
        let lifted = |x: &[[f64; 3]], dz: f64| -> Vec<[f64; 3]> {
            x.iter()
                .enumerate()
                .map(|(n, q)| if n < 9 { *q } else { [q[0], q[1], q[2] + dz] })
                .collect()
        };
        let mut rnd = stream(7);
        let xn = lifted(&jittered(&reference(), &mut rnd, 0.05, 0.002), 0.03);
        let pairing = pairing_at(&xn);
        let g0 = pairing.normal_gap(&xn);
        // open there (no coupling); the normal gap is the row's nodal gap
        // (-0.01 in the reference configuration, within round-off)
        assert!(middle_row(&xn, &pairing, 0.9, [0.0; 3], ([0.0; 3], 0.0), None).is_none());
        assert!((g0 - 0.02).abs() < 2e-3, "{g0}");
        let r = reference();
        assert!((pairing_at(&r).normal_gap(&r) + 0.01).abs() < 1e-15);
        // the slave slid by (0.02, 0.01) and the master came down by 0.024:
        // penetration about 0.005
        let slide = |x: &[[f64; 3]]| -> Vec<[f64; 3]> {
            x.iter()
                .enumerate()
                .map(|(n, q)| {
                    if n < 9 {
                        [q[0] + 0.02, q[1] + 0.01, q[2]]
                    } else {
                        [q[0], q[1], q[2] - 0.024]
                    }
                })
                .collect()
        };
        let x = slide(&xn);
        let (_, _, fixed, _) =
            middle_row(&x, &pairing, 5.0, [0.0; 3], ([0.0; 3], 0.0), None).unwrap();
        let (_, _, touched, _) =
            middle_row(&x, &pairing, 5.0, [0.0; 3], ([0.0; 3], 0.0), Some(g0)).unwrap();
        let g = touched.gap;
        assert!(g < 0.0 && g > -0.01, "{g}");
        assert_eq!(fixed.friction.status, FrictionStatus::Stick);
        assert_eq!(touched.friction.status, FrictionStatus::Stick);
        let ratio = touched.friction.tangential_force / fixed.friction.tangential_force;
        let expected = 1.0 - g0 / (g0 - g);
        println!(
            "first touch: g0 {g0:.4e}, g {g:.4e}, force ratio {ratio:.6e} (1 - tau {expected:.6e})"
        );
        assert!((ratio - expected).abs() < 1e-12, "{ratio} {expected}");
        // the tangent, stick (mu 0.9) and slip (mu 0.01)
        for (mu, status) in [(0.9, FrictionStatus::Stick), (0.01, FrictionStatus::Slip)] {
            let (s, worst) = fd_error(&x, &xn, mu, [0.0; 3], ([0.0; 3], 0.0), Some(g0)).unwrap();
            println!("first touch, {s:?}: K vs central differences {worst:.1e}");
            assert_eq!(s, status);
            assert!(worst < 1e-6, "{worst}");
        }
    }
}
