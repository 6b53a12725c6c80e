//! Coulomb friction with mortar contact on quadratic faces (issue 23 with
//! 18): 2D seg3 ([`super::seg3`]: quad8 / quad9 / tri6 faces, plane strain
//! and axisymmetric) and 3D tri6 / quad8 / quad9 faces
//! ([`super::quadratic3d`]), penalty or augmented Lagrangian. The return
//! map, the forces and their tangent are those of the linear mortar
//! friction ([`super::friction::respond`], [`super::friction3d::respond`]);
//! what changes is where the slip is measured and how the forces are
//! distributed, because the normal varies over a curved quadratic face.
//!
//! **Weighted slip** (Gitterle, Popp, Gee & Wall, IJNME 84 (2010) 543, the
//! objective form, taken pointwise): the integration points of slave node
//! `j`'s rows in the committed configuration `x^n` are kept ([`Pairing2`],
//! [`Pairing3`]): per point `q` the slave parameter `xi_q`, the master
//! parameter `eta_q` of the master point that faced it along the slave
//! normal at `x^n`, and the dual weight `w_jq = psi_j w ds` of the normal
//! part's integrals (the same points and weights that give `D_jk` and
//! `g~_j`: the slip is measured where the gap is, and where the forces are
//! taken). The weighted slip since `x^n` is
//!
//! 2D: `u~_j(x) = -sum_q w_jq t(xi_q; x) . (x_m(eta_q; x) - x_s(xi_q; x))`,
//! 3D: `u~_j(x) = -sum_q w_jq P(xi_q; x) (x_m(eta_q; x) - x_s(xi_q; x))`,
//!
//! with the current slave tangent `t = x_s' / |x_s'|` (2D) or tangent-plane
//! projector `P = I - n n^T` of the current slave normal at the point (3D),
//! and the nodal slip `s_j = u~_j / A^n_j`, `A^n_j = sum_q w_jq = sum_k
//! D^n_jk`. At `x^n` every term vanishes (the master point lies on the
//! slave normal line); a rigid motion of both bodies turns `t` (`P`) and
//! `x_m - x_s` together and leaves `s = 0`; a slave sliding by `v` along a
//! flat master gives `s = v` exactly. The linear code's per-segment
//! tangent (`t_e . C^n_je`) is the special case of a straight segment.
//!
//! **Forces**: 2D, the tangential row is the normal row `B_jk` ([`super::
//! seg3`]: `-int psi_j N_k n w ds` on the slave, `int psi_j N^_l n w ds`
//! on the master) turned by a right angle, `B^T_jk = int psi_j N_k t w ds`
//! (`t = (-n_y, n_x)`, the pointwise tangent), with its exact derivative
//! (the rotation is linear); 3D, the tangential force vector `t_j` of the
//! node's tangent plane is distributed by the scalar integrals `D_jk =
//! int psi_j N_k dA`, `M_jl = int psi_j N^_l dA` ([`super::quadratic3d::
//! face_pair_frictional`]), as [`super::friction3d`] does.
//!
//! Lagrange-multiplier friction stays refused, on quadratic faces as on
//! linear 3D mortar (`solve::check::quadratic_contact_refusal`).

use super::integrals::Weight;
use super::quadratic3d::{self, QuadSegment, MAX_NODES};
use super::seg3::{self, Seg3Segment};
use super::{
    enforcement, friction3d, pieces_seg3, total_forces, Coupling, FrictionInputs, FrictionInputs3,
    QuadPiece, Row, UNUSED,
};
use crate::contact::surface::SurfacePair as PairState3;
use crate::contact::{NodeContact, PairState};
use crate::model::{ContactMethod, ContactPair};

// ------------------------------------------------------------------ 2D

/// The committed points of one seg3 segment pair seen from one slave
/// node: the pair's nodes `[a, b, m, c, d, m']` and per point `[xi, eta,
/// w_j]`.
pub type Points2 = ([usize; 6], Vec<[f64; 3]>);

/// The committed pairing of one slave node on seg3 faces (module doc).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Pairing2 {
    /// `A^n_j = sum_q w_jq`.
    pub area: f64,
    /// Per segment pair of the node's support.
    pub pieces: Vec<Points2>,
}

impl Pairing2 {
    /// Adds segment pair `seg` (nodes `[a, b, m, c, d, m']`) seen from row
    /// `row` of its slave segment.
    pub fn add(&mut self, nodes: [usize; 6], row: usize, seg: &Seg3Segment) {
        let points: Vec<[f64; 3]> = seg
            .points
            .iter()
            .map(|p| [p.xi, p.eta, p.weight[row]])
            .collect();
        self.area += points.iter().map(|p| p[2]).sum::<f64>();
        self.pieces.push((nodes, points));
    }

    /// Every node the slip depends on.
    pub fn nodes(&self) -> impl Iterator<Item = usize> + '_ {
        self.pieces.iter().flat_map(|(n, _)| n.iter().copied())
    }

    /// The nodal slip `s = -sum_q w_q t . (x_m - x_s) / A^n` since the
    /// committed configuration and its gradient over `nodes` (sorted, 2
    /// components per node); `(0, 0)` without a committed pairing.
    pub fn slip(&self, x: &[[f64; 2]], nodes: &[usize]) -> (f64, Vec<f64>) {
        let mut grad = vec![0.0; 2 * nodes.len()];
        if self.area.is_nan() || self.area <= 0.0 || self.pieces.is_empty() {
            return (0.0, grad);
        }
        let pos = |n: usize| nodes.binary_search(&n).ok();
        let mut s = 0.0;
        for (pn, points) in &self.pieces {
            let Some(p) = pn
                .iter()
                .map(|&n| x.get(n).copied())
                .collect::<Option<Vec<_>>>()
            else {
                continue;
            };
            let slots: Vec<Option<usize>> = pn.iter().map(|&n| pos(n)).collect();
            for &[xi, eta, w] in points {
                let (ns, dns, nm) = (seg3::shape(xi), seg3::dshape(xi), seg3::shape(eta));
                let mut d = [0.0; 2];
                let mut r = [0.0; 2];
                for k in 0..3 {
                    for c in 0..2 {
                        d[c] += dns[k] * p[k][c];
                        r[c] += nm[k] * p[3 + k][c] - ns[k] * p[k][c];
                    }
                }
                let jac = d[0].hypot(d[1]);
                if jac.is_nan() || jac <= 0.0 {
                    continue;
                }
                let t = [d[0] / jac, d[1] / jac];
                let tr = t[0] * r[0] + t[1] * r[1];
                s += w * tr;
                // d(t . r): t . dr + r . dt, dt = (I - t t^T) dx' / J
                let q = [(r[0] - tr * t[0]) / jac, (r[1] - tr * t[1]) / jac];
                for k in 0..3 {
                    if let Some(a) = slots[k] {
                        for c in 0..2 {
                            grad[2 * a + c] += w * (-ns[k] * t[c] + dns[k] * q[c]);
                        }
                    }
                    if let Some(b) = slots[3 + k] {
                        for c in 0..2 {
                            grad[2 * b + c] += w * nm[k] * t[c];
                        }
                    }
                }
            }
        }
        let f = -1.0 / self.area;
        grad.iter_mut().for_each(|g| *g *= f);
        (s * f, grad)
    }
}

