//! Velocity and acceleration fields in the VTU output of dynamic runs,
//! mass-proportional Rayleigh damping on a free translation, and the
//! `spring` / `point_mass` deck items on a one-dof oscillator (issue 19).
//!
//! Reference: a rigid translation under `C = alpha M` obeys `v' = -alpha
//! v`; the average-acceleration Newmark rule is the trapezoidal rule on it,
//! so after n increments `v_n = v0 ((1 - alpha dt / 2) / (1 + alpha dt /
//! 2))^n` exactly (Hughes, The Finite Element Method, 2000, section 9.3:
//! the trapezoidal rule on a first-order system), `a_n = -alpha v_n`, and
//! the damping dissipates `K0 - K_n` (the energy audit's `damping_work`).
//!
//! ```text
//!   [=== bar ===] --> v0,  no support, no load:  v(t) = v0 exp(-alpha t)
//! ```

use ctc_engine::model::Model;
use ctc_engine::output::vtu_read::Vtu;
use ctc_engine::output::ResultWriter;
use ctc_engine::solve;

const DECK: &str = "analysis { dimension = plane_strain }
material m { elastic { E = 1  nu = 0 }  density = 2 }
body bar { mesh = rectangle { origin = (0, 0)  size = (4, 1)  divisions = (4, 1) }  material = m }
initial_velocity bar.all { vx = 0.5  vy = -0.25 }
step fly {
  time = 0 .. 2
  increments = 8
  dynamic { scheme = newmark  mass = lumped  rayleigh_alpha = 0.3 }
  newton { tol = 1e-12 }
}
output { fields = [displacement, velocity, acceleration] }
";

fn compile(text: &str) -> Result<Model, String> {
    let source = ctc_lang::Source::new(std::path::Path::new("fields.ctc"), text.to_string());
    ctc_lang::compile(&source).map_err(|d| d.render(&source))
}

#[test]
fn vtu_velocity_and_acceleration_follow_the_damped_translation() {
    let model = compile(DECK).unwrap();
    let tmp = tempfile::tempdir().unwrap();
    let mut w = ResultWriter::create(tmp.path(), &model).unwrap();
    let summary = solve::run(&model, &mut w).unwrap();
    w.finish(&summary).unwrap();
    let (alpha, dt, n) = (0.3, 0.25, 8);
    let ratio: f64 = (1.0 - 0.5 * alpha * dt) / (1.0 + 0.5 * alpha * dt);
    let v0 = [0.5, -0.25];
    let vtu = Vtu::read_file(&tmp.path().join(format!("inc_{n:04}.vtu"))).unwrap();
    let v = vtu.point("velocity").expect("velocity array");
    let a = vtu.point("acceleration").expect("acceleration array");
    assert_eq!((v.components, a.components), (3, 3));
    assert_eq!(v.values.len(), 3 * model.mesh.nodes.len());
    let mut worst: f64 = 0.0;
    for (vn, an) in v.values.chunks(3).zip(a.values.chunks(3)) {
        for k in 0..2 {
            let exact = v0[k] * ratio.powi(n);
            worst = worst
                .max((vn[k] - exact).abs() / v0[k].abs())
                .max((an[k] + alpha * exact).abs() / (alpha * v0[k].abs()));
        }
        assert_eq!((vn[2], an[2]), (0.0, 0.0));
    }
    assert!(worst < 1e-12, "velocity / acceleration error {worst:e}");
    // the damping's dissipation closes the balance: K0 - K = W_d
    let e = summary.energy.unwrap();
    let mass = 2.0 * 4.0; // rho A (unit thickness)
    let k0 = 0.5 * mass * (v0[0] * v0[0] + v0[1] * v0[1]);
    let k = k0 * ratio.powi(2 * n);
    assert!((e.kinetic - k).abs() < 1e-12 * k0, "{e:?}");
    assert!((e.damping - (k0 - k)).abs() < 1e-12 * k0, "{e:?}");
    assert!(e.balance.abs() < 1e-12 * k0, "{e:?}");
    // history.csv carries the damping work column
    let history = std::fs::read_to_string(tmp.path().join("history.csv")).unwrap();
    assert!(history.lines().next().unwrap().contains("damping_work"));
}

#[test]
fn velocity_output_in_a_quasi_static_analysis_is_refused_with_its_location() {
    let text = DECK
        .replace(
            "  dynamic { scheme = newmark  mass = lumped  rayleigh_alpha = 0.3 }\n",
            "",
        )
        .replace(
            "initial_velocity bar.all { vx = 0.5  vy = -0.25 }\n",
            "fix bar.left { ux uy }\n",
        );
    let e = compile(&text).unwrap_err();
    assert!(
        e.contains("output field `velocity` in a quasi-static analysis")
            && e.contains("fields.ctc:10:34")
            && e.contains("output field `acceleration`"),
        "{e}"
    );
}

/// Collects the x displacement of node 0 after every increment.
struct Track(Vec<f64>);

impl solve::Observer for Track {
    fn converged(&mut self, v: &solve::IncrementView<'_>) -> Result<(), String> {
        self.0.push(v.displacement[0][0]);
        Ok(())
    }
}

