//! Comparison of the contact methods on the Hertz cases: the same deck, the
//! same meshes at every refinement level, the contact method replaced by
//! each [`MethodVariant`] (penalty at several stiffnesses, Lagrange
//! multipliers, augmented Lagrangian). Every run is measured and judged
//! exactly like the case itself ([`crate::runner::run_level_with`]), and
//! records the wall time, the Newton and contact (active-set / Uzawa)
//! iterations and the largest penetration: the data of the
//! error-against-run-time (work-precision) plot.

use crate::case::{Case, Quantity};
use crate::cases;
use crate::deck::DeckFile;
use crate::method_variant::{MethodFamily, MethodVariant};
use crate::report::LevelReport;
use crate::runner::run_level_with;
use std::path::Path;

/// A method comparison to run on one case.
#[derive(Debug, Clone, PartialEq)]
pub struct MethodStudy {
    /// The case (deck, reference, tolerances).
    pub case: Case,
    /// Prescribed indentation of the deck (length): the scale penetrations
    /// are compared with.
    pub indentation: f64,
    /// Refinement levels run (0..levels).
    pub levels: usize,
    /// The methods compared.
    pub variants: Vec<MethodVariant>,
}

/// Area-penalty stiffnesses compared (pressure per unit gap; E = 1e3 in
/// the Hertz decks, so these are 1e2..1e4 x E per unit length). The last
/// is the decks' own and is judged with the case tolerances; the softer
/// ones show the penalty error (reported, not judged).
pub const PENALTIES: [f64; 3] = [1e5, 1e6, 1e7];

/// The penalty stiffness written in the Hertz decks.
pub const DECK_PENALTY: f64 = 1e7;

/// Penalty of the augmented Lagrangian (the smallest of [`PENALTIES`]: the
/// Uzawa loop makes up for it).
pub const AL_PENALTY: f64 = 1e5;

/// Relative penetration tolerance of the augmented Lagrangian: `gmax* =
/// AL_TOLERANCE x indentation`.
pub const AL_TOLERANCE: f64 = 1e-4;

/// The methods compared on a deck with the given indentation.
pub fn variants(indentation: f64) -> Vec<MethodVariant> {
    let mut v: Vec<MethodVariant> = PENALTIES
        .iter()
        .map(|&k| {
            let v = MethodVariant::penalty_area(k);
            if k < DECK_PENALTY {
                v.unjudged()
            } else {
                v
            }
        })
        .collect();
    v.push(MethodVariant::lagrange(false));
    v.push(MethodVariant::lagrange(true));
    v.push(MethodVariant::augmented(
        AL_PENALTY,
        AL_TOLERANCE * indentation,
    ));
    v
}

/// The method comparisons of `ctc verify --report`: the Hertz cylinder
/// (plane strain, indentation 0.01) and sphere (axisymmetric, 0.005), at
/// the first `levels` refinement levels.
pub fn studies(levels: usize) -> Vec<MethodStudy> {
    [
        (cases::hertz_cylinder(), 0.01),
        (cases::hertz_sphere(), 0.005),
    ]
    .into_iter()
    .map(|(case, indentation)| MethodStudy {
        case,
        indentation,
        levels,
        variants: variants(indentation),
    })
    .collect()
}

/// One method at one level.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct MethodRun {
    /// The method.
    pub method: MethodVariant,
    /// The measured and judged run (errors, wall time, iterations,
    /// penetration).
    pub result: LevelReport,
}

impl MethodRun {
    /// Computed peak pressure p0 (NaN if not measured).
    pub fn p0(&self) -> f64 {
        self.result
            .values
            .iter()
            .find(|v| v.quantity == Quantity::PeakPressure)
            .map_or(f64::NAN, |v| v.computed)
    }
}

/// All methods at all levels of one case.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct MethodComparison {
    /// Case name.
    pub case: String,
    /// Case title.
    pub title: String,
    /// Deck path.
    pub deck: String,
    /// Prescribed indentation (length).
    pub indentation: f64,
    /// Runs, method-major (all levels of the first method first).
    pub runs: Vec<MethodRun>,
    /// Why the comparison could not run (unreadable deck).
    pub failure: Option<String>,
}

