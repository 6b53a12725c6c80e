//! Restart reproduces the uninterrupted run bit for bit (issue 10, "no data
//! loss"): a deck is run uninterrupted; the same deck is run again and
//! "killed" in-process after k converged increments (an observer returning
//! an error, after the writer has written increment k but before its restart
//! point: the restart continues from increment k - 1, the realistic case);
//! the run is then continued from the directory's `restart.bin`. Every file
//! of the two result directories (VTU of every increment, PVD index,
//! history.csv, contact CSVs) must be byte-identical — values are printed
//! in shortest round-trip form, so equal bytes mean equal bits — and the
//! increment records (time, dt, iterations, residuals, cutbacks) of the
//! continued increments must be equal. Dynamic runs (issue 19) carry the
//! integrator's state (velocities, accelerations, energies) the same way.

use ctc_engine::geom::Dimension;
use ctc_engine::model::{AnyModel, Model};
use ctc_engine::output::ResultWriter;
use ctc_engine::solve::restart::Checkpoint;
use ctc_engine::solve::{self, IncrementView, IterationInfo, Observer, RunSummary};
use nalgebra::Const;
use std::path::Path;

fn source_of(example: &str, edits: &[(&str, &str)]) -> ctc_lang::Source {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("examples")
        .join(example);
    let mut text = std::fs::read_to_string(&path).unwrap();
    for (from, to) in edits {
        assert!(text.contains(from), "{example}: `{from}` not found");
        text = text.replace(from, to);
    }
    ctc_lang::Source::new(&path, text)
}

fn model_of(example: &str, edits: &[(&str, &str)]) -> Model {
    let source = source_of(example, edits);
    ctc_lang::compile(&source).unwrap_or_else(|d| panic!("{}", d.render(&source)))
}

fn solid_model_of(example: &str, edits: &[(&str, &str)]) -> Model<3> {
    let source = source_of(example, edits);
    match ctc_lang::compile_any(&source) {
        Ok(AnyModel::D3(m)) => m,
        Ok(AnyModel::D2(_)) => panic!("{example} is not a 3d deck"),
        Err(d) => panic!("{}", d.render(&source)),
    }
}

/// Forwards to the writer and fails after `stop_after` converged increments.
struct Killer<'a, const D: usize> {
    inner: &'a mut ResultWriter<D>,
    stop_after: usize,
    seen: usize,
}

impl<const D: usize> Observer<D> for Killer<'_, D>
where
    Const<D>: Dimension<D>,
{
    fn iteration(&mut self, info: &IterationInfo) {
        self.inner.iteration(info);
    }
    fn converged(&mut self, view: &IncrementView<'_, D>) -> Result<(), String> {
        self.inner.converged(view)?;
        self.seen += 1;
        if self.seen >= self.stop_after {
            return Err("killed".into());
        }
        Ok(())
    }
    fn cutback(&mut self, reason: &str, new_dt: f64) {
        self.inner.cutback(reason, new_dt);
    }
    fn wants_checkpoint(&self) -> bool {
        self.inner.wants_checkpoint()
    }
    fn checkpoint(&mut self, checkpoint: &Checkpoint<D>) -> Result<(), String> {
        self.inner.checkpoint(checkpoint)
    }
}

fn files(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n != "summary.json" && n != "restart.bin" && n != "progress.sta")
        .collect();
    names.sort();
    names
}

/// Runs the three phases and compares; returns (restart increment,
/// increments of the full run).
fn restart_matches<const D: usize>(model: &Model<D>, stop_after: usize) -> (usize, usize)
where
    Const<D>: Dimension<D>,
{
    let (from, n, _) = restart_matches_from(model, stop_after);
    (from, n)
}

