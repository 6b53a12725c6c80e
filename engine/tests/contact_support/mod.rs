//! Shared builders for the contact integration tests: hand-made models with
//! a row of slave nodes and one rigid tool.
#![allow(dead_code)]

use ctc_engine::contact::{evaluate_pair, NodeContact, PairState};
use ctc_engine::mesh::Mesh;
use ctc_engine::model::{
    Analysis, AnalysisKind, Body, ContactMethod, ContactPair, Formulation, Material, MaterialLaw,
    Model, OutputRequest, PenaltyKind, RigidTool, ToolGeometry, ToolMotion,
};

/// A model whose single body is the slave surface `nodes` joined by edges
/// `edges` (no cells: enough for contact kernels), against one tool.
/// (One argument per `Model` ingredient the tests vary.)
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
    let mut slave: Vec<usize> = edges.iter().flat_map(|e| [e[0], e[1]]).collect();
    slave.sort_unstable();
    slave.dedup();
    let n = nodes.len();
    Model {
        analysis: Analysis {
            kind: analysis,
            thickness,
        },
        mesh: Mesh {
            nodes,
            ..Mesh::default()
        },
        bodies: vec![Body {
            name: "body".into(),
            nodes: 0..n,
            cells: 0..0,
            material: 0,
            formulation: Formulation::Full,
            kinematics: Default::default(),
        }],
        materials: vec![Material {
            name: "m".into(),
            law: MaterialLaw::LinearElastic {
                young: 1.0,
                poisson: 0.3,
            },
        }],
        constraints: vec![],
        loads: vec![],
        tools: vec![RigidTool {
            name: "tool".into(),
            geometry,
            motion,
        }],
        contacts: vec![ContactPair {
            name: "body.surface -> tool".into(),
            body: 0,
            edges,
            nodes: slave,
            master: ctc_engine::model::ContactMaster::Tool(0),
            strategy: Default::default(),
            search: Default::default(),
            method,
            prof,
            friction: None,
        }],
        steps: vec![],
        output: OutputRequest::default(),
        thermal: None,
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
