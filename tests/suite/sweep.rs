//! `ctc sweep`: a penalty sweep of a Hertz deck, run locally with two
//! workers and through the generated Slurm job-array script.
//!
//! Reference: Hertz line contact (cylinder R = 8 on a rigid floor, plane
//! strain, VERIFICATION-CASES.md case 1, `examples/hertz_cylinder.ctc` on a
//! coarse mesh). With the floor driven by displacement, the penalty
//! stiffness k mostly changes the penetration: g ~ p / k, so a tenfold k
//! gives about a tenth of the penetration, while the contact force stays
//! close (the body, not the penalty, carries the imposed indentation).
//!
//! ```text
//!        ____ flat (uy = ramp(0, -0.08))
//!       /    \
//!      | disc |   R = 8, E = 200, nu = 0.3
//!       \____/  penalty k = 2e3, 2e4, 2e5 (and -1: rejected by the deck)
//!   ====floor====
//! ```

use std::path::Path;
use std::process::Command;

const DECK: &str = "\
# coarse Hertz cylinder for the sweep tests
analysis { dimension = plane_strain  thickness = 1 }
material soft { elastic { E = 200  nu = 0.3 } }
body disc {
  mesh = half_disc { center = (0, 8)  radius = 8  radial = 8  circumferential = 24
                     radial_grading = geometric(0.15)  circumferential_grading = center(8)
                     upper = false  element = quad4 }
  material = soft
}
tool floor = plane { point = (0, 0)  normal = (0, 1) }
contact disc.arc -> floor {
  method = penalty { kind = area  stiffness = 2e4 }
}
fix disc.flat { ux }
displace disc.flat { uy = ramp(0, -0.08) }
step press { time = 0 .. 1  increments = 2  newton { tol = 1e-9  max_iter = 20 } }
output { every = 1  fields = [displacement]
         history = [reaction(disc.flat), contact_force(disc.arc -> floor)] }
";

const VARY: &str = "contact.method.stiffness = 2e3, 2e4, 2e5, -1";

fn ctc(cwd: &Path) -> Command {
    let mut c = Command::new(env!("CARGO_BIN_EXE_ctc"));
    c.current_dir(cwd);
    c
}

/// The rows of `sweep.csv` as (header -> value) lookups.
fn table(dir: &Path) -> Vec<Vec<(String, String)>> {
    let text = std::fs::read_to_string(dir.join("sweep.csv")).unwrap();
    let mut lines = text.lines();
    let head: Vec<String> = lines.next().unwrap().split(',').map(String::from).collect();
    lines
        .map(|l| {
            // the reason column is last and may be quoted with commas
            let mut f: Vec<String> = l.splitn(head.len(), ',').map(String::from).collect();
            f.resize(head.len(), String::new());
            head.iter().cloned().zip(f).collect()
        })
        .collect()
}

fn get<'a>(row: &'a [(String, String)], key: &str) -> &'a str {
    row.iter()
        .find(|(k, _)| k == key)
        .map(|(_, v)| v.as_str())
        .unwrap_or("")
}

fn num(row: &[(String, String)], key: &str) -> f64 {
    get(row, key).parse().unwrap_or(f64::NAN)
}

