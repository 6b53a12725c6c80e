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

use super::surface::SurfacePair;
use super::{ContactStatus, NodeContact, PairState};
use crate::model::{AnalysisKind, ContactMethod, Model};
use ad::Ad;
use integrals::{segment_pair, Basis, MortarSegment, Weight};

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

/// Marks an unused variable slot of a piece (a tri3 facet in a pair of
/// 4-node slots).
const UNUSED: usize = usize::MAX;

/// The row of one slave node, summed over its mortar pieces (2D segment
/// pairs, 3D facet pairs): the weighted gap `g~`, the covered area `A`,
/// `B` (`-D_jk n` on the slave nodes, `M_jl n` on the master ones) and
/// their gradients over `nodes` (`dim` components per node).
struct Row<'a> {
    nodes: &'a [usize],
    dim: usize,
    g: f64,
    area: f64,
    dg: Vec<f64>,
    da: Vec<f64>,
    bv: Vec<f64>,
    /// `d B / d x`, row-major `nd x nd`.
    db: Vec<f64>,
}

/// Adds `v` (gradient over a piece's variables: variable `k` is
/// component `k % dim` of node `vars[k / dim]`) to `value` / `grad`
/// (gradient over `nodes`, sorted).
fn accumulate<const N: usize>(
    nodes: &[usize],
    dim: usize,
    vars: &[usize],
    v: &Ad<N>,
    value: &mut f64,
    grad: &mut [f64],
) {
    *value += v.v;
    for (k, dk) in v.d.iter().enumerate() {
        let Some(&node) = vars.get(k / dim).filter(|&&n| n != UNUSED) else {
            continue;
        };
        if let Ok(p) = nodes.binary_search(&node) {
            grad[dim * p + k % dim] += dk;
        }
    }
}

impl<'a> Row<'a> {
    fn new(nodes: &'a [usize], dim: usize) -> Self {
        let nd = dim * nodes.len();
        Row {
            nodes,
            dim,
            g: 0.0,
            area: 0.0,
            dg: vec![0.0; nd],
            da: vec![0.0; nd],
            bv: vec![0.0; nd],
            db: vec![0.0; nd * nd],
        }
    }

    fn pos(&self, node: usize) -> usize {
        self.nodes.binary_search(&node).unwrap_or(0)
    }

    /// Adds one piece: its weighted gap, area, the coefficients `(node,
    /// -D_jk or M_jl)` of `B` and the normal, all over the variables
    /// `vars`.
    fn add<const N: usize>(
        &mut self,
        vars: &[usize],
        gap: &Ad<N>,
        area: &Ad<N>,
        coefficients: impl Iterator<Item = (usize, Ad<N>)>,
        normal: &[Ad<N>],
    ) {
        let (nodes, dim) = (self.nodes, self.dim);
        let nd = dim * nodes.len();
        accumulate(nodes, dim, vars, gap, &mut self.g, &mut self.dg);
        accumulate(nodes, dim, vars, area, &mut self.area, &mut self.da);
        for (node, coef) in coefficients {
            for (c, nc) in normal.iter().enumerate() {
                let r = dim * self.pos(node) + c;
                let mut v = 0.0;
                accumulate(
                    nodes,
                    dim,
                    vars,
                    &(coef * *nc),
                    &mut v,
                    &mut self.db[r * nd..(r + 1) * nd],
                );
                self.bv[r] += v;
            }
        }
    }

