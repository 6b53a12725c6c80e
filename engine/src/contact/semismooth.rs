//! Semi-smooth Newton active set of contact with Lagrange multipliers
//! (Hüeber & Wohlmuth, CMAME 194 (2005) 3147; Popp, Gee & Wall, IJNME 79
//! (2009) 1354, §4; Popp et al., IJNME 83 (2010) 1428 in 3D): mortar
//! pairs, node-to-segment (2D) and node-to-facet (3D) pairs against a
//! deformable master or a rigid tool, every strategy and self contact.
//!
//! The contact conditions of slave node `j` (nodal force `lambda_j >= 0`,
//! nodal gap `g_j >= 0`, `lambda_j g_j = 0`) are the root of the
//! nonlinear complementarity function
//!
//! `C_j = lambda_j - max(0, lambda_j - c_j g_j)`
//!
//! (`c_j > 0`: any value gives the same solution, it only weighs the
//! force against the gap in the decision). Its generalized derivative is
//! the active-set strategy: where `lambda_j - c_j g_j > 0` the node is
//! active and `C_j = 0` reads `g_j = 0` (the constraint row of the saddle
//! point), elsewhere it is inactive and `C_j = 0` reads `lambda_j = 0` (no
//! row, no force). The active set is decided at **every Newton
//! iteration** from the current iterate, inside the Newton loop: no outer
//! active-set loop, and the loop converges only on an iteration that
//! leaves the set unchanged. `c_j = E w_j` with `E` the slave body's
//! Young's modulus and `w_j` the ratio of the node's tributary area to
//! its size (the thickness, or `2 pi r` in axisymmetry, in 2D; the square
//! root of the area in 3D): the force `c_j g_j` of a gap `g_j` is that of
//! the strain `g_j / h` on the node's area.
//!
//! Cycle guard: a node switched [`MAX_SWITCHES`] times in an increment
//! attempt is frozen (the semi-smooth decision leaves it as it is until
//! the increment converges or is cut back); the active-set loop around
//! the Newton loop (`crate::solve::contact_loop`, which still runs after
//! each Newton loop and, on a semi-smooth set, finds nothing to change)
//! then decides it on the converged iterate, under its own cycling
//! guard. A redundant node (its row dropped, [`super::redundancy`]: no
//! multiplier, its gap held by the rows it repeats) keeps its status.

use super::NodeContact;
use crate::model::{ContactMethod, ContactPair, Model};

/// Whether the pair's active set is semi-smooth: every pair with Lagrange
/// multipliers (mortar, node-to-segment, node-to-facet, rigid tools).
pub fn applies(cp: &ContactPair) -> bool {
    matches!(cp.method, ContactMethod::Lagrange { .. })
}

/// Switches of one node in an increment attempt after which the
/// semi-smooth decision leaves it as it is (the cycle guard). Measured on
/// `verification/cases/hertz_two_cylinders_nts_lagrange.ctc` at its three
/// levels (`ctc run`, debug; the modified double pass's edge nodes of the
/// two arcs take turns): Newton 34 / 61 / 85 iterations with 2 switches
/// (frozen nodes go to the outer loop), 31 / 68 / - with 3, 29 / 47 / 70
/// with 4, 29 / 49 / 65 without a guard.
pub const MAX_SWITCHES: u8 = 4;

/// Young's modulus of the pair's slave body (1 when it has none).
pub fn young<const D: usize>(model: &Model<D>, cp: &ContactPair) -> f64 {
    model
        .bodies
        .get(cp.body)
        .and_then(|b| model.materials.get(b.material))
        .map(|m| m.law.young())
        .filter(|e| e.is_finite() && *e > 0.0)
        .unwrap_or(1.0)
}

/// What one semi-smooth update changed: global nodes introduced and
/// released.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Switch {
    /// Nodes that became active (`lambda - c g > 0`).
    pub introduced: Vec<usize>,
    /// Nodes that became inactive (`lambda - c g <= 0`, or out of the
    /// search window).
    pub released: Vec<usize>,
    /// Nodes the decision would switch again but leaves frozen (switched
    /// [`MAX_SWITCHES`] times already in this increment attempt).
    pub frozen: Vec<usize>,
}

impl Switch {
    /// Whether the set changed.
    pub fn is_empty(&self) -> bool {
        self.introduced.is_empty() && self.released.is_empty()
    }
}

