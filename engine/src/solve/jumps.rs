//! Run warnings for slave nodes that moved farther than the search window
//! relative to their master in one increment (see [`crate::contact::jump`]).
//!
//! Called once per converged increment with the displacements at its start
//! and end; stateless, so a restarted run warns exactly as the original.

use crate::contact::jump::{self, Jump};
use crate::contact::segment_search::SurfaceSearch;
use crate::contact::PairState;
use crate::model::{ContactMaster, Model};

/// Warning lines (one per pair with jumps) for the increment `increment`
/// from `(u0, t0)` to `(u1, t1)` (nodal displacements and times).
pub fn increment_warnings(
    model: &Model,
    pairs: &[PairState],
    (u0, t0): (&[[f64; 2]], f64),
    (u1, t1): (&[[f64; 2]], f64),
    increment: usize,
) -> Vec<String> {
    if model.contacts.is_empty() {
        return Vec::new();
    }
    let place = |u: &[[f64; 2]]| -> Vec<[f64; 2]> {
        model
            .mesh
            .nodes
            .iter()
            .zip(u)
            .map(|(x, d)| [x[0] + d[0], x[1] + d[1]])
            .collect()
    };
    let (x0, x1) = (place(u0), place(u1));
    let mut out = Vec::new();
    for (p, cp) in model.contacts.iter().enumerate() {
        let Some(state) = pairs.get(p) else {
            continue;
        };
        let prof = state.prof;
        let jumps: Vec<Jump> = match &cp.master {
            ContactMaster::Tool(_) => match state.shape.as_ref() {
                Some(shape) => jump::tool_jumps(model, p, shape, prof, (&x0, t0), (&x1, t1)),
                None => Vec::new(),
            },
            ContactMaster::Surface { edges, .. } => {
                let mut search = SurfaceSearch::new(edges, cp.search);
                search.update(&x1, prof);
                jump::surface_jumps(&search, &cp.nodes, &x0, &x1, &mut Vec::new())
            }
        };
        if let Some(w) = jump::warning(&cp.name, increment, t1, prof, &jumps) {
            out.push(w);
        }
    }
    out
}
