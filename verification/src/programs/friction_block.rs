//! An elastic block (plane strain, quad4) resting on a rigid plane
//! inclined at `alpha`, loaded by its weight, then pushed horizontally:
//! the scene of the friction cases ([`super::friction`]: inclined plane,
//! stick/slip, tangential penalty, first impact).
//!
//! ```text
//!          weight (or squeeze)
//!        +-----------+
//!  push->|   block   |  1 x 0.5, E = 1e5
//!        +-----------+
//!   ////// plane inclined at alpha //////
//! ```

use ctc_engine::contact::friction::{pair_dissipation, FrictionStatus};
use ctc_engine::contact::NodeContact;
use ctc_engine::mesh::{Cell, CellKind, Mesh};
use ctc_engine::model::{
    ContactMethod, Dirichlet, FirstImpact, Friction, Load, Model, NewtonSettings, PenaltyKind,
    TimeFunction, ToolGeometry, ToolMotion,
};
use ctc_engine::solve::{run, RunSummary};
use ctc_engine::testkit::{ramp, ModelBuilder, Recorder};

/// How the block is driven in the second step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Drive {
    /// Horizontal displacement `d` of the block's left side above the
    /// contact (uy free).
    LeftSide(f64),
    /// Horizontal displacement `d` of every node (rigid translation in x,
    /// uy free): every bottom node starts slipping at once.
    AllNodes(f64),
    /// Horizontal displacement `d` of every node above the base (the
    /// contact nodes are free: a uniform shear of the first element row).
    AboveBase(f64),
    /// Horizontal force `q` (total) on the contact nodes, as a uniform
    /// traction (end nodes take half).
    Force(f64),
}

/// The block problem.
#[derive(Debug, Clone)]
pub struct Block {
    /// Inclination of the plane (radians).
    pub alpha: f64,
    /// Friction coefficient.
    pub mu: f64,
    /// Normal method.
    pub method: ContactMethod,
    /// Tangential penalty (None: alpha_N / 10).
    pub friction_stiffness: Option<f64>,
    /// Elements along the slope and across the thickness.
    pub divisions: [usize; 2],
    /// Weight (total, on the top nodes as a uniform traction, vertical).
    pub weight: f64,
    /// Second step.
    pub drive: Drive,
    /// Increments of the second step.
    pub increments: usize,
    /// Normal load by displacement instead of the weight: the top nodes
    /// go down by `squeeze` (step 1), then follow the slope (step 2, with a
    /// displacement drive `d`: up by `d tan(alpha)`).
    pub squeeze: Option<f64>,
    /// Poisson's ratio of the block (E = 1e5).
    pub poisson: f64,
    /// Cell kind: quad4, or quad8 / quad9 (the grid elevated: the slave
    /// edges become 3-node edges, friction face-integrated; loads and
    /// drives stay on the corner nodes).
    pub cell: CellKind,
}

impl Block {
    /// A 1 x 0.5 block of weight 100, area penalty 1e7, 4 x 2 elements.
    pub fn new(alpha: f64, mu: f64, drive: Drive) -> Self {
        Block {
            alpha,
            mu,
            method: ContactMethod::Penalty {
                kind: PenaltyKind::Area,
                stiffness: 1e7,
            },
            friction_stiffness: None,
            divisions: [4, 2],
            weight: 100.0,
            drive,
            increments: 4,
            squeeze: None,
            poisson: 0.3,
            cell: CellKind::Quad4,
        }
    }

