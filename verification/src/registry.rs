//! The `ctc verify` case registry: every verification case of the
//! repository, with its name, tags, tolerances and levels.
//!
//! Two kinds of case share one shape ([`VerifyCase`]):
//! - [`CaseKind::Deck`]: a deck of `cases/` with refinement levels compared
//!   with a closed form ([`crate::cases`], run by [`crate::runner`]);
//! - [`CaseKind::Program`]: a program that builds and solves the problem of
//!   a level and returns the measured quantities (friction, upsetting,
//!   thermal, cross-code comparisons...); the registry judges them against
//!   the case's [`Check`]s exactly as for decks.
//!
//! `ctc verify --list` prints the registry, `--tag` and a name filter
//! select from it, and the cargo tests run the same entries (so a case
//! cannot pass in one and fail in the other). To register a case, add a
//! constructor to [`all`].

use crate::case::{Case, Check};
use crate::measure::Value;
use crate::report::{CaseReport, LevelReport};
use crate::runner;
use std::collections::BTreeMap;
use std::path::Path;
use std::sync::{Arc, Mutex, OnceLock};
use std::time::Instant;

/// What one level of a program case measured.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ProgramLevel {
    /// The measured quantities (judged by the case's checks).
    pub values: Vec<Value>,
    /// Characteristic mesh size (for rates; NaN when meaningless).
    pub h: f64,
    /// Nodes of the model(s).
    pub nodes: usize,
    /// Free degrees of freedom (of the largest model run).
    pub free_dofs: usize,
    /// Converged increments (all runs).
    pub increments: usize,
    /// Newton iterations (all runs).
    pub newton_total: usize,
    /// Largest number of Newton iterations of an increment.
    pub newton_max: usize,
    /// Cutbacks (all runs).
    pub cutbacks: usize,
    /// Figures drawn into the report ([`crate::plot::Figure`]).
    pub figures: Vec<crate::plot::Figure>,
}

impl ProgramLevel {
    /// Adds the counts of one run of the level: nodes and free dofs of the
    /// largest model, increments, Newton iterations and cutbacks summed,
    /// the largest iteration count of an increment.
    pub fn add_run(&mut self, summary: &ctc_engine::solve::RunSummary) {
        self.nodes = self.nodes.max(summary.nodes);
        self.free_dofs = self.free_dofs.max(summary.free_dofs);
        self.increments += summary.increments.len();
        self.newton_total += summary.newton_iterations;
        let most = summary.increments.iter().map(|i| i.iterations).max();
        self.newton_max = self.newton_max.max(most.unwrap_or(0));
        self.cutbacks += summary.cutbacks;
    }
}

/// A case computed by a program.
#[derive(Debug, Clone)]
pub struct ProgramCase {
    /// Levels the program defines (`run` accepts `0..max_levels`).
    pub max_levels: usize,
    /// Solves level `level` and measures it.
    pub run: fn(usize) -> Result<ProgramLevel, String>,
}

/// How a case runs.
#[derive(Debug, Clone)]
pub enum CaseKind {
    /// A deck with refinement levels against a closed form.
    Deck(Case),
    /// A program.
    Program(ProgramCase),
}

/// One case of `ctc verify`.
#[derive(Debug, Clone)]
pub struct VerifyCase {
    /// Identifier (the name filter matches substrings of it).
    pub name: &'static str,
    /// What it shows (one line).
    pub title: &'static str,
    /// Where the reference comes from (paper, book section, other code).
    pub source: &'static str,
    /// Tags `--tag` selects on.
    pub tags: &'static [&'static str],
    /// Levels run by default (`ctc verify`); `--max-level` runs more, up
    /// to what the case defines.
    pub levels: usize,
    /// Quantities judged, with their per-level tolerances and rates.
    pub checks: Vec<Check>,
    /// How it runs.
    pub kind: CaseKind,
}

impl VerifyCase {
    /// A deck case of [`crate::cases`].
    pub fn deck(case: Case) -> VerifyCase {
        VerifyCase {
            name: case.name,
            title: case.title,
            source: case.source,
            tags: case.tags,
            levels: case.levels,
            checks: case.checks.clone(),
            kind: CaseKind::Deck(case),
        }
    }

    /// Whether the case matches a name filter (substring) and carries
    /// every tag of `tags`.
    pub fn matches(&self, filter: Option<&str>, tags: &[String]) -> bool {
        filter.is_none_or(|f| self.name.contains(f))
            && tags.iter().all(|t| self.tags.contains(&t.as_str()))
    }

    /// The levels the case defines (`None`: read from the deck's
    /// refinement markers when it runs).
    pub fn max_levels(&self) -> Option<usize> {
        match &self.kind {
            CaseKind::Deck(_) => None,
            CaseKind::Program(p) => Some(p.max_levels),
        }
    }

