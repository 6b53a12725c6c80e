//! The `ctc` binary: exit codes and what a user sees.

use std::path::Path;
use std::process::Command;

fn ctc() -> Command {
    let mut c = Command::new(env!("CARGO_BIN_EXE_ctc"));
    c.current_dir(env!("CARGO_MANIFEST_DIR"));
    c
}

#[test]
fn check_accepts_every_example() {
    for deck in [
        "examples/hertz_cylinder.ctc",
        "examples/hertz_sphere_axi.ctc",
    ] {
        let out = ctc().args(["check", deck]).output().unwrap();
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
    }
}

#[test]
fn check_explain_prints_the_plan() {
    let out = ctc()
        .args(["check", "--explain", "examples/lame_cylinder_axi.ctc"])
        .output()
        .unwrap();
    assert!(out.status.success());
    insta::assert_snapshot!(String::from_utf8_lossy(&out.stdout));
}

#[test]
fn bad_deck_gives_located_errors_and_nonzero_exit() {
    let dir = tempfile::tempdir().unwrap();
    let deck = dir.path().join("bad.ctc");
    std::fs::write(
        &deck,
        "analysis { dimension = plane_strain }\nmaterial m { elastic { E = -1  nu = 0.3 } }\n",
    )
    .unwrap();
    let out = ctc().arg("check").arg(&deck).output().unwrap();
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("bad.ctc:2:"), "{err}");
    assert!(err.contains('^'), "{err}");
}

#[test]
fn missing_deck_is_a_clean_error() {
    let out = ctc().args(["run", "no/such/deck.ctc"]).output().unwrap();
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("cannot read deck"));
}

#[test]
fn run_writes_results() {
    let dir = tempfile::tempdir().unwrap();
    let out = ctc()
        .args(["run", "examples/lame_cylinder_axi.ctc", "-q", "-o"])
        .arg(dir.path())
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    for f in ["results.pvd", "summary.json", "history.csv"] {
        assert!(Path::new(&dir.path().join(f)).exists(), "{f} missing");
    }
}

/// A deck with `analysis { units = mm_N_s }`: summary.json names the units
/// and every VTU says them in its header; the same deck without a system
/// has neither (its numbers are in the user's consistent units).
#[test]
fn run_with_a_unit_system_labels_its_results() {
    let text = std::fs::read_to_string("examples/lame_cylinder_axi.ctc").unwrap();
    let with = text.replace(
        "  dimension = axisymmetric\n",
        "  dimension = axisymmetric\n  units = mm_N_s\n",
    );
    assert_ne!(with, text);
    for (deck, units) in [(with, true), (text, false)] {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("lame.ctc");
        std::fs::write(&path, deck).unwrap();
        let out_dir = dir.path().join("out");
        let out = ctc()
            .args(["run", "-q", "-o"])
            .arg(&out_dir)
            .arg(&path)
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let summary: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(out_dir.join("summary.json")).unwrap())
                .unwrap();
        let vtu = std::fs::read(out_dir.join("inc_0002.vtu")).unwrap();
        let header = String::from_utf8_lossy(&vtu[..2000.min(vtu.len())]).into_owned();
        if units {
            let u = &summary["units"];
            assert_eq!(u["system"], "mm_N_s");
            assert_eq!(
                (u["length"].as_str(), u["stress"].as_str()),
                (Some("mm"), Some("MPa"))
            );
            assert_eq!(
                (u["force"].as_str(), u["energy"].as_str()),
                (Some("N"), Some("N*mm"))
            );
            assert!(
                header.contains("<!-- units mm_N_s: length mm, force N, stress MPa"),
                "{header}"
            );
        } else {
            assert!(summary.get("units").is_none(), "{summary}");
            assert!(!header.contains("<!-- units"), "{header}");
        }
    }
}

/// `ctc verify --list | head`: the reader closes the pipe; ctc must end
/// quietly (killed by SIGPIPE like any Unix filter), not panic in
/// `println!` ("failed printing to stdout: Broken pipe"). The read end is
/// closed before ctc starts (a pipe made here, only its write end handed to
/// ctc), so its first write always fails: closing the read end after the
/// spawn raced with ctc writing its whole list into the pipe's buffer on a
/// loaded machine.
#[cfg(unix)]
#[test]
fn closed_output_pipe_ends_quietly_without_a_panic() {
    use std::os::fd::{FromRawFd, OwnedFd};
    use std::os::unix::process::ExitStatusExt;
    use std::process::Stdio;
    let mut fds = [0; 2];
    // SAFETY: `pipe` fills two new descriptors; each is owned once below.
    assert_eq!(unsafe { libc::pipe(fds.as_mut_ptr()) }, 0);
    // SAFETY: the descriptors are open and owned by nothing else.
    let (read, write) = unsafe { (OwnedFd::from_raw_fd(fds[0]), OwnedFd::from_raw_fd(fds[1])) };
    drop(read);
    let child = ctc()
        .args(["verify", "--list"])
        .stdout(Stdio::from(write))
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let out = child.wait_with_output().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert_eq!(out.status.signal(), Some(libc::SIGPIPE), "{:?}", out.status);
}

