//! ctc-verification: the verification harness of ctc.
//!
//! Every case is a runnable `.ctc` deck in `cases/` (written at its coarsest
//! level, with `# refine:` markers listing the mesh divisions of finer
//! levels, see [`refine`]) plus a closed-form reference in code
//! ([`analytical`]). [`run`] solves each level with the engine, extracts the
//! quantities from the converged final state ([`capture`], [`profile`],
//! [`measure`]), compares them with the reference, computes observed
//! convergence rates and returns a [`Report`]; with a report directory it
//! also writes SVG plots ([`plot`]), `report.md` ([`markdown`]) and
//! `report.json`. [`run_bench`] times the issue-3 benchmark ([`bench`]).
//!
//! Modules:
//! - [`analytical`]: Hertz (cylinder, sphere), Lamé, contact patch;
//! - [`refine`]: refinement markers of decks; [`deck`]: read and compile;
//! - [`capture`]: observer keeping the final state; [`profile`]: contact
//!   pressure profile and the half-width estimator; [`measure`]: quantities;
//! - [`case`]: what a deck case is; [`cases`]: the deck cases;
//!   [`programs`]: the program cases; [`registry`]: every case of
//!   `ctc verify` with its tags, tolerances and levels;
//! - [`runner`]: levels, judging, rates; [`report`]: tables and JSON;
//! - [`plot`], [`markdown`]: the report directory; [`bench`]: the benchmark;
//! - [`fenicsx_export`], [`fenicsx`]: FEniCSx reference solutions on the
//!   same meshes (issue 9); `meshio` (feature `meshio`): cross-checks of the
//!   VTU writer and the gmsh reader with Python's meshio through pyo3.

#![warn(missing_docs)]

pub mod analytical;
pub mod bench;
pub mod capture;
pub mod case;
pub mod cases;
pub mod cross_check;
pub mod deck;
pub mod fenicsx;
pub mod fenicsx_export;
pub mod history_plot;
pub mod markdown;
pub mod measure;
pub mod memo;
#[cfg(feature = "meshio")]
pub mod meshio;
pub mod method_plots;
pub mod method_variant;
pub mod methods;
pub mod penalty;
pub mod plot;
pub mod profile;
pub mod programs;
pub mod refine;
pub mod registry;
pub mod report;
pub mod runner;
pub mod search_bench;
pub mod solid_bench;
pub mod stress;
pub mod studies;

pub use bench::{run_bench, BenchOptions, BenchReport};
pub use report::Report;
pub use search_bench::{run_search_bench, SearchBenchOptions, SearchBenchReport};
pub use stress::{run_stress, StressReport};

use std::path::{Path, PathBuf};
use std::time::Instant;

/// Options of [`run`] (the `ctc verify` command).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct VerifyOptions {
    /// Run only the cases whose name contains this text.
    pub filter: Option<String>,
    /// Write plots, `report.md` and `report.json` into this directory
    /// (created if needed).
    pub report_dir: Option<PathBuf>,
    /// Highest refinement level to run (0 = the decks as written). `None`:
    /// each case's default number of levels. Capped by the levels a deck
    /// defines.
    pub max_level: Option<usize>,
    /// Directory of the case decks (overrides everything). `None`:
    /// [`default_cases_dir`].
    pub cases_dir: Option<PathBuf>,
    /// Print one line per finished level to stderr.
    pub progress: bool,
    /// Run only the cases carrying every one of these tags.
    pub tags: Vec<String>,
    /// Cases run at the same time, each on its own thread (`None`: the
    /// machine's available parallelism). Every case is independent and
    /// sequential inside, so the report is the same whatever the count.
    pub jobs: Option<usize>,
    /// Names of cases left out (the catalogue test leaves out
    /// [`registry::RUN_BY_THE_CTC_SUITE`]).
    pub exclude: Vec<String>,
}

/// Environment variable overriding the cases directory (for a `ctc`
/// binary moved away from its source tree).
pub const CASES_DIR_ENV: &str = "CTC_CASES_DIR";

