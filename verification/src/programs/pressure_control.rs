//! Pressure-cycle control (issue 22, the "optimization of the applied
//! pressure cycle" of superplastic forming) as a `ctc verify` case: a
//! Norton-Hoff cylinder (axisymmetric) and block (3D, quarter model with
//! symmetry planes) pushed by a follower pressure on its top whose factor
//! the controller adjusts after every increment so that the largest
//! equivalent plastic strain rate holds the target `r*`.
//!
//! In uniaxial compression under a follower pressure the Cauchy stress is
//! the pressure (force = p x current area). Once the elastic transient is
//! over the flow is steady: the Kirchhoff stress is the Norton-Hoff
//! `tau = sigma0 (r* / r0)^m` and, Hencky elasticity carrying `tr e_e =
//! (1 - 2 nu) tau / E` (compression: `tau < 0`), `J = exp((1 - 2 nu) tau /
//! E)` and the pressure that holds `r*` is exactly
//! `p* = |tau| exp((1 - 2 nu) |tau| / E)`.
//! Checked: the pressure and the rate over the last half of the run
//! against `p*` and `r*` (the controller with `exponent = m` lands on them
//! to round-off once the transient is over), and the increments the
//! controller needs to bring the rate within 1 % of `r*` from a pressure 16
//! times too low (the factor is bounded by 2 per increment).
//! Source: the controller of Abaqus' creep strain-rate control for
//! superplastic forming (Abaqus Analysis User's Guide, "Superplastic
//! forming"); the law: Norton (1929), Hoff (1954).
//!
//! ```text
//!      p(t) (follower, controlled)
//!    vvvvvvvvvv
//!   +----------+  Norton-Hoff sigma0 = 50, r0 = 1e-3, m = 1/2
//!   |          |  target r* = 1e-2:  p* = 50 sqrt(10) exp(0.4 |tau| / E)
//!   +----------+
//!   ////////////  (axis and symmetry planes on rollers)
//! ```

use super::error;
use crate::case::{Check, Quantity};
use crate::registry::{CaseKind, ProgramCase, ProgramLevel, VerifyCase};
use ctc_engine::model::AnyModel;
use ctc_engine::solve::{run, IncrementView, Observer, RunSummary};

const E: f64 = 200e3;
const NU: f64 = 0.3;
const SIGMA0: f64 = 50.0;
const R0: f64 = 1e-3;
const M: f64 = 0.5;
const TARGET: f64 = 1e-2;
/// Initial pressure: 16 times below `p*` (4 increments at the bound).
const P_START: f64 = 10.0;

const AXI_P: &str = "axisymmetric: max |p - p*| / p* (second half)";
const AXI_R: &str = "axisymmetric: max |rate - r*| / r* (second half)";
const AXI_N: &str = "axisymmetric: increments to reach r* within 1 %";
const SOLID_P: &str = "3d: max |p - p*| / p* (second half)";
const SOLID_R: &str = "3d: max |rate - r*| / r* (second half)";
const SOLID_N: &str = "3d: increments to reach r* within 1 %";

fn material() -> String {
    format!(
        "material sp {{\n  elastic {{ E = {E}  nu = {NU} }}\n  norton_hoff {{ stress = {SIGMA0}  rate = {R0}  m = {M} }}\n}}\n"
    )
}

fn control() -> String {
    format!(
        "p = {P_START}  follower = true  control = strain_rate {{ target = {TARGET}  exponent = {M} }}"
    )
}

fn deck(solid: bool) -> String {
    let steps = "step s { time = 0 .. 30  increments = 60 }\n";
    if solid {
        format!(
            "analysis {{ dimension = 3d }}\n{}\
             body b {{ mesh = box {{ size = (1, 1, 1)  divisions = (2, 2, 2) }}  material = sp  kinematics = finite }}\n\
             fix b.xmin {{ ux }}\nfix b.ymin {{ uy }}\nfix b.zmin {{ uz }}\n\
             pressure b.zmax {{ {} }}\n{steps}",
            material(),
            control()
        )
    } else {
        format!(
            "analysis {{ dimension = axisymmetric }}\n{}\
             body b {{ mesh = rectangle {{ origin = (0, 0)  size = (1, 1)  divisions = (2, 2) }}  material = sp  kinematics = finite }}\n\
             fix b.bottom {{ uy }}\nfix b.left {{ ux }}\n\
             pressure b.top {{ {} }}\n{steps}",
            material(),
            control()
        )
    }
}

