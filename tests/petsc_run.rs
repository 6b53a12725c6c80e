//! `mpirun -n N ctc run DECK --solver petsc` against the serial faer run of
//! the same deck (issue "a PETSc + MPI backend"): on 1 and 2 ranks the 2D
//! Hertz cylinder (examples/hertz_cylinder.ctc) and a coarse 3D Hertz
//! sphere (tests/decks/hertz_sphere_3d_coarse.ctc) take the same Newton
//! iterations in every increment and give the same history (forces,
//! reactions) and contact pressures to the linear solver's round-off, as
//! do a plastic finite-strain upsetting (examples/upsetting.ctc), a
//! finite-strain Neo-Hooke indentation, two deformable cylinders in
//! node-to-segment contact (examples/two_cylinders_hertz.ctc) and two
//! deformable 3D blocks in mortar contact
//! (examples/contact_blocks_mortar_3d.ctc), and the Hertz cylinder on
//! quadratic cells (examples/hertz_cylinder_quadratic.ctc) and a tube
//! expanded by a follower pressure into a die
//! (examples/tube_hydroforming.ctc without its thermal coupling), and a
//! bar impact in implicit dynamics with springs, dashpots and point
//! masses (examples/bar_impact.ctc), all assembled distributed; the pieces of each increment's parallel VTU
//! (`.pvtu`) join into the serial VTU; CG + GAMG chosen by PETSc options
//! converges to the same answer; a failing run stops every rank with one
//! diagnosis and a non-zero exit; `-- -log_view` prints PETSc's log.
//!
//! ```text
//!   serial:  ctc run deck                 ──▶ out/faer  ┐
//!   MPI:     mpirun -n 1 ctc run deck --solver petsc ─▶ ├─ compare
//!            mpirun -n 2 ctc run deck --solver petsc ─▶ ┘
//! ```
//!
//! Needs the `petsc` feature and `mpirun` (`bash petsc/install.sh`); run by
//! `.ci/run` as `cargo test -p ctc -p ctc-petsc --features ctc/petsc --lib
//! --test mpi_elasticity --test petsc_run` (alone: `cargo test --features
//! petsc --test petsc_run`).
#![cfg(feature = "petsc")]

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// `ctc run deck -o dir [extra]`, under `mpirun -n ranks` when given.
fn run(deck: &str, dir: &Path, ranks: Option<usize>, extra: &[&str]) -> Output {
    let exe = env!("CARGO_BIN_EXE_ctc");
    let mut cmd = match ranks {
        Some(n) => {
            let mut c = Command::new("mpirun");
            c.args([
                "--allow-run-as-root",
                "--oversubscribe",
                "-n",
                &n.to_string(),
                exe,
            ]);
            c
        }
        None => Command::new(exe),
    };
    cmd.current_dir(root())
        .args(["run", deck, "-q", "-o"])
        .arg(dir)
        .args(extra);
    cmd.output().expect("ctc runs")
}

fn ok(out: Output, what: &str) {
    assert!(
        out.status.success(),
        "{what} failed:\n{}\n{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
}

/// Header and numeric rows of a CSV file (empty cells are NaN).
fn csv(path: &Path) -> (Vec<String>, Vec<Vec<f64>>) {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut lines = text.lines();
    let head = lines
        .next()
        .unwrap()
        .split(',')
        .map(str::to_string)
        .collect();
    let rows = lines
        .map(|l| {
            l.split(',')
                .map(|v| v.parse().unwrap_or(f64::NAN))
                .collect()
        })
        .collect();
    (head, rows)
}

fn summary(dir: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(dir.join("summary.json")).unwrap()).unwrap()
}

fn iterations(s: &serde_json::Value) -> Vec<u64> {
    s["increments"]
        .as_array()
        .unwrap()
        .iter()
        .map(|i| i["iterations"].as_u64().unwrap())
        .collect()
}

/// Largest difference between two histories over the largest value of
/// either (forces and reactions share one scale).
fn history_difference(a: &Path, b: &Path) -> f64 {
    let (ha, ra) = csv(&a.join("history.csv"));
    let (hb, rb) = csv(&b.join("history.csv"));
    assert_eq!(ha, hb);
    assert_eq!(ra.len(), rb.len(), "same number of increments");
    let scale = ra.iter().flatten().fold(0.0f64, |m, v| m.max(v.abs()));
    let diff = ra
        .iter()
        .flatten()
        .zip(rb.iter().flatten())
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()));
    diff / scale
}

/// The contact pressures of the last increment of pair 0, and their peak.
fn pressures(dir: &Path, last: usize) -> (Vec<f64>, f64) {
    let (head, rows) = csv(&dir.join(format!("contact_0_{last:04}.csv")));
    let k = head.iter().position(|h| h == "pressure").unwrap();
    let p: Vec<f64> = rows.iter().map(|r| r[k]).collect();
    let peak = p.iter().fold(0.0f64, |m, v| m.max(*v));
    (p, peak)
}