/// [`restart_matches`], also returning the restart point it continued from.
fn restart_matches_from<const D: usize>(
    model: &Model<D>,
    stop_after: usize,
) -> (usize, usize, Checkpoint<D>)
where
    Const<D>: Dimension<D>,
{
    let tmp = tempfile::tempdir().unwrap();
    let full_dir = tmp.path().join("full");
    let cut_dir = tmp.path().join("cut");

    let mut w = ResultWriter::create(&full_dir, model).unwrap();
    let full: RunSummary = solve::run(model, &mut w).expect("uninterrupted run");
    w.finish(&full).unwrap();
    assert!(full.increments.len() > stop_after, "deck too short");

    let mut w = ResultWriter::create(&cut_dir, model).unwrap();
    let mut killer = Killer {
        inner: &mut w,
        stop_after,
        seen: 0,
    };
    let e = solve::run(model, &mut killer).unwrap_err();
    assert!(e.message.contains("killed"), "{}", e.message);
    drop(w); // no finish(): the process "died" here

    let (mut w, cp) = ResultWriter::resume(&cut_dir, model).unwrap();
    let from = cp.increment;
    assert!(from < stop_after && from >= 1, "restart point {from}");
    let rest = solve::run_from(model, &mut w, Some(&cp)).expect("restarted run");
    w.finish(&rest).unwrap();
    assert!(rest.completed);

    // the continued increments are the uninterrupted ones, bit for bit
    let tail = &full.increments[from..];
    assert_eq!(rest.increments.len(), tail.len());
    for (a, b) in rest.increments.iter().zip(tail) {
        assert_eq!(a.increment, b.increment);
        assert_eq!(a.time.to_bits(), b.time.to_bits());
        assert_eq!(a.dt.to_bits(), b.dt.to_bits());
        assert_eq!(a.iterations, b.iterations);
        assert_eq!(a.cutbacks, b.cutbacks);
        assert_eq!(a.active_contacts, b.active_contacts);
        let bits = |r: &[f64]| r.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        assert_eq!(
            bits(&a.residuals),
            bits(&b.residuals),
            "increment {}",
            a.increment
        );
        assert_eq!(a.max_penetration.to_bits(), b.max_penetration.to_bits());
    }
    // every result file identical
    let names = files(&full_dir);
    assert_eq!(names, files(&cut_dir));
    assert!(names.iter().any(|n| n.ends_with(".vtu")));
    for n in &names {
        let a = std::fs::read(full_dir.join(n)).unwrap();
        let b = std::fs::read(cut_dir.join(n)).unwrap();
        assert!(a == b, "{n} differs after restart");
    }
    // the progress log has the same increment lines (comments say where
    // the run restarted, and wall times differ)
    let lines = |d: &Path| -> Vec<String> {
        std::fs::read_to_string(d.join("progress.sta"))
            .unwrap()
            .lines()
            .filter(|l| !l.starts_with('#'))
            .map(String::from)
            .collect()
    };
    let sta = lines(&full_dir);
    assert_eq!(sta.len(), full.increments.len());
    assert_eq!(sta, lines(&cut_dir));
    (from, full.increments.len(), cp)
}

#[test]
fn restart_upsetting_plastic_with_cutbacks_matches_uninterrupted_run() {
    // J2 finite strain + penalty contact; max_iter = 4 forces cutbacks, so
    // the restart carries a reduced increment size and plastic history
    let model = model_of(
        "upsetting.ctc",
        &[
            ("increments = 10", "increments = 2"),
            (
                "newton { tol = 1e-10 }",
                "newton { tol = 1e-10  max_iter = 4 }",
            ),
        ],
    );
    let (from, n) = restart_matches(&model, 6);
    assert_eq!((from, n), (5, 12));
}

#[test]
fn restart_hertz_lagrange_multipliers_match_uninterrupted_run() {
    // Lagrange multipliers and active set carried over the restart
    let model = model_of("hertz_cylinder_lagrange.ctc", &[]);
    let (from, _) = restart_matches(&model, 3);
    assert_eq!(from, 2);
}

