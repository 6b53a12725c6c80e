//! The outcome of a verification run: per case, per refinement level, per
//! quantity; observed convergence rates; a plain-text table and JSON.

use crate::case::Quantity;
use crate::measure::ProfileData;
use std::fmt::Write as _;

/// One quantity at one level, judged against its tolerance.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Judged {
    /// What was measured.
    pub quantity: Quantity,
    /// Reference value (`None` when the quantity is an error norm).
    pub reference: Option<f64>,
    /// Computed value.
    pub computed: f64,
    /// Relative error.
    pub error: f64,
    /// Tolerance at this level (`None`: reported, not judged).
    pub tolerance: Option<f64>,
    /// `error <= tolerance` (true when not judged).
    pub passed: bool,
}

/// One refinement level of a case.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct LevelReport {
    /// Refinement level (0 = the deck as written).
    pub level: usize,
    /// Characteristic mesh size (see the case's quantities).
    pub h: f64,
    /// Number of nodes.
    pub nodes: usize,
    /// Free degrees of freedom.
    pub free_dofs: usize,
    /// Converged increments.
    pub increments: usize,
    /// Newton iterations in total (all attempts).
    pub newton_total: usize,
    /// Largest number of Newton iterations of a converged increment.
    pub newton_max: usize,
    /// Increment cutbacks.
    pub cutbacks: usize,
    /// Wall time of the solve (`ctc_engine::solve::run`), seconds.
    pub solve_time: f64,
    /// Wall time of the deck compilation (parse, mesh generation), seconds.
    pub compile_time: f64,
    /// The measured quantities.
    pub values: Vec<Judged>,
    /// Why the level produced no measurement (compile error, solver
    /// failure, extraction error).
    pub failure: Option<String>,
    /// Contact pressure profile (contact cases).
    pub profile: Option<ProfileData>,
    /// Largest penetration `max(0, -g)` at the last converged increment
    /// (`IncrementRecord::max_penetration`, length).
    pub max_penetration: f64,
    /// Contact iterations of all converged increments: Lagrange active-set
    /// changes plus augmented-Lagrangian (Uzawa) updates (0 for penalty).
    pub contact_iterations: usize,
    /// Figures a program case measured (histories of its runs), drawn by
    /// [`crate::plot::case_plots`]; not written to `report.json`.
    #[serde(skip)]
    pub figures: Vec<crate::plot::Figure>,
}

impl LevelReport {
    /// Whether the level ran and every judged quantity passed.
    pub fn passed(&self) -> bool {
        self.failure.is_none() && self.values.iter().all(|v| v.passed)
    }

    /// The error of `q` at this level, if measured.
    pub fn error_of(&self, q: Quantity) -> Option<f64> {
        self.values
            .iter()
            .find(|v| v.quantity == q)
            .map(|v| v.error)
    }
}

/// Observed convergence rate of a quantity between two levels:
/// `log(e1 / e2) / log(h1 / h2)`.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct RateReport {
    /// The quantity.
    pub quantity: Quantity,
    /// Coarser level.
    pub from_level: usize,
    /// Finer level.
    pub to_level: usize,
    /// The rate (`None` if an error is at round-off or the mesh size did
    /// not change).
    pub rate: Option<f64>,
    /// Smallest accepted rate (only on the last pair of levels).
    pub min_rate: Option<f64>,
    /// `rate >= min_rate` (true when not judged).
    pub passed: bool,
}

/// Errors below this are round-off: they carry no convergence rate.
pub const ROUND_OFF: f64 = 1e-9;

/// Observed rate from errors and mesh sizes (`None` when an error is at
/// round-off level or the mesh size did not change).
pub fn observed_rate(e1: f64, e2: f64, h1: f64, h2: f64) -> Option<f64> {
    let r = (e1 / e2).ln() / (h1 / h2).ln();
    (e1 > ROUND_OFF && e2 > ROUND_OFF && h1 > 0.0 && h2 > 0.0 && h1 != h2 && r.is_finite())
        .then_some(r)
}

/// All levels of one case.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct CaseReport {
    /// Case identifier.
    pub name: String,
    /// What it shows.
    pub title: String,
    /// Where the reference comes from.
    pub source: String,
    /// Path of the deck run.
    pub deck: String,
    /// The levels run, coarsest first.
    pub levels: Vec<LevelReport>,
    /// Rates between consecutive levels, per quantity.
    pub rates: Vec<RateReport>,
    /// Why the case could not run at all (deck unreadable, bad markers).
    pub failure: Option<String>,
}

