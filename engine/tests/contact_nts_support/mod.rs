//! Shared models for the node-to-segment tests: two elastic blocks stacked
//! with non-matching interface meshes (contact patch test,
//! VERIFICATION-CASES.md case 3), with any strategy and method, and an
//! observer keeping the converged increments.
#![allow(dead_code)]

use ctc_engine::contact::{ContactStatus, NodeContact};
use ctc_engine::mesh::generate::{generate, Grading, MeshSpec};
use ctc_engine::mesh::{CellKind, Mesh};
use ctc_engine::model::{
    Analysis, AnalysisKind, Body, ContactMaster, ContactMethod, ContactPair, ContactStrategy,
    Dirichlet, Formulation, LagrangeFormulation, Material, MaterialLaw, Model, MultiplierUpdate,
    NewtonSettings, OutputRequest, PenaltyKind, Step, TimeFunction,
};
use ctc_engine::solve::{run, IncrementView, IterationInfo, Observer, RunSummary};

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

/// Appends `other` to `mesh` (nodes and cells renumbered), returning the
/// node offset; `other`'s sets are added with the prefix `prefix.`.
pub fn append(mesh: &mut Mesh, other: &Mesh, prefix: &str) -> usize {
    let off = mesh.nodes.len();
    mesh.nodes.extend_from_slice(&other.nodes);
    for c in &other.cells {
        let mut c = *c;
        for n in &mut c.nodes {
            *n += off;
        }
        mesh.cells.push(c);
    }
    for (k, v) in &other.node_sets {
        mesh.node_sets
            .insert(format!("{prefix}.{k}"), v.iter().map(|n| n + off).collect());
    }
    for (k, v) in &other.edge_sets {
        mesh.edge_sets.insert(
            format!("{prefix}.{k}"),
            v.iter().map(|e| [e[0] + off, e[1] + off]).collect(),
        );
    }
    off
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

fn fixed(label: &str, nodes: Vec<usize>, component: usize, value: TimeFunction) -> Dirichlet {
    Dirichlet {
        label: label.into(),
        nodes,
        component,
        value,
    }
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
    let mut mesh = Mesh::default();
    let base = block([0.0, 0.0], n_base, 2);
    let top = block([0.0, 1.0], n_top, 2);
    let off_base = append(&mut mesh, &base, "base");
    let off_top = append(&mut mesh, &top, "top");
    let slave = mesh.edge_sets["top.bottom"].clone();
    let master = mesh.edge_sets["base.top"].clone();
    let body = |name: &str, m: &Mesh, n0: usize, c0: usize| Body {
        name: name.into(),
        nodes: n0..n0 + m.nodes.len(),
        cells: c0..c0 + m.cells.len(),
        material: 0,
        formulation: Formulation::Full,
        kinematics: Default::default(),
    };
    let bodies = vec![
        body("base", &base, off_base, 0),
        body("top", &top, off_top, base.cells.len()),
    ];
    let zero = TimeFunction::Constant(0.0);
    let constraints = vec![
        fixed(
            "base bottom uy",
            mesh.node_sets["base.bottom"].clone(),
            1,
            zero.clone(),
        ),
        fixed(
            "base left ux",
            mesh.node_sets["base.left"].clone(),
            0,
            zero.clone(),
        ),
        fixed("top left ux", mesh.node_sets["top.left"].clone(), 0, zero),
        fixed(
            "top top uy",
            mesh.node_sets["top.top"].clone(),
            1,
            TimeFunction::Ramp {
                t0: 0.0,
                t1: 1.0,
                v0: 0.0,
                v1: -DEPTH,
            },
        ),
    ];
    Model {
        analysis: Analysis {
            kind: AnalysisKind::PlaneStrain,
            thickness: 1.0,
        },
        bodies,
        mesh,
        materials: vec![Material {
            name: "soft".into(),
            law: MaterialLaw::LinearElastic {
                young: E,
                poisson: 0.0,
            },
        }],
        constraints,
        loads: vec![],
        tools: vec![],
        contacts: vec![ContactPair {
            name: "top.bottom -> base.top".into(),
            body: 1,
            nodes: nodes_of(&slave),
            edges: slave,
            master: ContactMaster::Surface {
                body: 0,
                nodes: nodes_of(&master),
                edges: master,
            },
            strategy,
            search: Default::default(),
            method,
            prof: None,
            friction: None,
        }],
        steps: vec![Step {
            name: "press".into(),
            t_start: 0.0,
            t_end: 1.0,
            increments,
            min_fraction: 1.0 / 64.0,
            newton: NewtonSettings {
                tol: 1e-10,
                tol_displacement: 1e-10,
                max_iter: 30,
                line_search: true,
            },
        }],
        output: OutputRequest::default(),
        thermal: None,
    }
}

/// One converged increment.
#[derive(Debug, Clone)]
pub struct Record {
    /// Time.
    pub time: f64,
    /// Contact evaluation of pair 0.
    pub contact: Vec<NodeContact>,
    /// Reaction per node.
    pub reaction: Vec<[f64; 2]>,
    /// Displacements.
    pub u: Vec<[f64; 2]>,
    /// Newton iterations.
    pub iterations: usize,
}

impl Record {
    /// Closed contact entries.
    pub fn closed(&self) -> Vec<&NodeContact> {
        self.contact
            .iter()
            .filter(|c| c.status == ContactStatus::Closed)
            .collect()
    }

    /// Largest penetration.
    pub fn max_penetration(&self) -> f64 {
        self.contact.iter().map(|c| -c.gap).fold(0.0, f64::max)
    }

    /// Sum of all contact forces (slave and master ends): zero by the
    /// element's equilibrium.
    pub fn net_contact_force(&self) -> [f64; 2] {
        let mut f = [0.0; 2];
        for c in &self.contact {
            f[0] += c.force[0];
            f[1] += c.force[1];
            if let Some(m) = &c.master {
                for g in m.forces {
                    f[0] += g[0];
                    f[1] += g[1];
                }
            }
        }
        f
    }

    /// Total force on the slave nodes.
    pub fn slave_force(&self) -> [f64; 2] {
        self.contact
            .iter()
            .fold([0.0; 2], |a, c| [a[0] + c.force[0], a[1] + c.force[1]])
    }
}

/// Records converged increments.
#[derive(Default)]
pub struct Recorder {
    /// Converged increments.
    pub records: Vec<Record>,
}

impl Observer for Recorder {
    fn iteration(&mut self, _info: &IterationInfo) {}
    fn converged(&mut self, view: &IncrementView<'_>) -> Result<(), String> {
        self.records.push(Record {
            time: view.time,
            contact: view.contact[0].clone(),
            reaction: view.reaction.to_vec(),
            u: view.displacement.to_vec(),
            iterations: view.residuals.len(),
        });
        Ok(())
    }
    fn cutback(&mut self, _reason: &str, _new_dt: f64) {}
}

/// Runs `model`; `Err` with the solver's message on failure.
pub fn solve(model: &Model) -> Result<(RunSummary, Recorder), String> {
    let mut rec = Recorder::default();
    let summary = run(model, &mut rec).map_err(|e| e.message)?;
    Ok((summary, rec))
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