    /// The nodal gap `g~ / A`, the force `R = max(0, shift - alpha g)`
    /// (`support` the node's reference tributary area) and, when closed,
    /// the [`Coupling`] of slave `node`; `touching`: a closed-gap start
    /// (closed with zero force, the penalty tangent). `None` when the
    /// master does not cover the node's support or the gap exceeds
    /// `prof`. With Lagrange multipliers (`lagrange = Some((active,
    /// lambda))`) see [`Row::close_lagrange`].
    #[allow(clippy::too_many_arguments)]
    fn close<const D: usize>(
        &self,
        node: usize,
        support: f64,
        alpha: f64,
        shift: f64,
        prof: f64,
        touching: f64,
        entity: usize,
        lagrange: Option<(bool, f64)>,
    ) -> Option<(NodeContact<D>, Option<Coupling>)> {
        let area = self.area;
        if area.is_nan() || area <= 1e-12 * support || support.is_nan() || support <= 0.0 {
            return None;
        }
        let gap = self.g / area;
        if gap > prof {
            return None;
        }
        let nd = self.bv.len();
        let at = D * self.pos(node);
        let sn: [f64; D] = std::array::from_fn(|c| self.bv[at + c]);
        let sl = sn.iter().map(|v| v * v).sum::<f64>().sqrt();
        let normal = if sl > 0.0 {
            sn.map(|v| -v / sl)
        } else {
            [0.0; D]
        };
        let (closed, pressure, coupling) = match lagrange {
            Some((active, lambda)) => {
                let (pressure, coupling) = self.close_lagrange(node, lambda);
                (active, pressure, active.then_some(coupling))
            }
            None => {
                let dgap: Vec<f64> = self
                    .dg
                    .iter()
                    .zip(&self.da)
                    .map(|(a, b)| (a - gap * b) / area)
                    .collect();
                let rn = (shift - alpha * gap).max(0.0);
                let closed =
                    rn > 0.0 || (touching > 0.0 && (0.0..=touching).contains(&gap) && alpha > 0.0);
                let pressure = rn / support;
                let coupling = closed.then(|| {
                    let dp: Vec<f64> = dgap.iter().map(|v| -alpha / support * v).collect();
                    let force: Vec<f64> = self.bv.iter().map(|b| pressure * b).collect();
                    let mut tangent = vec![0.0; nd * nd];
                    for r in 0..nd {
                        for c in 0..nd {
                            tangent[r * nd + c] =
                                -(self.bv[r] * dp[c] + pressure * self.db[r * nd + c]);
                        }
                    }
                    Coupling {
                        nodes: self.nodes.to_vec(),
                        force,
                        tangent,
                        slave: node,
                        gap_gradient: Vec::new(),
                    }
                });
                (closed, pressure, coupling)
            }
        };
        let nc = NodeContact {
            node,
            gap,
            normal,
            force: [0.0; D],
            stiffness: [[0.0; D]; D],
            // reported per reference area (the nominal pressure, as
            // node-to-segment's and node-to-facet's): the slave force
            // `pressure A` over the reference tributary area
            pressure: if closed {
                pressure * area / support
            } else {
                0.0
            },
            status: if closed {
                ContactStatus::Closed
            } else {
                ContactStatus::Open
            },
            entity,
            master: None,
            friction: Default::default(),
        };
        Some((nc, coupling))
    }

    /// Lagrange multipliers: the constraint of an active node is its nodal
    /// gap `g~ / A = 0`, its row `B / A` (the gap's gradient with `D`, `M`
    /// and the normal held fixed, exact where the gap vanishes pointwise),
    /// the multiplier `lambda` the nodal normal force: force `lambda B /
    /// A`, tangent `-lambda d(B / A)/dx`, pressure `lambda / A` (per
    /// covered current area, as the penalty's `R / T` with `|B| = A`).
    /// Returns the pressure and the coupling (its `gap_gradient` the row).
    fn close_lagrange(&self, node: usize, lambda: f64) -> (f64, Coupling) {
        let area = self.area;
        let nd = self.bv.len();
        let row: Vec<f64> = self.bv.iter().map(|b| b / area).collect();
        let force: Vec<f64> = row.iter().map(|b| lambda * b).collect();
        let mut tangent = vec![0.0; nd * nd];
        for r in 0..nd {
            for c in 0..nd {
                // d(B/A)/dx = dB/A - B dA / A^2
                let d = self.db[r * nd + c] / area - row[r] * self.da[c] / area;
                tangent[r * nd + c] = -lambda * d;
            }
        }
        let coupling = Coupling {
            nodes: self.nodes.to_vec(),
            force,
            tangent,
            slave: node,
            gap_gradient: row,
        };
        (lambda / area, coupling)
    }
}