impl CaseReport {
    /// Whether every level and every rate check passed.
    pub fn passed(&self) -> bool {
        self.failure.is_none()
            && !self.levels.is_empty()
            && self.levels.iter().all(LevelReport::passed)
            && self.rates.iter().all(|r| r.passed)
    }

    /// Quantities measured in this case, in order of first appearance.
    pub fn quantities(&self) -> Vec<Quantity> {
        let mut qs: Vec<Quantity> = Vec::new();
        for l in &self.levels {
            for v in &l.values {
                if !qs.contains(&v.quantity) {
                    qs.push(v.quantity);
                }
            }
        }
        qs
    }
}

/// The outcome of `ctc verify`.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Report {
    /// The cases run, in catalogue order.
    pub cases: Vec<CaseReport>,
    /// Directory the decks were read from.
    pub cases_dir: String,
    /// Wall time of the whole verification, seconds.
    pub wall_time: f64,
    /// Method comparison, penalty sweep and penalty scaling (run with a
    /// report directory only).
    pub studies: Option<crate::studies::Studies>,
}

impl Report {
    /// Whether every case passed (and at least one ran).
    pub fn passed(&self) -> bool {
        !self.cases.is_empty()
            && self.cases.iter().all(CaseReport::passed)
            && self
                .studies
                .as_ref()
                .is_none_or(|s| s.failures().is_empty())
    }

    /// One line per failed check, level or case.
    pub fn failures(&self) -> Vec<String> {
        let mut out = Vec::new();
        if self.cases.is_empty() {
            out.push("no case matched the filter".to_string());
        }
        if let Some(st) = &self.studies {
            out.extend(st.failures());
        }
        for c in &self.cases {
            if let Some(f) = &c.failure {
                out.push(format!("{}: {f}", c.name));
            }
            for l in &c.levels {
                if let Some(f) = &l.failure {
                    out.push(format!("{} level {}: {f}", c.name, l.level));
                }
                for v in l.values.iter().filter(|v| !v.passed) {
                    out.push(format!(
                        "{} level {}: {} error {:.3e} > tolerance {:.1e}",
                        c.name,
                        l.level,
                        v.quantity,
                        v.error,
                        v.tolerance.unwrap_or(f64::NAN)
                    ));
                }
            }
            for r in c.rates.iter().filter(|r| !r.passed) {
                out.push(format!(
                    "{}: {} observed rate {} between levels {} and {} < {}",
                    c.name,
                    r.quantity,
                    r.rate.map_or("n/a".to_string(), |x| format!("{x:.2}")),
                    r.from_level,
                    r.to_level,
                    r.min_rate.unwrap_or(f64::NAN)
                ));
            }
        }
        out
    }

    /// Pretty JSON of the whole report.
    pub fn to_json(&self) -> String {
        serde_json::to_string_pretty(self).unwrap_or_else(|e| format!("{{\"error\": \"{e}\"}}"))
    }

    /// Plain-text table: case, level, quantity, reference, computed, error,
    /// tolerance, pass/fail, Newton iterations (total/max per increment),
    /// wall time; then the observed rates and a verdict.
    pub fn table(&self) -> String {
        let mut s = String::new();
        let header = format!(
            "{:<22} {:>3} {:>9} {:>7} {:<13} {:>11} {:>11} {:>9} {:>7} {:<4} {:>9} {:>8}",
            "case",
            "lvl",
            "h",
            "dofs",
            "quantity",
            "reference",
            "computed",
            "rel.err",
            "tol",
            "ok",
            "newton",
            "time[s]"
        );
        let _ = writeln!(s, "{header}");
        let _ = writeln!(s, "{}", "-".repeat(header.len()));
        for c in &self.cases {
            if let Some(f) = &c.failure {
                let _ = writeln!(s, "{:<22} FAILED: {f}", c.name);
                continue;
            }
            for l in &c.levels {
                let newton = format!("{}/{}", l.newton_total, l.newton_max);
                if let Some(f) = &l.failure {
                    let _ = writeln!(
                        s,
                        "{:<22} {:>3} {:>9} {:>7} FAILED: {}",
                        c.name,
                        l.level,
                        fmt_num(l.h),
                        l.free_dofs,
                        first_line(f)
                    );
                    continue;
                }
                for v in &l.values {
                    let _ = writeln!(
                        s,
                        "{:<22} {:>3} {:>9} {:>7} {:<13} {:>11} {:>11} {:>9} {:>7} {:<4} {:>9} {:>8.3}",
                        c.name,
                        l.level,
                        fmt_num(l.h),
                        l.free_dofs,
                        v.quantity.name(),
                        v.reference.map_or("-".to_string(), fmt_num),
                        fmt_num(v.computed),
                        format!("{:.2e}", v.error),
                        v.tolerance.map_or("-".to_string(), |t| format!("{t:.1e}")),
                        if v.passed { "pass" } else { "FAIL" },
                        newton,
                        l.solve_time
                    );
                }
            }
            let rates: Vec<String> = c
                .rates
                .iter()
                .filter_map(|r| {
                    r.rate.map(|x| {
                        let mark = match (r.min_rate, r.passed) {
                            (Some(m), true) => format!(" (>= {m})"),
                            (Some(m), false) => format!(" (FAIL < {m})"),
                            _ => String::new(),
                        };
                        format!(
                            "{} {}->{}: {x:.2}{mark}",
                            r.quantity, r.from_level, r.to_level
                        )
                    })
                })
                .collect();
            if !rates.is_empty() {
                let _ = writeln!(s, "{:<22} rates: {}", c.name, rates.join(", "));
            }
            let _ = writeln!(
                s,
                "{:<22} {}",
                c.name,
                if c.passed() { "PASSED" } else { "FAILED" }
            );
            let _ = writeln!(s);
        }
        if let Some(st) = &self.studies {
            s.push_str(&st.table());
        }
        let n_pass = self.cases.iter().filter(|c| c.passed()).count();
        let _ = writeln!(
            s,
            "{} of {} cases passed in {:.1} s",
            n_pass,
            self.cases.len(),
            self.wall_time
        );
        s
    }
}

