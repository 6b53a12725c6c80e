//! Flat rigid punch with sharp (convex) corners, described as a polyline,
//! pressed into an elastic plane-strain block through the full solver:
//! the corner (radius-0 circle) treatment must let Newton converge, the
//! contact force must balance the support reaction and the pressure must
//! show the edge concentration of a flat punch (larger at the edges than
//! at the centre, Sadowsky/Boussinesq: p(x) = P / (pi sqrt(b^2 - x^2))).

use ctc_engine::contact::{pair_total_force, ContactStatus, NodeContact};
use ctc_engine::mesh::{Cell, Mesh};
use ctc_engine::model::{ContactMethod, PenaltyKind, ToolGeometry, ToolMotion};
use ctc_engine::solve::{run, IncrementView, Observer};
use ctc_engine::testkit::{ramp, ModelBuilder};

#[derive(Default)]
struct Last {
    contact: Vec<NodeContact>,
    reaction_y: f64,
    residuals: Vec<Vec<f64>>,
}

impl Observer for Last {
    fn converged(&mut self, view: &IncrementView<'_>) -> Result<(), String> {
        self.contact = view.contact[0].clone();
        self.reaction_y = view.reaction.iter().map(|r| r[1]).sum();
        self.residuals.push(view.residuals.to_vec());
        Ok(())
    }
}

#[test]
fn contact_punch_smoke_flat_polyline_punch_with_corners() {
    // Block [-3, 3] x [-3, 0], uniform 48 x 24 quads (h = 0.125); the punch
    // half-width 1 falls on nodes.
    let (nx, ny) = (48, 24);
    let mut nodes = Vec::new();
    for j in 0..=ny {
        for i in 0..=nx {
            nodes.push([
                -3.0 + 6.0 * i as f64 / nx as f64,
                -3.0 + 3.0 * j as f64 / ny as f64,
            ]);
        }
    }
    let id = |i: usize, j: usize| j * (nx + 1) + i;
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
    let mesh = Mesh::new(nodes, cells);
    let nc = mesh.cells.len();
    let top: Vec<[usize; 2]> = mesh
        .boundary_edges(0..nc)
        .into_iter()
        .filter(|e| mesh.nodes[e[0]][1] == 0.0 && mesh.nodes[e[1]][1] == 0.0)
        .collect();
    let bottom: Vec<usize> = (0..=nx).collect();
    let model = ModelBuilder::plane_strain()
        .elastic("m", 1000.0, 0.3)
        .body("block", mesh, "m")
        .fix(bottom.clone(), 0)
        .fix(bottom, 1)
        .tool(
            "punch",
            // Down the right side, left along the face, up the left side:
            // free side (left of the walk) is outside the punch.
            ToolGeometry::Polyline {
                points: vec![[1.0, 1.0], [1.0, 0.0], [-1.0, 0.0], [-1.0, 1.0]],
            },
            ToolMotion {
                uy: ramp(0.0, 1.0, -0.01),
                ..ToolMotion::fixed()
            },
        )
        .contact_tool(
            "block.top -> punch",
            "block",
            top,
            "punch",
            ContactMethod::Penalty {
                kind: PenaltyKind::Area,
                stiffness: 1e6,
            },
        )
        .step("press", 1.0, 2)
        .min_fraction(1.0 / 64.0)
        .tol(1e-9)
        .build();
    let mut last = Last::default();
    let summary = run(&model, &mut last).unwrap_or_else(|e| panic!("{}", e.message));
    for (k, r) in last.residuals.iter().enumerate() {
        let s: Vec<String> = r.iter().map(|v| format!("{v:.2e}")).collect();
        println!("increment {}: residuals [{}]", k + 1, s.join(", "));
    }
    assert!(summary.completed);
    assert!(summary.increments.iter().all(|i| i.iterations <= 10));
    let f = pair_total_force(&last.contact);
    let err = (f[1] + last.reaction_y).abs() / f[1].abs();
    println!(
        "punch force {:.6e}, reaction {:.6e}, difference {err:.1e}",
        -f[1], last.reaction_y
    );
    assert!(f[1] < 0.0 && err < 1e-6);
    let mut p: Vec<(f64, f64)> = last
        .contact
        .iter()
        .filter(|c| c.status == ContactStatus::Closed)
        .map(|c| (model.mesh.nodes[c.node][0], c.pressure))
        .collect();
    p.sort_by(|a, b| a.0.total_cmp(&b.0));
    let centre = p.iter().find(|q| q.0.abs() < 1e-12).unwrap().1;
    let edge = p
        .iter()
        .filter(|q| q.0.abs() > 0.8)
        .map(|q| q.1)
        .fold(0.0, f64::max);
    let width = p.iter().map(|q| q.0.abs()).fold(0.0, f64::max);
    println!(
        "pressure: centre {centre:.4e}, max near the edges {edge:.4e}, contact half-width {width}"
    );
    assert!(
        edge > 1.5 * centre,
        "no edge concentration: {edge} vs {centre}"
    );
    assert!(
        (width - 1.0).abs() < 1e-9,
        "contact must end at the punch corners: {width}"
    );
}
