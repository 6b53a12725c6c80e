//! Penalty studies of `ctc verify --report`.
//!
//! - **Sensitivity** ([`penalty_sweep`]): one Hertz level run with an area
//!   penalty swept over decades of `E / h` (h: the contact-zone edge of the
//!   mesh), recording the p0 error, the largest penetration and the Newton
//!   iterations against the penalty, with the Lagrange-multiplier solution
//!   on the same mesh as the limit `k -> infinity` (the seed: "a sensitivity
//!   analysis to this parameter is always needed").
//! - **Mesh scaling** ([`penalty_scaling`], VERIFICATION-CASES.md §7): a
//!   block pressed on a plane on uniform meshes `h = 1/4 .. 1/32` with an
//!   area penalty k, a nodal penalty at fixed `alpha = k h0`, and a nodal
//!   penalty scaled with the mesh, `alpha = k h`: the gap at the middle node
//!   and the error of the mean pressure against the rigid-contact pressure
//!   `E d / H`, against h.

use crate::capture::{Capture, FinalState};
use crate::case::{Case, Quantity, Reference};
use crate::deck::{compile_text, DeckFile};
use crate::measure::max_cell_edge;
use crate::method_variant::MethodVariant;
use crate::report::LevelReport;
use crate::runner::run_level_with;
use ctc_engine::model::Model;
use ctc_engine::solve::{run, RunSummary};
use std::path::Path;
use std::time::Instant;

/// Penalty factors of the sweep: `k = factor x E / h`.
pub const SWEEP_FACTORS: [f64; 7] = [1e-1, 1e0, 1e1, 1e2, 1e3, 1e4, 1e5];

/// One penalty value of the sweep.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct SweepPoint {
    /// `k / (E / h)`.
    pub factor: f64,
    /// The area penalty k (pressure per unit gap).
    pub stiffness: f64,
    /// The measured run.
    pub result: LevelReport,
}

/// The penalty sensitivity study of one case level.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct PenaltySweep {
    /// Case name.
    pub case: String,
    /// Refinement level swept.
    pub level: usize,
    /// Young's modulus of the body.
    pub young: f64,
    /// Contact-zone edge length h of the level.
    pub h: f64,
    /// Prescribed indentation (length).
    pub indentation: f64,
    /// The Lagrange-multiplier run on the same mesh (the `k -> infinity`
    /// limit).
    pub lagrange: Option<LevelReport>,
    /// The penalty runs, increasing k.
    pub points: Vec<SweepPoint>,
    /// Why the sweep could not run.
    pub failure: Option<String>,
}

/// Young's modulus of a Hertz reference (`None` for other references).
fn young_of(reference: &Reference) -> Option<f64> {
    match reference {
        Reference::HertzCylinder { young, .. } | Reference::HertzSphere { young, .. } => {
            Some(*young)
        }
        _ => None,
    }
}

/// Sweeps the area penalty of `case` at `level` over `factors x E / h`.
pub fn penalty_sweep(
    case: &Case,
    cases_dir: &Path,
    level: usize,
    indentation: f64,
    factors: &[f64],
    progress: &mut dyn FnMut(&str),
) -> PenaltySweep {
    let mut out = PenaltySweep {
        case: case.name.to_string(),
        level,
        young: f64::NAN,
        h: f64::NAN,
        indentation,
        lagrange: None,
        points: Vec::new(),
        failure: None,
    };
    let Some(young) = young_of(&case.reference) else {
        out.failure = Some(format!("{}: the sweep needs a Hertz case", case.name));
        return out;
    };
    out.young = young;
    let deck = match DeckFile::read(&cases_dir.join(case.deck)) {
        Ok(d) => d,
        Err(e) => {
            out.failure = Some(e);
            return out;
        }
    };
    // The Lagrange run gives h (the contact-zone edge) and the limit.
    let lagrange = run_level_with(case, &deck, level, Some(&MethodVariant::lagrange(false)));
    if let Some(f) = &lagrange.failure {
        out.failure = Some(format!("Lagrange reference run: {f}"));
        out.lagrange = Some(lagrange);
        return out;
    }
    out.h = lagrange.h;
    out.lagrange = Some(lagrange);
    for &factor in factors {
        let stiffness = factor * young / out.h;
        let result = run_level_with(
            case,
            &deck,
            level,
            Some(&MethodVariant::penalty_area(stiffness)),
        );
        progress(&format!(
            "penalty sweep {} level {level}: k = {factor:e} E/h = {stiffness:.3e}: p0 error {:.2e}, penetration {:.2e}, {} Newton{}",
            case.name,
            result.error_of(Quantity::PeakPressure).unwrap_or(f64::NAN),
            result.max_penetration,
            result.newton_total,
            result.failure.as_deref().map_or(String::new(), |f| format!(" -- FAILED: {}", f.lines().next().unwrap_or("")))
        ));
        out.points.push(SweepPoint {
            factor,
            stiffness,
            result,
        });
    }
    out
}