#[test]
fn restart_skin_pass_output_every_5_matches_uninterrupted_run() {
    // output every 5 increments: the restart point is the last written
    // increment (10), increments 11..12 are recomputed
    let model = model_of("skin_pass.ctc", &[]);
    let (from, n) = restart_matches(&model, 12);
    assert_eq!((from, n), (10, 20));
}

#[test]
fn restart_with_a_changed_deck_is_refused() {
    let model = model_of("hertz_cylinder_lagrange.ctc", &[]);
    let tmp = tempfile::tempdir().unwrap();
    let mut w = ResultWriter::create(tmp.path(), &model).unwrap();
    let mut killer = Killer {
        inner: &mut w,
        stop_after: 3,
        seen: 0,
    };
    solve::run(&model, &mut killer).unwrap_err();
    let other = model_of("hertz_cylinder_lagrange.ctc", &[("E = ", "E = 1")]);
    let e = ResultWriter::resume(tmp.path(), &other).unwrap_err();
    assert!(e.contains("different model"), "{e}");
}

#[test]
fn restart_upsetting_with_friction_matches_uninterrupted_run() {
    // friction: stick points and slip history carried over the restart
    let model = model_of("upsetting_friction.ctc", &[]);
    let (from, _) = restart_matches(&model, 5);
    assert!(from >= 4, "{from}");
}

#[test]
fn restart_mortar_friction_matches_uninterrupted_run() {
    // mortar friction (issue 18): the stick points in slip coordinates of
    // the committed configuration, rebased at every commit, carried over
    // the restart; the coarsened Cattaneo cylinders, restarted in the shear
    let model = model_of(
        "cattaneo_cylinders_mortar.ctc",
        &[
            ("circumferential = 64", "circumferential = 24"),
            ("circumferential = 80", "circumferential = 30"),
            ("radial = 12", "radial = 5"),
        ],
    );
    // (8 increments since the mortar friction's cone tie: a trial on the
    // cone to round-off slips; 11 with 2 cutbacks in the press before it)
    let (from, n) = restart_matches(&model, 7);
    assert_eq!((from, n), (6, 8));
}

#[test]
fn restart_3d_mortar_friction_matches_uninterrupted_run() {
    // 3D mortar friction (issue 18): the stick vectors in slip coordinates
    // of the committed configuration (rebased at every commit) and the
    // committed positions the weighted slip is measured from, carried over
    // the restart; the two blocks of the example restarted in the slide
    let model = solid_model_of("friction_blocks_mortar_3d.ctc", &[]);
    let (from, n) = restart_matches(&model, 5);
    assert_eq!((from, n), (4, 6));
}

#[test]
fn restart_double_pass_resumes_with_the_right_slave_side() {
    // double pass: the slave side alternates with the converged increments;
    // the restart resumes the alternation from the checkpoint's count
    let model = model_of(
        "contact_patch.ctc",
        &[
            ("strategy = single_pass", "strategy = double_pass"),
            ("stiffness = 1e10", "stiffness = 1e8"),
            ("increments = 2", "increments = 4"),
        ],
    );
    // restart after 1 converged increment: the next one has the master
    // surface as slave (odd count); a restart that forgot the count would
    // redo the first side and differ
    let (from, _) = restart_matches(&model, 2);
    assert_eq!(from, 1);
}

#[test]
fn restart_3d_hertz_sphere_matches_uninterrupted_run() {
    // 3D: hex8 block against an analytical sphere tool (area penalty); the
    // VTU files (hexahedra, 3-component fields), history and contact CSVs
    // of the continued run are the uninterrupted ones, byte for byte. On
    // a 10^3 block rather than the example's 16^3 (the same check; the
    // three phases, 9 increments, took 121 s of the `ctc` suite's wall
    // under load 13-17 on 16^3; the example runs as written in
    // `examples.rs`)
    let model = solid_model_of(
        "hertz_sphere_3d.ctc",
        &[("divisions = (16, 16, 16)", "divisions = (10, 10, 10)")],
    );
    let (from, n) = restart_matches(&model, 3);
    assert_eq!((from, n), (2, 4));
}

