//! Runs cases level by level: render the deck, compile, solve with a
//! [`Capture`] observer, measure, judge against the tolerances, compute the
//! observed convergence rates.

use crate::capture::Capture;
use crate::case::{Case, Check};
use crate::deck::{compile_text, DeckFile};
use crate::measure::{measure, Value};
use crate::method_variant::MethodVariant;
use crate::report::{observed_rate, CaseReport, Judged, LevelReport, RateReport};
use ctc_engine::solve::{run, RunSummary};
use std::path::Path;
use std::time::Instant;

/// Runs levels `0..=last` of `case`, where `last` is `max_level` (capped at
/// the levels the deck defines) or the case's default number of levels.
/// `progress` receives one line per level as it finishes.
pub fn run_case(
    case: &Case,
    cases_dir: &Path,
    max_level: Option<usize>,
    progress: &mut dyn FnMut(&str),
) -> CaseReport {
    let path = cases_dir.join(case.deck);
    let mut report = CaseReport {
        name: case.name.to_string(),
        title: case.title.to_string(),
        source: case.source.to_string(),
        deck: path.display().to_string(),
        levels: Vec::new(),
        rates: Vec::new(),
        failure: None,
    };
    let deck = match DeckFile::read(&path) {
        Ok(d) => d,
        Err(e) => {
            report.failure = Some(e);
            return report;
        }
    };
    let count = match max_level {
        Some(m) => (m + 1).min(deck.levels()),
        None => case.levels.min(deck.levels()),
    };
    for level in 0..count {
        let l = run_level(case, &deck, level);
        progress(&progress_line(case.name, &l));
        report.levels.push(l);
    }
    report.rates = rates(case, &report.levels);
    report
}

/// The progress line of a finished level: dofs, Newton iterations, time,
/// verdict.
pub fn progress_line(name: &str, l: &LevelReport) -> String {
    format!(
        "{name} level {}: {} dofs, {} Newton iterations, {:.2} s{}",
        l.level,
        l.free_dofs,
        l.newton_total,
        l.solve_time,
        match (&l.failure, l.passed()) {
            (Some(f), _) => format!(" -- FAILED: {}", f.lines().next().unwrap_or("")),
            (None, true) => " -- pass".to_string(),
            (None, false) => " -- FAIL".to_string(),
        }
    )
}

/// Runs one level of a case.
pub fn run_level(case: &Case, deck: &DeckFile, level: usize) -> LevelReport {
    run_level_with(case, deck, level, None)
}

/// Runs one level of a case with the deck's contact method replaced by
/// `method` (`None`: as written), see [`MethodVariant`].
pub fn run_level_with(
    case: &Case,
    deck: &DeckFile,
    level: usize,
    method: Option<&MethodVariant>,
) -> LevelReport {
    let mut report = LevelReport {
        level,
        h: f64::NAN,
        nodes: 0,
        free_dofs: 0,
        increments: 0,
        newton_total: 0,
        newton_max: 0,
        cutbacks: 0,
        solve_time: 0.0,
        compile_time: 0.0,
        values: Vec::new(),
        failure: None,
        profile: None,
        max_penetration: 0.0,
        contact_iterations: 0,
        figures: Vec::new(),
    };
    let t0 = Instant::now();
    let compiled = match method {
        None => deck.compile(level),
        Some(m) => deck
            .render(level)
            .and_then(|text| m.apply(&text))
            .and_then(|text| compile_text(&deck.path, &text)),
    };
    let model = match compiled {
        Ok(m) => m,
        Err(e) => {
            report.failure = Some(e);
            return report;
        }
    };
    report.compile_time = t0.elapsed().as_secs_f64();
    report.nodes = model.mesh.nodes.len();
    let mut capture = Capture::default();
    let t1 = Instant::now();
    let outcome = run(&model, &mut capture);
    report.solve_time = t1.elapsed().as_secs_f64();
    let summary = match outcome {
        Ok(s) => s,
        Err(e) => {
            fill_counts(&mut report, &e.summary);
            report.failure = Some(format!("solver: {}", e.message));
            return report;
        }
    };
    fill_counts(&mut report, &summary);
    let Some(state) = capture.last.as_ref() else {
        report.failure = Some("the solver converged no increment (no state to measure)".into());
        return report;
    };
    match measure(&case.reference, &model, state) {
        Ok(m) => {
            report.h = m.h;
            report.profile = m.profile;
            report.values = judge(&case.checks, level, m.values);
        }
        Err(e) => report.failure = Some(format!("measurement: {e}")),
    }
    report
}

/// Judges measured values against the tolerances of `checks` at `level`
/// (a value without a check is reported, not judged).
pub fn judge(checks: &[Check], level: usize, values: Vec<Value>) -> Vec<Judged> {
    values
        .into_iter()
        .map(|v| {
            let tolerance = checks
                .iter()
                .find(|c| c.quantity == v.quantity)
                .map(|c| c.tolerance_at(level));
            Judged {
                passed: tolerance.is_none_or(|t| v.error <= t),
                quantity: v.quantity,
                reference: v.reference,
                computed: v.computed,
                error: v.error,
                tolerance,
            }
        })
        .collect()
}

