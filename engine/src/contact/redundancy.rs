//! Redundant Lagrange constraints of the modified double pass and of self
//! contact (seed slides, "Three usual strategies": the modified double
//! step "may be over-constrained").
//!
//! When both surfaces are slave at once, a node `a` of one side that lies
//! on (or next to) a node `b` of the other side gives a row `d g_a / d x`
//! over `a` and the facet holding `b`, and `b` a row over `b` and the
//! facet holding `a`: with `a` and `b` coincident the two rows are the same
//! constraint (up to sign), and the saddle-point system is singular (its
//! LU yields a non-finite correction); nearly coincident, the pair of
//! multipliers is ill-determined (only their sum is) and the active set
//! chatters. Such a row is **redundant**: it is dropped from the saddle
//! point (no multiplier, no force), while its node stays in the active set
//! and its gap is held by the rows it depends on.
//!
//! The test is local and deterministic: the active rows of a pair are taken
//! in slave order; a row is redundant when its distance to the span of the
//! rows already kept that share a node with it is below [`REDUNDANT`] of
//! its own norm (a modified Gram-Schmidt over those few neighbours).
//! Globally dependent chains (every row independent of its neighbours) are
//! not redundant in this sense; they are over-constrained but regular.

use super::rows::NodeTerm;
use std::collections::BTreeMap;

/// Relative distance of a row to the span of its kept neighbours below
/// which it is redundant. Two coincident nodes of a flat interface give
/// 1e-16; on a curved interface the facets' normals differ by the angle
/// `h / R` between them, and the rows are that far apart: below 1e-3
/// (normals within 0.06 degrees) the pair of multipliers is ill-determined
/// to 1e3 times the force and the dropped row's gap is at most 1e-3 of the
/// nodes' separation.
pub const REDUNDANT: f64 = 1e-3;

/// Which rows of `rows` (terms of each active row, in slave order) are
/// redundant with respect to the rows before them that are kept.
pub fn redundant_rows(rows: &[&[NodeTerm]]) -> Vec<bool> {
    let mut out = vec![false; rows.len()];
    // node -> rows kept so far that touch it
    let mut by_node: BTreeMap<usize, Vec<usize>> = BTreeMap::new();
    let mut neighbours = Vec::new();
    for (r, terms) in rows.iter().enumerate() {
        neighbours.clear();
        for t in terms.iter() {
            if let Some(k) = by_node.get(&t.node) {
                neighbours.extend_from_slice(k);
            }
        }
        neighbours.sort_unstable();
        neighbours.dedup();
        if !neighbours.is_empty() && in_span(terms, neighbours.iter().map(|&k| rows[k])) {
            out[r] = true;
            continue;
        }
        let mut nodes: Vec<usize> = terms.iter().map(|t| t.node).collect();
        nodes.sort_unstable();
        nodes.dedup();
        for n in nodes {
            by_node.entry(n).or_default().push(r);
        }
    }
    out
}

/// The row of a node over `nodes` (`dim` components each, node-major) from
/// its gradient `grad`, restricted to the free coordinates (`free(node,
/// component)`).
pub fn free_row(
    nodes: &[usize],
    grad: &[f64],
    dim: usize,
    free: &dyn Fn(usize, usize) -> bool,
) -> Vec<NodeTerm> {
    (0..grad.len())
        .map(|k| NodeTerm {
            node: nodes[k / dim],
            component: k % dim,
            coefficient: grad[k],
        })
        .filter(|t| free(t.node, t.component))
        .collect()
}

/// [`redundant_rows`] of pair `pair` (its name for the `CTC_LOG=debug`
/// count of the rows dropped).
pub fn redundant_rows_of(pair: &str, rows: &[Vec<NodeTerm>]) -> Vec<bool> {
    let views: Vec<&[NodeTerm]> = rows.iter().map(Vec::as_slice).collect();
    let drop = redundant_rows(&views);
    if super::log::debug_enabled() {
        let n = drop.iter().filter(|&&d| d).count();
        eprintln!(
            "[ctc contact] pair '{pair}': {n} redundant Lagrange rows dropped of {}",
            drop.len()
        );
    }
    drop
}

