//! Free bulging of a clamped circular diaphragm at a controlled pole strain
//! rate (issue 22, superplastic forming before the die is reached), as a
//! `ctc verify` case: an axisymmetric Norton-Hoff sheet, radius `a = 50`,
//! thickness `s0 = 1`, clamped at `r = a`, blown by a follower pressure
//! whose cycle the controller adjusts so that the equivalent plastic strain
//! rate at the pole holds `r*` (`control = strain_rate { .. at = (0, 0) }`).
//!
//! The thin-membrane relations checked:
//! - **Equilibrium of the pole** (exact for a membrane, by symmetry: the
//!   stresses there are equi-biaxial): `p = 2 sigma s / rho`, with `s` the
//!   pole thickness, `rho` the radius of curvature of the mid-surface at
//!   the pole (the circle through the pole and the mid-surface point at
//!   `R = 3`) and `sigma = sigma0 (rate / r0)^m` the Norton-Hoff stress at
//!   the measured pole rate. The difference falls with the mesh (bending and
//!   the through-thickness variation of the rate are the rest).
//! - **The controller**: the pole rate holds `r*` once the elastic
//!   transient is over.
//! - **Pole thickness**: Hill's approximate theory (R. Hill, "A theory of
//!   the plastic bulging of a metal diaphragm by lateral pressure", Phil.
//!   Mag. 41, 1950: spherical dome, material points moving along the
//!   normal) gives `s = s0 / (1 + h^2 / a^2)^2` whatever the law, the
//!   uniform-thickness spherical cap (Jovane, "An approximate analysis of
//!   the superplastic forming of a thin circular diaphragm", Int. J. Mech.
//!   Sci. 10, 1968) `s = s0 / (1 + h^2 / a^2)`. A rate-sensitive sheet
//!   spreads the thinning: the pole lies between the two for `m = 0.5`, and
//!   on Hill's curve for a nearly rate-insensitive sheet (`m = 0.1`) up to
//!   `h = a / 2`.
//!
//! ```text
//!            pole (r = 0)     h
//!         .-~~~~~~~~~~~-.     ^
//!       /                 \   |   s(t), rho(t)
//!   ===|=====================|===  clamped at r = a = 50
//!      ^  ^  ^  ^  ^  ^  ^  ^
//!       p(t) (follower, controlled so that the pole rate = r*)
//! ```

use super::error;
use crate::case::{Check, Quantity};
use crate::registry::{CaseKind, ProgramCase, ProgramLevel, VerifyCase};
use ctc_engine::model::AnyModel;
use ctc_engine::solve::{run, IncrementView, Observer, RunSummary};

/// Die radius (the clamped edge).
pub(crate) const A: f64 = 50.0;
/// Initial thickness.
pub(crate) const S0: f64 = 1.0;
/// Norton-Hoff flow stress at the reference rate.
pub(crate) const SIGMA0: f64 = 20.0;
/// Reference rate.
pub(crate) const R0: f64 = 1e-3;
/// Target pole rate.
pub(crate) const TARGET: f64 = 1e-3;
/// Radius of the second mid-surface point of the pole's circle.
const R_FIT: f64 = 3.0;

const EQUILIBRIUM: &str =
    "m = 0.5: pole equilibrium, max |p - 2 sigma s / rho| / p (0.2 <= h/a <= 1)";
const RATE: &str = "m = 0.5: pole rate, max |rate - r*| / r* (t >= 100)";
const BRACKET: &str = "m = 0.5: pole thickness outside [Hill, uniform cap], max relative excess";
const HILL: &str = "m = 0.1: pole thickness vs Hill (1950), max relative difference (h/a <= 0.5)";
const HEIGHT: &str = "m = 0.5: pole height h/a at t = 1000 (reported)";