/// The directory of the case decks: `$CTC_CASES_DIR` if set, else the
/// `cases/` directory of this crate's sources (compiled in), so the `ctc`
/// binary finds the decks whatever the working directory.
pub fn default_cases_dir() -> PathBuf {
    match std::env::var_os(CASES_DIR_ENV) {
        Some(dir) if !dir.is_empty() => PathBuf::from(dir),
        _ => Path::new(env!("CARGO_MANIFEST_DIR")).join("cases"),
    }
}

/// Runs the verification cases selected by `opts`. `Err` only when the
/// report directory cannot be written or the cases directory does not
/// exist; failed cases are in the [`Report`] (see [`Report::passed`]).
pub fn run(opts: &VerifyOptions) -> Result<Report, String> {
    let start = Instant::now();
    let dir = opts.cases_dir.clone().unwrap_or_else(default_cases_dir);
    if !dir.is_dir() {
        return Err(format!(
            "verification cases directory {} does not exist (pass the directory of the .ctc case decks)",
            dir.display()
        ));
    }
    let progress = |line: &str| {
        if opts.progress {
            eprintln!("{line}");
        }
    };
    let cases: Vec<_> = registry::all()
        .into_iter()
        .filter(|c| c.matches(opts.filter.as_deref(), &opts.tags))
        .filter(|c| !opts.exclude.iter().any(|e| e == c.name))
        .collect();
    let jobs = opts
        .jobs
        .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get()));
    let mut report = Report {
        cases: run_cases(&cases, jobs, &|c| {
            if opts.max_level.is_none() && opts.cases_dir.is_none() {
                registry::run_default(c, &mut |line| progress(line))
            } else {
                c.run(&dir, opts.max_level, &mut |line| progress(line))
            }
        }),
        cases_dir: dir.display().to_string(),
        wall_time: 0.0,
        studies: None,
    };
    // The method studies (comparison of the contact methods, penalty sweep
    // and mesh scaling) belong to the written report.
    if opts.report_dir.is_some() && opts.tags.is_empty() {
        report.studies = Some(studies::run_studies(
            opts.filter.as_deref(),
            &dir,
            &mut |line| progress(line),
        ));
    }
    report.wall_time = start.elapsed().as_secs_f64();
    if let Some(out) = &opts.report_dir {
        write_report_dir(&report, out)?;
    }
    Ok(report)
}

/// The cases whose default levels took longest (debug build; seconds of
/// CPU, estimated as the level lines' wall of `ctc verify --json -j 2`
/// times the run's CPU over their sum, 618 / 3967, at load ~10, stop 47):
/// with several jobs they start first, so that no long case starts last
/// and runs alone while the other cores idle (longest-first scheduling).
/// Before, in registry order, `blankholder` (levels 0 and 1) started 132nd
/// of 136 and ended the catalogue test alone; `hertz_sphere_3d` (its
/// level 1) and `taylor_bar_jc_3d` were missing here until stop 47. A
/// scheduling hint only: every case is independent and the reports stay
/// in registry order; a name not in the registry is skipped (a unit test
/// keeps the list true).
pub const SLOW_CASES_FIRST: &[&str] = &[
    "hertz_sphere_block_mortar_quadratic_3d", // 81 s
    "blankholder",                            // 24 + 48 s
    "taylor_bar_3d",                          // 56 s
    "hertz_sphere_block_mortar_3d",           // 56 s
    "contact_patch_mortar_quadratic_3d",      // 51 s
    "hertz_sphere_3d",                        // 4 + 44 s
    "ironing_ntf_3d",                         // 41 s
    "contact_patch_mortar_mixed_3d",          // 24 s
    "taylor_bar_jc_3d",                       // 22 s
    "blade_loss_3d",                          // 17 s (level 0, -O2 engine)
    "contact_patch_friction_3d",              // 16 s
    "hertz_two_spheres_3d",                   // 14 s
    "hertz_sphere_block_mortar_lagrange_3d",  // 13 s
    "contact_patch_friction_quadratic_3d",    // 12 s
    "superplastic_free_bulge",                // 11 s
];