/// The largest absolute value of the columns of a history whose names
/// start with `name` (the force of a contact pair over the run).
fn largest(dir: &Path, name: &str) -> f64 {
    let (head, rows) = csv(&dir.join("history.csv"));
    let columns: Vec<usize> = (0..head.len())
        .filter(|&k| head[k].starts_with(name))
        .collect();
    assert!(!columns.is_empty(), "no column {name} in {head:?}");
    rows.iter()
        .flat_map(|r| columns.iter().map(|&k| r[k].abs()))
        .fold(0.0f64, f64::max)
}

/// The VTU of the last written increment of a serial run, and the union of
/// the pieces of a PETSc run's `.pvtu` of the same increment (which
/// `results.pvd` lists), read back; their arrays agree to `tol` of each
/// array's largest value (the solutions differ by the linear solver's
/// round-off).
fn pieces_are_the_serial_vtu(serial: &Path, dir: &Path, ranks: usize, tol: f64) {
    use ctc_engine::output::vtu_read::{join_pieces, Vtu};
    let pvd = std::fs::read_to_string(dir.join("results.pvd")).unwrap();
    let last = pvd
        .lines()
        .filter_map(|l| l.split("file=\"").nth(1)?.split('"').next())
        .rfind(|f| f.ends_with(".pvtu"))
        .expect("the PVD lists the .pvtu files");
    let text = std::fs::read_to_string(dir.join(last)).unwrap();
    let sources: Vec<&str> = text
        .lines()
        .filter_map(|l| l.split("Source=\"").nth(1)?.split('"').next())
        .collect();
    assert_eq!(sources.len(), ranks, "{text}");
    let pieces: Vec<Vtu> = sources
        .iter()
        .map(|f| Vtu::read_file(&dir.join(f)).unwrap())
        .collect();
    let joined = join_pieces(&pieces).unwrap();
    let whole = Vtu::read_file(&serial.join(last.replace(".pvtu", ".vtu"))).unwrap();
    assert_eq!((joined.points, joined.cells), (whole.points, whole.cells));
    let names = |v: &Vtu| -> Vec<String> { v.arrays.iter().map(|a| a.name.clone()).collect() };
    assert_eq!(names(&joined), names(&whole));
    for (j, w) in joined.arrays.iter().zip(&whole.arrays) {
        let scale = w.values.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let diff = j
            .values
            .iter()
            .zip(&w.values)
            .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
        assert!(
            diff <= tol * scale,
            "{ranks} ranks: {} differs by {diff:.2e} of {scale:.3e}",
            w.name
        );
    }
    // every array the pieces hold is declared by the parallel file
    for a in &pieces[0].arrays {
        if matches!(
            a.section,
            ctc_engine::output::vtu_read::Section::PointData
                | ctc_engine::output::vtu_read::Section::CellData
        ) {
            assert!(text.contains(&format!("Name=\"{}\"", a.name)), "{}", a.name);
        }
    }
}

/// The serial and the 1- and 2-rank PETSc runs of `deck` agree; both are
/// assembled distributed (each rank its cells), and the pieces of the
/// parallel VTU join into the serial VTU. Prints the figures compared.
fn same_as_serial(deck: &str, name: &str, tol: f64) {
    let tmp = tempfile::tempdir().unwrap();
    let serial = tmp.path().join(format!("{name}_faer"));
    let start = std::time::Instant::now();
    ok(run(deck, &serial, None, &[]), "serial run");
    let wall0 = start.elapsed().as_secs_f64();
    let s0 = summary(&serial);
    let n_inc = s0["increments"].as_array().unwrap().len();
    let (p0, peak0) = pressures(&serial, n_inc);
    assert!(peak0 > 0.0);
    let force = |dir: &Path| largest(dir, "contact_force");
    eprintln!(
        "{name}: serial: iterations {:?}, largest contact force {:.10e}, peak pressure \
         {peak0:.10e}, wall {wall0:.2} s",
        iterations(&s0),
        force(&serial)
    );
    for ranks in [1, 2] {
        let dir = tmp.path().join(format!("{name}_petsc{ranks}"));
        let start = std::time::Instant::now();
        ok(
            run(deck, &dir, Some(ranks), &["--solver", "petsc"]),
            "petsc run",
        );
        let wall = start.elapsed().as_secs_f64();
        let s = summary(&dir);
        assert_eq!(
            iterations(&s),
            iterations(&s0),
            "{ranks} ranks: Newton iterations"
        );
        assert_eq!(s["distributed"]["ranks"], ranks);
        assert_eq!(s["distributed"]["assembly"], "distributed");
        assert_eq!(s["completed"], true);
        pieces_are_the_serial_vtu(&serial, &dir, ranks, tol);
        let h = history_difference(&serial, &dir);
        let (p, peak) = pressures(&dir, n_inc);
        eprintln!(
            "{name}: {ranks} rank(s): iterations {:?}, largest contact force {:.10e}, peak \
             pressure {peak:.10e}, history difference {h:.2e}, wall {wall:.2} s",
            iterations(&s),
            force(&dir)
        );
        let dp = p0
            .iter()
            .zip(&p)
            .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()))
            / peak0;
        assert!(h < tol, "{ranks} ranks: history differs by {h:.2e}");
        assert!(
            dp < tol,
            "{ranks} ranks: pressures differ by {dp:.2e} of p0"
        );
        assert!((peak - peak0).abs() <= tol * peak0);
    }
}

