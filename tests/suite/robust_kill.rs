//! A run killed mid-way (SIGKILL) leaves every finished increment readable
//! (issue 10, "no data loss"), and `ctc run --restart` then finishes it
//! with the same results as an uninterrupted run.
//!
//! The `ctc` binary runs the skin-pass example (finite-strain plasticity,
//! 20 increments, output every increment, ~1.5 s in the dev profile); the
//! test kills it as soon as two increments are on disk, then checks: the
//! PVD index parses and lists increasing times; every VTU it references
//! exists, is complete XML and has the model's point count with complete
//! arrays; every history.csv line is complete (all columns, all numbers)
//! and there is at least one row per indexed VTU.

use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

fn deck(dir: &Path) -> std::path::PathBuf {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/skin_pass.ctc");
    let text = std::fs::read_to_string(src)
        .unwrap()
        .replace("every = 5", "every = 1");
    let path = dir.join("skin_pass_every1.ctc");
    std::fs::write(&path, text).unwrap();
    path
}

fn node_count(deck: &Path) -> usize {
    let source = ctc_lang::Source::read(deck).unwrap();
    ctc_lang::compile(&source).unwrap().mesh.nodes.len()
}

/// `file="..."` entries of a PVD index for the bodies (part 0), with
/// their times; the rigid tools' files (the other parts) must exist and
/// read as VTU files.
fn pvd_entries(text: &str, dir: &Path) -> Vec<(f64, String)> {
    assert!(text.starts_with("<?xml"), "pvd header");
    assert!(text.trim_end().ends_with("</VTKFile>"), "pvd incomplete");
    for l in text
        .lines()
        .filter(|l| l.contains("<DataSet") && !l.contains("part=\"0\""))
    {
        let start = l.find("file=\"").unwrap() + 6;
        let file = &l[start..start + l[start..].find('"').unwrap()];
        assert!(file.starts_with("tool_"), "{l}");
        let bytes = std::fs::read(dir.join(file)).unwrap();
        ctc_engine::output::vtu_read::Vtu::read(&bytes).unwrap_or_else(|e| panic!("{file}: {e}"));
    }
    text.lines()
        .filter(|l| l.contains("<DataSet") && l.contains("part=\"0\""))
        .map(|l| {
            let attr = |name: &str| {
                let start = l.find(&format!("{name}=\"")).unwrap() + name.len() + 2;
                let end = start + l[start..].find('"').unwrap();
                l[start..end].to_string()
            };
            (attr("timestep").parse().unwrap(), attr("file"))
        })
        .collect()
}

/// Checks one VTU file: complete file, point count, complete displacement array.
fn check_vtu(path: &Path, nodes: usize) {
    let bytes = std::fs::read(path).unwrap();
    assert!(
        String::from_utf8_lossy(&bytes)
            .trim_end()
            .ends_with("</VTKFile>"),
        "{} incomplete",
        path.display()
    );
    let vtu = ctc_engine::output::vtu_read::Vtu::read(&bytes)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    assert_eq!(vtu.points, nodes);
    let values = &vtu.point("displacement").unwrap().values;
    assert_eq!(values.len(), 3 * nodes, "{}", path.display());
    assert!(values.iter().all(|v| v.is_finite()));
}

/// Checks the result directory after a kill; returns the indexed increments.
fn check_dir(dir: &Path, nodes: usize) -> usize {
    let pvd = std::fs::read_to_string(dir.join("results.pvd")).unwrap();
    let entries = pvd_entries(&pvd, dir);
    for w in entries.windows(2) {
        assert!(w[0].0 < w[1].0, "pvd times not increasing");
    }
    for (_, file) in &entries {
        check_vtu(&dir.join(file), nodes);
    }
    let history = std::fs::read_to_string(dir.join("history.csv")).unwrap();
    assert!(history.ends_with('\n'), "history.csv ends mid-line");
    let mut lines = history.lines();
    let cols = lines.next().unwrap().split(',').count();
    let mut rows = 0;
    for l in lines {
        let v: Vec<&str> = l.split(',').collect();
        assert_eq!(v.len(), cols, "incomplete history row `{l}`");
        assert!(v.iter().all(|x| x.parse::<f64>().is_ok()), "row `{l}`");
        rows += 1;
    }
    assert!(rows >= entries.len(), "{rows} rows, {} vtu", entries.len());
    entries.len()
}

