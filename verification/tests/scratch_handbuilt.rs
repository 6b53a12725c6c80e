//! TEMPORARY scratch (removed before hand-off): hand-built models while
//! ctc-lang cannot compile decks yet.
use ctc_engine::mesh::generate::{generate, Grading, MeshSpec};
use ctc_engine::mesh::CellKind;
use ctc_engine::model::*;
use ctc_engine::solve::run;
use ctc_verification::capture::Capture;
use ctc_verification::measure::hertz::{measure, HertzSetup};

fn block(n: usize, d: f64, k: f64) -> Model {
    let rx: f64 = std::env::var("RX").map(|s| s.parse().unwrap()).unwrap_or(60.0);
    let ry: f64 = std::env::var("RY").map(|s| s.parse().unwrap()).unwrap_or(0.01);
    let bs: f64 = std::env::var("BS").map(|s| s.parse().unwrap()).unwrap_or(4.0);
    let mesh = generate(&MeshSpec::Rectangle { origin: [0.0, -bs], size: [bs, bs], divisions: [n, n],
        grading: [Grading::Geometric { ratio: rx }, Grading::Geometric { ratio: ry }], kind: CellKind::Quad4 }).unwrap();
    let (nn, c) = (mesh.nodes.len(), mesh.cells.len());
    let edges = mesh.edge_sets["top"].clone();
    let mut nodes: Vec<usize> = edges.iter().flatten().copied().collect();
    nodes.sort_unstable();
    nodes.dedup();
    let bottom = mesh.node_sets["bottom"].clone();
    let left = mesh.node_sets["left"].clone();
    Model {
        analysis: Analysis { kind: AnalysisKind::PlaneStrain, thickness: 1.0 },
        mesh,
        bodies: vec![Body { name: "block".into(), nodes: 0..nn, cells: 0..c, material: 0, formulation: Formulation::Full }],
        materials: vec![Material { name: "m".into(), law: MaterialLaw::LinearElastic { young: 1e3, poisson: 0.3 } }],
        constraints: vec![
            Dirichlet { label: "b".into(), nodes: bottom.clone(), component: 0, value: TimeFunction::Constant(0.0) },
            Dirichlet { label: "b".into(), nodes: bottom, component: 1, value: TimeFunction::Constant(0.0) },
            Dirichlet { label: "l".into(), nodes: left, component: 0, value: TimeFunction::Constant(0.0) },
        ],
        loads: vec![],
        tools: vec![RigidTool { name: "punch".into(), geometry: ToolGeometry::Circle { center: [0.0, 1.0], radius: 1.0, side: ToolSide::Outside },
            motion: ToolMotion { ux: TimeFunction::Constant(0.0), uy: TimeFunction::Ramp { t0: 0.0, t1: 1.0, v0: 0.0, v1: -d }, rotation: TimeFunction::Constant(0.0), center: [0.0, 1.0] } }],
        contacts: vec![ContactPair { name: "top".into(), body: 0, edges, nodes, tool: 0, method: ContactMethod::Penalty { kind: PenaltyKind::Area, stiffness: k }, prof: None }],
        steps: vec![Step { name: "s".into(), t_start: 0.0, t_end: 1.0, increments: 5, min_fraction: 1.0 / 1024.0, newton: NewtonSettings { tol: 1e-10, tol_displacement: 1e-10, max_iter: 30, line_search: true } }],
        output: OutputRequest::default(),
    }
}

