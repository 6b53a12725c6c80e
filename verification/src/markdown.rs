//! The Markdown report `report.md`: a summary, then per case what it shows,
//! the deck and the command, the plots, the measured table, the observed
//! rates, and the error against the run time of each level.

use crate::plot::PlotFile;
use crate::report::{fmt_num, CaseReport, Report};
use std::fmt::Write as _;

/// Renders the report; `plots` are linked by file name (same directory).
pub fn markdown(report: &Report, plots: &[PlotFile]) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "# ctc verification report\n");
    let passed = report.cases.iter().filter(|c| c.passed()).count();
    let _ = writeln!(
        s,
        "{} of {} cases passed ({}), {:.1} s wall time. Decks: `{}`.\n",
        passed,
        report.cases.len(),
        if report.passed() {
            "**PASSED**"
        } else {
            "**FAILED**"
        },
        report.wall_time,
        report.cases_dir
    );
    let _ = writeln!(
        s,
        "Errors are relative. Observed rates are `log(e1/e2) / log(h1/h2)` between consecutive \
         levels. Times are the wall time of the solve (`ctc_engine::solve::run`).\n"
    );
    let _ = writeln!(
        s,
        "| case | levels | finest dofs | finest errors | status |"
    );
    let _ = writeln!(s, "|---|---:|---:|---|---|");
    for c in &report.cases {
        let finest = c.levels.iter().rev().find(|l| l.failure.is_none());
        let errors = finest.map_or("-".to_string(), |l| {
            l.values
                .iter()
                .map(|v| format!("{} {:.2e}", v.quantity, v.error))
                .collect::<Vec<_>>()
                .join(", ")
        });
        let _ = writeln!(
            s,
            "| [{}](#{}) | {} | {} | {} | {} |",
            c.name,
            c.name,
            c.levels.len(),
            finest.map_or(0, |l| l.free_dofs),
            errors,
            if c.passed() { "pass" } else { "**FAIL**" }
        );
    }
    let failures = report.failures();
    if !failures.is_empty() {
        let _ = writeln!(s, "\n## Failures\n");
        for f in failures {
            let _ = writeln!(s, "- {}", f.replace('\n', " "));
        }
    }
    for c in &report.cases {
        case_section(&mut s, c, plots);
    }
    s
}

/// One case's section.
fn case_section(s: &mut String, c: &CaseReport, plots: &[PlotFile]) {
    let _ = writeln!(s, "\n## {}\n", c.name);
    let _ = writeln!(s, "{}\n", c.title);
    let _ = writeln!(s, "- Reference: {}", c.source);
    let _ = writeln!(s, "- Deck: `{}`", c.deck);
    let _ = writeln!(s, "- Run: `ctc verify {}`", c.name);
    let _ = writeln!(
        s,
        "- Status: {}\n",
        if c.passed() { "pass" } else { "**FAIL**" }
    );
    if let Some(f) = &c.failure {
        let _ = writeln!(s, "Could not run:\n\n```\n{f}\n```");
        return;
    }
    for p in plots.iter().filter(|p| p.case == c.name) {
        let _ = writeln!(s, "![{} {}]({})\n", c.name, p.kind, p.file);
    }
    let _ = writeln!(
        s,
        "| level | h | dofs | quantity | reference | computed | rel. error | tolerance | status |"
    );
    let _ = writeln!(s, "|---:|---:|---:|---|---:|---:|---:|---:|---|");
    for l in &c.levels {
        if let Some(f) = &l.failure {
            let _ = writeln!(
                s,
                "| {} | {} | {} | **failed** | | | | | {} |",
                l.level,
                fmt_num(l.h),
                l.free_dofs,
                f.lines().next().unwrap_or("").replace('|', "/")
            );
            continue;
        }
        for v in &l.values {
            let _ = writeln!(
                s,
                "| {} | {} | {} | {} | {} | {} | {:.3e} | {} | {} |",
                l.level,
                fmt_num(l.h),
                l.free_dofs,
                v.quantity,
                v.reference.map_or("-".into(), fmt_num),
                fmt_num(v.computed),
                v.error,
                v.tolerance.map_or("-".into(), |t| format!("{t:.1e}")),
                if v.passed { "pass" } else { "**FAIL**" }
            );
        }
    }
    if !c.rates.is_empty() {
        let _ = writeln!(s, "\nObserved convergence rates:\n");
        let _ = writeln!(s, "| quantity | levels | rate | required |");
        let _ = writeln!(s, "|---|---|---:|---:|");
        for r in &c.rates {
            let _ = writeln!(
                s,
                "| {} | {} -> {} | {} | {} |",
                r.quantity,
                r.from_level,
                r.to_level,
                r.rate.map_or("n/a".into(), |x| format!("{x:.2}")),
                match (r.min_rate, r.passed) {
                    (Some(m), true) => format!(">= {m}"),
                    (Some(m), false) => format!("**>= {m} FAILED**"),
                    (None, _) => "-".into(),
                }
            );
        }
    }
    let qs = c.quantities();
    let _ = writeln!(s, "\nError against run time:\n");
    let mut head = "| level | dofs | Newton total / max per increment | increments | solve [s] | compile [s] |".to_string();
    let mut rule = "|---:|---:|---:|---:|---:|---:|".to_string();
    for q in &qs {
        head.push_str(&format!(" {q} |"));
        rule.push_str("---:|");
    }
    let _ = writeln!(s, "{head}\n{rule}");
    for l in &c.levels {
        let mut row = format!(
            "| {} | {} | {} / {} | {} | {:.3} | {:.3} |",
            l.level,
            l.free_dofs,
            l.newton_total,
            l.newton_max,
            l.increments,
            l.solve_time,
            l.compile_time
        );
        for q in &qs {
            row.push_str(&match l.error_of(*q) {
                Some(e) => format!(" {e:.2e} |"),
                None => " - |".into(),
            });
        }
        let _ = writeln!(s, "{row}");
    }
}
