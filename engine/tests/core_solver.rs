//! Solver tests: hand solutions of one-element problems, Newton on linear
//! problems (exactly one iteration per increment), cutback exhaustion with
//! a diagnosis, rigid-body modes caught before solving, reaction balance.

mod support;

use ctc_engine::mesh::{Cell, Mesh};
use ctc_engine::model::*;
use ctc_engine::solve::run;
use support::*;

fn force(nodes: Vec<usize>, component: usize, value: TimeFunction) -> Load {
    Load::NodalForce {
        label: format!("force {component}"),
        nodes,
        component,
        value,
    }
}

fn unit_square(cells: Vec<Cell>) -> Mesh {
    Mesh::new(vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]], cells)
}

/// Plane stress square, E = 100, nu = 0.25, t = 0.5, pulled by 1 + 1 at
/// x = 1: sigma = 2 / 0.5 = 4, eps_x = 0.04, eps_y = -0.01 (exact for both
/// the bilinear quad and two triangles: the field is linear).
fn uniaxial(cells: Vec<Cell>) {
    let mut m = one_body(
        AnalysisKind::PlaneStress,
        unit_square(cells),
        100.0,
        0.25,
        Formulation::Full,
    );
    m.analysis.thickness = 0.5;
    m.constraints = vec![fix(vec![0, 3], 0, 0.0), fix(vec![0, 1], 1, 0.0)];
    m.loads = vec![force(vec![1, 2], 0, TimeFunction::Constant(1.0))];
    let mut rec = Recorder::default();
    let s = run(&m, &mut rec).unwrap();
    assert!(s.completed);
    assert_eq!(s.free_dofs, 4);
    let u = &rec.increments[0].displacement;
    let expect = [[0.0, 0.0], [0.04, 0.0], [0.04, -0.01], [0.0, -0.01]];
    for (a, b) in u.iter().zip(expect) {
        assert!(
            (a[0] - b[0]).abs() < 1e-14 && (a[1] - b[1]).abs() < 1e-14,
            "{u:?}"
        );
    }
    let r = &rec.increments[0].reaction;
    assert!(
        (r[0][0] + 1.0).abs() < 1e-13 && (r[3][0] + 1.0).abs() < 1e-13,
        "{r:?}"
    );
    assert!(r[0][1].abs() < 1e-13 && r[1][1].abs() < 1e-13, "{r:?}");
    assert_eq!(r[2], [0.0, 0.0]);
}

#[test]
fn one_quad4_uniaxial_tension_matches_hand_solution() {
    uniaxial(vec![Cell::quad(0, 1, 2, 3)]);
}

#[test]
fn two_tri3_uniaxial_tension_matches_hand_solution() {
    uniaxial(vec![Cell::tri(0, 1, 2), Cell::tri(0, 2, 3)]);
}

#[test]
fn one_tri3_hand_stiffness_solution() {
    // Triangle (0,0) (1,0) (0,1), E = 1, nu = 0, t = 1, plane stress; node 0
    // fixed, node 2 fixed in x. Free dofs (u1x, u1y, u2y): by hand
    // K = A B^T D B = diag(0.5, 0.25, 0.5); f = (1, 0.5, 1) -> u = (2, 2, 2).
    let mesh = Mesh::new(
        vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]],
        vec![Cell::tri(0, 1, 2)],
    );
    let mut m = one_body(AnalysisKind::PlaneStress, mesh, 1.0, 0.0, Formulation::Full);
    m.constraints = vec![fix(vec![0, 2], 0, 0.0), fix(vec![0], 1, 0.0)];
    m.loads = vec![
        force(vec![1], 0, TimeFunction::Constant(1.0)),
        force(vec![1], 1, TimeFunction::Constant(0.5)),
        force(vec![2], 1, TimeFunction::Constant(1.0)),
    ];
    let mut rec = Recorder::default();
    run(&m, &mut rec).unwrap();
    let u = &rec.increments[0].displacement;
    assert!(
        (u[1][0] - 2.0).abs() < 1e-13 && (u[1][1] - 2.0).abs() < 1e-13,
        "{u:?}"
    );
    assert!((u[2][1] - 2.0).abs() < 1e-13, "{u:?}");
    // reactions balance the applied loads
    let r = &rec.increments[0].reaction;
    let sum = r.iter().fold([0.0, 0.0], |a, x| [a[0] + x[0], a[1] + x[1]]);
    assert!(
        (sum[0] + 1.0).abs() < 1e-13 && (sum[1] + 1.5).abs() < 1e-13,
        "{sum:?}"
    );
    // by hand: reaction = f_int - f_ext = K_{0x,1x} u1x + K_{0x,1y} u1y
    //                    = -0.5 * 2 - 0.25 * 2 = -1.5
    assert!((r[0][0] + 1.5).abs() < 1e-13, "{r:?}");
}