    /// "quantity <= tolerance" at the finest default level, per check.
    pub fn tolerance_summary(&self) -> String {
        let level = self.levels.saturating_sub(1);
        let parts: Vec<String> = self
            .checks
            .iter()
            .map(|c| {
                let mut s = format!("{} <= {:e}", c.quantity, c.tolerance_at(level));
                if let Some(r) = c.min_rate {
                    s.push_str(&format!(" (rate >= {r})"));
                }
                s
            })
            .collect();
        parts.join(", ")
    }

    /// Runs levels `0..=max_level` (capped by what the case defines), or
    /// the default levels. `progress` gets one line per level.
    pub fn run(
        &self,
        cases_dir: &Path,
        max_level: Option<usize>,
        progress: &mut dyn FnMut(&str),
    ) -> CaseReport {
        match &self.kind {
            CaseKind::Deck(case) => runner::run_case(case, cases_dir, max_level, progress),
            CaseKind::Program(p) => self.run_program(p, max_level, progress),
        }
    }

    fn run_program(
        &self,
        p: &ProgramCase,
        max_level: Option<usize>,
        progress: &mut dyn FnMut(&str),
    ) -> CaseReport {
        let count = match max_level {
            Some(m) => (m + 1).min(p.max_levels),
            None => self.levels.min(p.max_levels),
        };
        let mut report = CaseReport {
            name: self.name.to_string(),
            title: self.title.to_string(),
            source: self.source.to_string(),
            deck: String::new(),
            levels: Vec::new(),
            rates: Vec::new(),
            failure: None,
        };
        for level in 0..count {
            let t = Instant::now();
            // a panicking program fails its level, not the suite
            let outcome = std::panic::catch_unwind(|| (p.run)(level))
                .unwrap_or_else(|_| Err("the case panicked".to_string()));
            let solve_time = t.elapsed().as_secs_f64();
            let mut l = LevelReport {
                level,
                h: f64::NAN,
                nodes: 0,
                free_dofs: 0,
                increments: 0,
                newton_total: 0,
                newton_max: 0,
                cutbacks: 0,
                solve_time,
                compile_time: 0.0,
                values: Vec::new(),
                failure: None,
                profile: None,
                max_penetration: 0.0,
                contact_iterations: 0,
                figures: Vec::new(),
            };
            match outcome {
                Ok(m) => {
                    l.h = m.h;
                    l.nodes = m.nodes;
                    l.free_dofs = m.free_dofs;
                    l.increments = m.increments;
                    l.newton_total = m.newton_total;
                    l.newton_max = m.newton_max;
                    l.cutbacks = m.cutbacks;
                    l.figures = m.figures;
                    l.values = runner::judge(&self.checks, level, m.values);
                    if l.values.is_empty() {
                        l.failure = Some("the case measured nothing".into());
                    }
                }
                Err(e) => l.failure = Some(e),
            }
            progress(&runner::progress_line(self.name, &l));
            report.levels.push(l);
        }
        report.rates = runner::rates_of(&self.checks, self.levels, &report.levels);
        report
    }
}

/// The cases whose default level the `ctc` crate's cargo tests run (the
/// run shared with the examples test's summary of the deck, and judged
/// by the case's checks there): the catalogue test of this crate
/// (`cases_coarse`) leaves them out, so that `cargo test` runs each
/// flight once. `ctc verify` runs them as any other case.
pub const RUN_BY_THE_CTC_SUITE: &[&str] = &["blade_loss", "blade_loss_3d"];

/// Every case, in report order.
pub fn all() -> Vec<VerifyCase> {
    let mut v: Vec<VerifyCase> = crate::cases::all()
        .into_iter()
        .map(VerifyCase::deck)
        .collect();
    v.extend(crate::programs::all());
    v
}

/// The case called `name`.
pub fn find(name: &str) -> Option<VerifyCase> {
    all().into_iter().find(|c| c.name == name)
}

/// The reports of cases run on their default levels from the default
/// decks, kept for the life of the process: a program that asks for a case
/// twice (a test binary running the whole catalogue and a test of that
/// case) runs it once. A case asked for by two threads at once runs once;
/// the second waits for it.
type DefaultRuns = BTreeMap<&'static str, Arc<OnceLock<CaseReport>>>;
static DEFAULT_RUNS: Mutex<DefaultRuns> = Mutex::new(BTreeMap::new());

/// `case` on its default levels from the default decks, run once per
/// process (see [`DEFAULT_RUNS`]); `progress` hears the levels of a run
/// made here, not of one found done.
pub fn run_default(case: &VerifyCase, progress: &mut dyn FnMut(&str)) -> CaseReport {
    let cell = DEFAULT_RUNS
        .lock()
        .unwrap_or_else(|e| e.into_inner())
        .entry(case.name)
        .or_default()
        .clone();
    cell.get_or_init(|| case.run(&crate::default_cases_dir(), None, progress))
        .clone()
}