/// The seg3 pairings of every slave node in the committed configuration
/// and the converged-increment count they were computed for.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct CommittedPairing2 {
    /// `SurfacePair::increments` when computed.
    pub key: usize,
    /// Per slave index.
    pub rows: Vec<Pairing2>,
}

/// The normal row of a slave node from its seg3 pieces and the tangential
/// row (the same with every `B` vector turned by a right angle: `(-b_y,
/// b_x)`, the pointwise tangent `t = (-n_y, n_x)`).
fn seg3_rows<'a>(list: &[super::Seg3Piece], nodes: &'a [usize]) -> (Row<'a>, Row<'a>) {
    let mut row = Row::new(nodes, 2);
    let mut tangential = Row::new(nodes, 2);
    for p in list {
        let s = &p.seg;
        let j = p.row;
        let area = s.d[j][0] + s.d[j][1] + s.d[j][2];
        row.add_vectors(
            &p.nodes,
            &s.gap[j],
            &area,
            (0..6).map(|k| (p.nodes[k], &s.b[j][k][..])),
        );
        let turned: [[seg3::Ad12; 2]; 6] = std::array::from_fn(|k| {
            let b = s.b[j][k];
            [-b[1], b[0]]
        });
        tangential.add_vectors(
            &p.nodes,
            &s.gap[j],
            &area,
            (0..6).map(|k| (p.nodes[k], &turned[k][..])),
        );
    }
    (row, tangential)
}

/// The seg3 branch of [`super::evaluate`] with Coulomb friction (penalty
/// or augmented Lagrangian): the committed pairings once per increment,
/// then per slave node its normal and tangential rows, closed by
/// [`Row::close_with_friction`]. Returns the projection tests.
#[allow(clippy::too_many_arguments)]
pub(super) fn evaluate_seg3(
    cp: &ContactPair,
    law: &crate::model::Friction,
    state: &mut PairState,
    sp: &mut crate::contact::node_to_segment::SurfacePair,
    x: &[[f64; 2]],
    w: Weight,
    couplings: &mut Vec<Coupling>,
    out: &mut Vec<NodeContact>,
) -> usize {
    let prof = state.prof;
    state.friction.incremental = true;
    let key = sp.increments;
    if sp.seg3_pairing.as_ref().map(|p| p.key) != Some(key) {
        let xn = std::mem::take(&mut sp.committed_positions);
        let xn = if xn.len() == x.len() { xn } else { x.to_vec() };
        let mut old_tests = 0;
        let old = pieces_seg3(sp, &state.slaves, &xn, w, prof, &mut old_tests);
        sp.committed_positions = xn;
        let rows = old
            .iter()
            .map(|list| {
                let mut p = Pairing2::default();
                for piece in list {
                    p.add(piece.nodes, piece.row, &piece.seg);
                }
                p
            })
            .collect();
        sp.seg3_pairing = Some(CommittedPairing2 { key, rows });
    }
    sp.positions.clear();
    sp.positions.extend_from_slice(x);
    let mut tests = 0usize;
    let pieces = pieces_seg3(sp, &state.slaves, x, w, prof, &mut tests);
    let mut nodes = Vec::new();
    for (i, list) in pieces.iter().enumerate() {
        let node = state.slaves[i];
        state.last_entity[i] = list.first().map(|p| p.master);
        if list.is_empty() {
            state.friction.open(i, [0.0; 2]);
            continue;
        }
        let pairing = sp.seg3_pairing.as_ref().and_then(|p| p.rows.get(i));
        nodes.clear();
        for p in list {
            nodes.extend_from_slice(&p.nodes);
        }
        if let Some(p) = pairing {
            nodes.extend(p.nodes());
        }
        nodes.sort_unstable();
        nodes.dedup();
        let (row, tangential) = seg3_rows(list, &nodes);
        let support = state.tributary.get(i).copied().unwrap_or(0.0);
        let method = cp.method_at(node);
        let (alpha, shift, _) = enforcement(cp, state, i, &method, support);
        let f = &state.friction;
        let inputs = FrictionInputs {
            mu: law.mu,
            alpha_t: crate::contact::friction::tangential_stiffness(law, &method, support),
            shift: match cp.method {
                ContactMethod::AugmentedLagrange { .. } => f.multiplier[i],
                _ => 0.0,
            },
            anchor: f.base[i].or(f.committed_anchor[i]).map_or(0.0, |a| a[0]),
            slip: pairing.map_or_else(|| (0.0, vec![0.0; 2 * nodes.len()]), |p| p.slip(x, &nodes)),
        };
        // a normal force of a round-off penetration: open (the seg3
        // integrals of two meshes touching on a flat interface give nodal
        // gaps of round-off of either sign; closed with friction, such a
        // node sticks or slips in a direction of noise: the press of
        // `contact_patch_friction_quadratic` chattered on the interface's
        // end nodes and cut back to the smallest increment), as in 3D
        // ([`friction3d::ROUND_OFF`])
        let rn = shift - alpha * row.g / row.area;
        let closed = if rn <= alpha * friction3d::ROUND_OFF * support.max(0.0).sqrt() {
            row.close::<2>(node, support, 0.0, 0.0, prof, 0.0, list[0].master, None)
                .map(|(nc, _)| (nc, None, None))
        } else {
            row.close_with_friction(
                &tangential,
                node,
                support,
                alpha,
                shift,
                prof,
                list[0].master,
                &inputs,
            )
        };
        let Some((nc, coupling, response)) = closed else {
            state.friction.open(i, [0.0; 2]);
            continue;
        };
        match response {
            Some(r) => {
                state.friction.anchor[i] = Some([r.anchor, 0.0]);
                state.friction.position[i] = [r.position, 0.0];
            }
            None => state.friction.open(i, [0.0; 2]),
        }
        couplings.extend(coupling);
        out.push(nc);
    }
    tests
}