/// A distorted 6 x 4 quad plate, clamped on the left, pulled and sheared on
/// the right by ramped nodal forces and a ramped prescribed displacement.
fn plate(increments: usize) -> Model {
    let (nx, ny) = (6, 4);
    let mesh = grid(nx, ny, [0.0, 0.0], [3.0, 2.0], 0.25, 7, false);
    let mut m = one_body(
        AnalysisKind::PlaneStrain,
        mesh,
        1000.0,
        0.3,
        Formulation::Full,
    );
    let left: Vec<usize> = (0..=ny).map(|j| grid_node(nx, 0, j)).collect();
    let right: Vec<usize> = (0..=ny).map(|j| grid_node(nx, nx, j)).collect();
    m.constraints = vec![
        fix(left.clone(), 0, 0.0),
        fix(left, 1, 0.0),
        Dirichlet {
            label: "pull".into(),
            nodes: vec![right[0]],
            component: 0,
            value: TimeFunction::Ramp {
                t0: 0.0,
                t1: 1.0,
                v0: 0.0,
                v1: 0.01,
            },
        },
    ];
    m.loads = vec![force(
        right[1..].to_vec(),
        1,
        TimeFunction::Ramp {
            t0: 0.0,
            t1: 1.0,
            v0: 0.0,
            v1: -2.0,
        },
    )];
    m.steps = vec![step(increments)];
    m
}

#[test]
fn newton_linear_problem_takes_one_iteration_per_increment() {
    let m = plate(4);
    let mut rec = Recorder::default();
    let s = run(&m, &mut rec).unwrap();
    assert_eq!(s.increments.len(), 4);
    assert_eq!(s.newton_iterations, 4, "{:?}", s.increments);
    assert_eq!(s.linear_solver, "cholesky");
    for inc in &s.increments {
        assert_eq!(inc.iterations, 1);
        assert_eq!(inc.residuals.len(), 1);
        assert!(inc.residuals[0] < 1e-12, "{:?}", inc.residuals);
        assert_eq!(inc.cutbacks, 0);
    }
    assert_eq!(rec.iterations.len(), 4);
    assert!(rec.iterations.iter().all(|i| i.step_length == 1.0));
    // linearity: the state at t = 0.5 is half the final one
    let (half, end) = (&rec.increments[1], &rec.increments[3]);
    assert_eq!(half.time, 0.5);
    assert_eq!(end.time, 1.0);
    let umax = end
        .displacement
        .iter()
        .fold(0.0f64, |a, u| a.max(u[0].abs()).max(u[1].abs()));
    for (a, b) in half.displacement.iter().zip(&end.displacement) {
        for k in 0..2 {
            assert!((2.0 * a[k] - b[k]).abs() < 1e-10 * umax);
        }
    }
    // one increment or four: the same final state
    let mut one = Recorder::default();
    run(&plate(1), &mut one).unwrap();
    for (a, b) in one.increments[0].displacement.iter().zip(&end.displacement) {
        for k in 0..2 {
            assert!((a[k] - b[k]).abs() < 1e-10 * umax);
        }
    }
    // global equilibrium: reactions balance the applied forces (4 x -2 in y)
    let r = end
        .reaction
        .iter()
        .fold([0.0, 0.0], |a, x| [a[0] + x[0], a[1] + x[1]]);
    assert!(r[0].abs() < 1e-9 && (r[1] - 8.0).abs() < 1e-9, "{r:?}");
    println!(
        "plate {} free dofs, {} nonzeros: timings {:?}",
        s.free_dofs, s.matrix_nonzeros, s.timings
    );
}

