//! Trust at run time (issue 14): decks that made `ctc run` panic, hang, or
//! say the wrong thing, each run through the CLI binary with a time limit
//! (`tests/decks/*.ctc`). Every run must end, with a clear message and the
//! right exit code.

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// What a finished `ctc` process printed.
struct Outcome {
    success: bool,
    stdout: String,
    stderr: String,
}

fn deck(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/decks")
        .join(name)
}

/// Runs `ctc args..`, killing it (and failing the test) after `limit`.
fn ctc(args: &[&std::ffi::OsStr], limit: Duration) -> Outcome {
    let out_dir = tempfile::tempdir().unwrap();
    let mut child = Command::new(env!("CARGO_BIN_EXE_ctc"))
        .args(args)
        .current_dir(out_dir.path())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("ctc starts");
    let start = Instant::now();
    loop {
        if let Some(_status) = child.try_wait().unwrap() {
            let out = child.wait_with_output().unwrap();
            return Outcome {
                success: out.status.success(),
                stdout: String::from_utf8_lossy(&out.stdout).into_owned(),
                stderr: String::from_utf8_lossy(&out.stderr).into_owned(),
            };
        }
        if start.elapsed() > limit {
            child.kill().ok();
            child.wait().ok();
            panic!("ctc {args:?} did not end within {limit:?}");
        }
        std::thread::sleep(Duration::from_millis(50));
    }
}

/// `ctc run DECK -o DIR`, limited to `limit`.
fn run(name: &str, dir: &Path, extra: &[&str], limit: Duration) -> Outcome {
    let d = deck(name);
    let mut args: Vec<&std::ffi::OsStr> = vec!["run".as_ref(), d.as_os_str(), "-o".as_ref()];
    args.push(dir.as_os_str());
    args.extend(extra.iter().map(std::ffi::OsStr::new));
    ctc(&args, limit)
}

fn summary(dir: &Path) -> serde_json::Value {
    let text = std::fs::read_to_string(dir.join("summary.json")).expect("summary.json");
    serde_json::from_str(&text).expect("summary.json is JSON")
}

/// Item 2: a thermal run failing before its first converged increment
/// wrote summary.json and then spun in the plot of the empty history.
#[test]
fn thermal_run_failing_before_its_first_increment_ends() {
    let dir = tempfile::tempdir().unwrap();
    let o = run(
        "thermal_fails_first_increment.ctc",
        dir.path(),
        &[],
        Duration::from_secs(60),
    );
    assert!(!o.success, "{}", o.stdout);
    assert!(
        o.stderr.contains("the analysis stopped before the end"),
        "{}",
        o.stderr
    );
    let s = summary(dir.path());
    assert_eq!(s["completed"], false);
    assert_eq!(s["increments"].as_array().map(Vec::len), Some(0));
    assert!(!dir.path().join("temperature.svg").exists());
    assert!(!dir.path().join("force_stroke.svg").exists());
}

/// Last value of column `col` of `history.csv` in `dir`.
fn last_history(dir: &Path, col: &str) -> f64 {
    let text = std::fs::read_to_string(dir.join("history.csv")).expect("history.csv");
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let i = header
        .iter()
        .position(|h| h.trim_matches('"') == col)
        .unwrap_or_else(|| panic!("no column {col} in {header:?}"));
    let last = lines.rfind(|l| !l.trim().is_empty()).unwrap();
    last.split(',').nth(i).unwrap().parse().unwrap()
}

/// Item 4: a body that is only the master of a contact pair, held in y by
/// that contact alone, was refused as free to translate.
#[test]
fn master_only_body_is_supported_through_its_contact_pair() {
    let dir = tempfile::tempdir().unwrap();
    let o = run(
        "master_only_supported.ctc",
        dir.path(),
        &["-q"],
        Duration::from_secs(120),
    );
    assert!(o.success, "{}{}", o.stdout, o.stderr);
    // the reaction under the base balances the pressure 10 on a width of 1
    let r = last_history(dir.path(), "reaction(base.bottom)_y");
    assert!((r - 10.0).abs() < 1e-6, "reaction {r}");
}

/// Item 4 (the other side): bodies linked only to each other by contact,
/// neither held nor touching a tool, are reported, both of them, by `ctc
/// check` (item 9: the rigid-body check runs in `ctc check` too).
#[test]
fn contact_group_without_support_is_reported_by_check_and_run() {
    let d = deck("unsupported_contact_group.ctc");
    let o = ctc(&["check".as_ref(), d.as_os_str()], Duration::from_secs(60));
    assert!(!o.success, "{}", o.stdout);
    for body in ["`base`", "`top`"] {
        assert!(
            o.stderr
                .contains(&format!("body {body} is free to translate along y")),
            "{}",
            o.stderr
        );
    }
    assert!(
        o.stderr
            .contains("link it only to bodies that are not held either"),
        "{}",
        o.stderr
    );
    let dir = tempfile::tempdir().unwrap();
    let o = run(
        "unsupported_contact_group.ctc",
        dir.path(),
        &["-q"],
        Duration::from_secs(60),
    );
    assert!(!o.success);
    assert!(
        o.stderr.contains("free to translate along y"),
        "{}",
        o.stderr
    );
}

