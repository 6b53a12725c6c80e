//! Two elastic blocks stacked with non-matching interface meshes (contact
//! patch test, VERIFICATION-CASES.md case 3), with any strategy and
//! method, for the node-to-segment tests.

use super::ModelBuilder;
use ctc_engine::contact::{ContactStatus, NodeContact};
use ctc_engine::mesh::generate::{generate, Grading, MeshSpec};
use ctc_engine::mesh::{CellKind, Mesh};
use ctc_engine::model::{
    ContactMethod, ContactStrategy, LagrangeFormulation, Model, MultiplierUpdate, NewtonSettings,
    PenaltyKind,
};

/// Young's modulus of both blocks.
pub const E: f64 = 2e6;
/// Top displacement (strain -0.05 in each block of height 1).
pub const DEPTH: f64 = 0.1;

/// Area-weighted penalty.
pub fn penalty(k: f64) -> ContactMethod {
    ContactMethod::Penalty {
        kind: PenaltyKind::Area,
        stiffness: k,
    }
}

/// Lagrange multipliers (single formulation, sparse LU).
pub fn lagrange() -> ContactMethod {
    ContactMethod::Lagrange {
        formulation: LagrangeFormulation::Single,
    }
}

/// Area-weighted augmented Lagrangian (Uzawa after each Newton loop).
pub fn augmented(k: f64, tolerance: f64) -> ContactMethod {
    ContactMethod::AugmentedLagrange {
        kind: PenaltyKind::Area,
        penalty: k,
        tolerance,
        update: MultiplierUpdate::Converged,
    }
}

fn block(origin: [f64; 2], nx: usize, ny: usize) -> Mesh {
    generate(&MeshSpec::Rectangle {
        origin,
        size: [1.0, 1.0],
        divisions: [nx, ny],
        grading: [Grading::Uniform, Grading::Uniform],
        kind: CellKind::Quad4,
    })
    .expect("rectangle")
}

fn nodes_of(edges: &[[usize; 2]]) -> Vec<usize> {
    let mut n: Vec<usize> = edges.iter().flat_map(|e| [e[0], e[1]]).collect();
    n.sort_unstable();
    n.dedup();
    n
}

/// The contact patch test: base [0,1]x[0,1] (`n_base` quads across), top
/// [0,1]x[1,2] (`n_top` across), E = 2e6, nu = 0, base bottom uy = 0,
/// both left edges ux = 0, top edge displaced by -0.1; slave = top block's
/// bottom, master = base block's top.
pub fn patch(
    method: ContactMethod,
    strategy: ContactStrategy,
    n_base: usize,
    n_top: usize,
    increments: usize,
) -> Model {
    let b = ModelBuilder::plane_strain()
        .elastic("soft", E, 0.0)
        .body("base", block([0.0, 0.0], n_base, 2), "soft")
        .body("top", block([0.0, 1.0], n_top, 2), "soft");
    let slave = b.edge_set("top.bottom");
    let master = b.edge_set("base.top");
    let (base_bottom, base_left) = (b.node_set("base.bottom"), b.node_set("base.left"));
    let (top_left, top_top) = (b.node_set("top.left"), b.node_set("top.top"));
    b.fix(base_bottom, 1)
        .fix(base_left, 0)
        .fix(top_left, 0)
        .displace(top_top, 1, super::ramp(0.0, 1.0, -DEPTH))
        .contact_surface(
            "top.bottom -> base.top",
            ("top", slave),
            ("base", master),
            method,
        )
        .strategy(strategy)
        .step("press", 1.0, increments)
        .min_fraction(1.0 / 64.0)
        .newton(NewtonSettings {
            tol: 1e-10,
            tol_displacement: 1e-10,
            max_iter: 30,
            line_search: true,
            predictor: true,
            stabilize: None,
        })
        .build()
}

/// Pressure statistics over the closed nodes: (mean, max |p - mean| / mean,
/// max |p - exact| / exact).
pub fn pressure_deviation(contact: &[NodeContact], exact: f64) -> (f64, f64, f64) {
    let p: Vec<f64> = contact
        .iter()
        .filter(|c| c.status == ContactStatus::Closed)
        .map(|c| c.pressure)
        .collect();
    if p.is_empty() {
        return (0.0, f64::INFINITY, f64::INFINITY);
    }
    let mean = p.iter().sum::<f64>() / p.len() as f64;
    let dev = p.iter().map(|x| (x - mean).abs()).fold(0.0, f64::max) / mean;
    let err = p.iter().map(|x| (x - exact).abs()).fold(0.0, f64::max) / exact;
    (mean, dev, err)
}

/// Nodal traction on the surface `edges` (plane strain, unit thickness):
/// the total normal (y) contact force each node receives, as slave and as
/// master end of other nodes' elements, divided by its tributary length.
/// A uniform pressure `p` gives `p` at every node (consistent nodal
/// forces of linear edges).
pub fn nodal_traction(model: &Model, contact: &[NodeContact], edges: &[[usize; 2]]) -> Vec<f64> {
    let nodes = nodes_of(edges);
    let mut force = vec![0.0; nodes.len()];
    let mut length = vec![0.0; nodes.len()];
    for &[a, b] in edges {
        let (pa, pb) = (model.mesh.nodes[a], model.mesh.nodes[b]);
        let l = (pb[0] - pa[0]).hypot(pb[1] - pa[1]);
        for n in [a, b] {
            length[nodes.binary_search(&n).unwrap()] += 0.5 * l;
        }
    }
    let mut add = |n: usize, f: [f64; 2]| {
        if let Ok(i) = nodes.binary_search(&n) {
            force[i] += f[1];
        }
    };
    for c in contact {
        add(c.node, c.force);
        if let Some(m) = &c.master {
            add(m.nodes[0], m.forces[0]);
            add(m.nodes[1], m.forces[1]);
        }
    }
    force
        .iter()
        .zip(&length)
        .map(|(f, l)| f.abs() / l)
        .collect()
}

/// (mean, max |t - mean| / mean) of nodal tractions.
pub fn deviation(t: &[f64]) -> (f64, f64) {
    let mean = t.iter().sum::<f64>() / t.len() as f64;
    let dev = t.iter().map(|x| (x - mean).abs()).fold(0.0, f64::max) / mean;
    (mean, dev)
}