// ------------------------------------------------------------------ 3D

/// The committed points of one quadratic face pair seen from one slave
/// node: the slave face's nodes, the master face's, and per point `(xi,
/// eta, w_j)`.
pub type Points3 = (Vec<usize>, Vec<usize>, Vec<([f64; 2], [f64; 2], f64)>);

/// The committed pairing of one slave node on quadratic 3D faces (module
/// doc).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Pairing3 {
    /// `A^n_j = sum_q w_jq`.
    pub area: f64,
    /// Per face pair of the node's support.
    pub pieces: Vec<Points3>,
}

impl Pairing3 {
    /// Adds face pair `seg` (variables `vars`: slave nodes at `0..ns`,
    /// master ones at `MAX_NODES..`) seen from the slave face's node `j`.
    pub fn add(&mut self, vars: &[usize; 2 * MAX_NODES], j: usize, seg: &QuadSegment) {
        let points: Vec<([f64; 2], [f64; 2], f64)> = seg
            .points
            .iter()
            .map(|p| (p.xi, p.eta, p.weight[j]))
            .collect();
        self.area += points.iter().map(|p| p.2).sum::<f64>();
        self.pieces.push((
            vars[..seg.ns].to_vec(),
            vars[MAX_NODES..MAX_NODES + seg.nm].to_vec(),
            points,
        ));
    }