/// Whether `row` lies within [`REDUNDANT`] (relative) of the span of
/// `basis`.
fn in_span<'a>(row: &[NodeTerm], basis: impl Iterator<Item = &'a [NodeTerm]>) -> bool {
    let basis: Vec<&[NodeTerm]> = basis.collect();
    // the coordinates (node, component) the rows touch
    let mut keys: Vec<(usize, usize)> = row
        .iter()
        .chain(basis.iter().flat_map(|b| b.iter()))
        .map(|t| (t.node, t.component))
        .collect();
    keys.sort_unstable();
    keys.dedup();
    let dense = |terms: &[NodeTerm]| {
        let mut v = vec![0.0; keys.len()];
        for t in terms {
            if let Ok(k) = keys.binary_search(&(t.node, t.component)) {
                v[k] += t.coefficient;
            }
        }
        v
    };
    let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>();
    let mut r = dense(row);
    let norm = dot(&r, &r).sqrt();
    if norm == 0.0 {
        return true;
    }
    let mut q: Vec<Vec<f64>> = Vec::with_capacity(basis.len());
    for b in basis {
        let mut v = dense(b);
        let n0 = dot(&v, &v).sqrt();
        for e in &q {
            let c = dot(&v, e);
            v.iter_mut().zip(e).for_each(|(x, y)| *x -= c * y);
        }
        let n = dot(&v, &v).sqrt();
        // a basis row dependent on the earlier ones adds no direction
        if n > 1e-12 * n0 {
            v.iter_mut().for_each(|x| *x /= n);
            q.push(v);
        }
    }
    for e in &q {
        let c = dot(&r, e);
        r.iter_mut().zip(e).for_each(|(x, y)| *x -= c * y);
    }
    dot(&r, &r).sqrt() <= REDUNDANT * norm
}

#[cfg(test)]
mod tests {
    use super::*;

    fn row(terms: &[(usize, usize, f64)]) -> Vec<NodeTerm> {
        terms
            .iter()
            .map(|&(node, component, coefficient)| NodeTerm {
                node,
                component,
                coefficient,
            })
            .collect()
    }

    /// Two coincident nodes 1 (lower side, facet 3-4 above) and 3 (upper
    /// side, facet 1-2 below) of a flat matching interface: each row is
    /// the other's negative at the vertex; the second is redundant, a
    /// third row elsewhere is not.
    #[test]
    fn coincident_nodes_of_a_flat_interface_give_one_row() {
        let a = row(&[(1, 1, -1.0), (3, 1, 1.0), (4, 1, 0.0)]);
        let b = row(&[(3, 1, -1.0), (1, 1, 1.0), (2, 1, 0.0)]);
        let c = row(&[(5, 1, -1.0), (4, 1, 0.5), (6, 1, 0.5)]);
        assert_eq!(redundant_rows(&[&a, &b, &c]), vec![false, true, false]);
    }

    /// Nodes apart (each at mid-facet of the other side): independent.
    #[test]
    fn a_node_at_mid_facet_is_not_redundant() {
        let a = row(&[(1, 1, -1.0), (3, 1, 0.5), (4, 1, 0.5)]);
        let b = row(&[(3, 1, -1.0), (1, 1, 0.5), (2, 1, 0.5)]);
        assert_eq!(redundant_rows(&[&a, &b]), vec![false, false]);
    }

    /// Coincident nodes of a curved interface: the facets' normals differ
    /// by an angle `theta`; the rows are `theta` apart, redundant below
    /// [`REDUNDANT`], kept above.
    #[test]
    fn the_angle_between_the_normals_decides() {
        for (theta, expect) in [(1e-4, true), (1e-2, false)] {
            let (s, c) = f64::sin_cos(theta);
            let a = row(&[(1, 0, 0.0), (1, 1, -1.0), (3, 0, 0.0), (3, 1, 1.0)]);
            let b = row(&[(3, 0, s), (3, 1, -c), (1, 0, -s), (1, 1, c)]);
            assert_eq!(
                redundant_rows(&[&a, &b]),
                vec![false, expect],
                "theta {theta}"
            );
        }
    }

    /// A row that is the sum of two kept neighbours is redundant (the span,
    /// not only a single parallel row).
    #[test]
    fn a_combination_of_kept_rows_is_redundant() {
        let a = row(&[(1, 1, 1.0), (2, 1, -1.0)]);
        let b = row(&[(2, 1, 1.0), (3, 1, -1.0)]);
        let c = row(&[(1, 1, 1.0), (3, 1, -1.0)]);
        assert_eq!(redundant_rows(&[&a, &b, &c]), vec![false, false, true]);
    }
}