#[test]
fn cutbacks_exhausted_reports_step_time_residuals_and_remedy() {
    let mut m = plate(2);
    m.steps[0].name = "press".into();
    // one iteration, whose next correction (round-off, 1e-16) must be
    // below 1e-30: never converges
    m.steps[0].newton.tol_displacement = 1e-30;
    m.steps[0].newton.max_iter = 1;
    m.steps[0].min_fraction = 0.25;
    let mut rec = Recorder::default();
    let e = run(&m, &mut rec).unwrap_err();
    println!("{}", e.message);
    assert!(e.message.contains("step `press`"), "{}", e.message);
    assert!(e.message.contains("t = 0"), "{}", e.message);
    assert!(e.message.contains("max_iter = 1"), "{}", e.message);
    assert!(e.message.contains("remedy"), "{}", e.message);
    assert!(e.message.contains("1.250e-1"), "{}", e.message); // smallest dt: 0.5 * 0.25
    assert!(!e.summary.completed);
    assert_eq!(e.summary.failure.as_deref(), Some(e.message.as_str()));
    // dt 0.5 -> 0.25 -> 0.125 (= min), then 0.0625 < min: two cutbacks
    assert_eq!(e.summary.cutbacks, 2);
    assert_eq!(rec.cutbacks.len(), 2);
    assert_eq!(rec.cutbacks[0].1, 0.25);
    assert_eq!(rec.cutbacks[1].1, 0.125);
    assert!(rec.increments.is_empty());
    assert_eq!(e.summary.newton_iterations, 3);
    assert_eq!(e.summary.cutback_log.len(), 2);
    assert_eq!(e.summary.cutback_log[1].to, 0.25);
}

/// Issue 14, item 6: a tolerance below what round-off allows (tol =
/// tol_displacement = 1e-30) used to stall until the increment was cut back
/// to the minimum; the residual reaches its round-off floor (4 eps |K| |u|)
/// and the increment converges there, flagged in the summary.
#[test]
fn tolerance_below_round_off_converges_on_the_floor() {
    let mut m = plate(2);
    m.steps[0].newton.tol = 1e-30;
    m.steps[0].newton.tol_displacement = 1e-30;
    let s = run(&m, &mut Recorder::default()).unwrap();
    assert_eq!(s.cutbacks, 0);
    for inc in &s.increments {
        assert!(inc.at_floor, "{inc:?}");
        assert!(
            inc.residual_floor > 0.0 && inc.residual_floor < 1e-12,
            "{inc:?}"
        );
        assert!(*inc.residuals.last().unwrap() > 1e-30, "{inc:?}");
    }
}

#[test]
fn unconstrained_rotation_is_reported_before_solving() {
    let mut m = plate(1);
    m.constraints = vec![fix(vec![0], 0, 0.0), fix(vec![0], 1, 0.0)];
    let e = run(&m, &mut Recorder::default()).unwrap_err();
    assert!(e.message.contains("free to rotate"), "{}", e.message);
    assert_eq!(e.summary.newton_iterations, 0);
}

#[test]
fn inverted_cell_is_reported_with_its_number() {
    let mut m = plate(1);
    // clockwise: nodes 1 and 3 swapped
    m.mesh.cells.nodes_mut(5).swap(1, 3);
    let e = run(&m, &mut Recorder::default()).unwrap_err();
    assert!(
        e.message.contains("cell 5") && e.message.contains("counter-clockwise"),
        "{}",
        e.message
    );
}

#[test]
fn multi_step_loads_follow_time_functions() {
    // step 1 ramps the force to -2 (t = 0..1), step 2 holds it (t = 1..2):
    // the second step's increments converge at once with the same state
    let mut m = plate(2);
    m.constraints.truncate(2);
    m.steps = vec![step(2), {
        let mut s = step(3);
        s.name = "hold".into();
        s.t_start = 1.0;
        s.t_end = 2.0;
        s
    }];
    let mut rec = Recorder::default();
    let s = run(&m, &mut rec).unwrap();
    assert_eq!(s.increments.len(), 5);
    assert_eq!(s.increments[4].step, "hold");
    assert_eq!(rec.increments[4].time, 2.0);
    let (a, b) = (
        &rec.increments[1].displacement,
        &rec.increments[4].displacement,
    );
    for (x, y) in a.iter().zip(b) {
        assert!((x[0] - y[0]).abs() < 1e-15 && (x[1] - y[1]).abs() < 1e-15);
    }
}

