//! Dual mortar with the Lagrange multipliers condensed out (issue 18:
//! "dual Lagrange multipliers (condensed, no saddle point)";
//! `engine/src/solve/linalg/condensed.rs`): `method = lagrange {
//! formulation = condensed }` against the saddle-point path (`method =
//! lagrange`) on the same decks.
//!
//! Source: Popp, Gee & Wall, IJNME 79 (2009) 1354, §4.3 (condensation of
//! the dual multipliers, semi-smooth Newton); Wohlmuth, SIAM J. Numer.
//! Anal. 38 (2000) 989 (dual basis); Hüeber & Wohlmuth, CMAME 194 (2005)
//! 3147. The condensation is exact algebra on the saddle point's Newton
//! system, so the reference of the condensed run is the saddle-point run
//! (same iterates, same active sets, same multipliers to round-off) and
//! the closed forms of the decks (uniform pressure of the patch test,
//! Hertz).
//!
//! ```text
//!   patch test (2D 4|3, 7|5; 3D 3x3 | 4x4 hex8 / tet4 facets):
//!     top block pushed down, slave = top.bottom -> master = base.top
//!     exact: p uniform (2D: E d / h, the top pushed 0.1 of 2)
//!   Hertz (verification/cases/hertz_two_cylinders_mortar.ctc):
//!     two quarter cylinders R = 1, non-matching arcs, flat pushed 0.02
//! ```

use super::mortar::{deviation, hertz_deck, hertz_run, measured, patch_deck};
use super::mortar_quadratic::Last;
use super::{compile, error};
use crate::case::{Check, Quantity};
use crate::registry::{CaseKind, ProgramCase, ProgramLevel, VerifyCase};
use ctc_engine::contact::{ContactStatus, NodeContact};
use ctc_engine::solve::RunSummary;
use std::path::Path;

/// The condensed method as deck text.
pub const CONDENSED: &str = "lagrange { formulation = condensed }";
/// The saddle-point method.
pub const SADDLE: &str = "lagrange";

/// The registry entries of this file.
pub fn cases() -> Vec<VerifyCase> {
    vec![patch_case(), hertz_case()]
}

// ------------------------------------------------------------ patch test

/// Levels: (base quads, top quads) across the 2D interface.
const MESHES: [(usize, usize); 2] = [(4, 3), (7, 5)];

/// Checks of the patch test (per level; measured values in
/// [`patch_case`]'s doc).
const PATCH_CHECKS: [(&str, &[f64]); 9] = [
    ("2D condensed p uniform", &[1e-8]),
    ("2D condensed vs saddle p", &[1e-10]),
    ("2D Newton iterations condensed - saddle", &[0.5]),
    ("2D multipliers in the condensed system", &[0.5]),
    ("hex8 condensed p uniform", &[1e-8]),
    ("hex8 condensed vs saddle p", &[1e-10]),
    ("tet4 condensed p uniform", &[1e-8]),
    ("tet4 condensed vs saddle p", &[1e-10]),
    ("3D Newton iterations condensed - saddle", &[0.5]),
];

/// The contact patch test with the condensed multipliers, against the
/// uniform pressure and against the saddle point.
///
/// Measured (`ctc verify contact_patch_mortar_condensed --max-level 1`,
/// debug; the 3D part at level 0 only): deviation from uniform 4.5e-15 /
/// 1.4e-14 (2D 4|3, 7|5), 1.1e-14 (hex8), 2.1e-14 (tet4); condensed vs
/// saddle pressures 5.7e-15 / 1.4e-14, 1.5e-14, 3.6e-14 of the mean; the
/// same Newton iterations; no multiplier left in the factorized system.
fn patch_case() -> VerifyCase {
    VerifyCase {
        name: "contact_patch_mortar_condensed",
        title: "Contact patch test, mortar with the dual Lagrange multipliers condensed out (2D \
                4|3, 7|5; 3D hex8 / tet4 3x3 | 4x4) vs uniform and vs the saddle point",
        source: "Taylor & Papadopoulos IJNME 31 (1991); Puso & Laursen CMAME 193 (2004); Popp, \
                 Gee & Wall IJNME 79 (2009) §4.3 (condensation)",
        tags: &[
            "contact",
            "patch",
            "mortar",
            "lagrange",
            "condensed",
            "3d",
            "exact",
        ],
        levels: 2,
        checks: PATCH_CHECKS
            .iter()
            .map(|(n, t)| Check::new(Quantity::Named(n), t))
            .collect(),
        kind: CaseKind::Program(ProgramCase {
            max_levels: MESHES.len(),
            run: patch_level,
        }),
    }
}