/// Copies the iteration counts of a run summary.
fn fill_counts(report: &mut LevelReport, summary: &RunSummary) {
    report.free_dofs = summary.free_dofs;
    report.increments = summary.increments.len();
    report.newton_total = summary.newton_iterations;
    report.newton_max = summary
        .increments
        .iter()
        .map(|i| i.iterations)
        .max()
        .unwrap_or(0);
    report.cutbacks = summary.cutbacks;
    report.contact_iterations = summary
        .increments
        .iter()
        .map(|i| i.contact_iterations)
        .sum();
    report.max_penetration = summary.increments.last().map_or(0.0, |i| i.max_penetration);
}

/// Observed rates between consecutive successful levels; the case's
/// minimum rate is checked on the last pair when it reaches the case's
/// default finest level (a run limited by `max_level` reports rates only).
pub fn rates(case: &Case, levels: &[LevelReport]) -> Vec<RateReport> {
    rates_of(&case.checks, case.levels, levels)
}

/// [`rates`] for any case: `checks` carry the minimum rates, judged on the
/// last pair once level `default_levels - 1` is reached.
pub fn rates_of(
    checks: &[Check],
    default_levels: usize,
    levels: &[LevelReport],
) -> Vec<RateReport> {
    let ok: Vec<&LevelReport> = levels.iter().filter(|l| l.failure.is_none()).collect();
    let mut out = Vec::new();
    let quantities: Vec<_> = {
        let mut qs = Vec::new();
        for l in &ok {
            for v in &l.values {
                if !qs.contains(&v.quantity) {
                    qs.push(v.quantity);
                }
            }
        }
        qs
    };
    for q in quantities {
        let check = checks.iter().find(|c| c.quantity == q);
        for (i, w) in ok.windows(2).enumerate() {
            let (Some(e1), Some(e2)) = (w[0].error_of(q), w[1].error_of(q)) else {
                continue;
            };
            let rate = observed_rate(e1, e2, w[0].h, w[1].h);
            // Judged on the last pair, and only once the case's default
            // finest level is reached: coarser pairs are pre-asymptotic.
            let last = i + 2 == ok.len() && w[1].level + 1 >= default_levels;
            let min_rate = if last {
                check.and_then(|c| c.min_rate)
            } else {
                None
            };
            let passed = match min_rate {
                Some(m) => rate.is_some_and(|r| r >= m),
                None => true,
            };
            out.push(RateReport {
                quantity: q,
                from_level: w[0].level,
                to_level: w[1].level,
                rate,
                min_rate,
                passed,
            });
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::case::{Check, Quantity, Reference};
    use crate::report::Judged;

    fn level(level: usize, h: f64, error: f64) -> LevelReport {
        LevelReport {
            level,
            h,
            nodes: 0,
            free_dofs: 0,
            increments: 1,
            newton_total: 1,
            newton_max: 1,
            cutbacks: 0,
            solve_time: 0.0,
            compile_time: 0.0,
            values: vec![Judged {
                quantity: Quantity::InnerDisplacement,
                reference: Some(1.0),
                computed: 1.0,
                error,
                tolerance: None,
                passed: true,
            }],
            failure: None,
            profile: None,
            max_penetration: 0.0,
            contact_iterations: 0,
            figures: Vec::new(),
        }
    }

    fn case(levels: usize) -> Case {
        Case {
            name: "c",
            title: "t",
            source: "s",
            deck: "d.ctc",
            tags: &[],
            levels,
            reference: Reference::Patch {
                patch: crate::cases::patch_plane_strain_patch(),
                pair: 0,
            },
            checks: vec![Check::new(Quantity::InnerDisplacement, &[1.0]).with_min_rate(1.5)],
        }
    }

    /// Rates are judged only on the pair reaching the default finest level.
    #[test]
    fn rate_check_only_on_default_finest_pair() {
        // Pre-asymptotic first pair (rate 1), asymptotic second (rate 2).
        let levels = [
            level(0, 0.4, 4e-2),
            level(1, 0.2, 2e-2),
            level(2, 0.1, 5e-3),
        ];
        let all = rates(&case(3), &levels);
        assert_eq!(all.len(), 2);
        assert!(all[0].min_rate.is_none() && all[0].passed);
        assert_eq!(all[1].min_rate, Some(1.5));
        assert!(all[1].passed, "{:?}", all[1]);
        // A run stopped at level 1 (max_level) reports but does not judge.
        let partial = rates(&case(3), &levels[..2]);
        assert!(partial[0].min_rate.is_none() && partial[0].passed);
        // A case whose default finest is level 1 judges the first pair.
        let judged = rates(&case(2), &levels[..2]);
        assert_eq!(judged[0].min_rate, Some(1.5));
        assert!(!judged[0].passed, "rate 1 < 1.5 must fail");
    }
}