#[test]
fn hertz_cylinder_2d_on_one_and_two_ranks_is_the_serial_run() {
    same_as_serial("examples/hertz_cylinder.ctc", "hertz2d", 1e-9);
}

#[test]
fn hertz_sphere_3d_on_one_and_two_ranks_is_the_serial_run() {
    same_as_serial("tests/decks/hertz_sphere_3d_coarse.ctc", "hertz3d", 1e-9);
}

#[test]
fn plastic_finite_strain_upsetting_on_one_and_two_ranks_is_the_serial_run() {
    // examples/upsetting.ctc: J2 plasticity at finite strain (F-bar, a
    // non-symmetric tangent), Swift hardening, penalty contact with a
    // rigid die; each rank evaluates the integration points of its cells
    same_as_serial("examples/upsetting.ctc", "upsetting", 1e-9);
}

#[test]
fn neo_hooke_indentation_on_one_and_two_ranks_is_the_serial_run() {
    // tests/decks/neo_hooke_indentation.ctc (finite-strain Neo-Hooke block
    // indented by a rigid circle to 40 % of its height; Newton backtracks
    // through inverted trial elements) with the contact and stress fields
    let tmp = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(root().join("tests/decks/neo_hooke_indentation.ctc"))
        .unwrap()
        .replace(
            "output { history = [reaction(block.bottom)] }",
            "output { fields = [displacement, stress, reaction, contact]\n  \
             history = [reaction(block.bottom), contact_force(block.top -> punch)] }",
        );
    assert!(text.contains("contact_force"));
    let deck = tmp.path().join("neo_hooke.ctc");
    std::fs::write(&deck, text).unwrap();
    same_as_serial(deck.to_str().unwrap(), "neo_hooke", 1e-9);
}

#[test]
fn two_deformable_cylinders_on_one_and_two_ranks_are_the_serial_run() {
    // examples/two_cylinders_hertz.ctc: node-to-segment contact between two
    // deformable half discs (the master arc replicated on every rank, the
    // rows of a node added by its owner)
    same_as_serial("examples/two_cylinders_hertz.ctc", "two_cylinders", 1e-9);
}

#[test]
fn quadratic_hertz_cylinder_on_one_and_two_ranks_is_the_serial_run() {
    // examples/hertz_cylinder_quadratic.ctc: quad8 cells (order = 2), the
    // contact rows of a quadratic face spanning its three nodes
    same_as_serial(
        "examples/hertz_cylinder_quadratic.ctc",
        "hertz_quadratic",
        1e-9,
    );
}

#[test]
fn mortar_blocks_3d_on_one_and_two_ranks_are_the_serial_run() {
    // examples/contact_blocks_mortar_3d.ctc (two deformable hex8 blocks,
    // non-matching interface, penalty mortar rows spanning slave and
    // master facets) with the fields and a contact force history
    let tmp = tempfile::tempdir().unwrap();
    let mut text =
        std::fs::read_to_string(root().join("examples/contact_blocks_mortar_3d.ctc")).unwrap();
    assert!(!text.contains("output {"));
    text.push_str(
        "output { fields = [displacement, stress, reaction, contact]\n  \
         history = [contact_force(top.zmin -> base.zmax), reaction(base.zmin)] }\n",
    );
    let deck = tmp.path().join("mortar3d.ctc");
    std::fs::write(&deck, text).unwrap();
    same_as_serial(deck.to_str().unwrap(), "mortar3d", 1e-9);
}

/// `examples/tube_hydroforming.ctc` without its thermal coupling (the
/// material's, the body's and the contact's `thermal` blocks left out),
/// coarser (2 x 2 x 6 cells, 10 increments: the tube still reaches the
/// die), with its thickness map (history columns and VTU field: the
/// thinnest point's place is the lowest-numbered node among those whose
/// thickness ties to round-off, `output::thickness::minimum`, so it is
/// the same on 1 and 2 ranks).
fn tube_hydroforming_isothermal() -> String {
    tube_hydroforming_small(false)
}