/// The controller's record of every converged increment: pressure, rate.
#[derive(Default)]
struct Records(Vec<(f64, f64)>);

impl<const D: usize> Observer<D> for Records
where
    nalgebra::Const<D>: ctc_engine::geom::Dimension<D>,
{
    fn converged(&mut self, v: &IncrementView<'_, D>) -> Result<(), String> {
        let c = v
            .controls
            .first()
            .ok_or("the increment reports no controller")?;
        self.0.push((c.pressure, c.rate));
        Ok(())
    }
}

fn solve(solid: bool) -> Result<(Records, RunSummary), String> {
    let src = ctc_lang::Source::new("pressure_control.ctc", deck(solid));
    let mut rec = Records::default();
    let summary = match ctc_lang::compile_any(&src).map_err(|d| d.render(&src))? {
        AnyModel::D2(m) => run(&m, &mut rec),
        AnyModel::D3(m) => run(&m, &mut rec),
    }
    .map_err(|e| e.message)?;
    if !summary.completed || rec.0.len() < 60 {
        return Err(format!(
            "the controlled run stopped after {} increments",
            rec.0.len()
        ));
    }
    Ok((rec, summary))
}

/// The pressure that holds the target rate (see the module doc).
pub fn steady_pressure() -> f64 {
    let tau = SIGMA0 * (TARGET / R0).powf(M);
    tau * ((1.0 - 2.0 * NU) * tau / E).exp()
}

fn level_run(_level: usize) -> Result<ProgramLevel, String> {
    let mut out = ProgramLevel {
        h: 1.0,
        nodes: 9,
        ..ProgramLevel::default()
    };
    let p_star = steady_pressure();
    for (solid, names) in [
        (false, [AXI_P, AXI_R, AXI_N]),
        (true, [SOLID_P, SOLID_R, SOLID_N]),
    ] {
        let (rec, summary) = solve(solid)?;
        let half = &rec.0[rec.0.len() / 2..];
        let dp = half
            .iter()
            .map(|(p, _)| (p - p_star).abs() / p_star)
            .fold(0.0, f64::max);
        let dr = half
            .iter()
            .map(|(_, r)| (r - TARGET).abs() / TARGET)
            .fold(0.0, f64::max);
        let settle = rec
            .0
            .iter()
            .position(|(_, r)| (r - TARGET).abs() <= 0.01 * TARGET)
            .map_or(rec.0.len(), |k| k + 1);
        out.values.push(error(names[0], dp));
        out.values.push(error(names[1], dr));
        out.values.push(error(names[2], settle as f64));
        out.add_run(&summary);
    }
    Ok(out)
}

/// The registry entry.
pub fn cases() -> Vec<VerifyCase> {
    vec![VerifyCase {
        name: "pressure_cycle_control",
        title: "Pressure-cycle control: a Norton-Hoff cylinder (axisymmetric) and block (3D) under a controlled follower pressure hold the target strain rate; steady pressure vs closed form",
        source: "Abaqus Analysis User's Guide, superplastic forming (creep strain-rate control); Norton (1929), Hoff (1954)",
        tags: &["forming", "control", "follower", "viscoplastic", "norton_hoff", "finite_strain", "axisymmetric", "3d", "closed_form"],
        levels: 1,
        checks: vec![
            Check::new(Quantity::Named(AXI_P), &[1e-9]),
            Check::new(Quantity::Named(AXI_R), &[1e-9]),
            Check::new(Quantity::Named(AXI_N), &[8.0]),
            Check::new(Quantity::Named(SOLID_P), &[1e-9]),
            Check::new(Quantity::Named(SOLID_R), &[1e-9]),
            Check::new(Quantity::Named(SOLID_N), &[8.0]),
        ],
        kind: CaseKind::Program(ProgramCase {
            max_levels: 1,
            run: level_run,
        }),
    }]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_steady_pressure_is_the_kirchhoff_stress_over_j() {
        // 50 sqrt(10) = 158.1139, J = exp(-0.4 x 158.1139 / 200e3)
        assert!((steady_pressure() - 158.163_890_9).abs() < 1e-6);
    }
}