fn deck(m: f64, divisions: (usize, usize), end: f64, increments: usize) -> String {
    let (nx, ny) = divisions;
    format!(
        "analysis {{ dimension = axisymmetric }}
material sheet {{
  elastic {{ E = 100e3  nu = 0.3 }}
  norton_hoff {{ stress = {SIGMA0}  rate = {R0}  m = {m} }}
}}
body d {{
  mesh = rectangle {{ origin = (0, 0)  size = ({A}, {S0})  divisions = ({nx}, {ny}) }}
  material = sheet
  kinematics = finite
  formulation = selective_reduced
}}
fix d.right {{ ux uy }}
fix d.left {{ ux }}
pressure d.bottom {{ p = 0.01  follower = true
  control = strain_rate {{ target = {TARGET}  exponent = {m}  at = (0, 0) }} }}
step blow {{ time = 0 .. {end}  increments = {increments} }}
"
    )
}

/// One converged increment at the pole.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Pole {
    /// Time.
    pub t: f64,
    /// Height of the mid-surface pole above the clamped plane's mid-surface.
    pub h: f64,
    /// Pole thickness.
    pub s: f64,
    /// Radius of curvature of the mid-surface at the pole.
    pub rho: f64,
    /// Applied pressure.
    pub p: f64,
    /// Measured pole rate.
    pub rate: f64,
}

/// The nodes of the pole (bottom, top) and of the fitting radius.
struct Watch {
    nodes: [usize; 4],
    reference: [[f64; 2]; 4],
    out: Vec<Pole>,
}

impl Observer<2> for Watch {
    fn converged(&mut self, v: &IncrementView<'_, 2>) -> Result<(), String> {
        let c = v
            .controls
            .first()
            .ok_or("the increment reports no controller")?;
        let x = |k: usize| {
            let (n, x0) = (self.nodes[k], self.reference[k]);
            let u = v.displacement[n];
            [x0[0] + u[0], x0[1] + u[1]]
        };
        let (b0, t0, b1, t1) = (x(0), x(1), x(2), x(3));
        let pole = [0.5 * (b0[0] + t0[0]), 0.5 * (b0[1] + t0[1])];
        let side = [0.5 * (b1[0] + t1[0]), 0.5 * (b1[1] + t1[1])];
        // the circle centred on the axis through both mid-surface points
        let dz = pole[1] - side[1];
        let rho = (side[0].powi(2) + dz * dz) / (2.0 * dz);
        self.out.push(Pole {
            t: v.time,
            h: pole[1] - 0.5 * S0,
            s: ((t0[0] - b0[0]).powi(2) + (t0[1] - b0[1]).powi(2)).sqrt(),
            rho,
            p: c.pressure,
            rate: c.rate,
        });
        Ok(())
    }
}

/// The axisymmetric free bulge of Norton-Hoff exponent `m` on `divisions`
/// (radial, through the thickness) quads up to `end` in `increments`: the
/// pole at every converged increment (also the reference of the 3D sheet,
/// [`super::superplastic_3d`]).
pub(crate) fn solve(
    m: f64,
    divisions: (usize, usize),
    end: f64,
    increments: usize,
) -> Result<(Vec<Pole>, RunSummary), String> {
    let src = ctc_lang::Source::new("free_bulge.ctc", deck(m, divisions, end, increments));
    let AnyModel::D2(model) = ctc_lang::compile_any(&src).map_err(|d| d.render(&src))? else {
        return Err("the free bulge is axisymmetric".into());
    };
    let targets = [[0.0, 0.0], [0.0, S0], [R_FIT, 0.0], [R_FIT, S0]];
    let mut nodes = [0; 4];
    let mut reference = [[0.0; 2]; 4];
    for (k, p) in targets.iter().enumerate() {
        let (n, x) = model
            .mesh
            .nodes
            .iter()
            .enumerate()
            .min_by(|a, b| {
                let d = |x: &[f64; 2]| (x[0] - p[0]).powi(2) + (x[1] - p[1]).powi(2);
                d(a.1).total_cmp(&d(b.1))
            })
            .ok_or("an empty mesh")?;
        nodes[k] = n;
        reference[k] = *x;
    }
    let mut watch = Watch {
        nodes,
        reference,
        out: Vec::new(),
    };
    let summary = run(&model, &mut watch).map_err(|e| e.message)?;
    if !summary.completed || watch.out.len() < increments {
        return Err(format!(
            "the bulge stopped after {} of {increments} increments",
            watch.out.len()
        ));
    }
    Ok((watch.out, summary))
}