#[test]
fn restart_3d_friction_in_the_slide_matches_uninterrupted_run() {
    // 3D friction: the stick points on the plane carried over the restart
    let model = solid_model_of("friction_block_3d.ctc", &[]);
    let (from, _) = restart_matches(&model, 4);
    assert_eq!(from, 3);
}

#[test]
fn restart_dynamic_bar_impact_matches_uninterrupted_run() {
    // implicit dynamics with contact (generalized-alpha, penalty wall, mass
    // redistribution): velocities, accelerations, the committed residual
    // and forces and the energy audit are carried over the restart; the
    // restart point (increment 40, t = 12) is mid-contact
    let model = model_of(
        "bar_impact.ctc",
        &[
            ("increments = 300", "increments = 100"),
            ("every = 100", "every = 10"),
        ],
    );
    let (from, n) = restart_matches(&model, 45);
    // history.csv (with the energy columns kinetic_energy .. energy_gain)
    // and every VTU are compared byte for byte by restart_matches
    assert_eq!((from, n), (40, 100));
}

#[test]
fn restart_damped_dynamic_bar_impact_matches_uninterrupted_run() {
    // Rayleigh damping: the damping matrices are rebuilt from the model at
    // the restart, the damping work carried in the restart point
    let model = model_of(
        "bar_impact.ctc",
        &[
            ("increments = 300", "increments = 60"),
            ("every = 100", "every = 10"),
            (
                "mass = consistent }",
                "mass = consistent  rayleigh_alpha = 0.01  rayleigh_beta = 0.05 }",
            ),
        ],
    );
    let (from, n) = restart_matches(&model, 25);
    assert_eq!((from, n), (20, 60));
}

#[test]
fn restart_free_rollers_carry_their_angle_bit_for_bit() {
    // issue 22: the rollers' angles are the pilot nodes' displacements;
    // stopped while the strip rolls them (output every 5 increments)
    let model = model_of(
        "blankholder.ctc",
        &[(
            "time = 1 .. 2\n  increments = 30",
            "time = 1 .. 1.2\n  increments = 6",
        )],
    );
    assert!(model
        .tools
        .iter()
        .all(|t| t.name.starts_with("roll") == t.free_rotation.is_some()));
    let (from, n) = restart_matches(&model, 47);
    assert!(from >= 40 && from < n, "restart from {from} of {n}");
}

#[test]
fn restart_quadratic_face_friction_matches_uninterrupted_run() {
    // friction on quadratic faces (issue 23): the stick points, tangential
    // shifts and normal multipliers of every integration point carried over
    // the restart; the quad8 block of `friction_quadratic` pushed up the
    // inclined plane (augmented Lagrangian) and the hex20 block of
    // `friction_block_3d` pulled into its slide (penalty)
    use ctc_engine::mesh::CellKind;
    use ctc_engine::model::{ContactMethod, MultiplierUpdate, PenaltyKind};
    use ctc_verification::programs::friction_block::{Block, Drive};
    let mut b = Block::new(0.1f64.atan(), 0.3, Drive::LeftSide(0.01));
    b.cell = CellKind::Quad8;
    b.squeeze = Some(1e-3);
    b.method = ContactMethod::AugmentedLagrange {
        kind: PenaltyKind::Area,
        penalty: 1e6,
        tolerance: 1e-6,
        update: MultiplierUpdate::Converged,
    };
    b.friction_stiffness = Some(1e6);
    let (from, n) = restart_matches(&b.model(), 3);
    assert_eq!((from, n), (2, 5));
    let model = ctc_verification::programs::friction_3d::pulled_block_on(CellKind::Hex20, 0)
        .expect("hex20 block");
    let (from, _) = restart_matches(&model, 6);
    assert_eq!(from, 5);
}

