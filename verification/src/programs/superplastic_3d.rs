//! Superplastic forming in 3D before the die is reached (issue 22, example
//! 3), as a `ctc verify` case: the sheet of
//! `examples/superplastic_forming_3d.ctc` (a quarter of a clamped circular
//! Norton-Hoff sheet, radius `a = 50`, thickness `s0 = 1`, `sigma = 20
//! (rate / 1e-3)^0.5`, hex8 F-bar, symmetry planes `x = 0`, `y = 0`) blown
//! by a follower pressure whose cycle holds the pole's equivalent plastic
//! strain rate at `r* = 1e-3` (`control = strain_rate { .. at = (0, 0, 0)
//! }`), with the IGES die of the example in place (the round pan, bottom
//! at `z = 21`): every converged increment before the first closed contact
//! node is a free bulge, judged by
//! - **pole equilibrium** `p = 2 sigma s / rho` (`s` the pole thickness,
//!   `rho` the radius of the circle centred on the axis through the
//!   mid-surface pole and the mid-surface point nearest to `R_FIT` on the
//!   symmetry plane `y = 0`, `sigma` the Norton-Hoff stress at the measured
//!   pole rate; exact for a membrane by symmetry) for `h / a >= 0.2`;
//! - **the controller**: the pole rate against `r*` after the elastic
//!   transient (`h / a >= 0.2`);
//! - **pole thickness** between Hill's `s0 / (1 + h^2/a^2)^2` (R. Hill,
//!   Phil. Mag. 41, 1950) and the uniform cap's `s0 / (1 + h^2/a^2)`
//!   (F. Jovane, Int. J. Mech. Sci. 10, 1968), as the axisymmetric
//!   `superplastic_free_bulge` does;
//! - **the axisymmetric run of the same problem** (`free_bulge::solve`, 100
//!   x 2 F-bar quads): the pressure at equal pole height (linear
//!   interpolation of the axisymmetric curve), and the pole thickness,
//!   for `h / a >= 0.2`;
//! - the mesh: `(2, 5, 1) x 2^level` (O-grid core, ring, layers; 2 layers
//!   at level 2), 35 x 2^level increments after a 5-increment start. Level
//!   0 (20 hex8) is coarse: its pressure is 11 % above the axisymmetric
//!   run's, level 1 (80 hex8) 1.8 % (`ctc verify superplastic_forming_3d
//!   --max-level 1`: equilibrium 4.8e-2 -> 3.4e-2, rate 2.9e-2 -> 9e-3,
//!   pressure 1.1e-1 -> 1.8e-2 at levels 0 -> 1);
//! - the die is reached (reported: the pole height `h / a` at the first
//!   contact; the bottom is 20 above the sheet's top).
//!
//! ```text
//!   z        die (IGES pan), bottom z = 21
//!   21 |____________________.
//!      |      .-~~~~~-.       |   free bulge: pole height h, thickness s,
//!      |    /           \     |   curvature radius rho
//!    1 |===|=============|====|   quarter sheet, clamped at r = 50
//!      +---^--^--^--^--^------+--> r
//!          p(t) (follower, controlled: pole rate = 1e-3 /s)
//! ```

use super::error;
use super::free_bulge::{cap_thickness, hill_thickness, Pole, A, R0, S0, SIGMA0, TARGET};
use crate::case::{Check, Quantity};
use crate::registry::{CaseKind, ProgramCase, ProgramLevel, VerifyCase};
use ctc_engine::contact::ContactStatus;
use ctc_engine::model::{AnyModel, Model};
use ctc_engine::solve::{run, IncrementView, Observer, RunSummary};

/// Radius of the second mid-surface point of the pole's circle.
const R_FIT: f64 = 8.0;
/// Norton-Hoff exponent.
const M: f64 = 0.5;

const EQUILIBRIUM: &str =
    "pole equilibrium before the die, max |p - 2 sigma s / rho| / p (h/a >= 0.2)";
const RATE: &str = "controller: pole rate before the die, max |rate - r*| / r* (h/a >= 0.2)";
const BRACKET: &str =
    "pole thickness before the die outside [Hill, uniform cap], max relative excess";
const AXI_PRESSURE: &str =
    "3D vs axisymmetric: pressure at equal pole height, max relative difference (h/a >= 0.2)";
const AXI_THICKNESS: &str =
    "3D vs axisymmetric: pole thickness at equal pole height, max relative difference (h/a >= 0.2)";
const CONTACT_HEIGHT: &str = "pole height h/a at the first die contact (reported)";