    /// Every node the slip depends on.
    pub fn nodes(&self) -> impl Iterator<Item = usize> + '_ {
        self.pieces
            .iter()
            .flat_map(|(s, m, _)| s.iter().chain(m.iter()).copied())
    }

    /// The nodal slip vector `s = -sum_q w_q P (x_m - x_s) / A^n` since the
    /// committed configuration and its gradient over `nodes` (sorted, 3
    /// components per node; `grad[c]` is `d s_c / d x`). Zero without a
    /// committed pairing.
    pub fn slip(&self, x: &[[f64; 3]], nodes: &[usize]) -> ([f64; 3], [Vec<f64>; 3]) {
        use crate::contact::mortar::ad::Ad;
        let nd = 3 * nodes.len();
        let mut grad = [vec![0.0; nd], vec![0.0; nd], vec![0.0; nd]];
        if self.area.is_nan() || self.area <= 0.0 || self.pieces.is_empty() {
            return ([0.0; 3], grad);
        }
        let pos = |n: usize| nodes.binary_search(&n).ok();
        let mut s = [0.0; 3];
        for (sn, mn, points) in &self.pieces {
            let (Some(ps), Some(pm)) = (
                sn.iter()
                    .map(|&n| x.get(n).copied())
                    .collect::<Option<Vec<_>>>(),
                mn.iter()
                    .map(|&n| x.get(n).copied())
                    .collect::<Option<Vec<_>>>(),
            ) else {
                continue;
            };
            let ss: Vec<Option<usize>> = sn.iter().map(|&n| pos(n)).collect();
            let ms: Vec<Option<usize>> = mn.iter().map(|&n| pos(n)).collect();
            for &(xi, eta, w) in points {
                let (n_s, g_s) = quadratic3d::shapes::<0>(sn.len(), xi.map(Ad::cst));
                let (n_m, _) = quadratic3d::shapes::<0>(mn.len(), eta.map(Ad::cst));
                let (mut a1, mut a2, mut r) = ([0.0; 3], [0.0; 3], [0.0; 3]);
                for (k, p) in ps.iter().enumerate() {
                    for c in 0..3 {
                        a1[c] += g_s[k][0].v * p[c];
                        a2[c] += g_s[k][1].v * p[c];
                        r[c] -= n_s[k].v * p[c];
                    }
                }
                for (l, p) in pm.iter().enumerate() {
                    for c in 0..3 {
                        r[c] += n_m[l].v * p[c];
                    }
                }
                let m = cross3(a1, a2);
                let ml = dot3(m, m).sqrt();
                if ml.is_nan() || ml <= 0.0 {
                    continue;
                }
                let n = m.map(|v| v / ml);
                let nr = dot3(n, r);
                for c in 0..3 {
                    s[c] += w * (r[c] - n[c] * nr);
                }
                // through r: w P dr (dr = N^_l on the master, -N_k on the
                // slave)
                let proj = |q: usize, c: usize| f64::from(u8::from(q == c)) - n[q] * n[c];
                for (l, slot) in ms.iter().enumerate() {
                    let Some(b) = *slot else { continue };
                    for (q, g) in grad.iter_mut().enumerate() {
                        for c in 0..3 {
                            g[3 * b + c] += w * n_m[l].v * proj(q, c);
                        }
                    }
                }
                for (k, slot) in ss.iter().enumerate() {
                    let Some(a) = *slot else { continue };
                    for c in 0..3 {
                        // dm = dN_k,1 e_c x a2 + a1 x dN_k,2 e_c
                        let mut e = [0.0; 3];
                        e[c] = 1.0;
                        let u = cross3(e, a2);
                        let v = cross3(a1, e);
                        let dm: [f64; 3] =
                            std::array::from_fn(|q| g_s[k][0].v * u[q] + g_s[k][1].v * v[q]);
                        let ndm = dot3(n, dm);
                        let dn: [f64; 3] = std::array::from_fn(|q| (dm[q] - n[q] * ndm) / ml);
                        let dnr = dot3(dn, r);
                        for (q, g) in grad.iter_mut().enumerate() {
                            g[3 * a + c] += w * (-n_s[k].v * proj(q, c) - dn[q] * nr - n[q] * dnr);
                        }
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

fn dot3(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn cross3(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// The quadratic 3D pairings of every slave node in the committed
/// configuration and the converged-increment count they were computed
/// for.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct CommittedPairing3 {
    /// `DeformablePair::increments` when computed.
    pub key: usize,
    /// Per slave index.
    pub rows: Vec<Pairing3>,
}

/// The normal row of a quadratic 3D slave node ([`super::row_quadratic`])
/// and its scalar row `[-D_jk, M_jl]` with the gradient (the distribution
/// of the friction forces).
fn rows_3d<'a>(
    pieces: &[QuadPiece],
    list: &[(usize, usize)],
    nodes: &'a [usize],
) -> (Row<'a>, friction3d::CoefficientRow) {
    let row = super::row_quadratic(pieces, list, nodes);
    let nd = 3 * nodes.len();
    let mut scalar = friction3d::CoefficientRow {
        coef: vec![0.0; nodes.len()],
        dcoef: vec![0.0; nodes.len() * nd],
    };
    for &(p, j) in list {
        let QuadPiece { vars, seg, .. } = &pieces[p];
        let Some(d) = seg.d.get(j) else { continue };
        let terms = (0..seg.ns)
            .map(|k| (vars[k], -d[k]))
            .chain((0..seg.nm).map(|l| (vars[MAX_NODES + l], d[MAX_NODES + l])));
        for (node, coef) in terms {
            if let Ok(q) = nodes.binary_search(&node) {
                super::accumulate(
                    nodes,
                    3,
                    vars,
                    &coef,
                    &mut scalar.coef[q],
                    &mut scalar.dcoef[q * nd..(q + 1) * nd],
                );
            }
        }
    }
    (row, scalar)
}

/// The quadratic branch of [`super::evaluate_3d`] with Coulomb friction
/// (penalty or augmented Lagrangian): the committed pairings once per
/// increment, then per slave node its normal row and scalar row, closed
/// by [`Row::close_with_friction_3d`].
pub(super) fn evaluate_3d(
    cp: &ContactPair,
    law: &crate::model::Friction,
    fp: &mut crate::contact::node_to_facet::DeformablePair,
    x: &[[f64; 3]],
    state: &mut PairState3,
    out: &mut Vec<NodeContact<3>>,
) {
    let prof = state.prof;
    state.friction.incremental = true;
    let key = fp.increments;
    if fp.quadratic_pairing.as_ref().map(|p| p.key) != Some(key) {
        let mut xn = std::mem::take(&mut fp.committed_positions);
        if xn.len() != x.len() {
            xn = x.to_vec();
        }
        let (old, old_rows, _, _) = super::quadratic_pieces(
            fp,
            &state.slaves,
            &xn,
            prof,
            quadratic3d::face_pair_frictional,
        );
        fp.committed_positions = xn;
        let rows = old_rows
            .iter()
            .map(|list| {
                let mut p = Pairing3::default();
                for &(k, j) in list {
                    p.add(&old[k].vars, j, &old[k].seg);
                }
                p
            })
            .collect();
        fp.quadratic_pairing = Some(CommittedPairing3 { key, rows });
    }
    fp.positions.clear();
    fp.positions.extend_from_slice(x);
    fp.tangential.clear();
    fp.tangential.resize(state.slaves.len(), [0.0; 3]);
    fp.couplings.clear();
    let (pieces, rows, queries, tests) = super::quadratic_pieces(
        fp,
        &state.slaves,
        x,
        prof,
        quadratic3d::face_pair_frictional,
    );
    fp.tests = tests;
    state.counters.queries += queries;
    let mut nodes = Vec::new();
    for (i, list) in rows.iter().enumerate() {
        let node = state.slaves[i];
        fp.last[i] = list.first().map(|&(p, _)| pieces[p].master);
        if list.is_empty() {
            state.friction.open(i, [0.0; 3]);
            continue;
        }
        let pairing = fp.quadratic_pairing.as_ref().and_then(|p| p.rows.get(i));
        nodes.clear();
        for &(p, _) in list {
            nodes.extend(pieces[p].vars.iter().copied().filter(|&n| n != UNUSED));
        }
        if let Some(p) = pairing {
            nodes.extend(p.nodes());
        }
        nodes.sort_unstable();
        nodes.dedup();
        let (row, scalar) = rows_3d(&pieces, list, &nodes);
        let support = state.area.get(i).copied().unwrap_or(0.0);
        let method = cp.method_at(node);
        let alpha = crate::contact::surface::alpha(&method, support);
        let augmented = matches!(method, ContactMethod::AugmentedLagrange { .. });
        let shift = if augmented {
            state.multiplier.get(i).copied().unwrap_or(0.0)
        } else {
            0.0
        };
        let entity = pieces[list[0].0].master;
        let f = &state.friction;
        let inputs = FrictionInputs3 {
            mu: law.mu,
            alpha_t: crate::contact::friction::tangential_stiffness(law, &method, support),
            shift: if augmented { f.shift[i] } else { [0.0; 3] },
            anchor: f.base[i].or(f.committed_anchor[i]).unwrap_or([0.0; 3]),
            slip: pairing.map_or_else(
                || {
                    let nd = 3 * nodes.len();
                    ([0.0; 3], [vec![0.0; nd], vec![0.0; nd], vec![0.0; nd]])
                },
                |p| p.slip(x, &nodes),
            ),
            start_gap: None,
        };
        let closed =
            row.close_with_friction_3d(&scalar, node, support, alpha, shift, prof, entity, &inputs);
        let Some((nc, coupling, response)) = closed else {
            state.friction.open(i, [0.0; 3]);
            continue;
        };
        match response {
            Some(r) => {
                state.friction.anchor[i] = Some(r.anchor);
                state.friction.position[i] = r.position;
                fp.tangential[i] = r.traction;
            }
            None => state.friction.open(i, [0.0; 3]),
        }
        fp.couplings.extend(coupling);
        out.push(nc);
    }
    total_forces(&fp.couplings, out);
    state.counters.faces_tested += fp.tests as u64;
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::friction::FrictionStatus;
    use crate::contact::node_to_segment::{Surface, SurfacePair};

    // ------------------------------------------------------------ 2D

    /// seg3 pair: slave corners 0, 1, 2 (walking -x near y = 0), midside
    /// nodes 3 (of [0, 1]) and 4 (of [1, 2]); master corners 5..=8 below
    /// walking +x, midside nodes 9, 10, 11.
    fn seg3_pair() -> SurfacePair {
        let mut sp = SurfacePair::default();
        sp.sides = [
            Surface::new(&[[0, 1], [1, 2]]),
            Surface::new(&[[5, 6], [6, 7], [7, 8]]),
        ];
        sp.midsides = [vec![3, 4], vec![9, 10, 11]];
        sp
    }

    /// Slave `y = bend x^2`, master `y = gap - bend x^2 / 2` (curved the
    /// same way: the master's midside nodes off its chords).
    fn seg3_reference(bend: f64, gap: f64) -> Vec<[f64; 2]> {
        let s = |x: f64| bend * x * x;
        let m = |x: f64| gap - 0.5 * bend * x * x;
        let mut v: Vec<[f64; 2]> = [1.0, 0.0, -1.0, 0.5, -0.5]
            .iter()
            .map(|&x| [x, s(x)])
            .collect();
        v.extend(
            [-1.3, -0.4, 0.5, 1.4, -0.85, 0.05, 0.95]
                .iter()
                .map(|&x| [x, m(x)]),
        );
        v
    }

    const SLAVES: [usize; 5] = [0, 1, 2, 3, 4];

    fn seg3_pieces(x: &[[f64; 2]], w: Weight) -> Vec<Vec<super::super::Seg3Piece>> {
        let mut tests = 0;
        pieces_seg3(&mut seg3_pair(), &SLAVES, x, w, 1.0, &mut tests)
    }

    fn pairing2(xn: &[[f64; 2]], node: usize, w: Weight) -> Pairing2 {
        let mut p = Pairing2::default();
        for piece in &seg3_pieces(xn, w)[SLAVES.binary_search(&node).unwrap()] {
            p.add(piece.nodes, piece.row, &piece.seg);
        }
        p
    }

    /// The frictional seg3 row of slave `node` at `x` with its pairing at
    /// `xn` (penalty 50 on a tributary area 0.5, tangential penalty 40):
    /// `(nodes, pieces' signature, entry, coupling, nodal gap x area)`.
    #[allow(clippy::type_complexity)]
    fn seg3_row(
        x: &[[f64; 2]],
        xn: &[[f64; 2]],
        node: usize,
        w: Weight,
        mu: f64,
        anchor: f64,
        shift: f64,
    ) -> Option<(Vec<usize>, Vec<usize>, NodeContact, Coupling, f64)> {
        let pairing = pairing2(xn, node, w);
        let now = seg3_pieces(x, w);
        let list = &now[SLAVES.binary_search(&node).ok()?];
        if list.is_empty() {
            return None;
        }
        let mut nodes: Vec<usize> = list.iter().flat_map(|p| p.nodes).collect();
        nodes.extend(pairing.nodes());
        nodes.sort_unstable();
        nodes.dedup();
        let (row, tangential) = seg3_rows(list, &nodes);
        let inputs = FrictionInputs {
            mu,
            alpha_t: 40.0,
            shift: 0.3 * shift,
            anchor,
            slip: pairing.slip(x, &nodes),
        };
        let (nc, coupling, _) =
            row.close_with_friction(&tangential, node, 0.5, 50.0, shift, 1.0, 0, &inputs)?;
        let masters = list
            .iter()
            .map(|p| 4 * p.master + 2 * usize::from(p.seg.lo > 0.0) + usize::from(p.seg.hi < 1.0))
            .collect();
        let gw = row.g;
        drop(row);
        drop(tangential);
        Some((nodes, masters, nc, coupling?, gw))
    }

    /// Moves the slave nodes (0..5) by `d`.
    fn slide(x: &[[f64; 2]], d: [f64; 2]) -> Vec<[f64; 2]> {
        x.iter()
            .enumerate()
            .map(|(k, q)| {
                if k < 5 {
                    [q[0] + d[0], q[1] + d[1]]
                } else {
                    *q
                }
            })
            .collect()
    }

    /// The weighted slip of every slave node (corners and midside nodes):
    /// 0 in the committed configuration and after a rigid motion of both
    /// curved bodies, the slide itself along a flat master.
    #[test]
    fn seg3_slip_is_zero_at_rest_and_for_a_rigid_motion_and_the_slide_on_a_flat_master() {
        let nodes: Vec<usize> = (0..12).collect();
        for w in [Weight::Thickness(1.0), Weight::Axisymmetric] {
            let shift = |x: Vec<[f64; 2]>| -> Vec<[f64; 2]> {
                x.into_iter().map(|p| [p[0] + 3.0, p[1]]).collect()
            };
            let xn = shift(seg3_reference(0.08, -0.01));
            let (c, s) = (0.3f64.cos(), 0.3f64.sin());
            let moved: Vec<[f64; 2]> = xn
                .iter()
                .map(|q| [c * q[0] - s * q[1] + 0.7, s * q[0] + c * q[1] - 0.2])
                .collect();
            let flat = shift(seg3_reference(0.0, -0.01));
            let slid = slide(&flat, [-0.05, 0.0]);
            for node in SLAVES {
                let p = pairing2(&xn, node, w);
                assert!(p.area > 0.0 && !p.pieces.is_empty());
                let (rest, _) = p.slip(&xn, &nodes);
                assert!(rest.abs() < 1e-12, "{w:?} node {node}: {rest}");
                if w == Weight::Thickness(1.0) {
                    let (rigid, _) = p.slip(&moved, &nodes);
                    assert!(rigid.abs() < 1e-12, "node {node}: {rigid}");
                }
                // the slave tangent is -x: a slide by -0.05 is a slip of 0.05
                let (s, _) = pairing2(&flat, node, w).slip(&slid, &nodes);
                assert!((s - 0.05).abs() < 1e-13, "{w:?} node {node}: {s}");
            }
        }
    }

    /// The frictional seg3 rows (corner and midside slave nodes, plane and
    /// axisymmetric, stick and slip, penalty and augmented shift): the
    /// tangent is minus the derivative of the forces (central differences,
    /// step 1e-7; the largest error measured by this test 1.8e-9 relative
    /// to the largest entry: `cargo test -p ctc-engine --lib
    /// friction_quadratic -- --nocapture`), the forces sum to zero and their moment is
    /// that of the friction force across the penetration, `-(R_T / T)
    /// g~_j` (the normal part's moment vanishes: its force is along `n` at
    /// every point, where `x_m - x_s` is).
    #[test]
    fn seg3_frictional_rows_balance_and_their_tangent_matches_finite_differences() {
        let (mut stick, mut slip, mut worst) = (0, 0, 0.0f64);
        for (bend, gap, dx) in [
            (0.0, -0.01, 0.0),
            (0.05, -0.02, 0.13),
            (-0.04, -0.015, -0.21),
        ] {
            let xn: Vec<[f64; 2]> = seg3_reference(bend, gap)
                .into_iter()
                .enumerate()
                .map(|(k, p)| [p[0] + 3.0 + if k < 5 { dx } else { 0.0 }, p[1] + 0.005])
                .collect();
            let x = slide(&xn, [-0.02, -0.005]);
            for w in [Weight::Thickness(1.0), Weight::Axisymmetric] {
                for node in [1, 3, 4, 0] {
                    for (mu, shift) in [(2.0, 0.0), (0.05, 0.0), (2.0, 0.7), (0.05, 0.7)] {
                        let Some((nodes, masters, nc, c, gw)) =
                            seg3_row(&x, &xn, node, w, mu, 0.001, shift)
                        else {
                            continue;
                        };
                        let nn = nodes.len();
                        let fsum: [f64; 2] = std::array::from_fn(|comp| {
                            (0..nn).map(|k| c.force[2 * k + comp]).sum()
                        });
                        let moment: f64 = (0..nn)
                            .map(|k| {
                                let p = x[nodes[k]];
                                p[0] * c.force[2 * k + 1] - p[1] * c.force[2 * k]
                            })
                            .sum();
                        let scale = c.force.iter().fold(0.0f64, |m, v| m.max(v.abs()));
                        assert!(
                            fsum[0].abs() < 1e-12 * scale && fsum[1].abs() < 1e-12 * scale,
                            "{w:?} node {node}: {fsum:?}"
                        );
                        let rt = nc.friction.tangential_force;
                        let want = -rt / 0.5 * gw;
                        assert!(
                            (moment - want).abs() < 1e-11 * scale,
                            "{w:?} node {node}: moment {moment} against {want}"
                        );
                        match nc.friction.status {
                            FrictionStatus::Stick => stick += 1,
                            _ => slip += 1,
                        }
                        let h = 1e-7;
                        let kscale = c.tangent.iter().fold(1.0f64, |m, v| m.max(v.abs()));
                        let nd = 2 * nn;
                        for (k, &n) in nodes.iter().enumerate() {
                            for comp in 0..2 {
                                let at = |dh: f64| {
                                    let mut y = x.clone();
                                    y[n][comp] += dh;
                                    seg3_row(&y, &xn, node, w, mu, 0.001, shift)
                                        .filter(|r| r.0 == nodes && r.1 == masters)
                                        .filter(|r| r.2.friction.status == nc.friction.status)
                                };
                                let (p, m) = at(h).zip(at(-h)).expect("same pieces");
                                let col = 2 * k + comp;
                                for r in 0..nd {
                                    let fd = -(p.3.force[r] - m.3.force[r]) / (2.0 * h);
                                    let err = (fd - c.tangent[r * nd + col]).abs() / kscale;
                                    worst = worst.max(err);
                                }
                            }
                        }
                    }
                }
            }
        }
        println!("seg3 friction rows: {stick} stick, {slip} slip, worst FD error {worst:.2e}");
        assert!(stick >= 10 && slip >= 10, "{stick} stick, {slip} slip");
        assert!(worst < 1e-6, "{worst}");
    }

    /// `|K - K_fd|` of slave `node`'s frictional row relative to the
    /// largest `|K|` (central differences, step 1e-7); `None` when the
    /// node is open or a perturbation changes the pieces or the status.
    fn seg3_fd_error(
        x: &[[f64; 2]],
        xn: &[[f64; 2]],
        node: usize,
        mu: f64,
        shift: f64,
    ) -> Option<f64> {
        let w = Weight::Thickness(1.0);
        let (nodes, masters, nc, c, _) = seg3_row(x, xn, node, w, mu, 0.002, shift)?;
        let h = 1e-7;
        let scale = c.tangent.iter().fold(1.0f64, |m, v| m.max(v.abs()));
        let nd = 2 * nodes.len();
        let mut worst = 0.0f64;
        for (k, &n) in nodes.iter().enumerate() {
            for comp in 0..2 {
                let at = |dh: f64| {
                    let mut y = x.to_vec();
                    y[n][comp] += dh;
                    seg3_row(&y, xn, node, w, mu, 0.002, shift)
                        .filter(|r| r.0 == nodes && r.1 == masters)
                        .filter(|r| r.2.friction.status == nc.friction.status)
                };
                let (p, m) = at(h).zip(at(-h))?;
                for r in 0..nd {
                    let fd = -(p.3.force[r] - m.3.force[r]) / (2.0 * h);
                    worst = worst.max((fd - c.tangent[r * nd + 2 * k + comp]).abs() / scale);
                }
            }
        }
        Some(worst)
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(48))]
        /// The frictional seg3 row's tangent against central differences
        /// on randomly bent and jittered pairs (committed and current
        /// configurations jittered apart, stick or slip by `mu`).
        #[test]
        fn seg3_frictional_tangent_matches_finite_differences(
            bend in -0.1f64..0.1,
            now in proptest::collection::vec((-0.05f64..0.05, -0.01f64..0.01), 12),
            old in proptest::collection::vec((-0.05f64..0.05, -0.005f64..0.005), 12),
            node in 0usize..5,
            mu in 0.05f64..2.0,
            shift in 0.0f64..1.0,
        ) {
            let r = seg3_reference(bend, -0.01);
            let x: Vec<[f64; 2]> =
                r.iter().zip(&now).map(|(q, d)| [q[0] + 3.0 + d.0, q[1] + d.1]).collect();
            let xn: Vec<[f64; 2]> =
                r.iter().zip(&old).map(|(q, d)| [q[0] + 3.0 + d.0, q[1] + 0.01 + d.1]).collect();
            if let Some(worst) = seg3_fd_error(&x, &xn, node, mu, shift) {
                proptest::prop_assert!(worst < 1e-6, "{}", worst);
            }
        }
    }

    // ------------------------------------------------------------ 3D

    fn parent(nn: usize, a: usize) -> [f64; 2] {
        use crate::element::reference::{quad9::Quad9, tri6::Tri6, ReferenceCell};
        if nn == 6 {
            <Tri6 as ReferenceCell<2, 6>>::NODES[a]
        } else {
            <Quad9 as ReferenceCell<2, 9>>::NODES[a]
        }
    }

    /// A slave face of `nn` nodes over `[0, 1]^2` (the unit triangle for
    /// tri6) at `z = bend (x^2 + y^2)`, outward `+z`, and a master face of
    /// `mm` nodes of size 2.2 turned by 0.3 around `(-0.4, -0.7)` (covering
    /// the slave) at `z =
    /// gap - bend (x^2 + y^2) / 2`, facing down; nodes `0..nn` and
    /// `nn..nn + mm`.
    fn faces_3d(nn: usize, mm: usize, bend: f64, gap: f64) -> Vec<[f64; 3]> {
        let mut x: Vec<[f64; 3]> = (0..nn)
            .map(|a| {
                let [r, s] = parent(nn, a);
                let (x, y) = if nn == 6 {
                    (r, s)
                } else {
                    (0.5 * (1.0 + r), 0.5 * (1.0 + s))
                };
                [x, y, bend * (x * x + y * y)]
            })
            .collect();
        let (c, sn) = (0.3f64.cos(), 0.3f64.sin());
        x.extend((0..mm).map(|a| {
            let [r, s] = parent(mm, a);
            let (u, v) = if mm == 6 {
                (s, r)
            } else {
                (0.5 * (1.0 + s), 0.5 * (1.0 + r))
            };
            let (u, v) = (2.2 * u, 2.2 * v);
            let (x, y) = (-0.4 + c * u - sn * v, -0.7 + sn * u + c * v);
            [x, y, gap - 0.5 * bend * (x * x + y * y)]
        }));
        x
    }

    fn piece_3d(x: &[[f64; 3]], nn: usize, mm: usize) -> Option<QuadPiece> {
        let seg = quadratic3d::face_pair_frictional(&x[..nn], &x[nn..nn + mm], 1.0, 1.0)?;
        let mut vars = [UNUSED; 2 * MAX_NODES];
        for (a, v) in vars.iter_mut().enumerate().take(nn) {
            *v = a;
        }
        for l in 0..mm {
            vars[MAX_NODES + l] = nn + l;
        }
        Some(QuadPiece {
            vars,
            master: 0,
            seg,
        })
    }

    /// The frictional row of slave node `j` of the face pair at `x` with
    /// its committed pairing `pairing` (penalty 50 on a tributary area 0.25,
    /// tangential penalty 40): `(entry, coupling, g~, tangential force
    /// vector)`.
    #[allow(clippy::too_many_arguments)]
    fn row_3d(
        x: &[[f64; 3]],
        pairing: &Pairing3,
        nn: usize,
        mm: usize,
        j: usize,
        mu: f64,
        anchor: [f64; 3],
        shift: f64,
    ) -> Option<(NodeContact<3>, Coupling, f64, [f64; 3])> {
        let pieces = vec![piece_3d(x, nn, mm)?];
        let nodes: Vec<usize> = (0..nn + mm).collect();
        let list = [(0, j)];
        let (row, scalar) = rows_3d(&pieces, &list, &nodes);
        let inputs = FrictionInputs3 {
            mu,
            alpha_t: 40.0,
            shift: [0.3 * shift, -0.2 * shift, 0.0],
            anchor,
            slip: pairing.slip(x, &nodes),
            start_gap: None,
        };
        let (nc, c, r) =
            row.close_with_friction_3d(&scalar, j, 0.25, 50.0, shift, 1.0, 0, &inputs)?;
        Some((nc, c?, row.g, r?.traction))
    }

    /// The 3D weighted slip (tri6, quad8, quad9 slave faces, covered by the
    /// master: a partly covered face may have rows of negative area): 0 in the
    /// committed configuration and after a rigid motion of both curved
    /// faces, the slide itself along a flat master.
    #[test]
    fn quadratic_3d_slip_is_zero_at_rest_and_for_a_rigid_motion_and_the_slide_on_a_flat_master() {
        for (nn, mm) in [(8, 8), (6, 9), (9, 8)] {
            let nodes: Vec<usize> = (0..nn + mm).collect();
            let xn = faces_3d(nn, mm, 0.1, -0.01);
            // rotation about (1, 2, 3) / |..| by 0.4 and a translation
            let axis = [1.0, 2.0, 3.0].map(|v: f64| v / 14f64.sqrt());
            let (c, s) = (0.4f64.cos(), 0.4f64.sin());
            let turn = |p: [f64; 3]| -> [f64; 3] {
                let kd = dot3(axis, p);
                let kx = cross3(axis, p);
                std::array::from_fn(|q| {
                    p[q] * c + kx[q] * s + axis[q] * kd * (1.0 - c) + [0.3, -0.1, 0.2][q]
                })
            };
            let moved: Vec<[f64; 3]> = xn.iter().map(|&p| turn(p)).collect();
            let flat = faces_3d(nn, mm, 0.0, -0.01);
            let v = [0.03, -0.02, 0.0];
            let slid: Vec<[f64; 3]> = flat
                .iter()
                .enumerate()
                .map(|(k, p)| {
                    if k < nn {
                        std::array::from_fn(|q| p[q] + v[q])
                    } else {
                        *p
                    }
                })
                .collect();
            let old = piece_3d(&xn, nn, mm).unwrap();
            let old_flat = piece_3d(&flat, nn, mm).unwrap();
            for j in 0..nn {
                let mut p = Pairing3::default();
                p.add(&old.vars, j, &old.seg);
                assert!(
                    p.area > 0.0,
                    "{nn}|{mm} node {j}: area {} overlap {}",
                    p.area,
                    old.seg.overlap
                );
                let (rest, _) = p.slip(&xn, &nodes);
                let (rigid, _) = p.slip(&moved, &nodes);
                let mut q = Pairing3::default();
                q.add(&old_flat.vars, j, &old_flat.seg);
                let (s, _) = q.slip(&slid, &nodes);
                for c in 0..3 {
                    assert!(rest[c].abs() < 1e-12, "{nn}|{mm} node {j}: {rest:?}");
                    assert!(rigid[c].abs() < 1e-12, "{nn}|{mm} node {j}: {rigid:?}");
                    assert!((s[c] - v[c]).abs() < 1e-13, "{nn}|{mm} node {j}: {s:?}");
                }
            }
        }
    }

    /// The frictional 3D rows on quadratic faces (quad8 | quad8 and tri6 |
    /// quad9, corner and midside slave nodes, stick and slip, penalty and
    /// augmented shift): the forces sum to zero, on a flat pair their
    /// moment is `-(g~ / T) n x t`, and the tangent is minus the
    /// derivative of the forces (central differences, step 1e-7, over the
    /// coordinates of the node itself, a neighbour and two master nodes;
    /// the largest error measured by this test 1.3e-9 relative to the
    /// largest entry: `cargo test -p ctc-engine --lib friction_quadratic --
    /// --nocapture`).
    #[allow(clippy::type_complexity)]
    #[test]
    fn quadratic_3d_frictional_rows_balance_and_their_tangent_matches_finite_differences() {
        let (mut stick, mut slip, mut worst) = (0, 0, 0.0f64);
        for (nn, mm, bend, j) in [
            (8, 8, 0.0, 0),
            (8, 8, 0.1, 5),
            (6, 9, 0.08, 3),
            (9, 8, 0.06, 8),
        ] {
            let xn = faces_3d(nn, mm, bend, 0.0);
            let x: Vec<[f64; 3]> = faces_3d(nn, mm, bend, -0.01)
                .into_iter()
                .enumerate()
                .map(|(k, p)| {
                    if k < nn {
                        [p[0] + 0.01, p[1] - 0.004, p[2]]
                    } else {
                        p
                    }
                })
                .collect();
            let mut pairing = Pairing3::default();
            let old = piece_3d(&xn, nn, mm).unwrap();
            pairing.add(&old.vars, j, &old.seg);
            // stick and slip, penalty and augmented shift over the cases
            let shift = if j % 2 == 0 { 0.0 } else { 0.4 };
            for mu in [3.0, 0.05] {
                let anchor = [0.001, 0.0, 0.0];
                let Some((nc, c, gw, t)) = row_3d(&x, &pairing, nn, mm, j, mu, anchor, shift)
                else {
                    panic!("{nn}|{mm} node {j}: open");
                };
                let n = nn + mm;
                let fsum: [f64; 3] =
                    std::array::from_fn(|q| (0..n).map(|k| c.force[3 * k + q]).sum());
                let scale = c.force.iter().fold(0.0f64, |m, v| m.max(v.abs()));
                for v in fsum {
                    assert!(v.abs() < 1e-12 * scale, "{nn}|{mm}: {fsum:?}");
                }
                if bend == 0.0 {
                    let mut moment = [0.0; 3];
                    for (k, p) in x.iter().enumerate() {
                        let f = [c.force[3 * k], c.force[3 * k + 1], c.force[3 * k + 2]];
                        let m = cross3(*p, f);
                        (0..3).for_each(|q| moment[q] += m[q]);
                    }
                    let want = cross3([0.0, 0.0, 1.0], t).map(|v| -gw / 0.25 * v);
                    for q in 0..3 {
                        assert!(
                            (moment[q] - want[q]).abs() < 1e-11 * scale,
                            "{moment:?} against {want:?}"
                        );
                    }
                }
                match nc.friction.status {
                    FrictionStatus::Stick => stick += 1,
                    _ => slip += 1,
                }
                let h = 1e-7;
                let kscale = c.tangent.iter().fold(1.0f64, |m, v| m.max(v.abs()));
                let nd = 3 * n;
                let other = if j == 0 { 1 } else { 0 };
                for node in [j, other, nn, nn + mm - 1] {
                    for comp in 0..3 {
                        let at = |dh: f64| {
                            let mut y = x.clone();
                            y[node][comp] += dh;
                            row_3d(&y, &pairing, nn, mm, j, mu, anchor, shift)
                                .filter(|r| r.0.friction.status == nc.friction.status)
                        };
                        let (p, m) = at(h).zip(at(-h)).expect("same status");
                        let col = 3 * node + comp;
                        for r in 0..nd {
                            let fd = -(p.1.force[r] - m.1.force[r]) / (2.0 * h);
                            worst = worst.max((fd - c.tangent[r * nd + col]).abs() / kscale);
                        }
                    }
                }
            }
        }
        println!(
            "quadratic 3D friction rows: {stick} stick, {slip} slip, worst FD error {worst:.2e}"
        );
        assert!(stick >= 2 && slip >= 2, "{stick} stick, {slip} slip");
        assert!(worst < 1e-6, "{worst}");
    }
}