/// Item 9: a singular tangent with contact present is found by its zero
/// pivot, named by node, body and dof, with the direction of the free
/// motion; the diagnosis does not blame the penalty.
#[test]
fn singular_tangent_with_contact_names_the_zero_pivot() {
    let dir = tempfile::tempdir().unwrap();
    let o = run(
        "singular_with_contact.ctc",
        dir.path(),
        &["-q"],
        Duration::from_secs(120),
    );
    assert!(!o.success, "{}", o.stdout);
    let e = &o.stderr;
    assert!(e.contains("a zero pivot at node"), "{e}");
    assert!(e.contains("of body `top`, dof ux"), "{e}");
    assert!(e.contains("node(s) of `top` along x"), "{e}");
    assert!(!e.contains("penalty too high"), "{e}");
    assert!(
        e.contains("likely cause: the stiffness matrix is singular"),
        "{e}"
    );
    // its contact is closed from the start (item 8): a stabilization
    // would not hold it along x, the hint is not given
    assert!(!e.contains("stabilize"), "{e}");
}

/// Item 9: the rigid-body check of `ctc check` counts what frictionless
/// contact with a tool can hold (its normals): a block on a flat floor with
/// nothing holding it in x is reported before any solve.
#[test]
fn check_reports_a_body_sliding_freely_on_a_frictionless_tool() {
    let d = deck("sliding_on_frictionless_floor.ctc");
    let o = ctc(&["check".as_ref(), d.as_os_str()], Duration::from_secs(60));
    assert!(!o.success, "{}", o.stdout);
    assert!(
        o.stderr
            .contains("body `block` is free to translate along x even with every node"),
        "{}",
        o.stderr
    );
}

/// Item 12: a pair that never closes and a penetration of most of the
/// tool's travel (E and the penalty in mixed units) are warned about after
/// the run, on the console and in summary.json.
#[test]
fn silent_contact_problems_are_warned_about_after_the_run() {
    let dir = tempfile::tempdir().unwrap();
    let o = run(
        "silent_contact.ctc",
        dir.path(),
        &[],
        Duration::from_secs(120),
    );
    assert!(o.success, "{}{}", o.stdout, o.stderr);
    let s = summary(dir.path());
    let warnings: Vec<String> = s["warnings"]
        .as_array()
        .unwrap()
        .iter()
        .map(|w| w.as_str().unwrap().to_string())
        .collect();
    assert_eq!(warnings.len(), 2, "{warnings:?}");
    assert!(
        warnings[0].starts_with("contact pair `block.top -> punch`: a penetration of")
            && warnings[0].contains("of the tool's travel 1.000e-1")
            && warnings[0].contains("same units"),
        "{warnings:?}"
    );
    assert!(
        warnings[1].starts_with("contact pair `block.top -> lid` never closed"),
        "{warnings:?}"
    );
    for w in &warnings {
        assert!(o.stdout.contains(&format!("warning: {w}")), "{}", o.stdout);
    }
}

/// Item 10: slave nodes that start inside a tool are reported before any
/// solve, with the hint that the tool's side may be reversed, and
/// `--explain` says which side of each tool is free.
#[test]
fn slave_nodes_starting_inside_a_reversed_tool_are_reported() {
    let d = deck("reversed_polyline.ctc");
    let o = ctc(
        &["check".as_ref(), "--explain".as_ref(), d.as_os_str()],
        Duration::from_secs(60),
    );
    assert!(o.success, "{}", o.stderr);
    assert!(
        o.stderr.contains(
            "warning: contact pair `block.bottom -> floor`: 5 of 5 slave nodes start inside tool \
             `floor` (deepest 1.000e-2"
        ) && o.stderr.contains("is the tool's side reversed?"),
        "{}",
        o.stderr
    );
    assert!(
        o.stdout.contains(
            "free side (where bodies may be): the free side of a polyline is on the left of its walk"
        ),
        "{}",
        o.stdout
    );
    let dir = tempfile::tempdir().unwrap();
    let o = run(
        "reversed_polyline.ctc",
        dir.path(),
        &[],
        Duration::from_secs(120),
    );
    let s = summary(dir.path());
    assert!(
        s["warnings"][0]
            .as_str()
            .unwrap()
            .contains("is the tool's side reversed?"),
        "{}{}",
        o.stdout,
        o.stderr
    );
}

