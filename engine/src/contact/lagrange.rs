//! Lagrange-multiplier enforcement of the normal contact constraint (seed
//! slides, "Part II – Lagrange multipliers"): on the active set the
//! constraint `g(x) = 0` is enforced exactly by a multiplier `lambda` (the
//! normal force, `lambda >= 0` in compression); nodes off the active set
//! carry no force. The active set is found by the solver's active-set loop
//! (`crate::solve::contact_loop`).
//!
//! Force on an active node `f = lambda n`; its tangent
//! `K_c = -d f / d x = -lambda h t ⊗ t` (the curvature term: the penalty
//! geometric term with `alpha g` replaced by `-lambda`), so that Newton
//! stays quadratic on curved tools. The constraint rows of the
//! saddle-point system use `d g / d x = n` ([`normal_rows`], in node terms;
//! node-to-segment: `d g / d x` over the slave and the segment's ends;
//! quadratic slave faces: the node's weighted gap over the nodes of its
//! faces, [`super::face_integrated::FacetPair::evaluate_lagrange`];
//! mortar: the full derivative of the nodal gap, with the force `B / A` as
//! a separate column, [`push_coupling`]).

use super::augmented::normal_response;
use super::penalty::Response;
use super::rows::{NodeRows, NodeTerm, RowKind};
use super::{ContactStatus, NodeContact, PairState};
use crate::model::{ContactMethod, Model};

/// Response of a slave node with multiplier `lambda`, in the active set or
/// not, unit normal `normal`, normal rate `normal_rate`, tributary area
/// `tributary`. An active node is reported closed even if `lambda` is
/// momentarily negative during the iterations (the active-set loop then
/// releases it).
pub fn respond(
    active: bool,
    lambda: f64,
    tributary: f64,
    normal: [f64; 2],
    normal_rate: f64,
) -> Response {
    if !active {
        return Response {
            force: [0.0; 2],
            stiffness: [[0.0; 2]; 2],
            pressure: 0.0,
            status: ContactStatus::Open,
        };
    }
    normal_response(0.0, lambda, tributary, normal, normal_rate)
}

/// Appends the constraint row `d g / d x` of every active node of every
/// Lagrange pair (evaluation `contact`, one list per pair) to `rows`.
pub fn normal_rows(
    model: &Model,
    pairs: &[PairState],
    contact: &[Vec<NodeContact>],
    rows: &mut NodeRows,
) {
    for (pi, cp) in model.contacts.iter().enumerate() {
        if !matches!(cp.method, ContactMethod::Lagrange { .. }) {
            continue;
        }
        for nc in &contact[pi] {
            let Some(i) = pairs[pi].slave_index(nc.node) else {
                continue;
            };
            if !pairs[pi].active.get(i).copied().unwrap_or(false)
                || pairs[pi].redundant.get(i).copied().unwrap_or(false)
            {
                continue;
            }
            let dim = nc.normal.len();
            // quadratic faces: the node's weighted gap over its faces' nodes
            if let Some(fp) = &pairs[pi].facets {
                if let Some(row) = fp.row(nc.node) {
                    rows.push(RowKind::Normal, (pi, i), row.gap, row.terms.iter().copied());
                }
                continue;
            }
            // smoothed node-to-segment: the row over the coupling's nodes
            if let Some(rows_of_pair) = &pairs[pi].couplings {
                if let Ok(k) = rows_of_pair.binary_search_by_key(&nc.node, |c| c.slave) {
                    push_coupling(rows, (pi, i), nc.gap, &rows_of_pair[k], dim);
                }
                continue;
            }
            match &nc.master {
                // against a rigid tool: the slave alone, d g / d x = n
                None => rows.push(
                    RowKind::Normal,
                    (pi, i),
                    nc.gap,
                    nc.normal
                        .iter()
                        .enumerate()
                        .map(|(component, &coefficient)| NodeTerm {
                            node: nc.node,
                            component,
                            coefficient,
                        }),
                ),
                // node-to-segment: slave and master ends
                Some(ms) => {
                    let nodes = [nc.node, ms.nodes[0], ms.nodes[1]];
                    rows.push(
                        RowKind::Normal,
                        (pi, i),
                        nc.gap,
                        (0..nodes.len() * dim).map(|k| NodeTerm {
                            node: nodes[k / dim],
                            component: k % dim,
                            coefficient: ms.gap_gradient[k],
                        }),
                    );
                }
            }
        }
    }
}

/// Appends the constraint row of a coupling (`gap_gradient`; mortar: its
/// `force_direction` as the saddle point's column).
pub fn push_coupling(
    rows: &mut NodeRows,
    owner: (usize, usize),
    gap: f64,
    c: &super::mortar::Coupling,
    dim: usize,
) {
    let terms = |v: &'_ [f64]| {
        let nodes = &c.nodes;
        (0..v.len())
            .map(move |k| NodeTerm {
                node: nodes[k / dim],
                component: k % dim,
                coefficient: v[k],
            })
            .collect::<Vec<_>>()
    };
    rows.push_split(
        RowKind::Normal,
        owner,
        c.slave,
        gap,
        terms(&c.gap_gradient),
        terms(&c.force_direction),
    );
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn active_node_carries_lambda_along_the_normal() {
        let r = respond(true, 3.0, 1.5, [0.6, 0.8], 0.0);
        assert_eq!(r.status, ContactStatus::Closed);
        assert!((r.force[0] - 1.8).abs() < 1e-15 && (r.force[1] - 2.4).abs() < 1e-15);
        assert_eq!(r.pressure, 2.0);
        assert_eq!(r.stiffness, [[0.0; 2]; 2]);
        let o = respond(false, 3.0, 1.5, [0.6, 0.8], 0.0);
        assert_eq!((o.status, o.force), (ContactStatus::Open, [0.0; 2]));
    }

    #[test]
    fn curvature_term_is_minus_lambda_h_tt() {
        // normal (0, 1), tangent (1, 0): K = -lambda h e_x ⊗ e_x
        let r = respond(true, 2.0, 1.0, [0.0, 1.0], 0.5);
        assert_eq!(r.stiffness, [[-1.0, 0.0], [0.0, 0.0]]);
    }
}