/// The order in which [`run_cases`] starts `cases`: the indices of the
/// [`SLOW_CASES_FIRST`] present (in that list's order), then the others in
/// registry order.
fn start_order(cases: &[registry::VerifyCase]) -> Vec<usize> {
    let slow = |c: &registry::VerifyCase| SLOW_CASES_FIRST.iter().position(|n| *n == c.name);
    let mut order: Vec<usize> = (0..cases.len()).collect();
    // stable: the cases not in the list keep registry order
    order.sort_by_key(|&i| slow(&cases[i]).unwrap_or(SLOW_CASES_FIRST.len()));
    order
}

/// `run_one` over `cases` on `jobs` threads (a shared queue, so a long
/// case does not hold up the others; the known long cases start first,
/// [`start_order`]); the reports in the order of `cases`. Progress lines
/// (stderr) arrive in finishing order.
fn run_cases(
    cases: &[registry::VerifyCase],
    jobs: usize,
    run_one: &(dyn Fn(&registry::VerifyCase) -> report::CaseReport + Sync),
) -> Vec<report::CaseReport> {
    let jobs = jobs.clamp(1, cases.len().max(1));
    if jobs == 1 {
        return cases.iter().map(run_one).collect();
    }
    let order = start_order(cases);
    let next = std::sync::atomic::AtomicUsize::new(0);
    let done: std::sync::Mutex<Vec<Option<report::CaseReport>>> =
        std::sync::Mutex::new(vec![None; cases.len()]);
    std::thread::scope(|s| {
        for _ in 0..jobs {
            s.spawn(|| loop {
                let k = next.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
                let Some(&i) = order.get(k) else { break };
                let case = &cases[i];
                let report = run_one(case);
                done.lock().unwrap()[i] = Some(report);
            });
        }
    });
    done.into_inner()
        .unwrap()
        .into_iter()
        .map(|r| r.expect("every case ran"))
        .collect()
}

/// Writes the plots, `report.md` and `report.json` into `dir`.
pub fn write_report_dir(report: &Report, dir: &Path) -> Result<(), String> {
    std::fs::create_dir_all(dir).map_err(|e| format!("cannot create {}: {e}", dir.display()))?;
    let mut plots = Vec::new();
    for c in &report.cases {
        plots.extend(plot::case_plots(c, dir)?);
    }
    if let Some(s) = &report.studies {
        plots.extend(studies::study_plots(s, dir)?);
    }
    let md = markdown::markdown(report, &plots);
    std::fs::write(dir.join("report.md"), md)
        .map_err(|e| format!("cannot write report.md: {e}"))?;
    std::fs::write(dir.join("report.json"), report.to_json())
        .map_err(|e| format!("cannot write report.json: {e}"))?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every name of [`SLOW_CASES_FIRST`] is a case of the registry (a
    /// renamed case would silently lose its early start), once; the start
    /// order is a permutation of the catalogue that begins with them and
    /// keeps registry order for the rest.
    #[test]
    fn slow_cases_start_first_and_every_case_starts_once() {
        let all = registry::all();
        for (k, name) in SLOW_CASES_FIRST.iter().enumerate() {
            assert!(
                all.iter().any(|c| c.name == *name),
                "{name} is not a case of the registry"
            );
            assert!(!SLOW_CASES_FIRST[..k].contains(name), "{name} twice");
        }
        let order = start_order(&all);
        let mut sorted = order.clone();
        sorted.sort_unstable();
        assert_eq!(sorted, (0..all.len()).collect::<Vec<_>>());
        let n = SLOW_CASES_FIRST.len();
        let first: Vec<&str> = order[..n].iter().map(|&i| all[i].name).collect();
        assert_eq!(first, SLOW_CASES_FIRST);
        assert!(order[n..].windows(2).all(|w| w[0] < w[1]));
    }
}