/// Whether node `j` is active under `C_j`: `lambda - c g > 0`. An inactive
/// node has `lambda = 0`: active when `g < -threshold` (a gap of round-off
/// does not introduce it).
pub fn is_active(active: bool, lambda: f64, gap: f64, c: f64, threshold: f64) -> bool {
    if active {
        lambda - c * gap > 0.0
    } else {
        gap < -threshold
    }
}

/// The semi-smooth update of one pair: the active flags and multipliers
/// of its `slaves` from the evaluation `contact` (one entry per slave node
/// the search found; the others are inactive), with `c(i)` the
/// complementarity parameter of slave `i`. Released nodes get `lambda =
/// 0`; introduced ones start from 0. `switches[i]` counts the switches of
/// slave `i` in the increment attempt (resized to the slaves): a node at
/// [`MAX_SWITCHES`] is frozen; `keep(i)`: slave `i` keeps its status (a
/// redundant row).
#[allow(clippy::too_many_arguments)]
pub fn update<const D: usize>(
    slaves: &[usize],
    active: &mut [bool],
    multiplier: &mut [f64],
    switches: &mut Vec<u8>,
    contact: &[NodeContact<D>],
    c: impl Fn(usize) -> f64,
    keep: impl Fn(usize) -> bool,
    threshold: f64,
) -> Switch {
    let mut switch = Switch::default();
    switches.resize(slaves.len(), 0);
    let mut seen = vec![false; slaves.len()];
    let mut flip = Vec::new();
    for nc in contact {
        let Ok(i) = slaves.binary_search(&nc.node) else {
            continue;
        };
        seen[i] = true;
        if !keep(i) && is_active(active[i], multiplier[i], nc.gap, c(i), threshold) != active[i] {
            flip.push(i);
        }
    }
    flip.extend((0..slaves.len()).filter(|&i| !seen[i] && active[i]));
    flip.sort_unstable();
    for i in flip {
        if switches[i] >= MAX_SWITCHES {
            switch.frozen.push(slaves[i]);
            continue;
        }
        switches[i] += 1;
        active[i] = !active[i];
        multiplier[i] = 0.0;
        if active[i] {
            switch.introduced.push(slaves[i]);
        } else {
            switch.released.push(slaves[i]);
        }
    }
    switch
}

