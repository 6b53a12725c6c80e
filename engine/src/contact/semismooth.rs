//! Semi-smooth Newton active set of mortar contact with Lagrange
//! multipliers (Hüeber & Wohlmuth, CMAME 194 (2005) 3147; Popp, Gee &
//! Wall, IJNME 79 (2009) 1354, §4; Popp et al., IJNME 83 (2010) 1428 in
//! 3D).
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

use super::NodeContact;
use crate::model::{ContactFormulation, ContactMethod, ContactPair, Model};

/// Whether the pair's active set is semi-smooth: mortar with Lagrange
/// multipliers (the other Lagrange pairs keep the active-set loop around
/// the Newton loop, `crate::solve::contact_loop`).
pub fn applies(cp: &ContactPair) -> bool {
    cp.formulation == ContactFormulation::Mortar
        && matches!(cp.method, ContactMethod::Lagrange { .. })
}

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
/// 0`; introduced ones start from 0.
pub fn update<const D: usize>(
    slaves: &[usize],
    active: &mut [bool],
    multiplier: &mut [f64],
    contact: &[NodeContact<D>],
    c: impl Fn(usize) -> f64,
    threshold: f64,
) -> Switch {
    let mut switch = Switch::default();
    let mut seen = vec![false; slaves.len()];
    for nc in contact {
        let Ok(i) = slaves.binary_search(&nc.node) else {
            continue;
        };
        seen[i] = true;
        let now = is_active(active[i], multiplier[i], nc.gap, c(i), threshold);
        if now != active[i] {
            active[i] = now;
            multiplier[i] = 0.0;
            if now {
                switch.introduced.push(nc.node);
            } else {
                switch.released.push(nc.node);
            }
        }
    }
    for (i, s) in seen.iter().enumerate() {
        if !s && active[i] {
            active[i] = false;
            multiplier[i] = 0.0;
            switch.released.push(slaves[i]);
        }
    }
    switch
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
        let s = update(&slaves, &mut active, &mut lambda, &contact, |_| 10.0, 1e-12);
        assert_eq!(s.introduced, vec![7]);
        assert_eq!(s.released, vec![5, 9]);
        assert_eq!(active, [true, false, true, false]);
        assert_eq!(lambda, [2.0, 0.0, 0.0, 0.0]);
        // the next Newton step closes 7's gap with a compressive force: a
        // second pass changes nothing (a node with zero force and zero gap
        // would go: `lambda - c g = 0` is not active)
        lambda[2] = 0.5;
        let contact = [nc(3, 0.0), nc(5, 1e-3), nc(7, 0.0)];
        let s = update(&slaves, &mut active, &mut lambda, &contact, |_| 10.0, 1e-12);
        assert!(s.is_empty(), "{s:?}");
    }
}