    /// The model.
    pub fn model(&self) -> Model {
        let (w, h) = (1.0, 0.5);
        let [nx, ny] = self.divisions;
        let (c, s) = (self.alpha.cos(), self.alpha.sin());
        let id = |i: usize, j: usize| j * (nx + 1) + i;
        let mut nodes = Vec::new();
        for j in 0..=ny {
            for i in 0..=nx {
                let (x, y) = (w * i as f64 / nx as f64, h * j as f64 / ny as f64);
                nodes.push([c * x - s * y, s * x + c * y]);
            }
        }
        let mut cells = Vec::new();
        for j in 0..ny {
            for i in 0..nx {
                cells.push(Cell::quad(
                    id(i, j),
                    id(i + 1, j),
                    id(i + 1, j + 1),
                    id(i, j + 1),
                ));
            }
        }
        let nn = nodes.len();
        let bottom_edges: Vec<[usize; 2]> = (0..nx).map(|i| [id(i, 0), id(i + 1, 0)]).collect();
        let top: Vec<usize> = (0..=nx).map(|i| id(i, ny)).collect();
        // the bottom-left node is a contact node: a prescribed ux there would
        // fight the stick constraint (over-constrained with multipliers)
        let left: Vec<usize> = (1..=ny).map(|j| id(0, j)).collect();
        let all: Vec<usize> = (0..nn).collect();
        let mut mesh = Mesh::new(nodes, cells);
        if self.cell != CellKind::Quad4 {
            mesh = ctc_engine::mesh::elevate::elevate(&mesh, self.cell)
                .expect("a quad4 grid elevates to quad8 / quad9");
        }
        let mut b = ModelBuilder::plane_strain()
            .elastic("m", 1e5, self.poisson)
            .body("block", mesh, "m");
        match self.squeeze {
            None => {
                // consistent with a uniform pressure: end nodes take half
                for (k, nodes) in [(0.5, vec![top[0], top[nx]]), (1.0, top[1..nx].to_vec())] {
                    b = b.load(Load::NodalForce {
                        label: "weight".into(),
                        nodes,
                        component: 1,
                        value: ramp(0.0, 1.0, -k * self.weight / nx as f64),
                    });
                }
            }
            Some(delta) => {
                let d = match self.drive {
                    Drive::LeftSide(d) | Drive::AllNodes(d) | Drive::AboveBase(d) => d,
                    Drive::Force(_) => 0.0,
                };
                b = b.constraint(Dirichlet {
                    label: "squeeze".into(),
                    nodes: top.clone(),
                    component: 1,
                    value: TimeFunction::Table(vec![
                        (0.0, 0.0),
                        (1.0, -delta),
                        (2.0, -delta + d * self.alpha.tan()),
                    ]),
                });
            }
        }
        b = match self.drive {
            Drive::LeftSide(d) => b.displace(left, 0, ramp(1.0, 2.0, d)),
            Drive::AllNodes(d) => b.displace(all, 0, ramp(1.0, 2.0, d)),
            Drive::AboveBase(d) => {
                b.displace((nx + 1..nn).collect::<Vec<_>>(), 0, ramp(1.0, 2.0, d))
            }
            Drive::Force(q) => {
                // a uniform shear traction on the base: no tipping moment
                let bottom: Vec<usize> = (0..=nx).map(|i| id(i, 0)).collect();
                for (k, nodes) in [
                    (0.5, vec![bottom[0], bottom[nx]]),
                    (1.0, bottom[1..nx].to_vec()),
                ] {
                    b = b.load(Load::NodalForce {
                        label: "pull".into(),
                        nodes,
                        component: 0,
                        value: ramp(1.0, 2.0, k * q / nx as f64),
                    });
                }
                b
            }
        };
        // the plane overlaps the block by 1e-6 at t = 0 so that contact is
        // closed from the first iteration on (the block has no other support)
        let n = [-s, c];
        let newton = NewtonSettings {
            tol: 1e-10,
            tol_displacement: 1e-10,
            max_iter: 30,
            line_search: true,
            predictor: true,
            stabilize: None,
        };
        b.tool(
            "plane",
            ToolGeometry::Plane {
                point: [1e-6 * n[0], 1e-6 * n[1]],
                normal: n,
            },
            ToolMotion::fixed(),
        )
        .contact_tool(
            "block.bottom -> plane",
            "block",
            bottom_edges,
            "plane",
            self.method.clone(),
        )
        .prof(0.1)
        .friction(Friction {
            mu: self.mu,
            stiffness: self.friction_stiffness,
            first_impact: FirstImpact::Intersect,
            cut_at_impact: false,
        })
        .step("weight", 1.0, 1)
        .min_fraction(1.0 / 64.0)
        .newton(newton)
        .step("push", 2.0, self.increments)
        .min_fraction(1.0 / 64.0)
        .newton(newton)
        .build()
    }
}

/// One converged increment.
#[derive(Debug, Clone)]
pub struct Row {
    /// Time.
    pub time: f64,
    /// Sum of the x reactions (the horizontal push of a displacement drive).
    pub push: f64,
    /// Sum of the y reactions (the vertical load of a squeeze).
    pub lift: f64,
    /// Contact nodes (force, friction, ...).
    pub contact: Vec<NodeContact>,
    /// Frictional work of the increment.
    pub dissipation: f64,
    /// Mean x displacement of the contact nodes.
    pub bottom_ux: f64,
    /// Newton iterations and residuals.
    pub residuals: Vec<f64>,
}

/// The converged increments of a run of the block.
#[derive(Default)]
pub struct Rows {
    /// Rows.
    pub rows: Vec<Row>,
}

impl Rows {
    fn of(rec: &Recorder) -> Self {
        let rows = rec
            .increments
            .iter()
            .map(|v| {
                let [push, lift] = v.total_reaction();
                let contact = v.contact[0].clone();
                let bottom_ux = contact
                    .iter()
                    .map(|c| v.displacement[c.node][0])
                    .sum::<f64>()
                    / contact.len().max(1) as f64;
                Row {
                    time: v.time,
                    push,
                    lift,
                    dissipation: pair_dissipation(&contact),
                    contact,
                    bottom_ux,
                    residuals: v.residuals.clone(),
                }
            })
            .collect();
        Rows { rows }
    }
}

/// Runs `block`; the recorded increments and the summary, or the error.
pub fn solve(block: &Block) -> Result<(Rows, RunSummary), String> {
    let model = block.model();
    let mut rec = Recorder::default();
    let summary = run(&model, &mut rec).map_err(|e| e.message)?;
    Ok((Rows::of(&rec), summary))
}

/// Number of contact nodes in `status`.
pub fn count(contact: &[NodeContact], status: FrictionStatus) -> usize {
    contact
        .iter()
        .filter(|c| c.friction.status == status)
        .count()
}