#[test]
fn restart_free_top_through_its_rotation_chart_matches_uninterrupted_run() {
    // a free 3D rigid body spun several turns (the torque-free top of
    // `ctc verify free_top_several_turns_3d`): its rotation vector is
    // carried over to psi (1 - 2 pi / |psi|) each time |psi| passes pi,
    // before the restart point is written, so the restarted run continues
    // bit for bit; the restart point (increment 40) is after several
    // changes of chart
    use ctc_engine::model::{Discrete, InitialVelocity};
    let deck = "analysis { dimension = 3d }\n\
         material m { elastic { E = 1e3  nu = 0.3 }  density = 0 }\n\
         body top { mesh = box { origin = (-0.1, -0.1, -0.1)  size = (0.2, 0.2, 0.2)  divisions = (1, 1, 1) }  material = m  kinematics = finite }\n\
         rigid_body top.all { center = (0, 0, 0)  mass = 1  inertia_diagonal = (1, 1, 1.5)  tie_stiffness = 1e6 }\n\
         step spin {\n  time = 0 .. 1.2\n  increments = 60\n  dynamic { scheme = newmark }\n  newton { tol = 1e-11 }\n}\n\
         output { every = 10 }\n";
    let src = ctc_lang::Source::new("free_top_turns.ctc", deck.to_string());
    let mut model =
        match ctc_lang::compile_any(&src).unwrap_or_else(|d| panic!("{}", d.render(&src))) {
            AnyModel::D3(m) => m,
            AnyModel::D2(_) => panic!("a 3d deck"),
        };
    let (pilot, spin, nodes) = model
        .discrete
        .iter()
        .find_map(|d| match d {
            Discrete::Rigid {
                nodes, pilot, spin, ..
            } => Some((*pilot, *spin, nodes.clone())),
            _ => None,
        })
        .expect("a rigid body");
    // the rigid velocity omega x (X - X_c) at every tied node, omega as
    // the rotation vector's rate (psi = 0)
    let w = [4.0, 0.0, 10.0];
    let xc = model.mesh.nodes[pilot];
    let mut v0 = vec![(spin, w)];
    for n in nodes {
        let x = model.mesh.nodes[n];
        let r = [x[0] - xc[0], x[1] - xc[1], x[2] - xc[2]];
        v0.push((
            n,
            [
                w[1] * r[2] - w[2] * r[1],
                w[2] * r[0] - w[0] * r[2],
                w[0] * r[1] - w[1] * r[0],
            ],
        ));
    }
    for (n, v) in v0 {
        for (c, x) in v.iter().enumerate() {
            model.initial_velocities.push(InitialVelocity {
                label: format!("rigid velocity of node {n}"),
                nodes: vec![n],
                component: c,
                value: *x,
            });
        }
    }
    // 77 increments: 17 cutbacks (Newton to 1e-11 at about 0.2 rad per
    // increment), restarted from increment 40
    let (from, n) = restart_matches(&model, 45);
    assert_eq!((from, n), (40, 77));
}