/// One trial of [`penalty_for_penetration`].
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct TargetTrial {
    /// Area penalty tried.
    pub stiffness: f64,
    /// Largest penetration reached.
    pub penetration: f64,
    /// Relative p0 error.
    pub p0_error: f64,
    /// Newton iterations of the run.
    pub newton: usize,
}

/// A penalty chosen from an allowed penetration.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct PenaltyTarget {
    /// Case name.
    pub case: String,
    /// Refinement level.
    pub level: usize,
    /// The allowed penetration (length).
    pub allowed: f64,
    /// The runs, in order: the first at `k = E / h`, then `k <- 1.1 k g /
    /// g_allowed` (the penetration of a penalty is `p / k` and p hardly
    /// changes once k is stiff) until the penetration is allowed.
    pub trials: Vec<TargetTrial>,
    /// Why no penalty was found.
    pub failure: Option<String>,
}

impl PenaltyTarget {
    /// The accepted trial (the last, if its penetration is allowed).
    pub fn chosen(&self) -> Option<&TargetTrial> {
        self.trials.last().filter(|t| t.penetration <= self.allowed)
    }
}

/// Picks an area penalty for `case` at `level` so that the largest
/// penetration is at most `allowed`: starts from `k = E / h` (h from a
/// Lagrange run on the same mesh) and rescales `k <- 1.1 k g / allowed`
/// after each run, at most `max_runs` runs. This is the harness-level
/// version of the rule; the deck cannot request it yet.
pub fn penalty_for_penetration(
    case: &Case,
    cases_dir: &Path,
    level: usize,
    allowed: f64,
    max_runs: usize,
) -> PenaltyTarget {
    let mut out = PenaltyTarget {
        case: case.name.to_string(),
        level,
        allowed,
        trials: Vec::new(),
        failure: None,
    };
    let Some(young) = young_of(&case.reference) else {
        out.failure = Some(format!("{}: needs a Hertz case", case.name));
        return out;
    };
    let deck = match DeckFile::read(&cases_dir.join(case.deck)) {
        Ok(d) => d,
        Err(e) => {
            out.failure = Some(e);
            return out;
        }
    };
    let lagrange = run_level_with(case, &deck, level, Some(&MethodVariant::lagrange(false)));
    if let Some(f) = lagrange.failure {
        out.failure = Some(format!("Lagrange run for h: {f}"));
        return out;
    }
    let mut k = young / lagrange.h;
    for _ in 0..max_runs {
        let r = run_level_with(case, &deck, level, Some(&MethodVariant::penalty_area(k)));
        if let Some(f) = r.failure {
            out.failure = Some(format!("k = {k:e}: {f}"));
            return out;
        }
        let g = r.max_penetration;
        out.trials.push(TargetTrial {
            stiffness: k,
            penetration: g,
            p0_error: r.error_of(Quantity::PeakPressure).unwrap_or(f64::NAN),
            newton: r.newton_total,
        });
        if g <= allowed {
            return out;
        }
        k *= 1.1 * g / allowed;
    }
    out.failure = Some(format!(
        "penetration still above {allowed:e} after {max_runs} runs"
    ));
    out
}

/// The three penalty flavours of the mesh-scaling study.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum ScalingFlavour {
    /// Area-weighted penalty k (pressure per unit gap), fixed.
    Area,
    /// Nodal penalty at fixed `alpha = k h0` (h0: the coarsest mesh).
    NodalFixed,
    /// Nodal penalty `alpha = k h`, halved with h.
    NodalScaled,
}

impl ScalingFlavour {
    /// All flavours, in report order.
    pub const ALL: [ScalingFlavour; 3] = [
        ScalingFlavour::Area,
        ScalingFlavour::NodalFixed,
        ScalingFlavour::NodalScaled,
    ];

    /// Label for tables and legends.
    pub fn label(self) -> &'static str {
        match self {
            ScalingFlavour::Area => "area k",
            ScalingFlavour::NodalFixed => "nodal alpha = k h0 (fixed)",
            ScalingFlavour::NodalScaled => "nodal alpha = k h (scaled)",
        }
    }
}

