//! Velocity and acceleration fields in the VTU output of dynamic runs, and
//! mass-proportional Rayleigh damping on a free translation (issue 19).
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