#[test]
fn restart_with_nodes_beside_the_rim_matches_uninterrupted_run() {
    // tests/decks/beside_rim_3d.ctc: a puck flies in under the free rim of
    // the base's top face (node-to-facet penalty, dynamics), its bottom
    // nodes 0.1 below the face's extension: flagged beside past the rim,
    // kept open by the committed flag over the face. The restart point
    // (increment 8, t = 0.08) has flagged nodes over the face (x < 1):
    // restored cleared, they would close at that depth at the first
    // evaluation (the restart files before CTCRST08 carried no flags)
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/decks/beside_rim_3d.ctc");
    let text = std::fs::read_to_string(&path).unwrap();
    let source = ctc_lang::Source::new(&path, text);
    let model = match ctc_lang::compile_any(&source) {
        Ok(AnyModel::D3(m)) => m,
        Ok(AnyModel::D2(_)) => panic!("a 3d deck"),
        Err(d) => panic!("{}", d.render(&source)),
    };
    let (from, n, cp) = restart_matches_from(&model, 9);
    assert_eq!((from, n), (8, 20));
    let slaves = ctc_engine::contact::node_to_facet::slave_nodes(&model, 0);
    let beside = &cp.pairs[0].beside;
    assert_eq!(beside.len(), slaves.len());
    let over: Vec<usize> = slaves
        .iter()
        .zip(beside)
        .filter(|&(&node, &b)| b && model.mesh.nodes[node][0] + cp.displacement[node][0] < 1.0)
        .map(|(&node, _)| node)
        .collect();
    assert!(
        !over.is_empty(),
        "no flagged node over the face: {beside:?}"
    );
    // the same restart point without its flags (as a CTCRST07 file
    // restores it): the continued run leaves the uninterrupted one
    struct Quiet;
    impl Observer<3> for Quiet {}
    let full = solve::run(&model, &mut Quiet).expect("uninterrupted run");
    let mut cleared = cp.clone();
    cleared.pairs[0].beside.clear();
    let bits = |r: &[f64]| r.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    let differs = solve::run_from(&model, &mut Quiet, Some(&cleared)).map_or(true, |rest| {
        rest.increments
            .iter()
            .zip(&full.increments[from..])
            .any(|(a, b)| {
                a.active_contacts != b.active_contacts
                    || bits(&a.residuals) != bits(&b.residuals)
                    || a.max_penetration.to_bits() != b.max_penetration.to_bits()
            })
    });
    assert!(differs, "the flags made no difference");
}

#[test]
fn restart_dynamic_friction_continues_the_friction_work() {
    // issue 19: a restarted dynamic run's `friction_work[..]` columns go on
    // from the restart point (the trapezoidal rule's committed friction
    // forces are in the restart point), and its summary's total is the
    // continued increments' share of the uninterrupted run's. A block
    // (1 x 1 x 0.5, rho 1e-3) pressed on a rigid floor (tz = -1, mu =
    // 0.3) slides at vx = 2 and is stopped by friction within the step
    // (4e-3 s; tests/decks/friction_slide_3d.ctc): friction work in every
    // increment of the tail
    let text = include_str!("../decks/friction_slide_3d.ctc");
    let source = ctc_lang::Source::new(Path::new("friction_slide_3d.ctc"), text.to_string());
    let model: Model<3> = match ctc_lang::compile_any(&source) {
        Ok(AnyModel::D3(m)) => m,
        Ok(AnyModel::D2(_)) => panic!("a 3d deck"),
        Err(d) => panic!("{}", d.render(&source)),
    };
    // history.csv (the friction_work column with the energy columns) is
    // compared byte for byte by restart_matches_from
    // 20 increments: the energy control (on by default) redoes the one
    // at t = 2.5e-3 (1.3e-5 created, node 3 leaving the floor by 7.2e-5)
    // smaller, and the next increments grow back
    let (from, n, cp) = restart_matches_from(&model, 10);
    assert_eq!((from, n), (8, 20));
    struct Quiet;
    impl Observer<3> for Quiet {}
    let full = solve::run(&model, &mut Quiet).expect("uninterrupted run");
    let rest = solve::run_from(&model, &mut Quiet, Some(&cp)).expect("restarted run");
    let tail: Vec<f64> = full.increments[from..]
        .iter()
        .map(|r| r.friction_work[0])
        .collect();
    assert!(tail.iter().filter(|w| **w != 0.0).count() >= 5, "{tail:?}");
    let continued: Vec<f64> = rest.increments.iter().map(|r| r.friction_work[0]).collect();
    assert_eq!(continued, tail);
    let sum: f64 = tail.iter().sum();
    assert!(
        (rest.friction_work[0] - sum).abs() <= 1e-12 * sum.abs(),
        "{} {sum}",
        rest.friction_work[0]
    );
}