/// `examples/tube_hydroforming.ctc` as [`tube_hydroforming_isothermal`],
/// with its thermal coupling when `thermal`.
fn tube_hydroforming_small(thermal: bool) -> String {
    let text = std::fs::read_to_string(root().join("examples/tube_hydroforming.ctc")).unwrap();
    let mut out = String::new();
    let mut in_block = false;
    for line in text.lines() {
        let t = line.trim();
        if in_block {
            in_block = t != "}";
            continue;
        }
        if !thermal && t.starts_with("thermal {") {
            in_block = !t.ends_with('}');
            continue;
        }
        let line = match t {
            "let nc = 4" => "let nc = 2",
            "let nz = 12" => "let nz = 6",
            "let steps = 20" => "let steps = 10",
            _ => line,
        };
        out.push_str(line);
        out.push('\n');
    }
    let code: Vec<&str> = out.lines().filter(|l| !l.starts_with('#')).collect();
    assert_eq!(code.iter().any(|l| l.contains("thermal")), thermal, "{out}");
    assert!(out.contains("follower = true") && out.contains("let nz = 6"));
    assert!(out.contains("thickness = (tube.outer, tube.inner)"));
    out
}

#[test]
fn follower_pressure_tube_on_one_and_two_ranks_is_the_serial_run() {
    // examples/tube_hydroforming.ctc (3D J2 tube at finite strain, F-bar,
    // expanded by an internal follower pressure into a rigid IGES die)
    // without its thermal coupling: each follower facet evaluated by the
    // rank of its cell, the forces summed over the ranks
    // (`follower::FollowerShare`)
    let tmp = tempfile::tempdir().unwrap();
    let deck = tmp.path().join("tube.ctc");
    std::fs::write(&deck, tube_hydroforming_isothermal()).unwrap();
    // the die's IGES file is found next to the deck
    std::fs::copy(
        root().join("examples/tube_hydroforming_die.igs"),
        tmp.path().join("tube_hydroforming_die.igs"),
    )
    .unwrap();
    same_as_serial(deck.to_str().unwrap(), "tube_follower", 1e-9);
}

#[test]
fn thermal_tube_on_one_and_two_ranks_is_the_serial_run() {
    // the coarse tube of `follower_pressure_tube_..` with its thermal
    // coupling (conductance to the cold die, plastic heating, flow stress
    // falling with temperature): the mechanical part assembled
    // distributed, the staggered heat step computed whole by every rank
    let tmp = tempfile::tempdir().unwrap();
    let deck = tmp.path().join("tube.ctc");
    std::fs::write(&deck, tube_hydroforming_small(true)).unwrap();
    std::fs::copy(
        root().join("examples/tube_hydroforming_die.igs"),
        tmp.path().join("tube_hydroforming_die.igs"),
    )
    .unwrap();
    same_as_serial(deck.to_str().unwrap(), "tube_thermal", 1e-9);
}

#[test]
fn dynamics_springs_and_masses_on_one_and_two_ranks_are_the_serial_run() {
    // examples/bar_impact.ctc (implicit generalized-alpha dynamics, a
    // consistent mass, penalty contact with a rigid wall) with
    // mass-proportional Rayleigh damping, a spring and dashpot from the
    // right end to the ground, a link spring from the left end to the
    // right end (nodes sharing no cell, on two ranks' parts) and point
    // masses at the right end, 60 increments to t = 15 (in contact from
    // t = 0.1 to 20): the inertia, spring and dashpot forces whole on
    // every rank, their tangent rows added by the node's (cell's) owner
    let text = std::fs::read_to_string(root().join("examples/bar_impact.ctc"))
        .unwrap()
        .replace("time = 0 .. 30", "time = 0 .. 15")
        .replace("increments = 300", "increments = 60")
        // its reactions (the held uy of a bar pushed along x) are
        // round-off, 4e-16, which the serial and PETSc runs do not share
        .replace("stress, reaction, contact", "stress, contact")
        .replace(
            "mass = consistent }",
            "mass = consistent  rayleigh_alpha = 0.01 }",
        )
        .replace(
            "initial_velocity bar.all",
            "spring bar.right { stiffness = 2e-3  damping = 1e-2 }\n\
             spring bar.left -> bar.right { stiffness = 1e-3  damping = 1e-3 }\n\
             point_mass bar.right { mass = 0.05 }\n\
             initial_velocity bar.all",
        );
    assert!(text.contains("rayleigh_alpha") && text.contains("point_mass"));
    assert!(text.contains("time = 0 .. 15") && !text.contains("reaction,"));
    let tmp = tempfile::tempdir().unwrap();
    let deck = tmp.path().join("bar_impact.ctc");
    std::fs::write(&deck, text).unwrap();
    same_as_serial(deck.to_str().unwrap(), "bar_impact", 1e-9);
}

/// `ctc run` arguments for `--solver petsc` with CG + GAMG, then `extra`
/// PETSc options.
fn cg_gamg<'a>(extra: &[&'a str]) -> Vec<&'a str> {
    let mut opts = vec![
        "--solver",
        "petsc",
        "--",
        "-ksp_type",
        "cg",
        "-pc_type",
        "gamg",
    ];
    opts.extend_from_slice(extra);
    opts
}