/// Item 6: a stiff penalty (k = 1e10 against a plane, E = 2.1e5) puts the
/// round-off floor of the residual above `tol = 1e-12`: the run used to
/// stall there and stop at t = 0. It converges on the floor, reports it,
/// and the contact force balances the reaction.
#[test]
fn stiff_penalty_converges_on_the_round_off_floor_and_reports_it() {
    let dir = tempfile::tempdir().unwrap();
    let o = run(
        "stiff_penalty_floor.ctc",
        dir.path(),
        &["-q"],
        Duration::from_secs(120),
    );
    assert!(o.success, "{}{}", o.stdout, o.stderr);
    let s = summary(dir.path());
    assert_eq!(s["cutbacks"], 0);
    let last = s["increments"].as_array().unwrap().last().unwrap().clone();
    let floor = last["residual_floor"].as_f64().unwrap();
    // 4 eps k |x| over the contact force: ~1e-9, far above tol = 1e-12
    assert!(floor > 1e-11 && floor < 1e-7, "{floor}");
    assert_eq!(last["at_floor"], true);
    let residual = last["residuals"]
        .as_array()
        .unwrap()
        .last()
        .unwrap()
        .as_f64()
        .unwrap();
    assert!(residual <= floor && residual > 1e-12, "{residual} {floor}");
    let reaction = last_history(dir.path(), "reaction(block.bottom)_y");
    let contact = last_history(dir.path(), "contact_force(block.top -> lid)_y");
    assert!(reaction > 1e3, "{reaction}");
    assert!(
        (reaction + contact).abs() < 1e-8 * reaction,
        "{reaction} {contact}"
    );
}

/// Item 7: trial iterates that invert elements under a punch are
/// backtracked along the Newton direction instead of cutting the increment
/// back. Measured on this deck: 58 Newton iterations and 2 cutbacks
/// before, 29 and none after.
#[test]
fn finite_strain_indentation_backtracks_instead_of_cutting_back() {
    let dir = tempfile::tempdir().unwrap();
    let o = run(
        "neo_hooke_indentation.ctc",
        dir.path(),
        &["-v"],
        Duration::from_secs(300),
    );
    assert!(o.success, "{}{}", o.stdout, o.stderr);
    let s = summary(dir.path());
    assert_eq!(s["cutbacks"], 0, "{}", o.stdout);
    assert_eq!(s["increments"].as_array().unwrap().len(), 4);
    let iterations = s["newton_iterations"].as_u64().unwrap();
    assert!(iterations < 40, "{iterations} Newton iterations");
    // some iterations took a shortened step
    assert!(
        o.stdout
            .lines()
            .any(|l| l.contains("iter") && l.contains("step 0.")),
        "{}",
        o.stdout
    );
}

/// Item 13: a cutback is one console line (what failed, the iteration
/// count, first and last residual to 3 significant digits, the new size);
/// the full residual sequence is in summary.json `cutback_log`.
#[test]
fn a_cutback_is_one_short_console_line_with_the_sequence_in_the_summary() {
    let dir = tempfile::tempdir().unwrap();
    let o = run(
        "singular_with_contact.ctc",
        dir.path(),
        &[],
        Duration::from_secs(120),
    );
    assert!(!o.success);
    let lines: Vec<&str> = o.stdout.lines().filter(|l| l.contains("cutback")).collect();
    assert!(!lines.is_empty(), "{}", o.stdout);
    for l in &lines {
        assert_eq!(l.matches("retrying with dt").count(), 1, "{l}");
        assert!(
            l.trim_start()
                .starts_with("cutback: step `press`, t = 0 -> "),
            "{l}"
        );
    }
    assert!(
        lines[0].ends_with("retrying with dt = 2.50e-1"),
        "{}",
        lines[0]
    );
    let s = summary(dir.path());
    let log = s["cutback_log"].as_array().unwrap();
    assert_eq!(log.len(), lines.len());
    assert_eq!(log[0]["to"], 0.5);
    assert_eq!(log[0]["new_dt"], 0.25);
    assert!(log[0]["reason"].as_str().unwrap().contains("zero pivot"));
}

/// `ctc run` of deck text `text` (written to `dir/name`) into `dir/out`.
fn run_text(dir: &Path, name: &str, text: &str) -> (Outcome, PathBuf) {
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    let out = dir.join("out");
    let args: Vec<&std::ffi::OsStr> = vec![
        "run".as_ref(),
        path.as_os_str(),
        "-o".as_ref(),
        out.as_os_str(),
        "-q".as_ref(),
    ];
    (ctc(&args, Duration::from_secs(120)), out)
}