#[test]
fn killed_run_leaves_every_finished_increment_readable_and_restart_completes_it() {
    let tmp = tempfile::tempdir().unwrap();
    let deck = deck(tmp.path());
    let nodes = node_count(&deck);
    let out = tmp.path().join("killed");
    let mut child = Command::new(env!("CARGO_BIN_EXE_ctc"))
        .args([
            "run",
            deck.to_str().unwrap(),
            "-q",
            "-o",
            out.to_str().unwrap(),
        ])
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let start = Instant::now();
    // kill as soon as two increments are indexed (mid-run)
    loop {
        let n = std::fs::read_to_string(out.join("results.pvd"))
            .map(|t| t.matches("part=\"0\"").count())
            .unwrap_or(0);
        if n >= 2 {
            break;
        }
        assert!(
            child.try_wait().unwrap().is_none(),
            "the run ended before it could be killed"
        );
        assert!(start.elapsed() < Duration::from_secs(120), "run too slow");
        std::thread::sleep(Duration::from_millis(5));
    }
    assert!(
        child.try_wait().unwrap().is_none(),
        "finished before the kill"
    );
    child.kill().unwrap(); // SIGKILL
    child.wait().unwrap();
    let indexed = check_dir(&out, nodes);
    assert!((2..20).contains(&indexed), "{indexed} increments indexed");
    eprintln!(
        "killed after {:.2} s with {indexed} of 20 increments indexed",
        start.elapsed().as_secs_f64()
    );
    assert!(
        !out.join("summary.json").exists(),
        "a killed run cannot have written its summary"
    );

    // continue the killed run, and run the deck uninterrupted
    let status = Command::new(env!("CARGO_BIN_EXE_ctc"))
        .args(["run", deck.to_str().unwrap(), "-q", "--restart", "-o"])
        .arg(&out)
        .status()
        .unwrap();
    assert!(status.success());
    let full = tmp.path().join("full");
    let status = Command::new(env!("CARGO_BIN_EXE_ctc"))
        .args(["run", deck.to_str().unwrap(), "-q", "-o"])
        .arg(&full)
        .status()
        .unwrap();
    assert!(status.success());
    assert_eq!(check_dir(&out, nodes), 20);
    for entry in std::fs::read_dir(&full).unwrap() {
        let name = entry.unwrap().file_name();
        let name = name.to_string_lossy();
        if name == "summary.json" || name == "restart.bin" {
            continue;
        }
        if name == "progress.sta" {
            // same increment lines; comments say where the run restarted
            let data = |d: &Path| -> Vec<String> {
                std::fs::read_to_string(d.join("progress.sta"))
                    .unwrap()
                    .lines()
                    .filter(|l| !l.starts_with('#'))
                    .map(String::from)
                    .collect()
            };
            assert_eq!(data(&full), data(&out));
            continue;
        }
        let a = std::fs::read(full.join(&*name)).unwrap();
        let b = std::fs::read(out.join(&*name)).unwrap();
        assert!(
            a == b,
            "{name} differs between the restarted and the full run"
        );
    }
}

#[test]
fn restart_without_a_restart_point_is_a_clear_error() {
    let tmp = tempfile::tempdir().unwrap();
    let deck = deck(tmp.path());
    let out = Command::new(env!("CARGO_BIN_EXE_ctc"))
        .args(["run", deck.to_str().unwrap(), "-q", "--restart", "-o"])
        .arg(tmp.path().join("nothing"))
        .output()
        .unwrap();
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("cannot read restart file"), "{err}");
}
