//! Smoke test of contact inside the full solver (VERIFICATION-CASES case 1,
//! coarse): a rigid cylinder pushed into an elastic plane-strain block
//! meshed by hand. Checks that Newton converges quadratically (the residual
//! sequence is printed), that the total contact force equals minus the
//! support reaction, and that the pressure profile is roughly Hertzian
//! (a = sqrt(4 P R / (pi E*)), p0 = 2 P / (pi a), p = p0 sqrt(1 - x^2/a^2)).

use ctc_engine::contact::{pair_total_force, ContactStatus, NodeContact};
use ctc_engine::mesh::{Cell, Mesh};
use ctc_engine::model::{ContactMethod, Model, PenaltyKind, ToolGeometry, ToolMotion, ToolSide};
use ctc_engine::solve::{run, IncrementView, IterationInfo, Observer};
use ctc_engine::testkit::{ramp, ModelBuilder};
use std::f64::consts::PI;

const E: f64 = 1000.0;
const NU: f64 = 0.3;
const R: f64 = 10.0;

/// Block [-4, 4] x [-4, 0], refined towards (0, 0).
fn block(nx: usize, ny: usize) -> Mesh {
    let mut nodes = Vec::new();
    for j in 0..=ny {
        let s = 1.0 - j as f64 / ny as f64; // 1 at the bottom, 0 at the top
        let y = -4.0 * (0.25 * s + 0.75 * s * s);
        for i in 0..=nx {
            let r = -1.0 + 2.0 * i as f64 / nx as f64;
            let x = 4.0 * (0.25 * r + 0.75 * r * r * r);
            nodes.push([x, y]);
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
    Mesh::new(nodes, cells)
}

fn model(nx: usize, ny: usize, depth: f64, increments: usize) -> Model {
    let mesh = block(nx, ny);
    let ncells = mesh.cells.len();
    let top: Vec<[usize; 2]> = mesh
        .boundary_edges(0..ncells)
        .into_iter()
        .filter(|e| mesh.nodes[e[0]][1] == 0.0 && mesh.nodes[e[1]][1] == 0.0)
        .collect();
    let bottom: Vec<usize> = (0..=nx).collect();
    let h_min = mesh.nodes[nx / 2 + 1][0] - mesh.nodes[nx / 2][0];
    ModelBuilder::plane_strain()
        .elastic("soft", E, NU)
        .body("block", mesh, "soft")
        .fix(bottom.clone(), 0)
        .fix(bottom, 1)
        .tool(
            "roller",
            ToolGeometry::Circle {
                center: [0.0, R],
                radius: R,
                side: ToolSide::Outside,
            },
            ToolMotion {
                uy: ramp(0.0, 1.0, -depth),
                ..ToolMotion::fixed()
            },
        )
        .contact_tool(
            "block.top -> roller",
            "block",
            top,
            "roller",
            ContactMethod::Penalty {
                kind: PenaltyKind::Area,
                // k_n = 100 E / h: penalty gap ~ 1% of the element size
                // at p ~ E.
                stiffness: 100.0 * E / h_min,
            },
        )
        .step("press", 1.0, increments)
        .min_fraction(1.0 / 64.0)
        .tol(1e-9)
        .build()
}

#[derive(Default)]
struct Record {
    iterations: Vec<IterationInfo>,
    last_contact: Vec<NodeContact>,
    last_reaction_y: f64,
    last_x: Vec<[f64; 2]>,
    residual_sequences: Vec<Vec<f64>>,
}

impl Observer for Record {
    fn iteration(&mut self, info: &IterationInfo) {
        self.iterations.push(info.clone());
    }
    fn converged(&mut self, view: &IncrementView<'_>) -> Result<(), String> {
        self.last_contact = view.contact[0].clone();
        self.last_reaction_y = view.reaction.iter().map(|r| r[1]).sum();
        self.last_x = view
            .model
            .mesh
            .nodes
            .iter()
            .zip(view.displacement)
            .map(|(x, u)| [x[0] + u[0], x[1] + u[1]])
            .collect();
        self.residual_sequences.push(view.residuals.to_vec());
        Ok(())
    }
}

#[test]
fn contact_hertz_smoke_rigid_cylinder_on_block() {
    let m = model(60, 24, 0.02, 4);
    let mut rec = Record::default();
    let summary = match run(&m, &mut rec) {
        Ok(s) => s,
        Err(e) => panic!("run failed: {}", e.message),
    };
    assert!(summary.completed);
    for (k, seq) in rec.residual_sequences.iter().enumerate() {
        let s: Vec<String> = seq.iter().map(|r| format!("{r:.2e}")).collect();
        println!("increment {}: residuals [{}]", k + 1, s.join(", "));
    }
    // Quadratic convergence: in the asymptotic phase (relative residual
    // below 0.1) each residual is at most ~ the square of the previous one
    // (constant 1e3 allowed), down to the round-off floor (~1e-10 here).
    let mut checked = 0;
    for seq in &rec.residual_sequences {
        assert!(seq.len() <= 6, "too many iterations: {seq:?}");
        for w in seq.windows(2) {
            let (prev, next) = (w[0], w[1]);
            if prev < 0.1 && next > 1e-9 {
                checked += 1;
                assert!(
                    next <= 1e3 * prev * prev,
                    "not quadratic: {prev:e} -> {next:e} in {seq:?}"
                );
            }
        }
    }
    assert!(
        checked >= 4,
        "only {checked} iteration pairs in the asymptotic phase"
    );
    // Equilibrium of the block: contact force + support reaction = 0.
    let f = pair_total_force(&rec.last_contact);
    let p_total = -f[1];
    let err = (f[1] + rec.last_reaction_y).abs() / p_total;
    println!(
        "contact force {p_total:.6e}, support reaction {:.6e}, relative difference {err:.2e}",
        rec.last_reaction_y
    );
    assert!(p_total > 0.0);
    assert!(err < 1e-6, "{err:e}");
    assert!(f[0].abs() < 1e-8 * p_total, "symmetric: fx = {}", f[0]);
    // Hertz: compare a and p0 with the measured load.
    let e_star = E / (1.0 - NU * NU);
    let a = (4.0 * p_total * R / (PI * e_star)).sqrt();
    let p0 = 2.0 * p_total / (PI * a);
    let mut profile: Vec<(f64, f64)> = rec
        .last_contact
        .iter()
        .filter(|c| c.status == ContactStatus::Closed)
        .map(|c| (rec.last_x[c.node][0], c.pressure))
        .collect();
    profile.sort_by(|p, q| p.0.total_cmp(&q.0));
    let a_fe = profile.iter().map(|p| p.0.abs()).fold(0.0f64, f64::max);
    let p_max = profile.iter().map(|p| p.1).fold(0.0f64, f64::max);
    println!(
        "Hertz: P = {p_total:.4e}, a = {a:.4} (a/R = {:.3}), p0 = {p0:.4e}; FE: outermost closed node |x| = {a_fe:.4}, max pressure {p_max:.4e} ({:+.1}%)",
        a / R,
        100.0 * (p_max / p0 - 1.0)
    );
    let mut worst = 0.0f64;
    for (x, p) in &profile {
        let exact = if x.abs() < a {
            p0 * (1.0 - x * x / (a * a)).sqrt()
        } else {
            0.0
        };
        println!("  x = {x:+.4}  p = {p:.4e}  hertz = {exact:.4e}");
        if x.abs() < 0.8 * a {
            worst = worst.max((p - exact).abs() / p0);
        }
    }
    println!(
        "worst pressure deviation inside 0.8 a: {:.1}% of p0",
        100.0 * worst
    );
    assert!(a / R <= 0.1, "a/R = {}", a / R);
    assert!((p_max / p0 - 1.0).abs() < 0.1, "p_max {p_max} vs p0 {p0}");
    assert!((a_fe / a - 1.0).abs() < 0.2, "a_fe {a_fe} vs a {a}");
    assert!(worst < 0.1, "profile deviation {worst}");
}

/// The same roller described as a full circle, as a clockwise arc and as a
/// rational quadratic NURBS arc (exact circle) gives the same solution to
/// the Newton tolerance: the three geometries share gap, normal and
/// curvature.
#[test]
fn contact_hertz_smoke_circle_arc_nurbs_agree() {
    let (t0, t1) = (290f64.to_radians(), 250f64.to_radians());
    let half = 0.5 * (t0 - t1);
    let c = [0.0, R];
    let at = |th: f64, r: f64| [c[0] + r * th.cos(), c[1] + r * th.sin()];
    let geometries = [
        ToolGeometry::Circle {
            center: c,
            radius: R,
            side: ToolSide::Outside,
        },
        ToolGeometry::Arc {
            center: c,
            radius: R,
            start_angle: t0,
            end_angle: t1,
        },
        ToolGeometry::Nurbs {
            degree: 2,
            control_points: vec![at(t0, R), at(0.5 * (t0 + t1), R / half.cos()), at(t1, R)],
            weights: vec![1.0, half.cos(), 1.0],
            knots: vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
        },
    ];
    let mut results = Vec::new();
    for g in geometries {
        let mut m = model(40, 16, 0.02, 2);
        m.tools[0].geometry = g;
        let mut rec = Record::default();
        let summary = run(&m, &mut rec).unwrap_or_else(|e| panic!("{}", e.message));
        let iters: Vec<usize> = summary.increments.iter().map(|i| i.iterations).collect();
        let f = pair_total_force(&rec.last_contact);
        let mut p: Vec<(usize, f64)> = rec
            .last_contact
            .iter()
            .map(|c| (c.node, c.pressure))
            .filter(|c| c.1 > 0.0)
            .collect();
        p.sort_by_key(|c| c.0);
        println!("force {:.10e}, Newton iterations {iters:?}", -f[1]);
        results.push((f, p));
    }
    let (f0, p0) = &results[0];
    for (f, p) in &results[1..] {
        assert!(
            (f[1] - f0[1]).abs() <= 1e-7 * f0[1].abs(),
            "{f:?} vs {f0:?}"
        );
        assert_eq!(p.len(), p0.len());
        for (a, b) in p.iter().zip(p0) {
            assert_eq!(a.0, b.0);
            assert!((a.1 - b.1).abs() <= 1e-6 * b.1, "{a:?} vs {b:?}");
        }
    }
}