/// Item 5: a 1 x 1 punch (10 x 10 quads) on a 2 x 1 block (16 x 8 quads),
/// non-matching node-to-segment interface, penalty 1e7 for E = 2.1e5: the
/// punch's middle node sits exactly above master node 144 (x = 1), pressed
/// into a valley of the master surface. Both projections fell outside
/// their segments and the nearer segment's line was kept: the normal
/// flipped between segments 7 and 8 at every iteration (a 2-cycle, the
/// residual frozen, no status change), reported as "contact status
/// changing back and forth". The vertex is now a circle of radius 0
/// (gap and normal continuous across the wedge). Reference: the mortar
/// (segment-to-segment) solution on the same meshes, the force within
/// 1 %; measured 1371.2 (node-to-segment) vs 1367.0 (mortar), 39 Newton
/// iterations, no cutback; with mu = 0.2: 1390.8, 28 iterations.
#[test]
fn punch_over_an_interior_master_node_converges_without_cycling() {
    let text = std::fs::read_to_string(deck("punch_on_block_nonmatching.ctc")).unwrap();
    let mortar_dir = tempfile::tempdir().unwrap();
    let (o, out) = run_text(
        mortar_dir.path(),
        "mortar.ctc",
        &text.replace(
            "stiffness = 1e7 }",
            "stiffness = 1e7 }  formulation = mortar",
        ),
    );
    assert!(o.success, "{}{}", o.stdout, o.stderr);
    let reference = last_history(&out, "contact_force(punch.bottom -> block.top)_y");
    for (name, iterations) in [
        ("punch_on_block_nonmatching.ctc", 45),
        ("punch_on_block_nonmatching_friction.ctc", 40),
    ] {
        let dir = tempfile::tempdir().unwrap();
        let o = run(name, dir.path(), &["-q"], Duration::from_secs(120));
        assert!(o.success, "{name}: {}{}", o.stdout, o.stderr);
        let s = summary(dir.path());
        assert_eq!(s["cutbacks"], 0, "{name}");
        let its = s["newton_iterations"].as_u64().unwrap();
        assert!(its <= iterations, "{name}: {its} Newton iterations");
        let contact = last_history(dir.path(), "contact_force(punch.bottom -> block.top)_y");
        let reaction = last_history(dir.path(), "reaction(block.bottom)_y");
        assert!(
            (contact - reaction).abs() < 1e-8 * reaction,
            "{name}: {contact} {reaction}"
        );
        assert!(
            (contact - reference).abs() < 0.02 * reference,
            "{name}: {contact} vs mortar {reference}"
        );
    }
}

