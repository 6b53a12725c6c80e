//! A clamped circular plate (axisymmetric, 40 x 2 quads, radius 50,
//! thickness 1, Hencky elasticity at finite strain) under a follower
//! pressure converges like under a dead one: the tangent is non-symmetric
//! only by the load stiffness, and the line search's test along the step
//! (`du . r`) still applies. With the residual-norm test the first
//! increment halved every step to 1/32 and stalled (25 iterations,
//! residual 2.1e-1 -> 8.6e-3).
//!
//! Reference: the dead-pressure run of the same plate (3 iterations), and
//! a run without line search (3 iterations, quadratic).
//!
//! The same holds for F-bar (`formulation = selective_reduced`, whose
//! exact tangent is non-symmetric): with the residual-norm test a 100 x 2
//! plate took 1975 iterations and 7 cutbacks over 10 increments, 41
//! without line search.
//!
//! ```text
//!        p (follower)
//!   ^  ^  ^  ^  ^  ^  ^
//!   |==================|  clamped at r = 50
//!   axis
//! ```

use ctc_engine::solve::{self, IncrementView, Observer};

/// The axial displacement of node 0 (the plate's centre, bottom).
#[derive(Default)]
struct Pole(f64);

impl Observer for Pole {
    fn converged(&mut self, v: &IncrementView<'_>) -> Result<(), String> {
        self.0 = v.displacement[0][1];
        Ok(())
    }
}

fn deck(follower: bool) -> String {
    deck_with(follower, "")
}

fn deck_with(follower: bool, formulation: &str) -> String {
    format!(
        "analysis {{ dimension = axisymmetric }}
material m {{ elastic {{ E = 100e3  nu = 0.3 }} }}
body d {{
  mesh = rectangle {{ origin = (0, 0)  size = (50, 1)  divisions = (40, 2) }}
  material = m
  kinematics = finite {formulation}
}}
fix d.right {{ ux uy }}
fix d.left {{ ux }}
pressure d.bottom {{ p = 0.01  follower = {follower} }}
step s {{ time = 0 .. 1  increments = 2 }}
"
    )
}

fn iterations(follower: bool) -> (Vec<usize>, f64) {
    iterations_of(deck(follower))
}

fn iterations_of(deck: String) -> (Vec<usize>, f64) {
    let src = ctc_lang::Source::new(std::path::Path::new("plate.ctc"), deck);
    let model = ctc_lang::compile(&src).map_err(|d| d.render(&src)).unwrap();
    let mut pole = Pole::default();
    let summary = solve::run(&model, &mut pole).unwrap();
    assert!(summary.completed);
    let its = summary.increments.iter().map(|i| i.iterations).collect();
    (its, pole.0)
}

#[test]
fn a_plate_under_a_follower_pressure_converges_like_under_a_dead_one() {
    let (dead, pole_dead) = iterations(false);
    let (follower, pole_follower) = iterations(true);
    println!("dead {dead:?} pole {pole_dead:e}, follower {follower:?} pole {pole_follower:e}");
    assert!(follower[0] <= dead[0] + 1, "{follower:?} vs {dead:?}");
    assert!(follower.iter().all(|&n| n <= 4), "{follower:?}");
    // the pressure turns little at this deflection: the same pole
    assert!((pole_follower - pole_dead).abs() <= 1e-2 * pole_dead.abs());
}

#[test]
fn an_f_bar_plate_converges_like_a_fully_integrated_one() {
    for follower in [false, true] {
        let (full, pole_full) = iterations_of(deck_with(follower, ""));
        let (fbar, pole_fbar) =
            iterations_of(deck_with(follower, "formulation = selective_reduced"));
        println!("follower {follower}: full {full:?} pole {pole_full:e}, F-bar {fbar:?} pole {pole_fbar:e}");
        assert!(fbar.len() == full.len(), "F-bar cut back: {fbar:?}");
        assert!(fbar.iter().all(|&n| n <= 4), "{fbar:?}");
        // bending of a thin plate: full integration is stiffer (parasitic
        // shear); both stay below the clamped Kirchhoff plate
        // w = p a^4 / (64 D), D = E t^3 / (12 (1 - nu^2)) (Timoshenko &
        // Woinowsky-Krieger, Theory of plates and shells, 1959, section 62)
        let d = 100e3 / (12.0 * (1.0 - 0.09));
        let kirchhoff = 0.01 * 50f64.powi(4) / (64.0 * d);
        assert!(
            pole_full.abs() < pole_fbar.abs(),
            "{pole_full} vs {pole_fbar}"
        );
        assert!(
            pole_fbar.abs() < 1.02 * kirchhoff,
            "{pole_fbar} vs {kirchhoff}"
        );
    }
}

/// `ctc run` writes the applied value of a follower pressure driven by a
/// time function (`p = ramp(0, 0.01)`) as the `pressure[..]` column of
/// `history.csv`, and plots it against time (`pressure_time.svg`); a dead
/// pressure has no such column.
#[test]
fn ctc_run_writes_the_applied_follower_pressure_and_its_plot() {
    for follower in [true, false] {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("plate.ctc");
        let text = deck(follower)
            .replace("p = 0.01", "p = ramp(0, 0.01)")
            .replace("increments = 2", "increments = 4");
        std::fs::write(&path, text).unwrap();
        let out_dir = dir.path().join("out");
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_ctc"))
            .args(["run", "--quiet"])
            .arg(&path)
            .arg("-o")
            .arg(&out_dir)
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let hist = std::fs::read_to_string(out_dir.join("history.csv")).unwrap();
        let mut lines = hist.lines();
        let header: Vec<&str> = lines.next().unwrap().split(',').collect();
        let col = header.iter().position(|h| h.starts_with("pressure["));
        assert_eq!(col.is_some(), follower, "{header:?}");
        assert_eq!(out_dir.join("pressure_time.svg").exists(), follower);
        let Some(col) = col else { continue };
        assert_eq!(header[col], "pressure[pressure d.bottom]");
        let rows: Vec<Vec<f64>> = lines
            .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
            .collect();
        assert_eq!(rows.len(), 4);
        for r in &rows {
            // ramp(0, 0.01) over the step time 0 .. 1
            assert!((r[col] - 0.01 * r[0]).abs() <= 1e-15, "{r:?}");
        }
    }
}