/// Hill's pole thickness at height `h`.
pub fn hill_thickness(h: f64) -> f64 {
    S0 / (1.0 + (h / A).powi(2)).powi(2)
}

/// The uniform thickness of a spherical cap of height `h`.
pub fn cap_thickness(h: f64) -> f64 {
    S0 / (1.0 + (h / A).powi(2))
}

fn level_run(level: usize) -> Result<ProgramLevel, String> {
    let k = 1usize << level;
    let divisions = (100 * k, 2 * k);
    let mut out = ProgramLevel {
        h: S0 / divisions.1 as f64,
        ..ProgramLevel::default()
    };
    let m = 0.5;
    let (poles, summary) = solve(m, divisions, 1000.0, 200)?;
    out.add_run(&summary);
    let window = |p: &&Pole| p.h >= 0.2 * A && p.h <= A;
    let equilibrium = poles
        .iter()
        .filter(window)
        .map(|p| {
            let sigma = SIGMA0 * (p.rate / R0).powf(m);
            (p.p - 2.0 * sigma * p.s / p.rho).abs() / p.p
        })
        .fold(0.0, f64::max);
    let rate = poles
        .iter()
        .filter(|p| p.t >= 100.0)
        .map(|p| (p.rate - TARGET).abs() / TARGET)
        .fold(0.0, f64::max);
    let bracket = poles
        .iter()
        .map(|p| {
            let (lo, hi) = (hill_thickness(p.h), cap_thickness(p.h));
            ((lo - p.s).max(p.s - hi).max(0.0)) / p.s
        })
        .fold(0.0, f64::max);
    let height = poles.last().map_or(f64::NAN, |p| p.h / A);
    let (hill_poles, hill_summary) = solve(0.1, divisions, 500.0, 100)?;
    out.add_run(&hill_summary);
    let hill = hill_poles
        .iter()
        .filter(|p| p.h <= 0.5 * A)
        .map(|p| (p.s - hill_thickness(p.h)).abs() / hill_thickness(p.h))
        .fold(0.0, f64::max);
    out.values.push(error(EQUILIBRIUM, equilibrium));
    out.values.push(error(RATE, rate));
    out.values.push(error(BRACKET, bracket));
    out.values.push(error(HILL, hill));
    out.values.push(error(HEIGHT, height));
    Ok(out)
}

/// The registry entry.
pub fn cases() -> Vec<VerifyCase> {
    vec![VerifyCase {
        name: "superplastic_free_bulge",
        title: "Free bulging of a clamped Norton-Hoff diaphragm at a controlled pole strain rate (axisymmetric): pole equilibrium p = 2 sigma s / rho, the controller, pole thickness vs Hill (1950) and the uniform cap",
        source: "R. Hill, Phil. Mag. 41 (1950) 1133 (bulging of a diaphragm); F. Jovane, Int. J. Mech. Sci. 10 (1968) 403 (superplastic diaphragm); Norton (1929), Hoff (1954)",
        tags: &["forming", "superplastic", "control", "follower", "viscoplastic", "norton_hoff", "finite_strain", "axisymmetric", "closed_form"],
        levels: 1,
        checks: vec![
            Check::new(Quantity::Named(EQUILIBRIUM), &[3e-2, 1.2e-2]),
            Check::new(Quantity::Named(RATE), &[5e-3, 5e-3]),
            Check::new(Quantity::Named(BRACKET), &[1e-12, 1e-12]),
            Check::new(Quantity::Named(HILL), &[5e-2, 5e-2]),
        ],
        kind: CaseKind::Program(ProgramCase {
            max_levels: 2,
            run: level_run,
        }),
    }]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hill_thins_the_pole_more_than_the_uniform_cap() {
        // a hemisphere (h = a): Hill s0 / 4, the cap s0 / 2
        assert!((hill_thickness(A) - 0.25).abs() < 1e-15);
        assert!((cap_thickness(A) - 0.5).abs() < 1e-15);
        assert_eq!(hill_thickness(0.0), S0);
    }
}