#[test]
fn verify_of_an_unknown_case_names_the_close_ones_and_fails() {
    let out = ctc().args(["verify", "bar_impct"]).output().unwrap();
    assert_eq!(out.status.code(), Some(1));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("no verification case matches `bar_impct`")
            && err.contains("`bar_impact_wave_theory`"),
        "{err}"
    );
    assert!(String::from_utf8_lossy(&out.stdout).is_empty());
}

/// `--solver petsc` in a ctc built without the `petsc` feature: a clear
/// error saying how to get it, before anything is written.
#[cfg(not(feature = "petsc"))]
#[test]
fn run_with_the_petsc_solver_without_the_feature_says_how_to_build_it() {
    let dir = tempfile::tempdir().unwrap();
    let out = ctc()
        .args([
            "run",
            "examples/hertz_cylinder.ctc",
            "-q",
            "--solver",
            "petsc",
            "-o",
        ])
        .arg(dir.path().join("p"))
        .output()
        .unwrap();
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("--features petsc") && err.contains("petsc/install.sh"),
        "{err}"
    );
    assert!(!dir.path().join("p").exists(), "nothing written");
}

#[test]
fn threads_do_not_change_results_and_the_first_tangent_is_exported() {
    let dir = tempfile::tempdir().unwrap();
    let run = |threads: &str, extra: &[&str]| {
        let out_dir = dir.path().join(format!("t{threads}"));
        let out = ctc()
            .args([
                "run",
                "examples/hertz_cylinder.ctc",
                "-q",
                "--threads",
                threads,
                "-o",
            ])
            .arg(&out_dir)
            .args(extra)
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        out_dir
    };
    let mtx = dir.path().join("K.mtx");
    let one = run("1", &[]);
    let two = run("2", &["--export-matrix", mtx.to_str().unwrap()]);
    for f in ["contact_0_0001.csv", "history.csv"] {
        assert_eq!(
            std::fs::read(one.join(f)).unwrap(),
            std::fs::read(two.join(f)).unwrap(),
            "{f}"
        );
    }
    let summary = std::fs::read_to_string(two.join("summary.json")).unwrap();
    assert!(summary.contains("\"threads\": 2"), "{summary}");
    // the first tangent: a symmetric Matrix Market file of the free dofs
    let text = std::fs::read_to_string(&mtx).unwrap();
    let mut lines = text
        .lines()
        .filter(|l| !l.starts_with('%') || l.starts_with("%%"));
    assert_eq!(
        lines.next(),
        Some("%%MatrixMarket matrix coordinate real symmetric")
    );
    let size: Vec<usize> = lines
        .next()
        .unwrap()
        .split_whitespace()
        .map(|v| v.parse().unwrap())
        .collect();
    assert_eq!(size[0], size[1]);
    assert!(
        summary.contains(&format!("\"free_dofs\": {}", size[0])),
        "{summary}"
    );
    assert_eq!(lines.count(), size[2]);
    let side = std::fs::read_to_string(dir.path().join("K.mtx.json")).unwrap();
    assert!(side.contains("\"ok\": true"), "{side}");
    // bad thread counts and export paths: clean errors
    let bad = ctc()
        .args(["run", "examples/hertz_cylinder.ctc", "-q", "--threads", "0"])
        .output()
        .unwrap();
    assert!(!bad.status.success());
    assert!(String::from_utf8_lossy(&bad.stderr).contains("--threads must be at least 1"));
    let bad = ctc()
        .args(["run", "examples/hertz_cylinder.ctc", "-q"])
        .env("CTC_THREADS", "two")
        .output()
        .unwrap();
    assert!(!bad.status.success());
    assert!(String::from_utf8_lossy(&bad.stderr).contains("CTC_THREADS = `two`"));
    let bad = ctc()
        .args([
            "run",
            "examples/hertz_cylinder.ctc",
            "-q",
            "--export-matrix",
            "no/such/dir/K.mtx",
        ])
        .output()
        .unwrap();
    assert!(!bad.status.success());
    assert!(String::from_utf8_lossy(&bad.stderr).contains("cannot write no/such/dir/K.mtx"));
}