#[test]
fn cg_gamg_from_petsc_options_converges_to_the_serial_answer() {
    let tmp = tempfile::tempdir().unwrap();
    let deck = "tests/decks/hertz_sphere_3d_coarse.ctc";
    let serial = tmp.path().join("faer");
    ok(run(deck, &serial, None, &[]), "serial run");
    let dir = tmp.path().join("gamg");
    let opts = cg_gamg(&["-ksp_rtol", "1e-12"]);
    ok(run(deck, &dir, Some(2), &opts), "CG + GAMG run");
    let s = summary(&dir);
    let d = &s["distributed"];
    // this tangent is indefinite (the serial run needs L D L^T): CG falls back to GMRES
    assert_eq!(d["solver"], "petsc: ksp gmres, pc gamg");
    assert!(d["fallbacks"].as_u64().unwrap() >= 1);
    assert_eq!(d["fallback_reason"], "indefinite matrix");
    let its = d["krylov_iterations"].as_u64().unwrap();
    let solves = d["solves"].as_u64().unwrap();
    assert!(
        its > solves,
        "an iterative solve takes more than one iteration"
    );
    assert_eq!(iterations(&s), iterations(&summary(&serial)));
    let h = history_difference(&serial, &dir);
    assert!(h < 1e-7, "CG + GAMG history differs by {h:.2e}");
}

#[test]
fn a_failing_run_stops_every_rank_with_one_diagnosis() {
    // the disc of this deck is held by nothing but its contact: the
    // factorization meets the zero-energy mode on every rank
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("fail");
    let out = run(
        "tests/decks/singular_with_contact.ctc",
        &dir,
        Some(2),
        &["--solver", "petsc"],
    );
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(
        err.matches("error:").count(),
        1,
        "one diagnosis, by rank 0:\n{err}"
    );
    assert!(err.contains("MUMPS found 1 null pivot"), "{err}");
}

/// A Krylov solve that stops before its tolerance (issue 21): CG + GAMG
/// capped at 2 iterations (`-ksp_max_it 2`) on the large contact deck at
/// its own size (n = 6, 8k dofs; 37-40 iterations a solve uncapped, see
/// `large_contact_deck_by_cg_gamg_reports_every_rank`). Every solve ends
/// `DIVERGED_ITS`; the increment is cut back once, fails the same way at
/// half its size and the run stops there (before, it halved down to the
/// smallest size: 10 cutbacks, a GAMG set-up each), on 1 and 2 ranks
/// alike: a non-zero exit, one diagnosis by rank 0 naming the linear
/// solver, PETSc's reason and the options to change (not "singular": the
/// matrix is fine), a summary saying the run did not complete after one
/// cutback and the same solves as the 1-rank run, and no result of an
/// unconverged state (no increment in the history, no `.pvtu` listed).
///
/// ```text
///   mpirun -n 1|2 ctc run large_contact_3d.ctc --solver petsc --
///       -ksp_type cg -pc_type gamg -ksp_max_it 2
///   K du = r: CG 2 its -> DIVERGED_ITS -> LinearError::NotConverged
///     -> FailureKind::LinearSolver -> 1 cutback -> the same at dt / 2
///     -> exit 1, "error: ..."
/// ```
#[test]
fn a_krylov_solve_that_does_not_converge_stops_every_rank_with_its_reason() {
    let tmp = tempfile::tempdir().unwrap();
    let deck = "tests/decks/large_contact_3d.ctc";
    let opts = cg_gamg(&["-ksp_max_it", "2"]);
    let mut attempts = Vec::new();
    for ranks in [1, 2] {
        let dir = tmp.path().join(format!("capped{ranks}"));
        let out = run(deck, &dir, Some(ranks), &opts);
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(
            !out.status.success(),
            "{ranks} ranks: the run must fail\n{err}"
        );
        assert_eq!(
            err.matches("error:").count(),
            1,
            "{ranks} ranks: one diagnosis, by rank 0:\n{err}"
        );
        for words in [
            "the Krylov solver did not converge: DIVERGED_ITS",
            "after 2 iterations",
            "the iterative linear solver did not converge",
            "failed the same way at dt = 5.000e-1 and, cut back once, at dt = 2.500e-1",
            "-ksp_max_it",
            "-ksp_rtol",
        ] {
            assert!(err.contains(words), "{ranks} ranks: no `{words}` in\n{err}");
        }
        assert!(
            !err.contains("singular"),
            "{ranks} ranks: a capped Krylov solve is not a singular matrix:\n{err}"
        );
        let s = summary(&dir);
        assert_eq!(s["completed"], false, "{ranks} ranks");
        let failure = s["failure"].as_str().unwrap();
        assert!(failure.contains("DIVERGED_ITS"), "{failure}");
        assert_eq!(s["distributed"]["ranks"], ranks);
        assert_eq!(s["distributed"]["fallbacks"], 0, "no GMRES fallback");
        assert!(iterations(&s).is_empty(), "no converged increment");
        assert_eq!(
            s["cutbacks"], 1,
            "{ranks} ranks: one cutback, not down to the smallest"
        );
        attempts.push((s["cutbacks"].clone(), s["distributed"]["solves"].clone()));
        // nothing of an unconverged state: the history has no row, the PVD
        // lists no parallel VTU
        let (_, rows) = csv(&dir.join("history.csv"));
        assert!(
            rows.len() <= 1,
            "{ranks} ranks: {} history rows",
            rows.len()
        );
        let pvd = std::fs::read_to_string(dir.join("results.pvd")).unwrap_or_default();
        assert_eq!(pvd.matches(".pvtu").count(), rows.len(), "{pvd}");
    }
    assert_eq!(
        attempts[0], attempts[1],
        "the same cutbacks and solves on 1 and 2 ranks"
    );
}