/// Coordinates `(x, y)` of the points of a VTU file.
fn vtu_points(path: &Path) -> Vec<[f64; 2]> {
    let bytes = std::fs::read(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let v = ctc_engine::output::vtu_read::Vtu::read(&bytes).unwrap();
    let c = &v.array(ctc_engine::output::vtu_read::Section::Points, "coordinates");
    c.unwrap().values.chunks(3).map(|p| [p[0], p[1]]).collect()
}

/// Item 10: each rigid tool's geometry is written at every written
/// increment (`tool_<k>_NNNN.vtu`), listed in results.pvd as its own block
/// (part k + 1), at its current position: the circle punch moves down by
/// `uy(t) = -0.05 t`, the fixed floor and wall do not move; `--explain`
/// says where each tool's free side is.
#[test]
fn rigid_tools_are_written_into_the_results_and_move_with_their_motion() {
    let dir = tempfile::tempdir().unwrap();
    let o = run(
        "tool_geometry_output.ctc",
        dir.path(),
        &["-q"],
        Duration::from_secs(120),
    );
    assert!(o.success, "{}{}", o.stdout, o.stderr);
    let pvd = std::fs::read_to_string(dir.path().join("results.pvd")).unwrap();
    for inc in [1, 2] {
        for (k, part) in [(0, 1), (1, 2), (2, 3)] {
            let line = format!("part=\"{part}\" file=\"tool_{k}_{inc:04}.vtu\"");
            assert!(pvd.contains(&line), "{line} missing from\n{pvd}");
        }
        assert!(pvd.contains(&format!("part=\"0\" file=\"inc_{inc:04}.vtu\"")));
    }
    // the punch (a circle of radius 1 about (1, 2)) at t = 0.5 and t = 1
    let (a, b) = (
        vtu_points(&dir.path().join("tool_0_0001.vtu")),
        vtu_points(&dir.path().join("tool_0_0002.vtu")),
    );
    assert_eq!(a.len(), b.len());
    assert!(a.len() > 8);
    for (p, q) in a.iter().zip(&b) {
        assert!((p[0] - q[0]).abs() < 1e-12, "{p:?} {q:?}");
        assert!((p[1] - q[1] - 0.025).abs() < 1e-12, "{p:?} {q:?}");
        let r = (q[0] - 1.0).hypot(q[1] - (2.0 - 0.05));
        assert!((r - 1.0).abs() < 1e-12, "{q:?}");
    }
    // the floor: a segment on y = 0 over the block's extent (x in 0..2)
    let f = vtu_points(&dir.path().join("tool_1_0002.vtu"));
    assert_eq!(f.len(), 2);
    assert!(f.iter().all(|p| p[1].abs() < 1e-12));
    assert!(f[0][0] < 0.0 && f[1][0] > 2.0, "{f:?}");
    // the wall does not move
    assert_eq!(
        vtu_points(&dir.path().join("tool_2_0001.vtu")),
        [[2.5, -1.0], [2.5, 2.0]]
    );
    let d = deck("tool_geometry_output.ctc");
    let o = ctc(
        &["check".as_ref(), "--explain".as_ref(), d.as_os_str()],
        Duration::from_secs(60),
    );
    assert!(o.success, "{}", o.stderr);
    for line in [
        "this circle's free side is outside (`side = outside`)",
        "free side at t = 0: at (1, 0) the normal into free space is (0, 1) (+y (above))",
        "free side at t = 0: at (2.5, 0.5) the normal into free space is (-1, 0) (-x (to the \
         left))",
    ] {
        assert!(
            o.stdout.contains(line),
            "`{line}` missing from\n{}",
            o.stdout
        );
    }
}

/// `peak contact pressure X` of a run's console summary.
fn peak_pressure(stdout: &str) -> f64 {
    let line = stdout
        .lines()
        .find(|l| l.trim_start().starts_with("peak contact pressure"))
        .unwrap_or_else(|| panic!("no peak pressure in\n{stdout}"));
    line.split_whitespace().nth(3).unwrap().parse().unwrap()
}

/// Items 1 and 5 with Lagrange multipliers (issue 18, "Lagrange
/// multipliers for deformable pairs that converge"): on the faceted master
/// the multiplier holds the punch's middle node exactly on the master
/// vertex, whose normal is undefined; the node switched segments at every
/// iteration and the run stopped, diagnosed as a status change. Now the
/// diagnosis names the segment switches and `smoothing = nodal`, and with
/// it the run converges. Measured: 31 Newton iterations (22 with the
/// semi-smooth active set, the faceted run still stops), force 1390.85
/// (penalty k = 1e7 on the same meshes: 1371.2, lower by its penetration
/// p / k ~ 2e-4 against a stroke of 0.01).
#[test]
fn lagrange_punch_converges_with_nodal_smoothing_and_faceted_is_diagnosed() {
    let dir = tempfile::tempdir().unwrap();
    let o = run(
        "punch_on_block_nonmatching_lagrange.ctc",
        dir.path(),
        &["-q"],
        Duration::from_secs(120),
    );
    assert!(o.success, "{}{}", o.stdout, o.stderr);
    let s = summary(dir.path());
    assert_eq!(s["cutbacks"], 0);
    assert!(s["newton_iterations"].as_u64().unwrap() <= 40);
    let lagrange = last_history(dir.path(), "contact_force(punch.bottom -> block.top)_y");
    let reaction = last_history(dir.path(), "reaction(block.bottom)_y");
    assert!((lagrange - reaction).abs() < 1e-8 * reaction);
    // the penalty solution of the same meshes, below by its penetration
    let pdir = tempfile::tempdir().unwrap();
    let o = run(
        "punch_on_block_nonmatching.ctc",
        pdir.path(),
        &["-q"],
        Duration::from_secs(120),
    );
    assert!(o.success);
    let penalty = last_history(pdir.path(), "contact_force(punch.bottom -> block.top)_y");
    let rel = (lagrange - penalty) / lagrange;
    assert!(
        rel > 0.0 && rel < 0.03,
        "lagrange {lagrange} penalty {penalty}"
    );
    // faceted: fails, and says why (no status change: segment switches)
    let text = std::fs::read_to_string(deck("punch_on_block_nonmatching_lagrange.ctc")).unwrap();
    let fdir = tempfile::tempdir().unwrap();
    let (o, _) = run_text(
        fdir.path(),
        "faceted.ctc",
        &text.replace("smoothing = nodal", "smoothing = none"),
    );
    assert!(!o.success);
    assert!(
        o.stderr.contains("no contact status changes")
            && o.stderr.contains("segments [7, 8]")
            && o.stderr.contains("smoothing = nodal")
            && !o.stderr.contains("status changing back and forth"),
        "{}",
        o.stderr
    );
}

/// Item 1 (issue 18: Lagrange on two curved deformable bodies):
/// `examples/two_cylinders_hertz.ctc` with `method = lagrange { }`
/// stalled at 6.5e-5 (every slave node of the mirrored meshes sits on a
/// master vertex). With `smoothing = nodal` it converges; the answer is
/// the penalty example's within the penalty error. Measured: 4 increments,
/// 26 Newton iterations (17 with the semi-smooth active set); force 8.4994 (penalty 8.4794, -0.24 %: its
/// penetration p / k = 4.4e-4 over a stroke of 0.16 is 0.28 %); peak
/// pressure 8.803 (penalty 8.769; Hertz 2 P / (pi a) = 8.62 for the
/// half-space, a / R = 0.16).
#[test]
fn lagrange_two_cylinders_converge_with_nodal_smoothing_like_penalty() {
    let dir = tempfile::tempdir().unwrap();
    let o = run(
        "two_cylinders_lagrange.ctc",
        dir.path(),
        &[],
        Duration::from_secs(300),
    );
    assert!(o.success, "{}{}", o.stdout, o.stderr);
    let s = summary(dir.path());
    assert_eq!(s["cutbacks"], 0);
    assert!(s["newton_iterations"].as_u64().unwrap() <= 35);
    let col = "contact_force(upper.arc -> lower.arc)_y";
    let lagrange = last_history(dir.path(), col);
    let p_lagrange = peak_pressure(&o.stdout);
    let example = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/two_cylinders_hertz.ctc");
    let pdir = tempfile::tempdir().unwrap();
    let args: Vec<&std::ffi::OsStr> = vec![
        "run".as_ref(),
        example.as_os_str(),
        "-o".as_ref(),
        pdir.path().as_os_str(),
    ];
    let o = ctc(&args, Duration::from_secs(300));
    assert!(o.success);
    let penalty = last_history(pdir.path(), col);
    let p_penalty = peak_pressure(&o.stdout);
    // penalty error: its penetration over the stroke (0.16)
    let penalty_error = p_penalty / 2e4 / 0.16;
    let rel = (lagrange - penalty) / lagrange;
    assert!(
        rel > 0.0 && rel < 2.0 * penalty_error,
        "lagrange {lagrange} penalty {penalty} ({penalty_error})"
    );
    assert!(
        (p_lagrange - p_penalty).abs() < 0.01 * p_lagrange,
        "{p_lagrange} {p_penalty}"
    );
}

/// Item 1 without smoothing (issue 18, the semi-smooth active set of
/// node-to-segment Lagrange pairs, `contact::semismooth`):
/// `examples/two_cylinders_hertz.ctc` with `method = lagrange { }` on the
/// faceted master stopped at t = 0.031 after 10 cutbacks while the active
/// set was decided between Newton loops. Decided inside Newton it
/// completes. Measured (`ctc run`, debug): 4 increments, 18 Newton
/// iterations, no cutback, force 8.4994 (the smoothed deck's 8.4994;
/// penalty 8.4794), penetration 2.6e-15.
#[test]
fn lagrange_two_cylinders_converge_on_the_faceted_master() {
    let example = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/two_cylinders_hertz.ctc");
    let text = std::fs::read_to_string(example).unwrap();
    let penalty = "method   = penalty { kind = area  stiffness = 2e4 }";
    assert!(text.contains(penalty));
    let dir = tempfile::tempdir().unwrap();
    let (o, out) = run_text(
        dir.path(),
        "faceted.ctc",
        &text.replace(penalty, "method = lagrange { }"),
    );
    assert!(o.success, "{}{}", o.stdout, o.stderr);
    let s = summary(&out);
    assert_eq!(s["cutbacks"], 0);
    assert!(s["newton_iterations"].as_u64().unwrap() <= 24, "{s}");
    // the smoothed deck's force (tests/decks/two_cylinders_lagrange.ctc,
    // 8.4994): the faceted and smoothed normals agree at the nodes
    let force = last_history(&out, "contact_force(upper.arc -> lower.arc)_y");
    assert!((force - 8.4994).abs() < 1e-3, "{force}");
}

/// The last `reaction(upper.top)` (x, y) of a run of `text` (a deck).
fn final_reaction(text: &str) -> [f64; 2] {
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path().join("deck.ctc");
    std::fs::write(&d, text).unwrap();
    let out = tmp.path().join("out");
    let o = ctc(
        &[
            "run".as_ref(),
            d.as_os_str(),
            "-q".as_ref(),
            "-o".as_ref(),
            out.as_os_str(),
        ],
        Duration::from_secs(120),
    );
    assert!(o.success, "{}{}", o.stdout, o.stderr);
    [
        last_history(&out, "reaction(upper.top)_x"),
        last_history(&out, "reaction(upper.top)_y"),
    ]
}

/// Item 11: the first touch of a node-to-segment pair follows
/// `first_impact = intersect` (the stick point is where the node met the
/// moving segment) instead of being frictionless, so the result no longer
/// depends on the first increment's size. Two blocks touching at t = 0,
/// pressed and sheared at once (an elastic stick interface: the solution
/// is path independent): 1 and 4 increments give the same forces; with
/// `first_impact = frictionless` (what node-to-segment pairs did before)
/// the shear force differs by most of its value. With an initial gap of
/// 0.002 (touch at t = 0.2), 5 and 10 increments agree too.
#[test]
fn first_impact_intersect_makes_node_to_segment_friction_independent_of_the_first_increment() {
    let text = std::fs::read_to_string(deck("touching_blocks_friction.ctc")).unwrap();
    let with = |n: usize, impact: &str, gap: bool| {
        let mut t = text
            .replace("increments = 4", &format!("increments = {n}"))
            .replace(
                "first_impact = intersect",
                &format!("first_impact = {impact}"),
            );
        if gap {
            t = t.replace("origin = (0.5, 0)", "origin = (0.5, 0.002)");
        }
        final_reaction(&t)
    };
    let rel = |a: [f64; 2], b: [f64; 2]| {
        let scale = b[0].hypot(b[1]);
        [(a[0] - b[0]).abs() / scale, (a[1] - b[1]).abs() / scale]
    };
    let (one, four) = (with(1, "intersect", false), with(4, "intersect", false));
    let d = rel(one, four);
    eprintln!("intersect, touching: 1 vs 4 increments: {one:?} {four:?} rel {d:?}");
    assert!(
        four[0] > 0.05 * four[1].abs(),
        "a real shear force: {four:?}"
    );
    assert!(d[0] < 1e-9 && d[1] < 1e-9, "{d:?}");
    let (one, four) = (
        with(1, "frictionless", false),
        with(4, "frictionless", false),
    );
    let d = rel(one, four);
    eprintln!("frictionless, touching: 1 vs 4 increments: {one:?} {four:?} rel {d:?}");
    assert!(
        d[0] > 0.01,
        "the old behaviour depends on the increment: {d:?}"
    );
    let (five, ten) = (with(5, "intersect", true), with(10, "intersect", true));
    let d = rel(five, ten);
    eprintln!("intersect, gap 0.002: 5 vs 10 increments: {five:?} {ten:?} rel {d:?}");
    assert!(d[0] < 1e-9 && d[1] < 1e-9, "{d:?}");
    let (five, ten) = (
        with(5, "frictionless", true),
        with(10, "frictionless", true),
    );
    let d = rel(five, ten);
    eprintln!("frictionless, gap 0.002: 5 vs 10 increments: {five:?} {ten:?} rel {d:?}");
    assert!(d[0] > 0.005, "{d:?}");
    // --explain says what happens at the first touch of this pair
    let d = deck("touching_blocks_friction.ctc");
    let o = ctc(
        &["check".as_ref(), "--explain".as_ref(), d.as_os_str()],
        Duration::from_secs(60),
    );
    assert!(
        o.stdout
            .contains("first impact: stick point where the node met the master segment"),
        "{}",
        o.stdout
    );
}

/// Final positions `X + u` of the points of the last increment's VTU in
/// `dir` (`inc_NNNN.vtu`, the highest number).
fn final_positions(dir: &Path) -> Vec<[f64; 2]> {
    let mut vtus: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| {
            p.file_name()
                .and_then(|n| n.to_str())
                .is_some_and(|n| n.starts_with("inc_") && n.ends_with(".vtu"))
        })
        .collect();
    vtus.sort();
    let last = vtus.last().expect("a VTU file");
    let bytes = std::fs::read(last).unwrap();
    let v = ctc_engine::output::vtu_read::Vtu::read(&bytes).unwrap();
    use ctc_engine::output::vtu_read::Section;
    let x = v
        .array(Section::Points, "coordinates")
        .unwrap()
        .values
        .clone();
    let u = v
        .array(Section::PointData, "displacement")
        .unwrap()
        .values
        .clone();
    x.chunks(3)
        .zip(u.chunks(3))
        .map(|(x, u)| [x[0] + u[0], x[1] + u[1]])
        .collect()
}

