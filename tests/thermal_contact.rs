//! Verification case 8 (thermal contact): steady conduction through a
//! pressed interface with a pressure-dependent conductance, at two contact
//! pressures, against the closed form.

use ctc_engine::model::Model;
use ctc_engine::solve::{IncrementView, Observer};
use std::path::Path;

fn compile_text(name: &str, text: &str) -> Model {
    let src = ctc_lang::Source::new(name, text);
    match ctc_lang::compile(&src) {
        Ok(m) => m,
        Err(d) => panic!("{}", d.render(&src)),
    }
}

/// The last converged increment's interface data.
#[derive(Default)]
struct Interface {
    /// Contact pressure of every closed node of pair 0.
    pressure: Vec<f64>,
    /// Total contact force (y) of pair 0.
    force: f64,
    /// Temperature of the slave nodes of pair 0.
    slave_temperature: Vec<f64>,
    /// Heat power into the slave side of pair 0.
    power: f64,
}

impl Observer for Interface {
    fn converged(&mut self, v: &IncrementView<'_>) -> Result<(), String> {
        let t = v.temperature.expect("thermal scene");
        let pair = &v.contact[0];
        self.pressure = pair.iter().map(|c| c.pressure).collect();
        self.force = pair.iter().map(|c| c.force[1]).sum();
        self.slave_temperature = pair.iter().map(|c| t[c.node]).collect();
        self.power = v.thermal.expect("thermal report").contact_power[0];
        Ok(())
    }
}

/// Runs the case-8 deck with the top pushed down by `stroke`; returns the
/// relative errors (flux, interface temperature) and the pressure.
fn case8_block_on_tool(stroke: f64) -> (f64, f64, f64) {
    let path =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("verification/cases/thermal_contact_tool.ctc");
    let text = std::fs::read_to_string(&path).unwrap();
    let text = text.replace("ramp(0, -0.004)", &format!("ramp(0, {})", -stroke));
    let model = compile_text("case8.ctc", &text);
    let mut probe = Interface::default();
    ctc_engine::solve::run(&model, &mut probe).unwrap();
    // width 1, thickness 1: the pressure is the force per unit area
    let p = probe.force;
    for pi in &probe.pressure {
        assert!(
            (pi - p).abs() < 1e-9 * p,
            "non-uniform pressure {pi} vs {p}"
        );
    }
    let (k1, l1, t_hot, t_cold) = (2.0, 2.0, 100.0, 20.0);
    let h = 3.0 + 0.5 * p.sqrt();
    let q = (t_hot - t_cold) / (l1 / k1 + 1.0 / h);
    let t_i = t_cold + q / h;
    // heat leaves the block through the interface: power into the slave < 0
    let flux_error = ((-probe.power) - q).abs() / q;
    let t_error = probe
        .slave_temperature
        .iter()
        .map(|t| (t - t_i).abs() / (t_hot - t_cold))
        .fold(0.0, f64::max);
    (flux_error, t_error, p)
}

#[test]
fn case8_thermal_contact_block_on_tool_matches_the_closed_form_at_two_pressures() {
    let mut pressures = Vec::new();
    for stroke in [0.004, 0.04] {
        let (eq, et, p) = case8_block_on_tool(stroke);
        eprintln!(
            "case 8 (block on tool), p = {p:.6}: flux relative error {eq:.2e}, interface \
             temperature relative error {et:.2e}"
        );
        assert!(eq <= 1e-8, "flux error {eq:e} at p = {p}");
        assert!(et <= 1e-8, "interface temperature error {et:e} at p = {p}");
        pressures.push(p);
    }
    // two genuinely different conductances
    assert!(pressures[1] > 5.0 * pressures[0], "{pressures:?}");
}