/// Runs the case `name` on its default levels as a cargo test does: prints
/// every value of the finest level, panics unless the case passes its own
/// tolerances, and returns the report for further checks. The run is
/// shared with every other default run of the case in the process
/// ([`run_default`]).
pub fn run_passing(name: &str) -> CaseReport {
    let case = find(name).unwrap_or_else(|| panic!("no case {name}"));
    let report = run_default(&case, &mut |l| eprintln!("{l}"));
    let level = report.levels.last().expect("one level");
    for v in &level.values {
        println!(
            "{name}: {} = {:.9e} (reference {:?}, error {:.2e}, tolerance {:?})",
            v.quantity, v.computed, v.reference, v.error, v.tolerance
        );
    }
    assert!(report.passed(), "{report:#?}");
    report
}

/// Every tag used, sorted.
pub fn tags() -> Vec<&'static str> {
    let mut t: Vec<&'static str> = all().iter().flat_map(|c| c.tags.iter().copied()).collect();
    t.sort_unstable();
    t.dedup();
    t
}

/// One line of `ctc verify --list`.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Listed {
    /// Case name.
    pub name: String,
    /// What it shows.
    pub title: String,
    /// Tags.
    pub tags: Vec<String>,
    /// Levels run by default.
    pub levels: usize,
    /// Levels defined (`None`: from the deck's markers).
    pub max_levels: Option<usize>,
    /// Tolerances at the finest default level.
    pub tolerance: String,
    /// Source of the reference.
    pub source: String,
}

/// The registry as `--list` shows it (filtered like a run).
pub fn list(filter: Option<&str>, tags: &[String]) -> Vec<Listed> {
    all()
        .into_iter()
        .filter(|c| c.matches(filter, tags))
        .map(|c| Listed {
            name: c.name.to_string(),
            title: c.title.to_string(),
            tags: c.tags.iter().map(|t| t.to_string()).collect(),
            levels: c.levels,
            max_levels: c.max_levels(),
            tolerance: c.tolerance_summary(),
            source: c.source.to_string(),
        })
        .collect()
}

/// The `--list` table.
pub fn list_table(rows: &[Listed]) -> String {
    use std::fmt::Write as _;
    let mut s = String::new();
    let w = rows.iter().map(|r| r.name.len()).max().unwrap_or(4).max(4);
    let _ = writeln!(s, "{:<w$}  {:>6}  {:<40}  title", "case", "levels", "tags");
    for r in rows {
        let levels = match r.max_levels {
            Some(m) => format!("{}/{m}", r.levels),
            None => format!("{}", r.levels),
        };
        let _ = writeln!(
            s,
            "{:<w$}  {:>6}  {:<40}  {}",
            r.name,
            levels,
            r.tags.join(","),
            r.title
        );
        let _ = writeln!(s, "{:<w$}  {:>6}  tolerance: {}", "", "", r.tolerance);
    }
    let _ = writeln!(s, "{} cases", rows.len());
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn registry_names_unique_every_case_tagged_and_judged() {
        let cases = all();
        let mut names: Vec<&str> = cases.iter().map(|c| c.name).collect();
        names.sort_unstable();
        let n = names.len();
        names.dedup();
        assert_eq!(names.len(), n, "duplicate case names");
        for c in &cases {
            assert!(!c.tags.is_empty(), "{} has no tags", c.name);
            assert!(!c.checks.is_empty(), "{} judges nothing", c.name);
            assert!(c.levels >= 1, "{}", c.name);
            if let Some(m) = c.max_levels() {
                assert!(m >= c.levels, "{}", c.name);
            }
        }
    }

    #[test]
    fn filters_select_by_name_and_every_tag() {
        let friction = list(None, &["friction".into()]);
        assert!(friction.iter().all(|r| r.tags.contains(&"friction".into())));
        let hertz = list(Some("hertz"), &[]);
        assert!(hertz.len() >= 3 && hertz.iter().all(|r| r.name.contains("hertz")));
        let none = list(None, &["hertz".into(), "thermal".into()]);
        assert!(none.is_empty(), "{none:?}");
        assert!(list_table(&hertz).contains("tolerance: a <= "));
    }

    /// The verification tests that were cargo-only are cases (issue 16):
    /// selectable by their tag, each judging a rate where it has levels.
    #[test]
    fn former_cargo_only_verifications_are_registered() {
        for (tag, name, rate) in [
            ("objectivity", "objectivity_plane_strain", false),
            ("viscoplastic", "perzyna_viscoplastic", true),
            ("penalty", "penalty_scaling", true),
        ] {
            let c = find(name).unwrap_or_else(|| panic!("{name} is not registered"));
            assert!(c.tags.contains(&tag), "{name} lacks tag {tag}");
            assert_eq!(
                c.checks.iter().any(|k| k.min_rate.is_some()),
                rate,
                "{name}"
            );
        }
        let fenicsx = list(None, &["fenicsx".into()]);
        assert_eq!(fenicsx.len(), crate::fenicsx::cases().len());
    }
}