/// One 2D patch run: the final contact and the summary.
fn run_2d(
    n_base: usize,
    n_top: usize,
    method: &str,
) -> Result<(Vec<NodeContact>, RunSummary), String> {
    let text = patch_deck(n_base, n_top, "mortar", "single_pass", method);
    let model = compile(Path::new("contact_patch_mortar_condensed.ctc"), &text)?;
    let mut last = Last::default();
    let s = ctc_engine::solve::run(&model, &mut last)
        .map_err(|e| format!("{method}: {}", e.message))?;
    if !s.completed {
        return Err(format!("{method}: the run did not complete"));
    }
    if !last.0.iter().any(|c| c.status == ContactStatus::Closed) {
        return Err(format!("{method}: no closed contact node"));
    }
    Ok((last.0, s))
}

/// Largest `|p_a - p_b| / mean(p_b)` over the nodes of two runs (the same
/// slave nodes in the same order), and whether the closed sets agree.
fn pressure_difference<const D: usize>(a: &[NodeContact<D>], b: &[NodeContact<D>]) -> f64 {
    if a.len() != b.len()
        || a.iter()
            .zip(b)
            .any(|(x, y)| x.node != y.node || x.status != y.status)
    {
        return f64::INFINITY;
    }
    let closed: Vec<f64> = b
        .iter()
        .filter(|c| c.status == ContactStatus::Closed)
        .map(|c| c.pressure)
        .collect();
    let mean = closed.iter().sum::<f64>() / closed.len().max(1) as f64;
    a.iter()
        .zip(b)
        .map(|(x, y)| (x.pressure - y.pressure).abs())
        .fold(0.0, f64::max)
        / mean
}

fn patch_level(level: usize) -> Result<ProgramLevel, String> {
    let (n_base, n_top) = *MESHES.get(level).ok_or("no such level")?;
    let mut out = ProgramLevel {
        h: 1.0 / n_top as f64,
        ..ProgramLevel::default()
    };
    let (cond, cs) = run_2d(n_base, n_top, CONDENSED)?;
    let (sad, ss) = run_2d(n_base, n_top, SADDLE)?;
    out.add_run(&cs);
    out.add_run(&ss);
    out.values
        .push(error("2D condensed p uniform", deviation(&cond)));
    out.values.push(error(
        "2D condensed vs saddle p",
        pressure_difference(&cond, &sad),
    ));
    out.values.push(error(
        "2D Newton iterations condensed - saddle",
        cs.newton_iterations.abs_diff(ss.newton_iterations) as f64,
    ));
    out.values.push(error(
        "2D multipliers in the condensed system",
        multipliers_left(&cs, &ss)?,
    ));
    if level == 0 {
        let mut iterations = [0usize; 2];
        for (cell, uniform, versus) in [
            (
                "hex8",
                "hex8 condensed p uniform",
                "hex8 condensed vs saddle p",
            ),
            (
                "tet4",
                "tet4 condensed p uniform",
                "tet4 condensed vs saddle p",
            ),
        ] {
            let (c3, cl, c_contact) = run_3d(cell, CONDENSED)?;
            let (s3, sl, s_contact) = run_3d(cell, SADDLE)?;
            super::contact_ntf_3d::add_level(&mut out, &cl);
            super::contact_ntf_3d::add_level(&mut out, &sl);
            iterations[0] += c3.iterations;
            iterations[1] += s3.iterations;
            out.values.push(error(uniform, c3.uniformity));
            out.values
                .push(error(versus, pressure_difference(&c_contact, &s_contact)));
        }
        out.values.push(error(
            "3D Newton iterations condensed - saddle",
            iterations[0].abs_diff(iterations[1]) as f64,
        ));
    }
    Ok(out)
}

