//! Mortar segment-to-segment contact between deformable bodies (2D, seg2).
//!
//! Instead of one constraint per slave node against the point under it
//! (node-to-segment), the gap is integrated along the slave surface
//! against the shape functions of the slave nodes ([`integrals`]): the
//! **weighted gap** of slave node `j`
//!
//! `g~_j = int N_j g w ds = n . (sum_l M_jl x_l - sum_k D_jk x_k)`
//!
//! summed over the mortar segments of the slave segments around `j`, and
//! its integration area `A_j = sum_k D_jk` (the part of `j`'s support the
//! master covers). The nodal gap `g_j = g~_j / A_j` decides contact, gives
//! the force and the reported pressure.
//!
//! Penalty (and augmented Lagrangian) enforcement: the nodal normal force
//! `R_j = max(0, lambda*_j - alpha_j g_j)` (`alpha_j` the penalty of
//! [`super::penalty::effective_stiffness`] with the node's reference
//! tributary area `T_j`; `lambda* = 0` for penalty), the pressure
//! `p_j = R_j / T_j` (with an area penalty `p_j = -stiffness g_j`), and
//! the forces of the mortar (Lagrange-multiplier) form
//!
//! `f = sum_j p_j B_j`, `B_j = n . (M_jl on the master, -D_jk on the slave)`
//!
//! i.e. `D`, `M` and `n` held fixed in the variation. With a flat interface
//! and a uniform gap this gives exactly the consistent nodal forces of a
//! uniform pressure on both sides (no tangential end forces), so the
//! contact patch test passes to round-off. The tangent is the exact
//! derivative `K = -d f / d x = -sum_j (B_j ⊗ d p_j / d x + p_j d B_j / d x)`
//! (the segmentation included, by the dual numbers of [`ad`]); it is not
//! symmetric, so the solver factorizes with LU.
//!
//! Each closed slave node gives one [`Coupling`] over its nodes (itself,
//! its slave neighbours, the master nodes of its mortar segments), stored
//! in [`PairState::couplings`]; the solver scatters those. The
//! [`NodeContact`] entries are for output (gap, pressure, status, the
//! total force on the slave node).

pub mod ad;
pub mod facets;
pub mod integrals;

use super::{ContactStatus, NodeContact, PairState};
use crate::model::{AnalysisKind, ContactMethod, Model};
use integrals::{segment_pair, Ad8, MortarSegment, Weight};

/// Forces and tangent of one mortar row over a list of nodes (also the
/// rows of smoothed node-to-segment in 2D and of node-to-facet in 3D,
/// `D` components per node).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Coupling {
    /// Global node numbers (sorted, distinct).
    pub nodes: Vec<usize>,
    /// Forces on the nodes, `D * nodes.len()` (node-major, x then y (then z)).
    pub force: Vec<f64>,
    /// `-d force / d x`, row-major `Dn x Dn` in the same order.
    pub tangent: Vec<f64>,
    /// Smoothed node-to-segment rows: the slave node of the row.
    pub slave: usize,
    /// Smoothed node-to-segment rows: `d g / d x` over the nodes (the
    /// Lagrange constraint row); empty for mortar rows.
    pub gap_gradient: Vec<f64>,
}

/// One mortar segment seen from one of its two slave nodes.
#[derive(Debug, Clone, Copy)]
struct Piece {
    /// Global nodes `[a, b, c, d]` of the segment pair.
    nodes: [usize; 4],
    /// Master segment index.
    master: usize,
    /// Row of the slave node (0: `a`, 1: `b`).
    row: usize,
    seg: MortarSegment,
}

/// Dense accumulator of a quantity and its gradient over a node list.
struct Local<'a> {
    nodes: &'a [usize],
}

impl Local<'_> {
    fn pos(&self, node: usize) -> usize {
        self.nodes.binary_search(&node).unwrap_or(0)
    }

    /// Adds `v` (gradient over the pair's 8 coordinates) to `value`/`grad`.
    fn add(&self, nodes: &[usize; 4], v: &Ad8, value: &mut f64, grad: &mut [f64]) {
        *value += v.v;
        for (k, dk) in v.d.iter().enumerate() {
            grad[2 * self.pos(nodes[k / 2]) + k % 2] += dk;
        }
    }
}

/// The integration weight of the model's analysis.
pub fn weight(model: &Model) -> Weight {
    match model.analysis.kind {
        AnalysisKind::Axisymmetric => Weight::Axisymmetric,
        _ => Weight::Thickness(model.analysis.thickness),
    }
}