/// The free-bulge deck: the example's sheet, die and contact, the
/// controller at the pole; `(core, ring, layers)` divisions.
fn deck(divisions: (usize, usize, usize), end: f64, increments: usize) -> String {
    let (core, ring, layers) = divisions;
    format!(
        "analysis {{ dimension = 3d  units = mm_N_s }}
material ti64 {{
  elastic {{ E = 100e3  nu = 0.3 }}
  norton_hoff {{ stress = {SIGMA0}  rate = {R0}  m = {M} }}
}}
body sheet {{
  mesh = cylinder {{ radius = {A}  angle = 90  height = {S0}
                    divisions = ({core}, {ring}, {layers})  element = hex8 }}
  material = ti64
  kinematics = finite
  formulation = selective_reduced
}}
tool die = iges {{ file = \"superplastic_forming_die.igs\" }}
contact sheet.zmax -> die {{
  method = penalty {{ kind = area  stiffness = 10 * E / h }}
  friction = coulomb {{ mu = 0.4 }}
}}
fix sheet.outer {{ ux uy uz }}
fix sheet.start {{ uy }}
fix sheet.end {{ ux }}
pressure sheet.zmin {{ p = 0.05  follower = true
  control = strain_rate {{ target = {TARGET}  exponent = {M}  at = (0, 0, 0) }} }}
step start {{ time = 0 .. 10  increments = 5 }}
step blow {{ time = 10 .. {end}  increments = {increments} }}
"
    )
}

/// The pole nodes (bottom, top), the fitting nodes (bottom, top).
struct Watch {
    nodes: [usize; 4],
    reference: [[f64; 3]; 4],
    /// The poles before the first closed contact node.
    free: Vec<Pole>,
    /// The pole height at the first contact.
    contact_h: Option<f64>,
}

impl Observer<3> for Watch {
    fn converged(&mut self, v: &IncrementView<'_, 3>) -> Result<(), String> {
        let c = v
            .controls
            .first()
            .ok_or("the increment reports no controller")?;
        let x = |k: usize| {
            let (n, x0) = (self.nodes[k], self.reference[k]);
            let u = v.displacement[n];
            [x0[0] + u[0], x0[1] + u[1], x0[2] + u[2]]
        };
        let (b0, t0, b1, t1) = (x(0), x(1), x(2), x(3));
        let mid = |a: [f64; 3], b: [f64; 3]| {
            [
                0.5 * (a[0] + b[0]),
                0.5 * (a[1] + b[1]),
                0.5 * (a[2] + b[2]),
            ]
        };
        let (pole, side) = (mid(b0, t0), mid(b1, t1));
        // the circle centred on the axis through both mid-surface points
        let r_side = side[0].hypot(side[1]);
        let dz = pole[2] - side[2];
        let rho = (r_side * r_side + dz * dz) / (2.0 * dz);
        let h = pole[2] - 0.5 * S0;
        let touching = v
            .contact
            .iter()
            .flatten()
            .any(|n| n.status == ContactStatus::Closed);
        if touching {
            self.contact_h.get_or_insert(h);
        } else if self.contact_h.is_none() {
            let s = (0..3).map(|k| (t0[k] - b0[k]).powi(2)).sum::<f64>().sqrt();
            self.free.push(Pole {
                t: v.time,
                h,
                s,
                rho,
                p: c.pressure,
                rate: c.rate,
            });
        }
        Ok(())
    }
}

fn compile(text: String) -> Result<Model<3>, String> {
    // a deck beside the example, so that the die's file resolves
    let path = super::examples_dir().join("superplastic_forming_3d_free_bulge.ctc");
    let src = ctc_lang::Source::new(path, text);
    match ctc_lang::compile_any(&src).map_err(|d| d.render(&src))? {
        AnyModel::D3(m) => Ok(m),
        AnyModel::D2(_) => Err("the sheet is 3D".into()),
    }
}

fn solve(
    divisions: (usize, usize, usize),
    end: f64,
    increments: usize,
) -> Result<(Vec<Pole>, Option<f64>, RunSummary), String> {
    let model = compile(deck(divisions, end, increments))?;
    let targets = [
        [0.0, 0.0, 0.0],
        [0.0, 0.0, S0],
        [R_FIT, 0.0, 0.0],
        [R_FIT, 0.0, S0],
    ];
    let mut nodes = [0; 4];
    let mut reference = [[0.0; 3]; 4];
    for (k, p) in targets.iter().enumerate() {
        let d = |x: &[f64; 3]| (0..3).map(|i| (x[i] - p[i]).powi(2)).sum::<f64>();
        let (n, x) = model
            .mesh
            .nodes
            .iter()
            .enumerate()
            .min_by(|a, b| d(a.1).total_cmp(&d(b.1)))
            .ok_or("an empty mesh")?;
        nodes[k] = n;
        reference[k] = *x;
    }
    let mut watch = Watch {
        nodes,
        reference,
        free: Vec::new(),
        contact_h: None,
    };
    let summary = run(&model, &mut watch).map_err(|e| e.message)?;
    if !summary.completed {
        return Err(format!(
            "the bulge stopped after {} of {increments} increments",
            summary.increments.len()
        ));
    }
    Ok((watch.free, watch.contact_h, summary))
}

/// `y(x)` on the polyline `(x, y)` (increasing `x`), `None` outside it.
fn interpolate(rows: &[(f64, f64)], x: f64) -> Option<f64> {
    rows.windows(2).find_map(|w| {
        let ((x0, y0), (x1, y1)) = (w[0], w[1]);
        (x >= x0 && x <= x1 && x1 > x0).then(|| y0 + (y1 - y0) * (x - x0) / (x1 - x0))
    })
}

fn level_run(level: usize) -> Result<ProgramLevel, String> {
    let k = 1usize << level;
    let divisions = (2 * k, 5 * k, if level >= 2 { 2 } else { 1 });
    let mut out = ProgramLevel {
        h: 25.0 / divisions.0 as f64,
        ..ProgramLevel::default()
    };
    let increments = 35 * k;
    let (poles, contact_h, summary) = solve(divisions, 360.0, increments)?;
    out.add_run(&summary);
    if poles.len() < increments / 2 {
        return Err(format!(
            "only {} increments before the die (of {increments})",
            poles.len()
        ));
    }
    let equilibrium = poles
        .iter()
        .filter(|p| p.h >= 0.2 * A)
        .map(|p| {
            let sigma = SIGMA0 * (p.rate / R0).powf(M);
            (p.p - 2.0 * sigma * p.s / p.rho).abs() / p.p
        })
        .fold(0.0, f64::max);
    // after the controller's transient: the window of the equilibrium
    let rate = poles
        .iter()
        .filter(|p| p.h >= 0.2 * A)
        .map(|p| (p.rate - TARGET).abs() / TARGET)
        .fold(0.0, f64::max);
    let bracket = poles
        .iter()
        .map(|p| {
            let (lo, hi) = (hill_thickness(p.h), cap_thickness(p.h));
            ((lo - p.s).max(p.s - hi).max(0.0)) / p.s
        })
        .fold(0.0, f64::max);
    // the axisymmetric run of the same sheet, past the die's depth
    let (axi, axi_summary) = super::free_bulge::solve(M, (100, 2), 300.0, 60)?;
    out.add_run(&axi_summary);
    let p_of_h: Vec<(f64, f64)> = axi.iter().map(|p| (p.h, p.p)).collect();
    let s_of_h: Vec<(f64, f64)> = axi.iter().map(|p| (p.h, p.s)).collect();
    let (mut axi_p, mut axi_s, mut compared) = (0.0f64, 0.0f64, 0);
    for p in poles.iter().filter(|p| p.h >= 0.2 * A) {
        if let (Some(pa), Some(sa)) = (interpolate(&p_of_h, p.h), interpolate(&s_of_h, p.h)) {
            axi_p = axi_p.max((p.p - pa).abs() / pa);
            axi_s = axi_s.max((p.s - sa).abs() / sa);
            compared += 1;
        }
    }
    if compared < 3 {
        return Err(format!(
            "only {compared} pole heights compared with the axisymmetric run"
        ));
    }
    out.values.push(error(EQUILIBRIUM, equilibrium));
    out.values.push(error(RATE, rate));
    out.values.push(error(BRACKET, bracket));
    out.values.push(error(AXI_PRESSURE, axi_p));
    out.values.push(error(AXI_THICKNESS, axi_s));
    out.values
        .push(error(CONTACT_HEIGHT, contact_h.map_or(f64::NAN, |h| h / A)));
    Ok(out)
}

/// The registry entry.
pub fn cases() -> Vec<VerifyCase> {
    vec![VerifyCase {
        name: "superplastic_forming_3d",
        title: "Superplastic forming in 3D before the die (quarter Norton-Hoff sheet, hex8 F-bar, IGES die in place): pole equilibrium p = 2 sigma s / rho, the pole-rate controller, pole thickness vs Hill and the uniform cap, pressure and thickness vs the axisymmetric run",
        source: "R. Hill, Phil. Mag. 41 (1950) 1133 (bulging of a diaphragm); F. Jovane, Int. J. Mech. Sci. 10 (1968) 403 (superplastic diaphragm); N. E. Arieli, A. Rosen, Metall. Trans. A 8 (1977) 1591 (Ti-6Al-4V, m = 0.5)",
        tags: &["3d", "forming", "superplastic", "control", "follower", "norton_hoff", "finite_strain", "iges", "closed_form"],
        levels: 1,
        checks: vec![
            Check::new(Quantity::Named(EQUILIBRIUM), &[6e-2, 4e-2, 3e-2]),
            Check::new(Quantity::Named(RATE), &[4e-2, 1.5e-2, 1e-2]),
            Check::new(Quantity::Named(BRACKET), &[1e-3, 1e-3, 1e-3]),
            Check::new(Quantity::Named(AXI_PRESSURE), &[0.13, 3e-2, 2e-2]),
            Check::new(Quantity::Named(AXI_THICKNESS), &[2.5e-2, 1e-2, 1e-2]),
        ],
        kind: CaseKind::Program(ProgramCase {
            max_levels: 3,
            run: level_run,
        }),
    }]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_interpolation_is_linear_inside_and_none_outside() {
        let rows = [(0.0, 1.0), (1.0, 3.0), (3.0, 4.0)];
        assert_eq!(interpolate(&rows, 0.5), Some(2.0));
        assert_eq!(interpolate(&rows, 2.0), Some(3.5));
        assert_eq!(interpolate(&rows, 3.5), None);
        assert_eq!(interpolate(&rows, -0.1), None);
    }
}