/// `-log_view` after `--` reaches PETSc (issue 21). PETSc reads it only
/// inside `PetscInitialize`: the run's options are handed to it there
/// (`PETSC_OPTIONS`, `petsc/src/env.rs`); inserted into the options
/// database after the start, as before last session's fix, it was
/// silently ignored and no log was printed. One rank, the Hertz cylinder
/// (examples/hertz_cylinder.ctc) in one increment: with the option,
/// PETSc's performance log with its events is on the standard output
/// (printed by `PetscFinalize`); without it, none of those words is (what
/// ctc prints under `-q` names no PETSc event), so the check can fail.
///
/// ```text
///   mpirun -n 1 ctc run hertz.ctc -q --solver petsc -- -log_view
///     PETSC_OPTIONS="-log_view" -> PetscInitialize ... PetscFinalize
///     -> stdout: "PETSc Performance Summary", "KSPSolve", "MatAssemblyEnd"
/// ```
#[test]
fn log_view_reaches_petsc_and_prints_its_log() {
    let tmp = tempfile::tempdir().unwrap();
    let deck = hertz_one_increment(tmp.path(), 20);
    let deck = deck.to_str().unwrap();
    let words = ["PETSc Performance Summary", "KSPSolve", "MatAssemblyEnd"];
    for (opts, logged) in [
        (vec!["--solver", "petsc"], false),
        (vec!["--solver", "petsc", "--", "-log_view"], true),
    ] {
        let dir = tmp.path().join(format!("log{logged}"));
        let out = run(deck, &dir, Some(1), &opts);
        let stdout = String::from_utf8_lossy(&out.stdout);
        assert!(
            out.status.success(),
            "{opts:?} failed:\n{stdout}\n{}",
            String::from_utf8_lossy(&out.stderr)
        );
        for w in words {
            assert_eq!(
                stdout.contains(w),
                logged,
                "{opts:?}: `{w}` in the standard output: {}, expected {logged}\n{stdout}",
                stdout.contains(w)
            );
        }
        assert_eq!(summary(&dir)["completed"], true);
    }
}

#[test]
fn petsc_options_without_the_petsc_solver_are_refused() {
    let tmp = tempfile::tempdir().unwrap();
    let out = run(
        "examples/hertz_cylinder.ctc",
        &tmp.path().join("x"),
        None,
        &["--", "-ksp_type", "cg"],
    );
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("need `--solver petsc`"));
}

/// The deck of `examples/hertz_cylinder.ctc` with one increment and
/// `max_iter` Newton iterations, written into `dir`, with the increment
/// predictor (at max_iter = 2 the serial run and the 2-rank PETSc run took
/// different iteration sequences through the cutbacks, [2, 2, 1, 1, 1, 1,
/// 1] against [2, 1, 1, 2, 1, 1, 1], while the predictor compared its
/// residual with each rank's partial `K_fp dp`: the ranks could decide
/// differently; now summed over the ranks, both take [2, 1, 1, 2, 1, 1,
/// 1]).
fn hertz_one_increment(dir: &Path, max_iter: usize) -> PathBuf {
    let text = std::fs::read_to_string(root().join("examples/hertz_cylinder.ctc"))
        .unwrap()
        .replace("increments = 4", "increments = 1")
        .replace("max_iter = 20", &format!("max_iter = {max_iter}"));
    let path = dir.join(format!("hertz_max_iter{max_iter}.ctc"));
    std::fs::write(&path, text).unwrap();
    path
}