/// Adds the forces of `couplings` on the slave nodes to their output
/// entries (`out` sorted by node).
fn total_forces<const D: usize>(couplings: &[Coupling], out: &mut [NodeContact<D>]) {
    for c in couplings {
        for (k, &n) in c.nodes.iter().enumerate() {
            if let Ok(o) = out.binary_search_by_key(&n, |nc| nc.node) {
                for comp in 0..D {
                    out[o].force[comp] += c.force[D * k + comp];
                }
            }
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
    let basis = Basis::Dual;
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
            let Some(seg) = segment_pair([xa, xb, x[c], x[d]], w, basis) else {
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
        let mut row = Row::new(&nodes, 2);
        for p in list {
            let s = &p.seg;
            let j = p.row;
            row.add(
                &p.nodes,
                &s.gap[j],
                &(s.d[j][0] + s.d[j][1]),
                (0..4).map(|slot| {
                    let coef = if slot < 2 {
                        -s.d[j][slot]
                    } else {
                        s.m[j][slot - 2]
                    };
                    (p.nodes[slot], coef)
                }),
                &s.normal,
            );
        }
        let support = state.tributary.get(i).copied().unwrap_or(0.0);
        let alpha = super::penalty::effective_stiffness(&cp.method_at(node), support);
        let shift = match cp.method {
            ContactMethod::AugmentedLagrange { .. } => {
                state.multiplier.get(i).copied().unwrap_or(0.0)
            }
            _ => 0.0,
        };
        let lagrange = matches!(cp.method, ContactMethod::Lagrange { .. }).then(|| {
            (
                state.active.get(i).copied().unwrap_or(false),
                state.multiplier.get(i).copied().unwrap_or(0.0),
            )
        });
        let Some((nc, coupling)) = row.close(
            node,
            support,
            alpha,
            shift,
            prof,
            0.0,
            list[0].master,
            lagrange,
        ) else {
            continue;
        };
        couplings.extend(coupling);
        out.push(nc);
    }
    total_forces(&couplings, &mut out);
    state.last_projection_tests = tests;
    state.last_brute_force_tests = sp.sides[0].edges.len() * sp.sides[1].edges.len();
    state.total_projection_tests += tests as u64;
    state.surface = Some(sp);
    state.couplings = Some(couplings);
    out
}

/// One 3D facet pair (slave facet, master facet): its variables (slave
/// facet nodes in slots 0..4, master ones in 4..8, [`UNUSED`] for a
/// tri3's fourth) and its integrals.
struct FacetPiece {
    vars: [usize; 8],
    master: usize,
    seg: facets::FacetSegment,
}

/// Evaluates the 3D mortar pair `pair` (deformable slave and master face
/// sets, tri3 / quad4, [`facets`]) at current coordinates `x`: one entry
/// per slave node whose support the master covers within `prof`, the
/// couplings of the closed ones in `state.deformable` (the solver
/// scatters them as node-to-facet's). Per slave facet, the candidate
/// master facets are those of the broad phase within the facet's radius
/// plus `prof` of its centre; a facet pair whose gaps (at the
/// integration points) all exceed `prof`, or all lie deeper than `max(prof,
/// h)` (`h` the slave facet's longest edge: the far side of a thin body),
/// is left out.
pub fn evaluate_3d(
    model: &Model<3>,
    pair: usize,
    x: &[[f64; 3]],
    state: &mut SurfacePair,
) -> Vec<NodeContact<3>> {
    let mut out = Vec::new();
    let Some(cp) = model.contacts.get(pair) else {
        return out;
    };
    let Some(mut fp) = state.deformable.take() else {
        return out;
    };
    state.evaluations += 1;
    let basis = Basis::Dual;
    let prof = state.prof;
    fp.sides[1].update(x, prof);
    fp.couplings.clear();
    fp.tests = 0;
    let mut pieces: Vec<FacetPiece> = Vec::new();
    let mut rows: Vec<Vec<(usize, usize)>> = vec![Vec::new(); state.slaves.len()];
    let mut candidates = Vec::new();
    for face in &fp.sides[0].faces {
        let sn = face.nodes();
        let Some(sx) = sn
            .iter()
            .map(|&n| x.get(n).copied())
            .collect::<Option<Vec<_>>>()
        else {
            continue;
        };
        let k = 1.0 / sn.len() as f64;
        let centre: [f64; 3] = std::array::from_fn(|c| sx.iter().map(|p| p[c]).sum::<f64>() * k);
        let dist =
            |a: [f64; 3], b: [f64; 3]| (0..3).map(|c| (a[c] - b[c]).powi(2)).sum::<f64>().sqrt();
        let radius = sx.iter().map(|&p| dist(p, centre)).fold(0.0, f64::max);
        let h = (0..sx.len())
            .map(|a| dist(sx[a], sx[(a + 1) % sx.len()]))
            .fold(0.0, f64::max);
        let depth = prof.max(h);
        fp.sides[1].query(centre, radius + prof, &mut candidates);
        state.counters.queries += 1;
        for &m in &candidates {
            let (mp, nm) = fp.sides[1].points(m, x);
            fp.tests += 1;
            let Some(seg) = facets::facet_pair_within(&sx, &mp[..nm], prof, depth, basis) else {
                continue;
            };
            let mut vars = [UNUSED; 8];
            vars[..sn.len()].copy_from_slice(sn);
            vars[4..4 + nm].copy_from_slice(fp.sides[1].faces[m].nodes());
            for (j, &node) in sn.iter().enumerate() {
                if let Some(i) = state.slave_index(node) {
                    rows[i].push((pieces.len(), j));
                }
            }
            pieces.push(FacetPiece {
                vars,
                master: m,
                seg,
            });
        }
    }
    let mut nodes = Vec::new();
    for (i, list) in rows.iter().enumerate() {
        let node = state.slaves[i];
        fp.last[i] = list.first().map(|&(p, _)| pieces[p].master);
        if list.is_empty() {
            continue;
        }
        nodes.clear();
        for &(p, _) in list {
            nodes.extend(pieces[p].vars.iter().copied().filter(|&n| n != UNUSED));
        }
        nodes.sort_unstable();
        nodes.dedup();
        let mut row = Row::new(&nodes, 3);
        for &(p, j) in list {
            let FacetPiece { vars, seg, .. } = &pieces[p];
            let area = seg.d[j].iter().fold(Ad::cst(0.0), |a, &b| a + b);
            row.add(
                vars,
                &seg.gap[j],
                &area,
                (0..seg.ns)
                    .map(|k| (vars[k], -seg.d[j][k]))
                    .chain((0..seg.nm).map(|l| (vars[4 + l], seg.m[j][l]))),
                &seg.normal,
            );
        }
        let support = state.area.get(i).copied().unwrap_or(0.0);
        let method = cp.method_at(node);
        let alpha = super::surface::alpha(&method, support);
        let shift = match method {
            ContactMethod::AugmentedLagrange { .. } => {
                state.multiplier.get(i).copied().unwrap_or(0.0)
            }
            _ => 0.0,
        };
        let entity = pieces[list[0].0].master;
        let Some((nc, coupling)) = row.close(
            node,
            support,
            alpha,
            shift,
            prof,
            state.touching,
            entity,
            None,
        ) else {
            continue;
        };
        fp.couplings.extend(coupling);
        out.push(nc);
    }
    total_forces(&fp.couplings, &mut out);
    state.counters.faces_tested += fp.tests as u64;
    state.deformable = Some(fp);
    out
}