/// One 3D mortar patch run (4 x 4 base facets under 3 x 3 top facets):
/// the outcome, its level figures and the final contact.
fn run_3d(cell: &str, method: &str) -> Result<super::contact_ntf_3d::PatchRun, String> {
    let text = super::contact_ntf_3d::mortar_patch_deck(cell, 4, method);
    super::contact_ntf_3d::run_patch_deck_with_contact(text, method)
        .map_err(|e| format!("{cell} {method}: {e}"))
}

// ------------------------------------------------------------------ Hertz

/// Checks of the Hertz comparison (per level 0, 1, 2).
const HERTZ_CHECKS: [(&str, &[f64]); 6] = [
    ("p0 condensed vs saddle", &[1e-10]),
    ("P condensed vs saddle", &[1e-10]),
    ("max |p| difference condensed vs saddle / p0", &[1e-10]),
    ("Newton iterations condensed - saddle", &[0.5]),
    ("multipliers in the condensed system", &[0.5]),
    ("p0 condensed vs Hertz", &[0.045, 0.025, 0.02]),
];

/// Hertz, two elastic cylinders on non-matching arcs (the deck of
/// `hertz_two_cylinders_mortar_lagrange`), mortar with the multipliers
/// condensed against the saddle point.
///
/// Measured (`ctc verify hertz_two_cylinders_mortar_condensed --max-level
/// 2`, debug; levels 0-2, 320 / 1,158 / 4,464 free dofs): p0 condensed vs
/// saddle 5.9e-15 / 2.6e-14 / 1.6e-14, P 3.8e-15 / 2.5e-15 / 1.3e-14, the
/// largest nodal pressure difference 5.9e-15 / 2.6e-14 / 3.5e-14 of p0
/// (tolerance: the decks' Newton tolerance 1e-10); Newton iterations 18 /
/// 25 / 27 on both paths (the semi-smooth active sets are the same); the
/// condensed system is the displacements alone, 320 / 1,158 / 4,464
/// against the saddle point's 326 / 1,169 / 4,486 (6 / 11 / 22 active
/// multipliers); p0 vs Hertz 3.1e-2 / 1.8e-2 / 9.9e-3 as the saddle
/// point's.
///
/// Cost (`cargo test -p ctc-verification --test suite -- --ignored
/// condensed_vs_saddle_point_cost --nocapture`, debug profile with the
/// dependencies (faer) at opt-level 3, machine load ~10 on 2 cores; CPU
/// seconds, factorization = assembly of the system + sparse LU):
///
/// | level | free dofs | order saddle / condensed | entries saddle / condensed | Newton | factorize CPU saddle / condensed | process CPU | asymmetry of A |
/// | --- | --- | --- | --- | --- | --- | --- | --- |
/// | 1 | 1,158 | 1,169 / 1,158 | 19,784 / 20,025 | 25 / 25 | 0.117 / 0.122 | 0.150 / 0.140 | 8.0e-2 |
/// | 2 | 4,464 | 4,486 / 4,464 | 78,336 / 78,941 | 27 / 27 | 0.729 / 0.649 | 0.880 / 0.770 | 5.7e-2 |
/// | 3 | 17,556 | 17,598 / 17,556 | 311,864 / 313,057 | 29 / 29 | 4.151 / 4.314 | 4.720 / 4.880 | 4.2e-2 |
///
/// In 2D the active multipliers are few against the dofs (11 / 22 / 42):
/// the condensed system is smaller by them but carries the slave rows onto
/// the master nodes (+0.4 to +1.2 % entries), and the factorizations cost
/// the same within the machine's noise. The condensed matrix is
/// unsymmetric (and the mortar tangent `K` already is, 1.3e-2 in
/// `newton/condensed_tests.rs`): LU, not LDL^T / Cholesky. What it gives
/// is a system in the displacements alone (no zero block).
fn hertz_case() -> VerifyCase {
    VerifyCase {
        name: "hertz_two_cylinders_mortar_condensed",
        title: "Hertz: two elastic cylinders, non-matching arcs, mortar with the dual Lagrange \
                multipliers condensed out vs the saddle point",
        source: "Johnson, Contact Mechanics §4.3; Popp, Gee & Wall IJNME 79 (2009) §4.3",
        tags: &[
            "contact",
            "hertz",
            "mortar",
            "two_bodies",
            "lagrange",
            "condensed",
            "plane_strain",
        ],
        levels: 1,
        checks: HERTZ_CHECKS
            .iter()
            .map(|(n, t)| Check::new(Quantity::Named(n), t))
            .collect(),
        kind: CaseKind::Program(ProgramCase {
            max_levels: 3,
            run: hertz_level,
        }),
    }
}