#[test]
fn two_ranks_agree_on_cutbacks_and_on_failure() {
    // max_iter = 2: the one increment does not converge, the step is cut
    // back (3 times) and finished in 8 increments; every rank must take the
    // same cutbacks, or the next collective solve would deadlock
    let tmp = tempfile::tempdir().unwrap();
    let deck = hertz_one_increment(tmp.path(), 2);
    let deck = deck.to_str().unwrap();
    let serial = tmp.path().join("serial");
    ok(run(deck, &serial, None, &[]), "serial run");
    let s0 = summary(&serial);
    assert!(s0["cutbacks"].as_u64().unwrap() >= 1, "the deck cuts back");
    let dir = tmp.path().join("petsc2");
    ok(
        run(deck, &dir, Some(2), &["--solver", "petsc"]),
        "petsc run",
    );
    let s = summary(&dir);
    assert_eq!(s["cutbacks"], s0["cutbacks"]);
    assert_eq!(iterations(&s), iterations(&s0));
    assert_eq!(s["newton_iterations"], s0["newton_iterations"]);
    assert!(history_difference(&serial, &dir) < 1e-9);

    // max_iter = 1: every cutback fails down to the smallest increment;
    // the run stops on both ranks with rank 0's one diagnosis, the
    // serial run's, and a summary saying so
    let deck = hertz_one_increment(tmp.path(), 1);
    let deck = deck.to_str().unwrap();
    let serial = tmp.path().join("serial_fail");
    let out0 = run(deck, &serial, None, &[]);
    assert!(!out0.status.success());
    let dir = tmp.path().join("petsc2_fail");
    let out = run(deck, &dir, Some(2), &["--solver", "petsc"]);
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(err.matches("error:").count(), 1, "one diagnosis:\n{err}");
    assert!(
        err.contains("no convergence in max_iter = 1 iterations"),
        "{err}"
    );
    let (s0, s) = (summary(&serial), summary(&dir));
    assert_eq!(s["completed"], false);
    assert_eq!(s["cutbacks"], s0["cutbacks"]);
    assert_eq!(s["newton_iterations"], s0["newton_iterations"]);
    assert_eq!(s["failure"], s0["failure"]);
    assert_eq!(s["distributed"]["ranks"], 2);
}

#[test]
fn large_contact_deck_by_cg_gamg_reports_every_rank() {
    // tests/decks/large_contact_3d.ctc at its own size (n = 6, 8k dofs):
    // the deck petsc/large_contact.sh scales up; a flat rigid floor keeps
    // the tangent positive definite, so CG + GAMG needs no fallback
    let tmp = tempfile::tempdir().unwrap();
    let deck = "tests/decks/large_contact_3d.ctc";
    let serial = tmp.path().join("faer");
    ok(run(deck, &serial, None, &[]), "serial run");
    let opts = cg_gamg(&["-ksp_rtol", "1e-10"]);
    for ranks in [1, 2] {
        let dir = tmp.path().join(format!("gamg{ranks}"));
        ok(run(deck, &dir, Some(ranks), &opts), "CG + GAMG run");
        let s = summary(&dir);
        let d = &s["distributed"];
        assert_eq!(d["solver"], "petsc: ksp cg, pc gamg");
        assert_eq!(d["fallbacks"], 0);
        assert_eq!(d["fallback_reason"], "");
        let h = history_difference(&serial, &dir);
        assert!(h < 1e-7, "{ranks} ranks: history differs by {h:.2e}");
        // Krylov iterations per Newton iteration: one group per set-up
        let groups = d["krylov_per_setup"].as_array().unwrap();
        assert_eq!(groups.len() as u64, d["setups"].as_u64().unwrap());
        assert_eq!(
            groups.len() as u64,
            s["newton_iterations"].as_u64().unwrap()
        );
        let per_solve: Vec<u64> = groups
            .iter()
            .flat_map(|g| g.as_array().unwrap().iter().map(|v| v.as_u64().unwrap()))
            .collect();
        assert_eq!(per_solve.len() as u64, d["solves"].as_u64().unwrap());
        assert_eq!(
            per_solve.iter().sum::<u64>(),
            d["krylov_iterations"].as_u64().unwrap()
        );
        assert!(per_solve.iter().all(|&k| k > 1), "{per_solve:?}");
        // every rank's share: the partition covers the mesh once, ghosts
        // and halo exist exactly when there are several ranks
        let per_rank = d["per_rank"].as_array().unwrap();
        assert_eq!(per_rank.len(), ranks);
        let total = |key: &str| -> u64 { per_rank.iter().map(|r| r[key].as_u64().unwrap()).sum() };
        assert_eq!(total("cells"), 12 * 6 * 6 * 6);
        // distributed assembly: each rank's element loop evaluates its own
        // cells and no other (a rank assembling the whole mesh, or cells
        // of another part, fails here)
        assert_eq!(d["assembly"], "distributed");
        for r in per_rank {
            assert_eq!(r["assembled_cells"], r["cells"], "{r}");
            for key in [
                "assembly_cpu_seconds",
                "solve_cpu_seconds",
                "process_cpu_seconds",
            ] {
                assert!(r[key].as_f64().unwrap() > 0.0, "{key}: {r}");
            }
        }
        assert_eq!(total("owned_nodes"), s["nodes"].as_u64().unwrap());
        let rows: Vec<u64> = per_rank
            .iter()
            .map(|r| r["rows"].as_u64().unwrap())
            .collect();
        let expected: Vec<u64> = d["rows_per_rank"]
            .as_array()
            .unwrap()
            .iter()
            .map(|v| v.as_u64().unwrap())
            .collect();
        assert_eq!(rows, expected);
        // a node shared by two parts belongs to the lower rank: the
        // ghosts are on rank 1, the halo (columns) on both
        assert_eq!(total("ghost_nodes") > 0, ranks > 1);
        for r in per_rank {
            let halo = r["halo_columns"].as_u64().unwrap();
            assert_eq!(halo > 0, ranks > 1, "{r}");
            assert_eq!(r["neighbours"].as_u64().unwrap(), ranks as u64 - 1, "{r}");
            assert!(r["off_rank_nonzeros"].as_u64().unwrap() >= halo, "{r}");
            assert!(r["peak_memory_bytes"].as_u64().unwrap() > 0, "{r}");
            assert!(r["assembly_seconds"].as_f64().unwrap() > 0.0, "{r}");
            assert!(r["solve_seconds"].as_f64().unwrap() > 0.0, "{r}");
        }
    }
}

