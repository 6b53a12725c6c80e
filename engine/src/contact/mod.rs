//! Contact between deformable bodies and rigid analytical tools.
//!
//! The solver calls [`evaluate_pair`] at every Newton iteration with the
//! current nodal coordinates; each active slave node returns its gap, the
//! force the tool exerts on it and the consistent 2x2 tangent block.
//! The same gap function is used to decide contact, to compute forces and to
//! post-process pressure.

use crate::model::Model;

/// Contact status of a slave node.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum ContactStatus {
    /// Within `prof` of the tool but with a positive gap.
    Open,
    /// Negative gap: a contact force acts.
    Closed,
}

/// Evaluation of one slave node against the pair's tool.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NodeContact {
    /// Global node number.
    pub node: usize,
    /// Signed normal gap (negative = penetration).
    pub gap: f64,
    /// Unit outward normal of the tool at the projection (points to free space).
    pub normal: [f64; 2],
    /// Force exerted by the tool on the node (total, axisymmetric: over 2*pi).
    pub force: [f64; 2],
    /// Tangent block `K_c = -d force / d x` (add to the global stiffness).
    pub stiffness: [[f64; 2]; 2],
    /// Contact pressure: normal force magnitude / tributary area (>= 0).
    pub pressure: f64,
    /// Open or closed.
    pub status: ContactStatus,
    /// Index of the tool entity (segment, span) the node projects on.
    pub entity: usize,
}

/// Persistent per-pair state kept by the solver between iterations
/// (search history, tributary areas).
#[derive(Debug, Clone, Default)]
pub struct PairState {
    /// Tributary area of each slave node (`ContactPair::nodes` order).
    pub tributary: Vec<f64>,
}

impl PairState {
    /// Prepares the state of pair `pair` of `model` (reference configuration).
    pub fn new(model: &Model, pair: usize) -> Self {
        let _ = (model, pair);
        PairState::default()
    }

    /// Called when an increment has converged: commits history variables.
    pub fn commit(&mut self) {}

    /// Called when an increment is cut back: restores the committed state.
    pub fn rollback(&mut self) {}
}

/// Evaluates pair `pair` at time `t` for current coordinates `x` (all nodes).
/// Returns one entry per slave node within `prof` of the tool.
pub fn evaluate_pair(
    model: &Model,
    pair: usize,
    x: &[[f64; 2]],
    t: f64,
    state: &mut PairState,
) -> Vec<NodeContact> {
    let _ = (model, pair, x, t, state);
    Vec::new()
}