impl MethodComparison {
    /// Whether every run converged, every quantity of a judged variant
    /// passed and the penetrations meet [`Self::penetration_failures`].
    pub fn passed(&self) -> bool {
        self.failure.is_none()
            && !self.runs.is_empty()
            && self
                .runs
                .iter()
                .all(|r| r.result.failure.is_none() && (!r.method.judged || r.result.passed()))
            && self.penetration_failures().is_empty()
    }

    /// The runs of method `label`, coarsest level first.
    pub fn runs_of<'a>(&'a self, label: &'a str) -> impl Iterator<Item = &'a MethodRun> + 'a {
        self.runs.iter().filter(move |r| r.method.label == label)
    }

    /// Method labels in run order.
    pub fn labels(&self) -> Vec<String> {
        let mut out: Vec<String> = Vec::new();
        for r in &self.runs {
            if !out.contains(&r.method.label) {
                out.push(r.method.label.clone());
            }
        }
        out
    }

    /// Penetration checks: Lagrange to round-off (`<= 1e-12 x
    /// indentation`), augmented Lagrangian below its tolerance, area
    /// penalty `max penetration = p0 / k` within 10 %. One message per
    /// violation.
    pub fn penetration_failures(&self) -> Vec<String> {
        let mut out = Vec::new();
        for r in self.runs.iter().filter(|r| r.result.failure.is_none()) {
            let g = r.result.max_penetration;
            let what = format!("{} level {} {}", self.case, r.result.level, r.method.label);
            match r.method.family {
                MethodFamily::Lagrange => {
                    if g > 1e-12 * self.indentation {
                        out.push(format!("{what}: penetration {g:.3e} > 1e-12 x indentation"));
                    }
                }
                MethodFamily::AugmentedLagrange => {
                    let tol = r.method.tolerance.unwrap_or(0.0);
                    if g > tol {
                        out.push(format!("{what}: penetration {g:.3e} > tolerance {tol:.3e}"));
                    }
                }
                MethodFamily::Penalty => {
                    let expected = r.p0() / r.method.penalty.unwrap_or(f64::NAN);
                    let rel = (g - expected).abs() / expected;
                    if rel.is_nan() || rel > 0.1 {
                        out.push(format!(
                            "{what}: penetration {g:.3e} vs p0/k = {expected:.3e} (differ by {rel:.1e} > 10 %)"
                        ));
                    }
                }
            }
        }
        out
    }
}

/// Runs `study` (levels `0..study.levels`, capped at the deck's levels)
/// with decks from `cases_dir`; `progress` receives one line per run.
pub fn compare_methods(
    study: &MethodStudy,
    cases_dir: &Path,
    progress: &mut dyn FnMut(&str),
) -> MethodComparison {
    let path = cases_dir.join(study.case.deck);
    let mut out = MethodComparison {
        case: study.case.name.to_string(),
        title: study.case.title.to_string(),
        deck: path.display().to_string(),
        indentation: study.indentation,
        runs: Vec::new(),
        failure: None,
    };
    let deck = match DeckFile::read(&path) {
        Ok(d) => d,
        Err(e) => {
            out.failure = Some(e);
            return out;
        }
    };
    let levels = study.levels.min(deck.levels());
    for v in &study.variants {
        for level in 0..levels {
            let result = run_level_with(&study.case, &deck, level, Some(v));
            progress(&format!(
                "methods {} {} level {level}: {} Newton, {} contact iterations, penetration {:.2e}, {:.3} s{}",
                study.case.name,
                v.label,
                result.newton_total,
                result.contact_iterations,
                result.max_penetration,
                result.solve_time,
                result
                    .failure
                    .as_deref()
                    .map_or(String::new(), |f| format!(" -- FAILED: {}", f.lines().next().unwrap_or("")))
            ));
            out.runs.push(MethodRun {
                method: v.clone(),
                result,
            });
        }
    }
    out
}
