//! Thermo-mechanical coupling through decks: adiabatic heating by plastic
//! dissipation against the closed form, and the clear refusal to restart a
//! thermal run.

use ctc_engine::model::Model;
use ctc_engine::solve::{IncrementView, Observer};

fn compile_text(name: &str, text: &str) -> Model {
    let src = ctc_lang::Source::new(name, text);
    match ctc_lang::compile(&src) {
        Ok(m) => m,
        Err(d) => panic!("{}", d.render(&src)),
    }
}

/// Small-strain J2 cylinder (r = 1, h = 1) compressed homogeneously, no
/// friction, insulated: all the plastic work times beta stays in it.
const COMPRESSED: &str = r#"
analysis { dimension = axisymmetric }
material m {
  elastic { E = 1000  nu = 0.3 }
  plastic { yield = 2  hardening = linear { H = 100 } }
  thermal { conductivity = 1  capacity = 2  density = 0.5  taylor_quinney = 0.9 }
}
body c {
  mesh = rectangle { origin = (0, 0)  size = (1, 1)  divisions = (2, 3)  element = quad4 }
  material = m
  thermal { initial = 20 }
}
fix c.left { ux }
fix c.bottom { uy }
displace c.top { uy = ramp(0, -0.05) }
step s { time = 0 .. 1  increments = 10  newton { tol = 1e-12 } }
"#;

#[derive(Default)]
struct Temperatures {
    last: Vec<f64>,
    plastic: f64,
}

impl Observer for Temperatures {
    fn converged(&mut self, v: &IncrementView<'_>) -> Result<(), String> {
        self.last = v.temperature.unwrap().to_vec();
        self.plastic += v.thermal.unwrap().plastic;
        Ok(())
    }
}

#[test]
fn adiabatic_plastic_heating_of_a_compressed_cylinder_matches_the_closed_form() {
    let model = compile_text("compressed.ctc", COMPRESSED);
    let mut probe = Temperatures::default();
    ctc_engine::solve::run(&model, &mut probe).unwrap();
    // uniaxial stress: q = sigma_y0 + H ep, ep = (eps - sigma_y0 / E) / (1 + H / E);
    // the kernel's dissipation per increment is q_{n+1} d(ep) (backward Euler)
    let (e, sy, h, beta, rho_c) = (1000.0, 2.0, 100.0, 0.9, 1.0);
    let volume = std::f64::consts::PI;
    let mut ep_old: f64 = 0.0;
    let mut work = 0.0;
    for n in 1..=10 {
        let eps = 0.05 * n as f64 / 10.0;
        let ep = ((eps - sy / e) / (1.0 + h / e)).max(0.0);
        work += (sy + h * ep) * (ep - ep_old);
        ep_old = ep;
    }
    let heat = beta * work * volume;
    let rel = (probe.plastic - heat).abs() / heat;
    let dt = heat / (rho_c * volume);
    let worst = probe
        .last
        .iter()
        .map(|t| (t - 20.0 - dt).abs() / dt)
        .fold(0.0, f64::max);
    eprintln!(
        "adiabatic plastic heating: heat {:.12e} vs closed form {heat:.12e} (relative {rel:.1e}); \
         temperature rise {dt:.6e}, max nodal relative error {worst:.1e}",
        probe.plastic
    );
    assert!(rel < 1e-9, "{} vs {heat}", probe.plastic);
    assert!(worst < 1e-9, "{worst:e}");
}

#[test]
fn a_thermal_run_refuses_to_restart_with_a_clear_message() {
    let model = compile_text("compressed.ctc", COMPRESSED);
    let dir = tempfile::tempdir().unwrap();
    let mut writer = ctc_engine::output::ResultWriter::create(dir.path(), &model).unwrap();
    let summary = ctc_engine::solve::run(&model, &mut writer).unwrap();
    writer.finish(&summary).unwrap();
    assert!(summary.temperature_dofs > 0);
    let message = match ctc_engine::output::ResultWriter::resume(dir.path(), &model) {
        Err(e) => e,
        Ok((mut w, cp)) => {
            ctc_engine::solve::run_from(&model, &mut w, Some(&cp))
                .unwrap_err()
                .message
        }
    };
    assert!(
        message.contains("cannot restart a thermo-mechanical run"),
        "{message}"
    );
}
