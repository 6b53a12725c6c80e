//! The search window `prof`: the largest gap for which a contact element is
//! created (seed slides: "prof = maximum gap allowed").
//!
//! Default when the deck gives none: the largest slave edge length in the
//! reference configuration (1x). Rationale: a node farther than one element
//! from the tool cannot touch it within one Newton iteration of a
//! reasonable increment, while a node that does penetrate deeper is still
//! found through its search memory (the entity it touched last is always
//! projected, see [`crate::contact::search`]); and open nodes within one
//! element are cheap to keep (zero force) while their projections make the
//! per-node memory ready for the next increment.

use crate::model::Model;

/// Largest slave edge length of pair `pair` (reference configuration);
/// 0 when the pair has no edge.
pub fn default_prof(model: &Model, pair: usize) -> f64 {
    let Some(cp) = model.contacts.get(pair) else {
        return 0.0;
    };
    let nodes = &model.mesh.nodes;
    cp.edges
        .iter()
        .filter_map(|&[a, b]| {
            let (pa, pb) = (nodes.get(a)?, nodes.get(b)?);
            Some((pb[0] - pa[0]).hypot(pb[1] - pa[1]))
        })
        .fold(0.0, f64::max)
}

/// The window used for pair `pair`: `ContactPair::prof` when given (finite
/// and >= 0), otherwise [`default_prof`].
pub fn effective_prof(model: &Model, pair: usize) -> f64 {
    match model.contacts.get(pair).and_then(|cp| cp.prof) {
        Some(p) if p.is_finite() && p >= 0.0 => p,
        _ => default_prof(model, pair),
    }
}