#[test]
fn sweep_hertz_penalty_two_workers_and_slurm_array() {
    let tmp = tempfile::tempdir().unwrap();
    let cwd = tmp.path();
    std::fs::write(cwd.join("hertz.ctc"), DECK).unwrap();

    // local, 2 workers
    let out = ctc(cwd)
        .args([
            "sweep",
            "hertz.ctc",
            "--vary",
            VARY,
            "--workers",
            "2",
            "-o",
            "local",
        ])
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{stdout}\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(stdout.contains("3 of 4 variants completed"), "{stdout}");
    let rows = table(&cwd.join("local"));
    assert_eq!(rows.len(), 4);
    let status: Vec<&str> = rows.iter().map(|r| get(r, "status")).collect();
    assert_eq!(
        status,
        ["completed", "completed", "completed", "deck error"]
    );
    assert!(
        get(&rows[3], "reason").contains("penalty stiffness"),
        "{:?}",
        rows[3]
    );
    let pen: Vec<f64> = rows[..3]
        .iter()
        .map(|r| num(r, "max_penetration"))
        .collect();
    let force: Vec<f64> = rows[..3]
        .iter()
        .map(|r| num(r, "contact_force(disc.arc -> floor)_y"))
        .collect();
    for w in pen.windows(2) {
        let ratio = w[0] / w[1];
        assert!(
            (5.0..12.0).contains(&ratio),
            "penetration ratio {ratio}: {pen:?}"
        );
    }
    assert!(force.iter().all(|f| *f > 0.0), "{force:?}");
    assert!(
        force[2] > force[0],
        "a stiffer penalty carries more of the indentation: {force:?}"
    );
    assert!((force[2] - force[1]) / force[2] < 0.1, "{force:?}");
    for r in &rows[..3] {
        let reaction = num(r, "reaction(disc.flat)_y");
        let contact = num(r, "contact_force(disc.arc -> floor)_y");
        assert!(
            (reaction + contact).abs() < 1e-8 * contact,
            "equilibrium {reaction} {contact}"
        );
        assert!(num(r, "newton_iterations") >= 2.0);
    }
    let svg = std::fs::read_to_string(cwd.join("local/sweep.svg")).unwrap();
    assert!(svg.starts_with("<svg") && svg.contains("max penetration"));
    let md = std::fs::read_to_string(cwd.join("local/sweep.md")).unwrap();
    assert!(md.lines().count() == 6, "{md}");

    // Slurm: the script, then each array task as Slurm would run it
    let out = ctc(cwd)
        .args([
            "sweep",
            "hertz.ctc",
            "--vary",
            VARY,
            "--slurm",
            "-o",
            "cluster",
        ])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let script = std::fs::read_to_string(cwd.join("cluster/sweep.sbatch")).unwrap();
    let sbatch: Vec<&str> = script
        .lines()
        .filter(|l| l.starts_with("#SBATCH"))
        .collect();
    assert!(sbatch.contains(&"#SBATCH --array=0-3"), "{script}");
    assert!(sbatch
        .iter()
        .any(|l| l.starts_with("#SBATCH --output=") && l.ends_with("/slurm-%A_%a.out")));
    assert!(script.starts_with("#!/bin/bash\n") && script.contains("$SLURM_ARRAY_TASK_ID"));
    assert!(
        !cwd.join("cluster/v000").exists(),
        "--slurm only writes the script"
    );
    for task in 0..4 {
        let out = Command::new("bash")
            .arg(cwd.join("cluster/sweep.sbatch"))
            .env("SLURM_ARRAY_TASK_ID", task.to_string())
            .env("CTC", env!("CARGO_BIN_EXE_ctc"))
            .output()
            .unwrap();
        assert_eq!(
            out.status.success(),
            task < 3,
            "task {task}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
    }
    let out = ctc(cwd)
        .args(["sweep", "--gather", "cluster"])
        .output()
        .unwrap();
    assert!(out.status.success());
    let cluster = table(&cwd.join("cluster"));
    for (a, b) in rows.iter().zip(&cluster) {
        for key in [
            "status",
            "max_penetration",
            "newton_iterations",
            "contact_force(disc.arc -> floor)_y",
        ] {
            assert_eq!(get(a, key), get(b, key), "{key}: same deck, same bits");
        }
    }
    let local_history = std::fs::read(cwd.join("local/v001/history.csv")).unwrap();
    let cluster_history = std::fs::read(cwd.join("cluster/v001/history.csv")).unwrap();
    assert_eq!(local_history, cluster_history);
}

#[test]
fn sweep_unknown_path_says_did_you_mean() {
    let tmp = tempfile::tempdir().unwrap();
    std::fs::write(tmp.path().join("hertz.ctc"), DECK).unwrap();
    let out = ctc(tmp.path())
        .args([
            "sweep",
            "hertz.ctc",
            "--vary",
            "contact.method.stifness = 1e4, 1e5",
        ])
        .output()
        .unwrap();
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("no key `stifness` in `contact.method`"),
        "{err}"
    );
    assert!(err.contains("did you mean `stiffness`?"), "{err}");
    assert!(err.contains("hertz.ctc:12:"), "{err}");
    assert!(
        !tmp.path().join("out").exists(),
        "nothing runs on a bad path"
    );
}

#[test]
fn sweep_gather_of_a_non_sweep_directory_is_an_error() {
    let tmp = tempfile::tempdir().unwrap();
    let out = ctc(tmp.path())
        .args(["sweep", "--gather", "."])
        .output()
        .unwrap();
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("is not a sweep directory"));
}