/// One flavour at one mesh size.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct ScalingPoint {
    /// The penalty flavour.
    pub flavour: ScalingFlavour,
    /// Refinement level.
    pub level: usize,
    /// Mesh size (largest cell edge).
    pub h: f64,
    /// The penalty used (k for area, alpha for nodal).
    pub penalty: f64,
    /// Gap of the slave node nearest the middle of the contact face.
    pub gap_middle: f64,
    /// Largest penetration (engine's `max_penetration`).
    pub max_penetration: f64,
    /// Mean contact pressure (total contact force / face width).
    pub pressure: f64,
    /// `|pressure - E d / H| / (E d / H)`: the penalty error against rigid
    /// contact.
    pub pressure_error: f64,
    /// Newton iterations.
    pub newton: usize,
    /// Nodes of the model.
    pub nodes: usize,
    /// Free degrees of freedom.
    pub free_dofs: usize,
    /// Solve wall time, seconds.
    pub solve_time: f64,
}

/// The mesh-scaling study.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct PenaltyScaling {
    /// Deck path.
    pub deck: String,
    /// The area penalty k (pressure per unit gap) all flavours derive from.
    pub stiffness: f64,
    /// Rigid-contact pressure `E d / H`.
    pub rigid_pressure: f64,
    /// Every flavour at every level.
    pub points: Vec<ScalingPoint>,
    /// Failures (level, flavour, message).
    pub failures: Vec<String>,
}

/// Constants of `cases/penalty_scaling.ctc`.
pub mod scaling_deck {
    /// Deck file name.
    pub const DECK: &str = "penalty_scaling.ctc";
    /// Young's modulus.
    pub const YOUNG: f64 = 1e3;
    /// Block height H (and width).
    pub const HEIGHT: f64 = 1.0;
    /// Prescribed top displacement d.
    pub const INDENT: f64 = 0.01;
    /// Area penalty k written in the deck.
    pub const STIFFNESS: f64 = 1e4;
}

/// Solves a compiled model, keeping the last converged state.
fn solve(model: &Model) -> Result<(RunSummary, FinalState, f64), String> {
    let mut capture = Capture::default();
    let t = Instant::now();
    let summary = run(model, &mut capture).map_err(|e| format!("solver: {}", e.message))?;
    let time = t.elapsed().as_secs_f64();
    let state = capture
        .last
        .ok_or_else(|| "the solver converged no increment".to_string())?;
    Ok((summary, state, time))
}

/// Runs the mesh-scaling study on `cases/penalty_scaling.ctc`, levels
/// `0..levels`.
pub fn penalty_scaling(
    cases_dir: &Path,
    levels: usize,
    progress: &mut dyn FnMut(&str),
) -> PenaltyScaling {
    use scaling_deck::*;
    let path = cases_dir.join(DECK);
    let rigid = YOUNG * INDENT / HEIGHT;
    let mut out = PenaltyScaling {
        deck: path.display().to_string(),
        stiffness: STIFFNESS,
        rigid_pressure: rigid,
        points: Vec::new(),
        failures: Vec::new(),
    };
    let deck = match DeckFile::read(&path) {
        Ok(d) => d,
        Err(e) => {
            out.failures.push(e);
            return out;
        }
    };
    let levels = levels.min(deck.levels());
    let mut h0 = f64::NAN;
    for level in 0..levels {
        let text = match deck.render(level) {
            Ok(t) => t,
            Err(e) => {
                out.failures.push(e);
                continue;
            }
        };
        let h = match compile_text(&path, &text) {
            Ok(m) => max_cell_edge(&m),
            Err(e) => {
                out.failures.push(e);
                continue;
            }
        };
        if level == 0 {
            h0 = h;
        }
        for flavour in ScalingFlavour::ALL {
            let point = match scaling_point(&path, &text, level, h, h0, flavour) {
                Ok(p) => p,
                Err(e) => {
                    out.failures
                        .push(format!("level {level} {}: {e}", flavour.label()));
                    continue;
                }
            };
            progress(&format!(
                "penalty scaling level {level} (h = {h:.4}) {}: middle gap {:.3e}, pressure error {:.2e}",
                flavour.label(),
                point.gap_middle,
                point.pressure_error
            ));
            out.points.push(point);
        }
    }
    out
}

