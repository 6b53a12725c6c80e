//! Shared helpers of the `core_*` integration tests: hand-built meshes,
//! one-body models and an observer that records everything.
#![allow(dead_code)]

use ctc_engine::mesh::{Cell, Mesh};
use ctc_engine::model::*;
use ctc_engine::solve::{IncrementView, IterationInfo, Observer};

/// Deterministic xorshift generator (tests must not depend on a seed source).
pub struct Rng(pub u64);

impl Rng {
    /// Uniform in [0, 1).
    pub fn next_f64(&mut self) -> f64 {
        let mut x = self.0;
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        self.0 = x;
        (x >> 11) as f64 / (1u64 << 53) as f64
    }
    /// Uniform in [-1, 1).
    pub fn sym(&mut self) -> f64 {
        2.0 * self.next_f64() - 1.0
    }
}

/// Node number of grid point (i, j) of an `nx` x `ny` cell grid.
pub fn grid_node(nx: usize, i: usize, j: usize) -> usize {
    j * (nx + 1) + i
}

/// A structured `nx` x `ny` grid of `[x0, x0 + w] x [y0, y0 + h]`; interior
/// nodes moved randomly by up to `jitter` times the cell size in each
/// direction; quads, or each quad split in two triangles (alternating
/// diagonals) when `tri`.
pub fn grid(
    nx: usize,
    ny: usize,
    origin: [f64; 2],
    size: [f64; 2],
    jitter: f64,
    seed: u64,
    tri: bool,
) -> Mesh {
    let mut rng = Rng(seed);
    let (hx, hy) = (size[0] / nx as f64, size[1] / ny as f64);
    let mut nodes = Vec::new();
    for j in 0..=ny {
        for i in 0..=nx {
            let mut p = [origin[0] + i as f64 * hx, origin[1] + j as f64 * hy];
            if i > 0 && i < nx && j > 0 && j < ny {
                p[0] += jitter * hx * rng.sym();
                p[1] += jitter * hy * rng.sym();
            }
            nodes.push(p);
        }
    }
    let mut cells = Vec::new();
    for j in 0..ny {
        for i in 0..nx {
            let a = grid_node(nx, i, j);
            let b = grid_node(nx, i + 1, j);
            let c = grid_node(nx, i + 1, j + 1);
            let d = grid_node(nx, i, j + 1);
            if !tri {
                cells.push(Cell::quad(a, b, c, d));
            } else if (i + j) % 2 == 0 {
                cells.push(Cell::tri(a, b, c));
                cells.push(Cell::tri(a, c, d));
            } else {
                cells.push(Cell::tri(a, b, d));
                cells.push(Cell::tri(b, c, d));
            }
        }
    }
    Mesh {
        nodes,
        cells,
        ..Default::default()
    }
}

/// Nodes on the boundary of an `nx` x `ny` grid.
pub fn grid_boundary(nx: usize, ny: usize) -> Vec<usize> {
    let mut out = Vec::new();
    for j in 0..=ny {
        for i in 0..=nx {
            if i == 0 || j == 0 || i == nx || j == ny {
                out.push(grid_node(nx, i, j));
            }
        }
    }
    out
}

/// One step `0 .. 1` with `increments` and default Newton settings.
pub fn step(increments: usize) -> Step {
    Step {
        name: "load".into(),
        t_start: 0.0,
        t_end: 1.0,
        increments,
        min_fraction: 1.0 / 1024.0,
        newton: NewtonSettings {
            tol: 1e-10,
            tol_displacement: 1e-10,
            ..NewtonSettings::default()
        },
    }
}

/// A model with one body made of all of `mesh`, no loads, no constraints,
/// one step of one increment.
pub fn one_body(
    kind: AnalysisKind,
    mesh: Mesh,
    young: f64,
    poisson: f64,
    formulation: Formulation,
) -> Model {
    let (nn, nc) = (mesh.nodes.len(), mesh.cells.len());
    Model {
        analysis: Analysis {
            kind,
            thickness: 1.0,
        },
        mesh,
        bodies: vec![Body {
            name: "body".into(),
            nodes: 0..nn,
            cells: 0..nc,
            material: 0,
            formulation,
            kinematics: Default::default(),
        }],
        materials: vec![Material {
            name: "mat".into(),
            law: MaterialLaw::LinearElastic { young, poisson },
        }],
        constraints: vec![],
        loads: vec![],
        tools: vec![],
        contacts: vec![],
        steps: vec![step(1)],
        output: OutputRequest::default(),
        thermal: None,
    }
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

/// A converged increment as seen by the observer.
#[derive(Debug, Clone)]
pub struct Snapshot {
    pub step: usize,
    pub increment: usize,
    pub time: f64,
    pub displacement: Vec<[f64; 2]>,
    pub reaction: Vec<[f64; 2]>,
    pub residuals: Vec<f64>,
    /// Total force of each contact pair's tool on the body.
    pub contact_force: Vec<[f64; 2]>,
}

/// Records every callback.
#[derive(Debug, Default)]
pub struct Recorder {
    pub increments: Vec<Snapshot>,
    pub iterations: Vec<IterationInfo>,
    pub cutbacks: Vec<(String, f64)>,
}

impl Observer for Recorder {
    fn iteration(&mut self, info: &IterationInfo) {
        self.iterations.push(info.clone());
    }
    fn converged(&mut self, v: &IncrementView<'_>) -> Result<(), String> {
        self.increments.push(Snapshot {
            step: v.step,
            increment: v.increment,
            time: v.time,
            displacement: v.displacement.to_vec(),
            reaction: v.reaction.to_vec(),
            residuals: v.residuals.to_vec(),
            contact_force: v
                .contact
                .iter()
                .map(|l| {
                    l.iter()
                        .fold([0.0, 0.0], |a, c| [a[0] + c.force[0], a[1] + c.force[1]])
                })
                .collect(),
        });
        Ok(())
    }
    fn cutback(&mut self, reason: &str, new_dt: f64) {
        self.cutbacks.push((reason.to_string(), new_dt));
    }
}