/// First line of a possibly multi-line message.
fn first_line(s: &str) -> &str {
    s.lines().next().unwrap_or("")
}

/// Compact number formatting for tables (4 significant digits).
pub fn fmt_num(x: f64) -> String {
    if x == 0.0 {
        "0".to_string()
    } else if x.is_nan() {
        "nan".to_string()
    } else if (1e-3..1e5).contains(&x.abs()) {
        let digits = (3 - x.abs().log10().floor() as i32).max(0) as usize;
        format!("{x:.digits$}")
    } else {
        format!("{x:.3e}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn observed_rate_second_order() {
        let r = observed_rate(4e-2, 1e-2, 0.2, 0.1).unwrap();
        assert!((r - 2.0).abs() < 1e-12);
        assert!(observed_rate(0.0, 1e-2, 0.2, 0.1).is_none());
        assert!(observed_rate(1e-2, 1e-3, 0.1, 0.1).is_none());
        assert!(observed_rate(1e-14, 1e-15, 0.2, 0.1).is_none());
    }

    fn level(error: f64, tol: f64) -> LevelReport {
        LevelReport {
            level: 0,
            h: 0.1,
            nodes: 10,
            free_dofs: 16,
            increments: 1,
            newton_total: 2,
            newton_max: 2,
            cutbacks: 0,
            solve_time: 0.01,
            compile_time: 0.0,
            values: vec![Judged {
                quantity: Quantity::HalfWidth,
                reference: Some(1.0),
                computed: 1.0 + error,
                error,
                tolerance: Some(tol),
                passed: error <= tol,
            }],
            failure: None,
            profile: None,
            max_penetration: 0.0,
            contact_iterations: 0,
            figures: Vec::new(),
        }
    }

    #[test]
    fn report_fails_when_one_quantity_fails() {
        let case = |e| CaseReport {
            name: "c".into(),
            title: "t".into(),
            source: "s".into(),
            deck: "d".into(),
            levels: vec![level(e, 0.02)],
            rates: vec![],
            failure: None,
        };
        let ok = Report {
            cases: vec![case(0.01)],
            cases_dir: ".".into(),
            wall_time: 0.1,
            studies: None,
        };
        assert!(ok.passed());
        assert!(ok.failures().is_empty());
        let bad = Report {
            cases: vec![case(0.01), case(0.03)],
            ..ok.clone()
        };
        assert!(!bad.passed());
        assert_eq!(bad.failures().len(), 1);
        let table = bad.table();
        assert!(table.contains("FAIL"), "{table}");
        assert!(table.contains("1 of 2 cases passed"), "{table}");
        let empty = Report {
            cases: vec![],
            ..ok
        };
        assert!(!empty.passed());
        let json: serde_json::Value = serde_json::from_str(&bad.to_json()).unwrap();
        assert_eq!(
            json["cases"][1]["levels"][0]["values"][0]["quantity"],
            "half_width"
        );
    }

    #[test]
    fn fmt_num_compact() {
        assert_eq!(fmt_num(0.07012345), "0.07012");
        assert_eq!(fmt_num(477464.8), "4.775e5");
        assert_eq!(fmt_num(12.3456), "12.35");
    }
}