/// Solves level `level` of the scaling deck (rendered `text`, largest cell
/// edge `h`, `h0` at level 0) with one penalty flavour and measures it.
pub fn scaling_point(
    path: &Path,
    text: &str,
    level: usize,
    h: f64,
    h0: f64,
    flavour: ScalingFlavour,
) -> Result<ScalingPoint, String> {
    use scaling_deck::*;
    let rigid = YOUNG * INDENT / HEIGHT;
    let (variant, penalty) = match flavour {
        ScalingFlavour::Area => (MethodVariant::penalty_area(STIFFNESS), STIFFNESS),
        ScalingFlavour::NodalFixed => {
            let a = STIFFNESS * h0;
            (MethodVariant::penalty_nodal(a), a)
        }
        ScalingFlavour::NodalScaled => {
            let a = STIFFNESS * h;
            (MethodVariant::penalty_nodal(a), a)
        }
    };
    let model = variant.apply(text).and_then(|t| compile_text(path, &t))?;
    let (summary, state, time) = solve(&model)?;
    let p = scaling_measure(&model, &state)?;
    Ok(ScalingPoint {
        flavour,
        level,
        h,
        penalty,
        gap_middle: p.gap_middle,
        max_penetration: summary.increments.last().map_or(0.0, |i| i.max_penetration),
        pressure: p.pressure,
        pressure_error: (p.pressure - rigid).abs() / rigid,
        newton: summary.newton_iterations,
        nodes: summary.nodes,
        free_dofs: summary.free_dofs,
        solve_time: time,
    })
}

/// Middle-node gap and mean pressure of the block on the plane.
struct ScalingMeasure {
    gap_middle: f64,
    pressure: f64,
}

/// Reads the gap of the slave node nearest `x = W/2` and the mean pressure
/// (total contact force over the face width) of pair 0.
fn scaling_measure(model: &Model, state: &FinalState) -> Result<ScalingMeasure, String> {
    let contacts = state
        .contact
        .first()
        .ok_or("the model has no contact pair")?;
    let xs: Vec<f64> = contacts
        .iter()
        .map(|c| model.mesh.nodes[c.node][0])
        .collect();
    let (lo, hi) = xs
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| {
            (a.min(x), b.max(x))
        });
    let width = hi - lo;
    if contacts.is_empty() || width <= 0.0 {
        return Err("the contact face has no width".into());
    }
    let mid = 0.5 * (lo + hi);
    let middle = contacts
        .iter()
        .zip(&xs)
        .min_by(|a, b| (a.1 - mid).abs().total_cmp(&(b.1 - mid).abs()))
        .map(|(c, _)| c.gap)
        .unwrap_or(f64::NAN);
    let force: f64 = contacts.iter().map(|c| c.force[1]).sum();
    Ok(ScalingMeasure {
        gap_middle: middle,
        pressure: force / (width * model.analysis.thickness),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Penalty sensitivity on the coarsest Hertz cylinder: the penetration
    /// falls as 1/k (p0 / k), and at a large k the p0 error tends to the
    /// Lagrange one on the same mesh.
    #[test]
    fn penalty_sweep_hertz_cylinder_penetration_scales_as_one_over_k() {
        let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("cases");
        let case = crate::cases::hertz_cylinder();
        let s = penalty_sweep(&case, &dir, 0, 0.01, &[1.0, 1e2, 1e4], &mut |_| {});
        assert!(s.failure.is_none(), "{:?}", s.failure);
        assert!(s.h > 0.0 && s.young == 1e3);
        let g: Vec<f64> = s.points.iter().map(|p| p.result.max_penetration).collect();
        for w in g.windows(2) {
            let r = w[0] / w[1];
            assert!(
                (10.0..1000.0).contains(&r),
                "penetration ratio {r} over 2 decades of k"
            );
        }
        let lag = s.lagrange.as_ref().unwrap();
        let e_lag = lag.error_of(Quantity::PeakPressure).unwrap();
        let e_stiff = s.points[2].result.error_of(Quantity::PeakPressure).unwrap();
        assert!(
            (e_stiff - e_lag).abs() < 1e-3,
            "{e_stiff} vs Lagrange {e_lag}"
        );
    }

    /// An allowed penetration picks the penalty: reached within a few runs.
    #[test]
    fn penalty_for_penetration_hertz_cylinder() {
        let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("cases");
        let t = penalty_for_penetration(&crate::cases::hertz_cylinder(), &dir, 0, 1e-6, 5);
        assert!(t.failure.is_none(), "{:?}", t.failure);
        let c = t.chosen().expect("a penalty");
        assert!(c.penetration <= 1e-6 && c.penetration > 0.5e-6, "{c:?}");
        assert!(t.trials.len() <= 3, "{:?}", t.trials);
    }
}
