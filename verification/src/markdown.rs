//! The Markdown report `report.md`: a summary, then per case what it shows,
//! the deck and the command, the plots, the measured table, the observed
//! rates, and the error against the run time of each level.

use crate::case::Quantity;
use crate::plot::PlotFile;
use crate::report::{fmt_num, CaseReport, Report};
use crate::studies::{method_rows, Studies, METHOD_COLUMNS};
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
                .map(|v| format!("{} {:.2e}", cell(v.quantity), v.error))
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
    if let Some(st) = &report.studies {
        studies_section(&mut s, st, plots);
    }
    s
}

/// Links the plots of `case` of kind `kind`.
/// A quantity's name as a table cell (program quantities such as
/// `max |du| / max |u|` contain pipes).
fn cell(q: crate::case::Quantity) -> String {
    q.to_string().replace('|', "\\|")
}

fn link_plots(s: &mut String, plots: &[PlotFile], case: &str, kind: &str) {
    for p in plots.iter().filter(|p| p.case == case && p.kind == kind) {
        let _ = writeln!(s, "![{} {}]({})\n", p.case, p.kind, p.file);
    }
}

/// The method comparison, penalty sweep and penalty scaling sections.
fn studies_section(s: &mut String, st: &Studies, plots: &[PlotFile]) {
    if !st.methods.is_empty() {
        let _ = writeln!(s, "\n## Contact methods: error against run time\n");
        let _ = writeln!(
            s,
            "Each Hertz deck is run unchanged except for its `method = ..` line: area penalty at \
             k = 1e5, 1e6, 1e7 (the deck's; E = 1e3), Lagrange multipliers (single: sparse LU; \
             doubled: L D L^T), augmented Lagrangian (k = 1e5, Uzawa updates after each converged \
             Newton loop, tolerance 1e-4 x indentation), on the same meshes at every level. \
             Requirements: Lagrange penetration <= 1e-12 x indentation, augmented Lagrangian below \
             its tolerance, penalty penetration = p0 / k within 10 %; the deck's penalty, Lagrange \
             and augmented Lagrangian meet the case tolerances, the softer penalties are shown, not \
             judged. Newton: all iterations of the run; active-set/Uzawa: active-set changes \
             (Lagrange) or multiplier updates (augmented) summed over increments. Solve: wall time \
             of `ctc_engine::solve::run`.\n"
        );
    }
    if let Some(q) = &st.quadratic {
        let _ = writeln!(
            s,
            "\n## Quadratic against linear elements: Hertz work precision\n"
        );
        let _ = writeln!(
            s,
            "The decks `hertz_cylinder.ctc` (plane strain) and `hertz_sphere.ctc` (axisymmetric) \
             on quad4 and on quad8 with half the divisions (about equal dofs), at the levels of \
             `hertz_quadratic` (issue 23): the p0 and L2(p) errors against the free dofs and \
             against the solve wall time of `ctc_engine::solve::run`.\n"
        );
        match q {
            Err(e) => {
                let _ = writeln!(s, "Could not run: `{e}`\n");
            }
            Ok(rows) => {
                link_plots(s, plots, "hertz_quadratic", "work-precision");
                let _ = writeln!(
                    s,
                    "| deck | cells | level | free dofs | p0 error | L2(p) error | solve [s] |"
                );
                let _ = writeln!(s, "|---|---|---:|---:|---:|---:|---:|");
                for r in rows {
                    let _ = writeln!(
                        s,
                        "| {} | {} | {} | {} | {:.2e} | {:.2e} | {:.3} |",
                        r.deck, r.cells, r.level, r.dofs, r.p0, r.l2, r.seconds
                    );
                }
            }
        }
    }
    if let Some(q) = &st.quadratic_3d {
        let _ = writeln!(
            s,
            "\n## Quadratic against linear elements: 3D Hertz work precision\n"
        );
        let _ = writeln!(
            s,
            "The rigid sphere pressed into the elastic block resolved under the contact (a \
             spans 4 / 8 / 16 hex8 cells; quarter model, Lagrange multipliers) on hex8 cells and on hex27 / hex20 cells of about the same number of \
             dofs, at the levels of `hertz_sphere_3d_quadratic` (issue 23): the p0 and L2(p) \
             errors against Hertz at the carried force, against the free dofs and against the \
             solve wall time of `ctc_engine::solve::run`.\n"
        );
        match q {
            Err(e) => {
                let _ = writeln!(s, "Could not run: `{e}`\n");
            }
            Ok(rows) => {
                link_plots(s, plots, "hertz_sphere_3d_quadratic", "work-precision");
                let _ = writeln!(
                    s,
                    "| cells | level | free dofs | p0 error | L2(p) error | solve [s] |"
                );
                let _ = writeln!(s, "|---|---:|---:|---:|---:|---:|");
                for r in rows {
                    let _ = writeln!(
                        s,
                        "| {} | {} | {} | {:.2e} | {:.2e} | {:.3} |",
                        r.cells, r.level, r.dofs, r.p0, r.l2, r.seconds
                    );
                }
            }
        }
    }
    for c in &st.methods {
        let _ = writeln!(s, "\n### {} — methods\n", c.case);
        let _ = writeln!(s, "{}. Deck: `{}`.\n", c.title, c.deck);
        if let Some(f) = &c.failure {
            let _ = writeln!(s, "Could not run: `{f}`\n");
            continue;
        }
        link_plots(s, plots, &c.case, "work-precision");
        let _ = writeln!(s, "| {} |", METHOD_COLUMNS.join(" | "));
        let _ = writeln!(
            s,
            "|---|{}",
            "---:|".repeat(METHOD_COLUMNS.len() - 2) + "---|"
        );
        for r in method_rows(c) {
            let _ = writeln!(s, "| {} |", r.join(" | "));
        }
        let pf = c.penetration_failures();
        if !pf.is_empty() {
            let _ = writeln!(s, "\nPenetration requirements missed:\n");
            for f in pf {
                let _ = writeln!(s, "- {f}");
            }
        }
    }
    if let Some(sw) = &st.sweep {
        let _ = writeln!(
            s,
            "\n## Penalty sensitivity ({} level {})\n",
            sw.case, sw.level
        );
        let _ = writeln!(
            s,
            "Area penalty k swept over decades of E / h (E = {}, h = {:.3e} the contact-zone edge, \
             E / h = {:.3e}); the Lagrange-multiplier solution on the same mesh is the limit \
             k -> infinity.\n",
            sw.young,
            sw.h,
            sw.young / sw.h
        );
        if let Some(f) = &sw.failure {
            let _ = writeln!(s, "Could not run: `{f}`\n");
        }
        link_plots(s, plots, &sw.case, "penalty sweep");
        let _ = writeln!(
            s,
            "| k | k / (E/h) | p0 error | a error | max penetration | Newton | solve [s] |"
        );
        let _ = writeln!(s, "|---:|---:|---:|---:|---:|---:|---:|");
        let row = |label: String, factor: String, l: &crate::report::LevelReport| match &l.failure {
            Some(f) => format!(
                "| {label} | {factor} | failed: {} | | | {} | |",
                f.lines().next().unwrap_or("").replace('|', "/"),
                l.newton_total
            ),
            None => format!(
                "| {label} | {factor} | {:.2e} | {:.2e} | {:.2e} | {} | {:.3} |",
                l.error_of(Quantity::PeakPressure).unwrap_or(f64::NAN),
                l.error_of(Quantity::HalfWidth).unwrap_or(f64::NAN),
                l.max_penetration,
                l.newton_total,
                l.solve_time
            ),
        };
        for p in &sw.points {
            let _ = writeln!(
                s,
                "{}",
                row(
                    format!("{:.3e}", p.stiffness),
                    format!("{:.0e}", p.factor),
                    &p.result
                )
            );
        }
        if let Some(l) = &sw.lagrange {
            let _ = writeln!(s, "{}", row("Lagrange".into(), "inf".into(), l));
        }
    }
    if let Some(t) = &st.target {
        let _ = writeln!(
            s,
            "\n## Penalty from an allowed penetration ({} level {})\n",
            t.case, t.level
        );
        let _ = writeln!(
            s,
            "Allowed penetration {:e}. First run at k = E / h, then k <- 1.1 k g / g_allowed \
             (g = p / k for a penalty) until g <= g_allowed. Harness-level only: a deck cannot \
             yet write `penetration = ..` instead of a stiffness.\n",
            t.allowed
        );
        let _ = writeln!(s, "| run | k | max penetration | p0 error | Newton |");
        let _ = writeln!(s, "|---:|---:|---:|---:|---:|");
        for (i, r) in t.trials.iter().enumerate() {
            let _ = writeln!(
                s,
                "| {} | {:.4e} | {:.3e} | {:.2e} | {} |",
                i + 1,
                r.stiffness,
                r.penetration,
                r.p0_error,
                r.newton
            );
        }
        if let Some(f) = &t.failure {
            let _ = writeln!(s, "\nFailed: {f}");
        }
    }
    if let Some(sc) = &st.scaling {
        let _ = writeln!(s, "\n## Penalty mesh scaling (VERIFICATION-CASES.md §7)\n");
        let _ = writeln!(
            s,
            "Block on a rigid plane (`{}`), E = 1e3, indentation d = 0.01 of H = 1: rigid-contact \
             pressure E d / H = {}. Area penalty k = {:e}; nodal alpha fixed at k h0 (h0 the \
             coarsest mesh); nodal alpha = k h. With the area penalty the gap is p / k at every h; \
             at fixed nodal alpha the gap halves with h (the effective traction penalty alpha / h \
             doubles); halving alpha with h restores the mesh-independent solution.\n",
            sc.deck, sc.rigid_pressure, sc.stiffness
        );
        link_plots(s, plots, "penalty_scaling", "penalty scaling");
        let _ = writeln!(s, "| flavour | level | h | penalty | middle gap | max penetration | mean pressure | error vs E d / H | Newton |");
        let _ = writeln!(s, "|---|---:|---:|---:|---:|---:|---:|---:|---:|");
        for p in &sc.points {
            let _ = writeln!(
                s,
                "| {} | {} | {:.4} | {:.3e} | {:.4e} | {:.4e} | {:.4} | {:.3e} | {} |",
                p.flavour.label(),
                p.level,
                p.h,
                p.penalty,
                p.gap_middle,
                p.max_penetration,
                p.pressure,
                p.pressure_error,
                p.newton
            );
        }
        for f in &sc.failures {
            let _ = writeln!(s, "- failed: {f}");
        }
    }
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
                cell(v.quantity),
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
                cell(r.quantity),
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
        head.push_str(&format!(" {} |", cell(*q)));
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::case::Quantity;

    #[test]
    fn pipes_in_quantity_names_are_escaped_in_table_cells() {
        let q = Quantity::Named("max |du| / max |u|");
        assert_eq!(cell(q), "max \\|du\\| / max \\|u\\|");
        assert_eq!(cell(Quantity::PeakPressure), "p0");
    }
}