fn hertz_level(level: usize) -> Result<ProgramLevel, String> {
    let (path, saddle_text) = hertz_deck(level, SADDLE)?;
    let (_, condensed_text) = hertz_deck(level, CONDENSED)?;
    let (sm, s_contact, ss) = hertz_run(&path, &saddle_text)?;
    let (cm, c_contact, cs) = hertz_run(&path, &condensed_text)?;
    let of = measured;
    let (p0_c, p0_err) = of(&cm, Quantity::PeakPressure)?;
    let (p0_s, _) = of(&sm, Quantity::PeakPressure)?;
    let (force_c, _) = of(&cm, Quantity::ContactForce)?;
    let (force_s, _) = of(&sm, Quantity::ContactForce)?;
    let mut out = ProgramLevel {
        h: 1.0 / (16 << level) as f64,
        ..ProgramLevel::default()
    };
    out.add_run(&ss);
    out.add_run(&cs);
    out.values = vec![
        error("p0 condensed vs saddle", ((p0_c - p0_s) / p0_s).abs()),
        error(
            "P condensed vs saddle",
            ((force_c - force_s) / force_s).abs(),
        ),
        error(
            "max |p| difference condensed vs saddle / p0",
            pressure_difference(&c_contact, &s_contact) * mean_closed(&s_contact) / p0_s,
        ),
        error(
            "Newton iterations condensed - saddle",
            cs.newton_iterations.abs_diff(ss.newton_iterations) as f64,
        ),
        error(
            "multipliers in the condensed system",
            multipliers_left(&cs, &ss)?,
        ),
        error("p0 condensed vs Hertz", p0_err),
    ];
    Ok(out)
}

/// Unknowns beyond the displacements in the largest condensed system
/// (0: every multiplier condensed; a fallback to the saddle point would
/// leave them all), after checking that the saddle-point run had
/// multipliers to condense.
fn multipliers_left(condensed: &RunSummary, saddle: &RunSummary) -> Result<f64, String> {
    if saddle.saddle_system.0 <= saddle.free_dofs {
        return Err(format!(
            "the saddle-point run factorized no multiplier (order {}, {} free dofs)",
            saddle.saddle_system.0, saddle.free_dofs
        ));
    }
    if condensed.saddle_system.0 == 0 {
        return Err("the condensed run factorized no contact system".into());
    }
    Ok(condensed
        .saddle_system
        .0
        .saturating_sub(condensed.free_dofs) as f64)
}

/// Mean pressure of the closed nodes.
fn mean_closed(contact: &[NodeContact]) -> f64 {
    let p: Vec<f64> = contact
        .iter()
        .filter(|c| c.status == ContactStatus::Closed)
        .map(|c| c.pressure)
        .collect();
    p.iter().sum::<f64>() / p.len().max(1) as f64
}
