//! A model whose single body is a row of slave nodes (no cells: enough for
//! the contact kernels) against one rigid tool.

use super::ModelBuilder;
use ctc_engine::contact::{evaluate_pair, NodeContact, PairState};
use ctc_engine::mesh::Mesh;
use ctc_engine::model::{
    AnalysisKind, ContactMethod, Model, PenaltyKind, ToolGeometry, ToolMotion,
};

/// The slave surface `nodes` joined by `edges` against one tool.
/// (One argument per model ingredient the tests vary.)
#[allow(clippy::too_many_arguments)]
pub fn surface_model(
    analysis: AnalysisKind,
    thickness: f64,
    nodes: Vec<[f64; 2]>,
    edges: Vec<[usize; 2]>,
    geometry: ToolGeometry,
    motion: ToolMotion,
    method: ContactMethod,
    prof: Option<f64>,
) -> Model {
    let b = ModelBuilder::new(analysis)
        .thickness(thickness)
        .elastic("m", 1.0, 0.3)
        .body("body", Mesh::new(nodes, vec![]), "m")
        .tool("tool", geometry, motion)
        .contact_tool("body.surface -> tool", "body", edges, "tool", method);
    match prof {
        Some(p) => b.prof(p).build(),
        None => b.build(),
    }
}

/// Nodal penalty of stiffness `k`.
pub fn nodal(k: f64) -> ContactMethod {
    ContactMethod::Penalty {
        kind: PenaltyKind::Nodal,
        stiffness: k,
    }
}

/// Area penalty of stiffness `k` (pressure per unit gap).
pub fn area(k: f64) -> ContactMethod {
    ContactMethod::Penalty {
        kind: PenaltyKind::Area,
        stiffness: k,
    }
}

/// A one-node probe: slave edge from node 0 (the probe) to a far node 1.
pub fn probe_model(geometry: ToolGeometry, motion: ToolMotion, prof: f64) -> Model {
    surface_model(
        AnalysisKind::PlaneStrain,
        1.0,
        vec![[0.0, 0.0], [1e6, 1e6]],
        vec![[0, 1]],
        geometry,
        motion,
        nodal(1.0e3),
        Some(prof),
    )
}

/// Evaluates the probe model with node 0 at `x` at time `t`; the entry of
/// node 0 if any.
pub fn probe(model: &Model, x: [f64; 2], t: f64) -> Option<NodeContact> {
    let mut state = PairState::new(model, 0);
    let coords = [x, [1e6, 1e6]];
    evaluate_pair(model, 0, &coords, t, &mut state)
        .into_iter()
        .find(|c| c.node == 0)
}

/// Central finite-difference tangent `-d force / d x` at `x` and the
/// relative error `max |K_fd - K| / max |K|` of the analytical block.
pub fn tangent_error(model: &Model, x: [f64; 2], t: f64, h: f64) -> Option<f64> {
    let c = probe(model, x, t)?;
    let mut kfd = [[0.0; 2]; 2];
    for j in 0..2 {
        let mut xp = x;
        let mut xm = x;
        xp[j] += h;
        xm[j] -= h;
        let fp = probe(model, xp, t)?.force;
        let fm = probe(model, xm, t)?.force;
        for i in 0..2 {
            kfd[i][j] = -(fp[i] - fm[i]) / (2.0 * h);
        }
    }
    let scale = c
        .stiffness
        .iter()
        .flatten()
        .fold(0.0f64, |m, v| m.max(v.abs()));
    let err = (0..2)
        .flat_map(|i| (0..2).map(move |j| (i, j)))
        .map(|(i, j)| (kfd[i][j] - c.stiffness[i][j]).abs())
        .fold(0.0f64, f64::max);
    Some(err / scale)
}