/// Evaluates mortar pair `pair` at current coordinates `x`: fills
/// `state.couplings` and returns one entry per slave node whose support
/// the master covers within `prof`.
pub fn evaluate(
    model: &Model,
    pair: usize,
    x: &[[f64; 2]],
    state: &mut PairState,
) -> Vec<NodeContact> {
    let mut out = Vec::new();
    let mut couplings = state.couplings.take().unwrap_or_default();
    couplings.clear();
    let (Some(cp), Some(mut sp)) = (model.contacts.get(pair), state.surface.take()) else {
        state.couplings = Some(couplings);
        return out;
    };
    let w = weight(model);
    let prof = state.prof;
    sp.sides[1].update(x);
    let mut pieces: Vec<Vec<Piece>> = vec![Vec::new(); state.slaves.len()];
    let mut candidates = std::mem::take(&mut sp.candidates);
    let mut tests = 0usize;
    for &[a, b] in &sp.sides[0].edges {
        let (Some(&xa), Some(&xb)) = (x.get(a), x.get(b)) else {
            continue;
        };
        let len = (xb[0] - xa[0]).hypot(xb[1] - xa[1]);
        let mid = [0.5 * (xa[0] + xb[0]), 0.5 * (xa[1] + xb[1])];
        candidates.clear();
        if let Some(grid) = &sp.sides[1].grid {
            grid.query(mid, 0.5 * len + prof, &mut candidates);
        }
        candidates.sort_unstable();
        candidates.dedup();
        let depth = prof.max(len);
        for &e in &candidates {
            let [c, d] = sp.sides[1].edges[e];
            tests += 1;
            let Some(seg) = segment_pair([xa, xb, x[c], x[d]], w) else {
                continue;
            };
            let [g0, g1] = seg.end_gaps;
            if (g0 > prof && g1 > prof) || (g0 < -depth && g1 < -depth) {
                continue;
            }
            for (row, node) in [a, b].into_iter().enumerate() {
                if let Some(i) = state.slave_index(node) {
                    pieces[i].push(Piece {
                        nodes: [a, b, c, d],
                        master: e,
                        row,
                        seg,
                    });
                }
            }
        }
    }
    sp.candidates = candidates;
    let mut nodes = Vec::new();
    for (i, list) in pieces.iter().enumerate() {
        let node = state.slaves[i];
        state.last_entity[i] = list.first().map(|p| p.master);
        if list.is_empty() {
            continue;
        }
        nodes.clear();
        for p in list {
            nodes.extend_from_slice(&p.nodes);
        }
        nodes.sort_unstable();
        nodes.dedup();
        let loc = Local { nodes: &nodes };
        let nd = 2 * nodes.len();
        // weighted gap, area, and B with their gradients
        let (mut g, mut area) = (0.0, 0.0);
        let mut dg = vec![0.0; nd];
        let mut da = vec![0.0; nd];
        let mut bv = vec![0.0; nd];
        let mut db = vec![0.0; nd * nd];
        for p in list {
            let s = &p.seg;
            let j = p.row;
            loc.add(&p.nodes, &s.gap[j], &mut g, &mut dg);
            loc.add(&p.nodes, &(s.d[j][0] + s.d[j][1]), &mut area, &mut da);
            // B: -D_jk n on slave k, +M_jl n on master l
            for (slot, node) in p.nodes.iter().enumerate() {
                let coef = if slot < 2 {
                    -s.d[j][slot]
                } else {
                    s.m[j][slot - 2]
                };
                for c in 0..2 {
                    let r = 2 * loc.pos(*node) + c;
                    let mut v = 0.0;
                    loc.add(
                        &p.nodes,
                        &(coef * s.normal[c]),
                        &mut v,
                        &mut db[r * nd..(r + 1) * nd],
                    );
                    bv[r] += v;
                }
            }
        }
        let support = state.tributary.get(i).copied().unwrap_or(0.0);
        if area.is_nan() || area <= 1e-12 * support || support.is_nan() || support <= 0.0 {
            continue;
        }
        let gap = g / area;
        if gap > prof {
            continue;
        }
        let dgap: Vec<f64> = dg
            .iter()
            .zip(&da)
            .map(|(a, b)| (a - gap * b) / area)
            .collect();
        let alpha = super::penalty::effective_stiffness(&cp.method_at(node), support);
        let shift = match cp.method {
            ContactMethod::AugmentedLagrange { .. } => {
                state.multiplier.get(i).copied().unwrap_or(0.0)
            }
            _ => 0.0,
        };
        let rn = (shift - alpha * gap).max(0.0);
        let pos_j = loc.pos(node);
        let sn = [bv[2 * pos_j], bv[2 * pos_j + 1]];
        let sl = sn[0].hypot(sn[1]);
        let normal = if sl > 0.0 {
            [-sn[0] / sl, -sn[1] / sl]
        } else {
            [0.0; 2]
        };
        let closed = rn > 0.0;
        if closed {
            let pressure = rn / support;
            let dp: Vec<f64> = dgap.iter().map(|v| -alpha / support * v).collect();
            let force: Vec<f64> = bv.iter().map(|b| pressure * b).collect();
            let mut tangent = vec![0.0; nd * nd];
            for r in 0..nd {
                for c in 0..nd {
                    tangent[r * nd + c] = -(bv[r] * dp[c] + pressure * db[r * nd + c]);
                }
            }
            couplings.push(Coupling {
                nodes: nodes.clone(),
                force,
                tangent,
                slave: node,
                gap_gradient: Vec::new(),
            });
        }
        out.push(NodeContact {
            node,
            gap,
            normal,
            force: [0.0; 2],
            stiffness: [[0.0; 2]; 2],
            pressure: if closed { rn / support } else { 0.0 },
            status: if closed {
                ContactStatus::Closed
            } else {
                ContactStatus::Open
            },
            entity: list[0].master,
            master: None,
            friction: Default::default(),
        });
    }
    // the total force on each slave node, for output
    for c in &couplings {
        for (k, &n) in c.nodes.iter().enumerate() {
            if let Ok(o) = out.binary_search_by_key(&n, |nc| nc.node) {
                out[o].force[0] += c.force[2 * k];
                out[o].force[1] += c.force[2 * k + 1];
            }
        }
    }
    state.last_projection_tests = tests;
    state.last_brute_force_tests = sp.sides[0].edges.len() * sp.sides[1].edges.len();
    state.total_projection_tests += tests as u64;
    state.surface = Some(sp);
    state.couplings = Some(couplings);
    out
}