/// The deck `text` (written as `name.ctc`, every increment an output and
/// restart point) run serially, then under `mpirun -n 2 --solver petsc`
/// stopped (SIGTERM to mpirun) once two increments are written, then
/// `--restart`ed to its end; asserts the restarted run completes on 2
/// ranks with the serial history to 1e-9 and returns the serial and the
/// restarted output directories.
fn stopped_and_restarted_on_two_ranks(
    tmp: &Path,
    name: &str,
    text: &str,
    increments: usize,
) -> (PathBuf, PathBuf) {
    let deck = tmp.join(format!("{name}.ctc"));
    std::fs::write(&deck, text.replace("output {", "output {\n  every = 1")).unwrap();
    let deck = deck.to_str().unwrap();
    let serial = tmp.join("serial");
    ok(run(deck, &serial, None, &[]), "serial run");
    let dir = tmp.join("petsc2");
    let mut child = Command::new("mpirun")
        .args(["--allow-run-as-root", "--oversubscribe", "-n", "2"])
        .arg(env!("CARGO_BIN_EXE_ctc"))
        .args(["run", deck, "-q", "--solver", "petsc", "-o"])
        .arg(&dir)
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .spawn()
        .unwrap();
    let start = std::time::Instant::now();
    loop {
        let n = std::fs::read_to_string(dir.join("results.pvd"))
            .map(|t| t.matches("part=\"0\"").count())
            .unwrap_or(0);
        if n >= 2 {
            break;
        }
        assert!(
            child.try_wait().unwrap().is_none(),
            "the run ended before it could be stopped"
        );
        assert!(start.elapsed().as_secs() < 300, "run too slow");
        std::thread::sleep(std::time::Duration::from_millis(5));
    }
    let status = Command::new("kill")
        .args(["-TERM", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(status.success());
    child.wait().unwrap();
    assert!(
        !dir.join("summary.json").exists(),
        "a stopped run has no summary"
    );
    let written = std::fs::read_to_string(dir.join("results.pvd"))
        .unwrap()
        .matches("part=\"0\"")
        .count();
    assert!(
        (2..increments).contains(&written),
        "{written} increments written"
    );
    ok(
        run(deck, &dir, Some(2), &["--restart", "--solver", "petsc"]),
        "restarted petsc run",
    );
    let s = summary(&dir);
    assert_eq!(s["completed"], true);
    assert_eq!(s["distributed"]["ranks"], 2);
    let h = history_difference(&serial, &dir);
    assert!(h < 1e-9, "restarted history differs by {h:.2e}");
    (serial, dir)
}

#[test]
fn restart_under_mpirun_finishes_a_stopped_run_as_the_serial_run() {
    // the coarse 3D Hertz sphere in 40 increments, stopped and restarted
    // (`stopped_and_restarted_on_two_ranks`): history and pressures
    let tmp = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(root().join("tests/decks/hertz_sphere_3d_coarse.ctc"))
        .unwrap()
        .replace("increments = 4", "increments = 40");
    let (serial, dir) = stopped_and_restarted_on_two_ranks(tmp.path(), "sphere40", &text, 40);
    let (p0, peak0) = pressures(&serial, 40);
    let (p, _) = pressures(&dir, 40);
    let dp = p0
        .iter()
        .zip(&p)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()))
        / peak0;
    assert!(dp < 1e-9, "pressures differ by {dp:.2e} of p0");
}

#[test]
fn plastic_restart_under_mpirun_gathers_every_rank_s_points() {
    // examples/upsetting.ctc (J2 at finite strain) on a 32 x 16 mesh in
    // 100 increments (the example's 4 x 2 in 200 increments ran whole in
    // 1.6 s on 2 ranks, before the stop could reach it; this one 4.9 s),
    // stopped and restarted on 2 ranks: each rank holds the committed
    // points of its own cells (and the border's), the restart file
    // gathers them on rank 0 and the restart gives each rank its own
    // back; the history and the last increment's fields (stress,
    // strain, von Mises) are the serial ones (a point lost or misplaced
    // in the gather changes the stresses of the last increment)
    let tmp = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(root().join("examples/upsetting.ctc"))
        .unwrap()
        .replace("increments = 10", "increments = 100")
        .replace("divisions = (4, 2)", "divisions = (32, 16)");
    let (serial, dir) = stopped_and_restarted_on_two_ranks(tmp.path(), "upsetting", &text, 100);
    pieces_are_the_serial_vtu(&serial, &dir, 2, 1e-9);
}
