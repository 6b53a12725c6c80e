//! Tributary areas of slave nodes, in the **reference** configuration.
//!
//! Each slave edge `[a, b]` of length `L` contributes to its two nodes the
//! integral of their linear shape functions over the edge's area:
//! - plane strain / stress: `thickness * L / 2` to each node;
//! - axisymmetric: `2 pi L (2 r_a + r_b) / 6` to `a` (and symmetrically to
//!   `b`), the exact integral of `N_a 2 pi r` along the edge.
//!
//! The axisymmetric rule is the consistent one rather than
//! `2 pi r_a L / 2`: both sum to the exact ring area, and they agree on
//! edges at constant radius, but only the consistent rule equals the nodal
//! loads of a uniform pressure, so a uniform contact pressure `p` gives
//! exactly the uniform gap `p / k` with the area penalty (verification case
//! 7), and a node on the axis (`r = 0`) keeps a non-zero area and contact
//! stiffness.

use crate::model::{AnalysisKind, Model};
use std::f64::consts::PI;

/// Tributary area of each slave node of pair `pair`, in
/// `ContactPair::nodes` order (zero for a node on no edge).
pub fn tributary_areas(model: &Model, pair: usize) -> Vec<f64> {
    let Some(cp) = model.contacts.get(pair) else {
        return Vec::new();
    };
    edge_areas(model, &cp.edges, &cp.nodes)
}

/// Tributary area of each node of `nodes` from the edges `edges` (same
/// rules; zero for a node on no edge).
pub fn edge_areas(model: &Model, edges: &[[usize; 2]], nodes_of: &[usize]) -> Vec<f64> {
    let mut area = vec![0.0; nodes_of.len()];
    let index = |node: usize| nodes_of.iter().position(|&n| n == node);
    let sorted = nodes_of.windows(2).all(|w| w[0] < w[1]);
    let find = |node: usize| {
        if sorted {
            nodes_of.binary_search(&node).ok()
        } else {
            index(node)
        }
    };
    let nodes = &model.mesh.nodes;
    for &[a, b] in edges {
        let (Some(&pa), Some(&pb)) = (nodes.get(a), nodes.get(b)) else {
            continue;
        };
        let len = (pb[0] - pa[0]).hypot(pb[1] - pa[1]);
        let (wa, wb) = match model.analysis.kind {
            AnalysisKind::PlaneStrain | AnalysisKind::PlaneStress | AnalysisKind::Solid => {
                let w = 0.5 * len * model.analysis.thickness;
                (w, w)
            }
            AnalysisKind::Axisymmetric => {
                let (ra, rb) = (pa[0].max(0.0), pb[0].max(0.0));
                (
                    2.0 * PI * len * (2.0 * ra + rb) / 6.0,
                    2.0 * PI * len * (ra + 2.0 * rb) / 6.0,
                )
            }
        };
        if let Some(i) = find(a) {
            area[i] += wa;
        }
        if let Some(i) = find(b) {
            area[i] += wb;
        }
    }
    area
}
