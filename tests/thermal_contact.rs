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
    /// Temperature of the master segment ends of pair 0 (deformable
    /// masters).
    master_temperature: Vec<f64>,
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
        self.master_temperature = pair
            .iter()
            .filter_map(|c| c.master.as_ref())
            .flat_map(|m| [t[m.nodes[0]], t[m.nodes[1]]])
            .collect();
        self.power = v.thermal.expect("thermal report").contact_power[0];
        Ok(())
    }
}

/// Runs `verification/cases/<deck>` with its top displacement `ramp`
/// replaced by a push of `stroke`; checks that the interface pressure is
/// uniform and returns the probe and that pressure (force per unit width).
fn run_case8(deck: &str, ramp: &str, stroke: f64) -> (Interface, f64) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("verification/cases")
        .join(deck);
    let text = std::fs::read_to_string(&path).unwrap();
    assert!(text.contains(ramp), "{deck} has no `{ramp}` to replace");
    let text = text.replace(ramp, &format!("ramp(0, {})", -stroke));
    let model = compile_text(deck, &text);
    let mut probe = Interface::default();
    ctc_engine::solve::run(&model, &mut probe).unwrap();
    let p = probe.force;
    for pi in &probe.pressure {
        assert!(
            (pi - p).abs() < 1e-9 * p,
            "non-uniform pressure {pi} vs {p}"
        );
    }
    (probe, p)
}

/// Runs the case-8 deck with the top pushed down by `stroke`; returns the
/// relative errors (flux, interface temperature) and the pressure.
fn case8_block_on_tool(stroke: f64) -> (f64, f64, f64) {
    // width 1, thickness 1: the pressure is the force per unit area
    let (probe, p) = run_case8("thermal_contact_tool.ctc", "ramp(0, -0.004)", stroke);
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

const SLIDING_BLOCK: &str = r#"
analysis { dimension = plane_strain }
material m {
  elastic { E = 1000  nu = 0.3 }
  thermal { conductivity = 1  capacity = 2  density = 0.5 }
}
body block {
  mesh = rectangle { origin = (0, 0)  size = (1, 1)  divisions = (4, 4)  element = quad4 }
  material = m
  thermal { initial = 20 }
}
tool floor = plane { point = (0, 0)  normal = (0, 1) }
contact block.bottom -> floor {
  method = penalty { kind = area  stiffness = 1e6 }
  friction = coulomb { mu = 0.3  stiffness = 1e6 }
  thermal { conductance = 0  tool_temperature = 20  friction_split = 0.75 }
}
displace block.top { uy = ramp(0, -0.01, 0, 1)  ux = ramp(0, 0.5, 1, 2) }
step press { time = 0 .. 1  increments = 1  newton { tol = 1e-12  max_iter = 30 } }
step slide { time = 1 .. 2  increments = 5  newton { tol = 1e-12  max_iter = 30 } }
"#;

/// Per increment: time, normal force, heat report, friction statuses.
#[derive(Default)]
struct Sliding {
    rows: Vec<(
        f64,
        f64,
        ctc_engine::thermal::solver::ThermalIncrement,
        bool,
    )>,
}

impl Observer for Sliding {
    fn converged(&mut self, v: &IncrementView<'_>) -> Result<(), String> {
        let pair = &v.contact[0];
        let normal: f64 = pair.iter().map(|c| c.force[1]).sum();
        let all_slip = pair
            .iter()
            .all(|c| c.friction.status == ctc_engine::contact::friction::FrictionStatus::Slip);
        self.rows
            .push((v.time, normal, v.thermal.unwrap().clone(), all_slip));
        Ok(())
    }
}

#[test]
fn case8_frictional_heating_of_a_sliding_block_equals_mu_rn_slip() {
    let model = compile_text("sliding.ctc", SLIDING_BLOCK);
    let mut probe = Sliding::default();
    ctc_engine::solve::run(&model, &mut probe).unwrap();
    let (mu, split, du) = (0.3, 0.75, 0.1);
    let mut steady = 0;
    for (k, (t, rn, heat, all_slip)) in probe.rows.iter().enumerate() {
        // adiabatic block (zero conductance): what is generated is stored,
        // to the round-off of the heat content rho c V T = 1 x 20
        let scale = heat.friction.abs().max(1e-300);
        assert!(
            (heat.stored - heat.generated).abs() <= 1e-12 * 20.0,
            "t = {t}: stored {} vs generated {}",
            heat.stored,
            heat.generated
        );
        // the slave (block) receives its share, the tool the rest
        assert!((heat.generated - split * heat.friction).abs() <= 1e-12 * scale);
        // steady sliding (every node slipping at the previous and this
        // increment): each node slides by the top's increment exactly, so
        // the heat is mu R_N du
        if k >= 2 && *all_slip && probe.rows[k - 1].3 {
            let expect = mu * rn * du;
            let rel = (heat.friction - expect).abs() / expect;
            eprintln!(
                "frictional heating t = {t}: friction work {:.12e} vs mu R_N slip {expect:.12e} \
                 (relative {rel:.1e}); stored heat {:.12e} = {split} x work",
                heat.friction, heat.stored
            );
            assert!(rel < 1e-9, "t = {t}: {} vs {expect}", heat.friction);
            steady += 1;
        }
    }
    assert!(steady >= 3, "expected steady sliding increments");
}

/// Runs the two-block case-8 deck with the top pushed down by `stroke`;
/// returns the relative errors (flux, interface temperatures) and the
/// pressure.
fn case8_two_blocks(stroke: f64) -> (f64, f64, f64) {
    // force of the base on the top block, width 1; matching meshes: the
    // node-to-segment pressure is uniform
    let (probe, p) = run_case8("thermal_contact_blocks.ctc", "ramp(0, -0.1)", stroke);
    let (k1, l1, k2, l2, t_hot, t_cold) = (2.0, 1.0, 0.5, 1.5, 100.0, 20.0);
    let h = 3.0 + 0.5 * p.sqrt();
    let q = (t_hot - t_cold) / (l1 / k1 + 1.0 / h + l2 / k2);
    let t_base = t_cold + q * l1 / k1;
    let t_top = t_base + q / h;
    // heat enters the top block's slave side from the base: power < 0
    let flux_error = ((-probe.power) - q).abs() / q;
    let slave = probe
        .slave_temperature
        .iter()
        .map(|t| (t - t_top).abs() / (t_hot - t_cold));
    let master = probe
        .master_temperature
        .iter()
        .map(|t| (t - t_base).abs() / (t_hot - t_cold));
    assert!(!probe.master_temperature.is_empty());
    let t_error = slave.chain(master).fold(0.0, f64::max);
    (flux_error, t_error, p)
}

#[test]
fn case8_thermal_contact_two_blocks_node_to_segment_matches_the_closed_form() {
    let mut pressures = Vec::new();
    for stroke in [0.01, 0.1] {
        let (eq, et, p) = case8_two_blocks(stroke);
        eprintln!(
            "case 8 (two blocks, node-to-segment), p = {p:.6}: flux relative \
             error {eq:.2e}, interface temperature relative error {et:.2e}"
        );
        assert!(eq <= 1e-8, "flux error {eq:e} at p = {p}");
        assert!(et <= 1e-8, "interface temperature error {et:e} at p = {p}");
        pressures.push(p);
    }
    assert!(pressures[1] > 5.0 * pressures[0], "{pressures:?}");
}