/// `spring` and `point_mass` items (issue 19): a one-cell block (mass 4,
/// lumped 1 per node) carrying a point mass 1 and a ground spring 8 at each
/// node, sliding along x: one dof with `omega^2 = 8 / 2 = 4`.
/// Reference: the average-acceleration rule on `m x'' + k x = 0`, `x(0) =
/// 0`, `x'(0) = v0`, is exactly `x_n = (v0 / omega) sin(n theta)`, `theta
/// = 2 atan(omega dt / 2)` (its energy is conserved and `x_1 = dt v0 / (1
/// + (omega dt)^2 / 4)`; Hughes 2000, section 9.3.2); the exact solution
/// `(v0 / omega) sin(omega t)` differs by the rule's period elongation.
///
/// ```text
///   |/\/\/\[ m ] --> v0
/// ```
#[test]
fn spring_and_point_mass_items_make_the_closed_form_oscillator() {
    let deck = "analysis { dimension = plane_strain }
material m { elastic { E = 1  nu = 0 }  density = 4 }
body block { mesh = rectangle { origin = (0, 0)  size = (1, 1)  divisions = (1, 1) }  material = m }
fix block.all { uy }
spring block.all { stiffness = 8 }
point_mass block.all { mass = 1 }
initial_velocity block.all { vx = 1 }
step vibrate {
  time = 0 .. 3 * pi
  increments = 120
  dynamic { scheme = newmark  mass = lumped }
  newton { tol = 1e-12 }
}
";
    let model = compile(deck).unwrap();
    assert_eq!(model.discrete.len(), 2);
    let mut track = Track(Vec::new());
    let summary = solve::run(&model, &mut track).unwrap();
    assert_eq!(track.0.len(), 120);
    let (omega, dt) = (2.0f64, 3.0 * std::f64::consts::PI / 120.0);
    let theta = 2.0 * (omega * dt / 2.0).atan();
    let amplitude = 1.0 / omega;
    let mut rule: f64 = 0.0;
    let mut exact: f64 = 0.0;
    for (n, u) in track.0.iter().enumerate() {
        let k = (n + 1) as f64;
        rule = rule.max((u - amplitude * (k * theta).sin()).abs() / amplitude);
        exact = exact.max((u - amplitude * (omega * k * dt).sin()).abs() / amplitude);
    }
    // measured: 1.2e-14 against the rule, 3.86e-2 against the exact
    // solution (phase lag 120 (omega dt)^3 / 12 = 3.9e-2 rad)
    assert!(rule < 1e-11, "against the discrete closed form: {rule:e}");
    assert!(
        exact > 1e-2 && exact < 5e-2,
        "against the exact solution: {exact:e}"
    );
    let e = summary.energy.unwrap();
    // kinetic energy of the total mass 8 (4 cell + 4 point) at v0 = 1
    assert!((e.kinetic + e.internal - 4.0).abs() < 1e-11, "{e:?}");
}

/// `history.csv`'s `friction_work[..]` column is the friction work of
/// each increment, not a running total (the energy columns beside it are
/// totals since the start): its rows are the summary's increments'
/// `friction_work`, its sum summary.json's `friction_work`, and `ctc doc
/// outputs` says so. The 3D tube's "8.1e-3 mJ from history.csv against
/// the case's 128 mJ" (stop 50's NOT-done list) was the column's last row:
/// `ctc run examples/dynamic_buckling_3d.ctc` (debug, --threads 1): the
/// last row 2.03e-3 mJ (x 4 for the full tube: 8.1e-3), the column's sum
/// 32.107 mJ (x 4: 128.4 mJ, the case's sum of the die nodes'
/// dissipations), summary.json's `friction_work` 32.107 mJ. The deck: a
/// block (1 x 1 x 0.5, rho 1e-3) pressed on a rigid floor (tz = -1, mu =
/// 0.3) slides at vx = 2 and is stopped by friction within the step
/// (`tests/decks/friction_slide_3d.ctc`, as `robust_restart`'s).
#[test]
fn history_friction_work_is_per_increment() {
    let text = include_str!("../decks/friction_slide_3d.ctc");
    let source = ctc_lang::Source::new(
        std::path::Path::new("friction_slide_3d.ctc"),
        text.to_string(),
    );
    let model = match ctc_lang::compile_any(&source) {
        Ok(ctc_engine::model::AnyModel::D3(m)) => m,
        Ok(_) => panic!("a 3d deck"),
        Err(d) => panic!("{}", d.render(&source)),
    };
    let tmp = tempfile::tempdir().unwrap();
    let mut w = ResultWriter::create(tmp.path(), &model).unwrap();
    let summary = solve::run(&model, &mut w).unwrap();
    w.finish(&summary).unwrap();
    let history = std::fs::read_to_string(tmp.path().join("history.csv")).unwrap();
    let mut lines = history.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let rows: Vec<Vec<f64>> = lines
        .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
        .collect();
    let col = |name: &str| {
        let k = header
            .iter()
            .position(|h| h.starts_with(name))
            .unwrap_or_else(|| panic!("no column {name} in {header:?}"));
        rows.iter().map(|r| r[k]).collect::<Vec<f64>>()
    };
    let friction = col("friction_work[");
    assert_eq!(friction.len(), summary.increments.len());
    for (row, inc) in friction.iter().zip(&summary.increments) {
        assert_eq!(*row, inc.friction_work[0]);
    }
    let total: f64 = friction.iter().sum();
    assert!(
        friction.iter().filter(|w| **w > 0.0).count() >= 5,
        "{friction:?}"
    );
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(tmp.path().join("summary.json")).unwrap())
            .unwrap();
    let reported = json["friction_work"][0].as_f64().unwrap();
    assert!(
        (reported - total).abs() <= 1e-12 * total,
        "summary.json {reported} vs the column's sum {total}"
    );
    assert!(*friction.last().unwrap() < 0.5 * total, "{friction:?}");
    // the energy columns are totals: the last row is the run's
    let e = summary.energy.unwrap();
    assert_eq!(*col("contact_work").last().unwrap(), e.contact);
    let doc = ctc_lang::reference::doc(Some("outputs")).unwrap();
    assert!(
        doc.contains("the friction work of the increment per pair")
            && doc.contains("totals since the start"),
        "{doc}"
    );
}
