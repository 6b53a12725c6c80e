//! `ctc check --explain`: the line describing a contact pair whose master
//! is a deformable surface (node-to-segment contact).

use ctc_engine::model::{
    ContactFormulation, ContactMaster, ContactPair, ContactStrategy, LocalSearch, Model,
};

/// One line about a deformable master (strategy, search, self contact);
/// `None` for a rigid tool.
pub fn describe(model: &Model, c: &ContactPair) -> Option<String> {
    let ContactMaster::Surface {
        body, edges, nodes, ..
    } = &c.master
    else {
        return None;
    };
    let body = model.bodies.get(*body).map_or("?", |b| b.name.as_str());
    let search = match c.search {
        LocalSearch::Memory => "candidates: last segment and its neighbours, then the bucket grid",
        LocalSearch::Circle => {
            "candidates: segments whose circle (centre mid-segment) holds the node"
        }
    };
    if edges == &c.edges {
        return Some(format!(
            "self contact (node-to-segment) on body `{body}`: each node against the surface's \
             segments except its own and the adjacent ones; {search}"
        ));
    }
    if c.formulation == ContactFormulation::Mortar {
        return Some(format!(
            "deformable master: {} segments and {} nodes of body `{body}`, mortar \
             segment-to-segment (slave segments cut against the projected master segments, \
             weighted gap per slave node decides contact, gives force and pressure; \
             unsymmetric tangent: LU)",
            edges.len(),
            nodes.len()
        ));
    }
    let strategy = match c.strategy {
        ContactStrategy::SinglePass => {
            "single pass (slave nodes against master segments; the master may penetrate the slave)"
        }
        ContactStrategy::DoublePass => {
            "double pass (master and slave swapped at every converged increment)"
        }
        ContactStrategy::ModifiedDoublePass => {
            "modified double pass (each surface master and slave at once, half tributary areas; \
             may over-constrain with Lagrange multipliers)"
        }
    };
    let normal = match c.smoothing {
        ctc_engine::model::NormalSmoothing::None => {
            "faceted master normal (a kink's vertex is a circle of radius 0)"
        }
        ctc_engine::model::NormalSmoothing::Nodal => {
            "nodal normal smoothing (unit mean nodal normals interpolated along each segment, \
             continuous across the master nodes; the element reaches the neighbouring \
             segments' far nodes; unsymmetric tangent: LU)"
        }
        ctc_engine::model::NormalSmoothing::Nagata => {
            "Nagata patches (quadratic facets through the nodes and their area-weighted nodal \
             normals; the element reaches the facets around the patch's nodes)"
        }
    };
    Some(format!(
        "deformable master: {} segments and {} nodes of body `{body}`, node-to-segment \
         elements (slave, m1, m2); {strategy}; {normal}; {search}",
        edges.len(),
        nodes.len()
    ))
}