/// Timing of an ~80k-dof plate (200 x 200 quads), 6 increments: run with
/// `cargo test -p ctc-engine --test core_solver -- --ignored --nocapture`.
#[test]
#[ignore]
fn perf_plate_80k_dofs() {
    let n = 200;
    let mesh = grid(n, n, [0.0, 0.0], [1.0, 1.0], 0.2, 3, false);
    let mut m = one_body(
        AnalysisKind::PlaneStrain,
        mesh,
        1000.0,
        0.3,
        Formulation::Full,
    );
    let bottom: Vec<usize> = (0..=n).map(|i| grid_node(n, i, 0)).collect();
    let top: Vec<usize> = (0..=n).map(|i| grid_node(n, i, n)).collect();
    m.constraints = vec![
        fix(bottom.clone(), 0, 0.0),
        fix(bottom, 1, 0.0),
        Dirichlet {
            label: "press".into(),
            nodes: top,
            component: 1,
            value: TimeFunction::Ramp {
                t0: 0.0,
                t1: 1.0,
                v0: 0.0,
                v1: -0.01,
            },
        },
    ];
    m.steps = vec![step(6)];
    let start = std::time::Instant::now();
    let s = run(&m, &mut Recorder::default()).unwrap();
    println!(
        "{} free dofs, {} nonzeros, {} iterations, wall {:.3} s: {:?}",
        s.free_dofs,
        s.matrix_nonzeros,
        s.newton_iterations,
        start.elapsed().as_secs_f64(),
        s.timings
    );
}

#[test]
fn body_held_only_by_open_contact_falls_onto_it() {
    // A block 0.5 above a rigid floor, fixed in x on its left side only,
    // pushed down by 3 x 1. Before it touches nothing holds it in y: the
    // first tangent is singular (Cholesky fails, LU factors with a round-off
    // pivot), the huge first correction is damped by the line search, the
    // contact catches the block, and the next increment is back on Cholesky.
    let mesh = grid(2, 2, [0.0, 0.0], [1.0, 1.0], 0.0, 1, false);
    let edges: Vec<[usize; 2]> = mesh
        .boundary_edges(0..mesh.cells.len())
        .into_iter()
        .filter(|e| mesh.nodes[e[0]][1] == 0.0 && mesh.nodes[e[1]][1] == 0.0)
        .collect();
    let mut m = one_body(
        AnalysisKind::PlaneStrain,
        mesh,
        100.0,
        0.3,
        Formulation::Full,
    );
    m.constraints = vec![fix(vec![0, 3, 6], 0, 0.0)];
    m.loads = vec![force(vec![6, 7, 8], 1, TimeFunction::Constant(-1.0))];
    m.tools = vec![RigidTool {
        name: "floor".into(),
        geometry: ToolGeometry::Plane {
            point: [0.0, -0.5],
            normal: [0.0, 1.0],
        },
        motion: ToolMotion::fixed(),
        free_rotation: None,
    }];
    m.contacts = vec![ContactPair {
        name: "block.bottom -> floor".into(),
        body: 0,
        edges,
        faces: Vec::new(),
        nodes: vec![0, 1, 2],
        master: ctc_engine::model::ContactMaster::Tool(0),
        strategy: Default::default(),
        search: Default::default(),
        formulation: Default::default(),
        smoothing: Default::default(),
        method: ContactMethod::Penalty {
            kind: PenaltyKind::Area,
            stiffness: 1e4,
        },
        prof: None,
        friction: None,
        local_penalty: Vec::new(),
    }];
    m.steps[0].increments = 2;
    let mut rec = Recorder::default();
    let s = run(&m, &mut rec).unwrap();
    for i in &rec.iterations {
        println!("{i:?}");
    }
    assert_eq!(s.linear_solver, "lu");
    assert!(
        s.lu_factorizations >= 1 && s.cholesky_factorizations >= 1,
        "{s:?}"
    );
    assert!(rec.iterations[0].step_length < 1.0, "line search expected");
    let last = rec.increments.last().unwrap();
    // the floor carries the load: total force 3, reactions only in x
    let fy: f64 = last.reaction.iter().map(|r| r[1]).sum();
    assert_eq!(fy, 0.0);
    assert!(
        (last.contact_force(0)[1] - 3.0).abs() < 1e-9,
        "{:?}",
        last.contact_force(0)
    );
    // bottom nodes rest on the floor with the penalty gap p / k ~ 3e-4
    for n in 0..3 {
        let y = last.displacement[n][1];
        assert!(y < -0.5 && y > -0.5 - 1e-3, "node {n}: {y}");
    }
    // second increment (same load): Cholesky again, one iteration
    assert_eq!(s.increments[1].iterations, 1, "{:?}", s.increments);
}