fn model(kind: AnalysisKind, radial: usize, circ: usize, d: f64, k: f64) -> Model {
    if std::env::var("BLOCK").is_ok() { return block(radial, d, k); }
    let mesh = generate(&MeshSpec::QuarterDisc {
        center: [0.0, 1.0],
        radius: 1.0,
        radial,
        circumferential: circ,
        radial_grading: Grading::Geometric { ratio: 0.1 },
        circumferential_grading: Grading::Geometric { ratio: 0.02 },
        upper: false,
        kind: CellKind::Quad4,
    })
    .unwrap();
    let (n, c) = (mesh.nodes.len(), mesh.cells.len());
    let edges = mesh.edge_sets["arc"].clone();
    let mut nodes: Vec<usize> = edges.iter().flatten().copied().collect();
    nodes.sort_unstable();
    nodes.dedup();
    let axis = mesh.node_sets["axis"].clone();
    let flat = mesh.node_sets["flat"].clone();
    Model {
        analysis: Analysis { kind, thickness: 1.0 },
        mesh,
        bodies: vec![Body { name: "cyl".into(), nodes: 0..n, cells: 0..c, material: 0, formulation: Formulation::Full }],
        materials: vec![Material { name: "m".into(), law: MaterialLaw::LinearElastic { young: 1e3, poisson: 0.3 } }],
        constraints: vec![
            Dirichlet { label: "axis".into(), nodes: axis, component: 0, value: TimeFunction::Constant(0.0) },
            Dirichlet { label: "flat".into(), nodes: flat, component: 1, value: TimeFunction::Ramp { t0: 0.0, t1: 1.0, v0: 0.0, v1: -d } },
        ],
        loads: vec![],
        tools: vec![RigidTool { name: "floor".into(), geometry: ToolGeometry::Plane { point: [0.0, 0.0], normal: [0.0, 1.0] }, motion: ToolMotion::fixed() }],
        contacts: vec![ContactPair { name: "arc".into(), body: 0, edges, nodes, tool: 0, method: ContactMethod::Penalty { kind: PenaltyKind::Area, stiffness: k }, prof: None }],
        steps: vec![Step { name: "s".into(), t_start: 0.0, t_end: 1.0, increments: 5, min_fraction: 1.0 / 1024.0, newton: NewtonSettings { tol: 1e-10, tol_displacement: 1e-10, max_iter: 30, line_search: true } }],
        output: OutputRequest::default(),
    }
}

#[test]
#[ignore]
fn scratch_hertz() {
    let sphere = std::env::var("SPHERE").is_ok();
    let kind = if sphere { AnalysisKind::Axisymmetric } else { AnalysisKind::PlaneStrain };
    let d: f64 = std::env::var("D").map(|s| s.parse().unwrap()).unwrap_or(0.01);
    let k: f64 = std::env::var("K").map(|s| s.parse().unwrap()).unwrap_or(1e7);
    let levels: Vec<(usize,usize)> = std::env::var("LV").map(|s| s.split(',').map(|t| { let n: usize = t.parse().unwrap(); (n, 2*n) }).collect()).unwrap_or(vec![(8, 16), (16, 32), (32, 64), (64, 128)]);
    for (r, c) in levels {
        let m = model(kind, r, c, d, k);
        let mut cap = Capture::default();
        let t = std::time::Instant::now();
        let s = run(&m, &mut cap);
        let dt = t.elapsed().as_secs_f64();
        let s = match s { Ok(s) => s, Err(e) => { println!("FAIL {}", e.message); continue; } };
        let setup = if sphere { HertzSetup::sphere(1e3, 0.3, 1.0, 0) } else { HertzSetup::cylinder(1e3, 0.3, 1.0, 0, 0.0, true, if std::env::var("BLOCK").is_ok() { ctc_verification::profile::Abscissa::Current } else { ctc_verification::profile::Abscissa::Reference }) };
        let meas = measure(&m, cap.last.as_ref().unwrap(), &setup).unwrap();
        let p = meas.profile.as_ref().unwrap();
        println!("{r}x{c}: dofs {} its {} time {dt:.2} h {:.2e} a_ref {:.4} a {:.4} p0 {:.3}", s.free_dofs, s.newton_iterations, meas.h, p.a, p.a_computed, p.p0);
        if std::env::var("PROF").is_ok() { for q in &p.points { if q[0] < 1.3 * p.a { println!("      x/a {:.4} p/p0 {:.4} hertz {:.4}", q[0]/p.a, q[1]/p.p0, (1.0-(q[0]/p.a).powi(2)).max(0.0).sqrt()); } } }
        for v in &meas.values { println!("   {} ref {:?} comp {:.5e} err {:.3e}", v.quantity, v.reference, v.computed, v.error); }
    }
}

#[test]
#[ignore]
fn scratch_report() {
    let r = ctc_verification::run(&ctc_verification::VerifyOptions { report_dir: Some("/tmp/vrep/report".into()), progress: true, filter: std::env::var("F").ok(), ..Default::default() }).unwrap();
    println!("{}", r.table());
}

#[test]
#[ignore]
fn scratch_bench() {
    let size: f64 = std::env::var("SZ").map(|s| s.parse().unwrap()).unwrap_or(0.05);
    let r = ctc_verification::run_bench(&ctc_verification::BenchOptions { size, ..Default::default() }).unwrap();
    println!("{r}");
    println!("{}", r.to_json());
}