/// Largest distance between matching points of `a` and `b`.
fn max_distance(a: &[[f64; 2]], b: &[[f64; 2]]) -> f64 {
    assert_eq!(a.len(), b.len());
    a.iter()
        .zip(b)
        .map(|(p, q)| (p[0] - q[0]).hypot(p[1] - q[1]))
        .fold(0.0, f64::max)
}

/// Item 8: force control of a body held only by contact. A quarter
/// cylinder pushed by a pressure onto a block, nothing else holding it in
/// y, failed at t = 0 at every dt ("contacts 0", singular along y).
/// - The deck (touching start, `newton { stabilize }`): converges; the
///   contact force and the reaction equal the pressure resultant 2 to
///   1e-8; the stabilization energy is below 5 % of the internal work and
///   its force is 0 at the step end (factor ramped to 0).
/// - Without `stabilize`: the touching node starts closed, the run
///   converges to the same final state (the end state of the stabilized
///   run is unstabilized equilibrium).
/// - Lifted 1e-3 above the block (an open gap): without `stabilize` the
///   run fails singular at t = 0 and the remedy names `newton { stabilize
///   }` and the body; with it, the cylinder settles onto the block and
///   ends in the same deformed configuration.
#[test]
fn force_controlled_body_held_only_by_contact_is_stabilized() {
    let name = "force_controlled_cylinder_on_block.ctc";
    let dir = tempfile::tempdir().unwrap();
    let o = run(name, dir.path(), &[], Duration::from_secs(120));
    assert!(o.success, "{}{}", o.stdout, o.stderr);
    assert!(
        o.stdout.contains("stabilization (step `press`"),
        "{}",
        o.stdout
    );
    let s = summary(dir.path());
    let resultant = 2.0;
    let contact = last_history(dir.path(), "contact_force(cylinder.arc -> block.top)_y");
    let reaction = last_history(dir.path(), "reaction(block.bottom)_y");
    let st = &s["stabilization"][0];
    let incs = s["increments"].as_array().unwrap();
    eprintln!(
        "stabilized: {} increments, {} Newton iterations, {} cutbacks; contact {contact:.12e} \
         (rel {:.1e}), reaction {reaction:.12e} (rel {:.1e}); energy {} / internal {} = {}; \
         end force {}",
        incs.len(),
        s["newton_iterations"],
        s["cutbacks"],
        (contact - resultant).abs() / resultant,
        (reaction - resultant).abs() / resultant,
        st["energy"],
        st["internal_energy"],
        st["ratio"],
        st["end_force"]
    );
    assert!((contact - resultant).abs() < 1e-8 * resultant, "{contact}");
    assert!(
        (reaction - resultant).abs() < 1e-8 * resultant,
        "{reaction}"
    );
    assert_eq!(st["bodies"][0], "cylinder");
    assert_eq!(st["completed"], true);
    assert_eq!(st["end_force"].as_f64(), Some(0.0));
    let ratio = st["ratio"].as_f64().unwrap();
    assert!(ratio > 0.0 && ratio < 0.05, "{ratio}");
    let last = incs.last().unwrap();
    assert_eq!(last["stabilization"]["factor"].as_f64(), Some(0.0));
    assert!(incs[0]["stabilization"]["factor"].as_f64().unwrap() > 0.0);
    let stabilized = final_positions(dir.path());
    let text = std::fs::read_to_string(deck(name)).unwrap();
    assert!(text.contains("stabilize }"));
    // the same deck without stabilization: the touching start alone
    let plain = tempfile::tempdir().unwrap();
    let (o, out) = run_text(plain.path(), "plain.ctc", &text.replace("stabilize }", "}"));
    assert!(o.success, "{}{}", o.stdout, o.stderr);
    let d = max_distance(&final_positions(&out), &stabilized);
    eprintln!("stabilized vs unstabilized final positions: max distance {d:.2e}");
    assert!(d < 1e-9, "{d}");
    // lifted 1e-3: the gap is open at the start
    let lifted = text.replace("center = (0, 1)", "center = (0, 1.001)");
    assert_ne!(lifted, text);
    let open = tempfile::tempdir().unwrap();
    let (o, _) = run_text(open.path(), "open.ctc", &lifted.replace("stabilize }", "}"));
    assert!(!o.success, "{}", o.stdout);
    assert!(
        o.stderr.contains("could not advance from time t = 0")
            && o.stderr.contains("singular")
            && o.stderr
                .contains("`cylinder` is held only by contact, which is still open at t = 0")
            && o.stderr
                .contains("add `newton { stabilize }` to step `press`"),
        "{}",
        o.stderr
    );
    let settled = tempfile::tempdir().unwrap();
    let (o, out) = run_text(settled.path(), "settled.ctc", &lifted);
    assert!(o.success, "{}{}", o.stdout, o.stderr);
    let s = summary(&out);
    let contact = last_history(&out, "contact_force(cylinder.arc -> block.top)_y");
    let d = max_distance(&final_positions(&out), &stabilized);
    eprintln!(
        "lifted 1e-3 and stabilized: {} increments, {} Newton iterations, ratio {}, contact rel \
         {:.1e}, final positions vs touching start: max distance {d:.2e}",
        s["increments"].as_array().unwrap().len(),
        s["newton_iterations"],
        s["stabilization"][0]["ratio"],
        (contact - resultant).abs() / resultant
    );
    assert!((contact - resultant).abs() < 1e-8 * resultant, "{contact}");
    assert!(d < 1e-8, "{d}");
    // a stabilization too strong for the problem is warned about
    let strong = tempfile::tempdir().unwrap();
    let (o, out) = run_text(
        strong.path(),
        "strong.ctc",
        &lifted.replace("stabilize }", "stabilize = 1e-3 }"),
    );
    assert!(o.success, "{}{}", o.stdout, o.stderr);
    let ratio = summary(&out)["stabilization"][0]["ratio"].as_f64().unwrap();
    eprintln!("stabilize = 1e-3, lifted: ratio {ratio}");
    assert!(ratio > 0.05, "{ratio}");
    let warnings = summary(&out)["warnings"].to_string();
    assert!(
        warnings.contains("the stabilization energy is") && warnings.contains("lower `stabilize`"),
        "{warnings}"
    );
    // nothing to stabilize: said so
    let held = tempfile::tempdir().unwrap();
    let (o, out) = run_text(
        held.path(),
        "held.ctc",
        &text
            .replace(
                "fix cylinder.axis { ux }",
                "fix cylinder.axis { ux }\nfix cylinder.flat { uy }",
            )
            .replace("pressure cylinder.flat { p = ramp(0, 2) }", ""),
    );
    assert!(o.success, "{}{}", o.stdout, o.stderr);
    let warnings = summary(&out)["warnings"].to_string();
    assert!(warnings.contains("has nothing to act on"), "{warnings}");
    // the other enforcements: touching (closed start) and lifted (stabilized)
    for method in [
        "lagrange { }",
        "augmented_lagrange { penalty = 1e4  tolerance = 1e-5 }",
    ] {
        for (start, deck_text) in [("touching", &text), ("lifted", &lifted)] {
            let dir = tempfile::tempdir().unwrap();
            let (o, out) = run_text(
                dir.path(),
                "method.ctc",
                &deck_text.replace("penalty { kind = area  stiffness = 1e4 }", method),
            );
            assert!(o.success, "{method} {start}: {}{}", o.stdout, o.stderr);
            let contact = last_history(&out, "contact_force(cylinder.arc -> block.top)_y");
            let s = summary(&out);
            eprintln!(
                "{method}, {start}: {} Newton iterations, {} cutbacks, ratio {}, contact rel {:.1e}",
                s["newton_iterations"],
                s["cutbacks"],
                s["stabilization"][0]["ratio"],
                (contact - resultant).abs() / resultant
            );
            assert!(
                (contact - resultant).abs() < 1e-8 * resultant,
                "{method} {start}: {contact}"
            );
        }
    }
}