/// `CTC_LOG=debug`: one line per pair whose set changed (or froze a node)
/// at this iteration.
pub fn log(pair: &str, s: &Switch) {
    if super::log::debug_enabled() && !(s.is_empty() && s.frozen.is_empty()) {
        eprintln!(
            "[ctc contact] pair '{pair}': semi-smooth active set: {} introduced {:?}, {} released \
             {:?}, {} frozen {:?}",
            s.introduced.len(),
            s.introduced,
            s.released.len(),
            s.released,
            s.frozen.len(),
            s.frozen
        );
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::ContactStatus;

    fn nc(node: usize, gap: f64) -> NodeContact {
        NodeContact {
            node,
            gap,
            normal: [0.0, 1.0],
            force: [0.0; 2],
            stiffness: [[0.0; 2]; 2],
            pressure: 0.0,
            status: ContactStatus::Open,
            entity: 0,
            master: None,
            friction: Default::default(),
        }
    }

    #[test]
    fn complementarity_decides_the_set() {
        // active: kept while lambda > c g (a small opening with a large
        // force stays, a tensile force goes)
        assert!(is_active(true, 1.0, 1e-3, 100.0, 0.0));
        assert!(!is_active(true, 1.0, 2e-2, 100.0, 0.0));
        assert!(!is_active(true, -1e-3, -1e-6, 100.0, 0.0));
        assert!(is_active(true, -1e-3, -1e-4, 100.0, 0.0));
        // inactive (lambda = 0): a penetration beyond round-off introduces
        assert!(is_active(false, 0.0, -1e-6, 100.0, 1e-12));
        assert!(!is_active(false, 0.0, -1e-13, 100.0, 1e-12));
        assert!(!is_active(false, 0.0, 1e-3, 100.0, 1e-12));
    }

    #[test]
    fn update_switches_nodes_and_zeroes_their_multipliers() {
        let slaves = [3, 5, 7, 9];
        let mut active = [true, true, false, true];
        let mut lambda = [2.0, -0.5, 0.0, 1.0];
        // 3 stays, 5 in tension goes, 7 penetrates, 9 not found: goes
        let contact = [nc(3, 1e-4), nc(5, 0.0), nc(7, -1e-3)];
        let mut switches = Vec::new();
        let s = update(
            &slaves,
            &mut active,
            &mut lambda,
            &mut switches,
            &contact,
            |_| 10.0,
            |_| false,
            1e-12,
        );
        assert_eq!(s.introduced, vec![7]);
        assert_eq!(s.released, vec![5, 9]);
        assert_eq!(active, [true, false, true, false]);
        assert_eq!(lambda, [2.0, 0.0, 0.0, 0.0]);
        // the next Newton step closes 7's gap with a compressive force: a
        // second pass changes nothing (a node with zero force and zero gap
        // would go: `lambda - c g = 0` is not active)
        lambda[2] = 0.5;
        let contact = [nc(3, 0.0), nc(5, 1e-3), nc(7, 0.0)];
        let s = update(
            &slaves,
            &mut active,
            &mut lambda,
            &mut switches,
            &contact,
            |_| 10.0,
            |_| false,
            1e-12,
        );
        assert!(s.is_empty(), "{s:?}");
        assert_eq!(switches, [0, 1, 1, 1]);
    }

    /// One semi-smooth update of `slaves` (c = 10, threshold 1e-12).
    fn step(
        slaves: &[usize],
        state: &mut (Vec<bool>, Vec<f64>, Vec<u8>),
        contact: &[NodeContact],
        keep: &[bool],
    ) -> Switch {
        update(
            slaves,
            &mut state.0,
            &mut state.1,
            &mut state.2,
            contact,
            |_| 10.0,
            |i| keep[i],
            1e-12,
        )
    }

    #[test]
    fn a_node_entering_a_node_released_and_the_cycle_guard() {
        // node-to-segment / node-to-facet: the multipliers are nodal forces
        // set by the saddle point between two updates
        let slaves = [2, 4, 6];
        let mut st = (vec![false, true, true], vec![0.0, 1.0, 0.0], Vec::new());
        // iteration 1: node 2 penetrates and enters; node 6 (a redundant
        // row: no multiplier, gap held by the row it repeats) opens by
        // round-off and stays
        let keep = [false, false, true];
        let s = step(
            &slaves,
            &mut st,
            &[nc(2, -1e-3), nc(4, 0.0), nc(6, 1e-15)],
            &keep,
        );
        assert_eq!((s.introduced, s.released), (vec![2], vec![]));
        // iteration 2: the solve gave node 2 a tensile multiplier: it
        // leaves (lambda - c g = -0.1 - 10 * 1e-4 < 0); node 4 keeps its
        // compressive force
        st.1[0] = -0.1;
        let s = step(
            &slaves,
            &mut st,
            &[nc(2, -1e-4), nc(4, 0.0), nc(6, 0.0)],
            &keep,
        );
        assert_eq!((s.introduced, s.released), (vec![], vec![2]));
        assert_eq!((st.0[0], st.1[0]), (false, 0.0));
        // it goes on flipping: penetrating when out, in tension when in,
        // until it has switched MAX_SWITCHES times; then it is frozen (the
        // outer active-set loop decides it on the converged iterate)
        for k in 2..MAX_SWITCHES {
            if !st.0[0] {
                let s = step(
                    &slaves,
                    &mut st,
                    &[nc(2, -1e-3), nc(4, 0.0), nc(6, 0.0)],
                    &keep,
                );
                assert_eq!(s.introduced, vec![2], "switch {k}");
            } else {
                st.1[0] = -0.1;
                let s = step(
                    &slaves,
                    &mut st,
                    &[nc(2, 0.0), nc(4, 0.0), nc(6, 0.0)],
                    &keep,
                );
                assert_eq!(s.released, vec![2], "switch {k}");
            }
        }
        assert_eq!(st.2[0], MAX_SWITCHES);
        let frozen = st.0[0];
        st.1[0] = if frozen { -0.1 } else { 0.0 };
        let gap = if frozen { 0.0 } else { -1e-3 };
        let s = step(
            &slaves,
            &mut st,
            &[nc(2, gap), nc(4, 0.0), nc(6, 0.0)],
            &keep,
        );
        assert!(s.is_empty() && s.frozen == vec![2], "{s:?}");
        assert_eq!(st.0[0], frozen);
        // node 4 in tension still leaves (its first switch)
        st.1[1] = -1.0;
        let s = step(
            &slaves,
            &mut st,
            &[nc(2, gap), nc(4, 0.0), nc(6, 0.0)],
            &keep,
        );
        assert_eq!((s.released, s.frozen), (vec![4], vec![2]));
        assert_eq!(st.2, [MAX_SWITCHES, 1, 0]);
        assert!(st.0[2]);
    }
}
