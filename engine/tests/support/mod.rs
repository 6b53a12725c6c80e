//! Shared scenes of the engine's integration tests, all built with the
//! engine's test kit (`ctc_engine::testkit`):
//! - here: one-body models, Newton settings, constraints;
//! - [`contact`]: a row of slave nodes against one rigid tool (kernels);
//! - [`lagrange`]: a rigid cylinder on a block, the Hertz half disc;
//! - [`nts`]: two stacked blocks for the node-to-segment patch test
//!   (the friction block lives in `ctc_verification::programs::friction_block`).
#![allow(dead_code, unused_imports)]

pub mod contact;
pub mod lagrange;
pub mod nts;

pub use ctc_engine::testkit::grid::{grid, grid_boundary, grid_node};
pub use ctc_engine::testkit::{ramp, solve, Increment, ModelBuilder, Recorder, Rng};

use ctc_engine::mesh::Mesh;
use ctc_engine::model::*;

/// Newton settings of the tests: tolerances 1e-10, defaults otherwise.
pub fn tight() -> NewtonSettings {
    NewtonSettings {
        tol: 1e-10,
        tol_displacement: 1e-10,
        ..NewtonSettings::default()
    }
}

/// One step `0 .. 1` with `increments` and [`tight`] Newton settings.
pub fn step(increments: usize) -> Step {
    Step {
        name: "load".into(),
        t_start: 0.0,
        t_end: 1.0,
        increments,
        min_fraction: 1.0 / 1024.0,
        newton: tight(),
        dynamic: None,
    }
}

/// A model with one linear elastic body made of all of `mesh`, no loads,
/// no constraints, one step of one increment.
pub fn one_body(
    kind: AnalysisKind,
    mesh: Mesh,
    young: f64,
    poisson: f64,
    formulation: Formulation,
) -> Model {
    ModelBuilder::new(kind)
        .elastic("mat", young, poisson)
        .body("body", mesh, "mat")
        .formulation(formulation)
        .step("load", 1.0, 1)
        .newton(tight())
        .build()
}

/// `component` of `nodes` fixed to a constant value.
pub fn fix(nodes: Vec<usize>, component: usize, value: f64) -> Dirichlet {
    Dirichlet {
        label: format!("fix {component}"),
        nodes,
        component,
        value: TimeFunction::Constant(value),
    }
}
