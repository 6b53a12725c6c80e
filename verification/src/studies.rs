//! The method studies `ctc verify --report` adds to the case report: the
//! comparison of the contact methods on the Hertz cases
//! ([`crate::methods`]), the penalty sensitivity sweep and the penalty
//! mesh scaling ([`crate::penalty`]), with their tables and plots.

use crate::cases;
use crate::method_plots::{scaling_plot, sweep_plot, work_precision_plot};
use crate::methods::{compare_methods, studies, MethodComparison};
use crate::penalty::{
    penalty_for_penetration, penalty_scaling, penalty_sweep, PenaltyScaling, PenaltySweep,
    PenaltyTarget, SWEEP_FACTORS,
};
use crate::plot::PlotFile;
use std::path::Path;

/// Refinement levels of the method comparison (levels 0..=3: 160 to
/// 8.6k free dofs).
pub const METHOD_LEVELS: usize = 4;

/// Level of the Hertz cylinder swept over the penalty.
pub const SWEEP_LEVEL: usize = 1;

/// Allowed penetration of the penalty-from-penetration demonstration
/// (1e-4 x the Hertz cylinder's indentation).
pub const TARGET_PENETRATION: f64 = 1e-6;

/// Refinement levels of the mesh-scaling study (h = 1/4 .. 1/32).
pub const SCALING_LEVELS: usize = 4;

/// Results of the method studies.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Studies {
    /// Method comparisons, one per Hertz case selected.
    pub methods: Vec<MethodComparison>,
    /// Penalty sensitivity sweep (Hertz cylinder).
    pub sweep: Option<PenaltySweep>,
    /// Penalty mesh scaling (VERIFICATION-CASES.md §7).
    pub scaling: Option<PenaltyScaling>,
    /// Penalty picked from an allowed penetration (Hertz cylinder).
    pub target: Option<PenaltyTarget>,
    /// Hertz cylinder and sphere, quad8 against quad4 at about equal dofs
    /// through the levels of `hertz_quadratic` (issue 23): the rows of the
    /// work-precision plot, or why they could not be run.
    pub quadratic: Option<Result<Vec<QuadraticRow>, String>>,
    /// The rigid sphere into the 3D block, hex20 and hex27 against hex8 at
    /// about equal dofs through the levels of `hertz_sphere_3d_quadratic`:
    /// the rows of its work-precision plot (deck "sphere_3d"), or why they
    /// could not be run.
    pub quadratic_3d: Option<Result<Vec<QuadraticRow>, String>>,
}

/// One run of the quadratic-vs-linear Hertz study.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct QuadraticRow {
    /// "cylinder", "sphere" or "sphere_3d".
    pub deck: String,
    /// Quadratic cells (quad8, hex20, hex27) or linear ones.
    pub quadratic: bool,
    /// The cell kind ("quad4", "quad8", "hex8", "hex20", "hex27").
    pub cells: String,
    /// Level of `hertz_quadratic` (or `hertz_sphere_3d_quadratic`).
    pub level: usize,
    /// Free dofs.
    pub dofs: usize,
    /// Solve wall time, seconds.
    pub seconds: f64,
    /// Relative error of p0.
    pub p0: f64,
    /// Relative L2 error of p(x).
    pub l2: f64,
}

/// Levels of the quadratic-vs-linear Hertz study (those of
/// `hertz_quadratic`).
pub const QUADRATIC_LEVELS: usize = 3;

/// The rows of the quadratic-vs-linear Hertz study.
pub fn quadratic_rows(levels: usize) -> Result<Vec<QuadraticRow>, String> {
    let mut out = Vec::new();
    for level in 0..levels {
        for r in crate::programs::quadratic_contact::hertz_work_precision(level)? {
            out.push(QuadraticRow {
                deck: r.deck.to_string(),
                quadratic: r.quadratic,
                cells: if r.quadratic { "quad8" } else { "quad4" }.to_string(),
                level,
                dofs: r.dofs,
                seconds: r.seconds,
                p0: r.errors[1],
                l2: r.errors[2],
            });
        }
    }
    Ok(out)
}

/// Levels of the 3D quadratic-vs-linear Hertz study (those of
/// `hertz_sphere_3d_quadratic`).
pub const QUADRATIC_3D_LEVELS: usize = 3;

/// The rows of the 3D quadratic-vs-linear Hertz study (deck "sphere_3d").
pub fn quadratic_3d_rows(levels: usize) -> Result<Vec<QuadraticRow>, String> {
    let mut out = Vec::new();
    for level in 0..levels {
        for r in crate::programs::quadratic_contact::hertz_3d_work_precision(level)? {
            out.push(QuadraticRow {
                deck: "sphere_3d".to_string(),
                quadratic: r.kind.order() == 2,
                cells: r.kind.name().to_string(),
                level,
                dofs: r.summary.free_dofs,
                seconds: r.seconds,
                p0: r.errors[1],
                l2: r.errors[2],
            });
        }
    }
    Ok(out)
}

impl Studies {
    /// One line per failed run or violated penetration requirement.
    pub fn failures(&self) -> Vec<String> {
        let mut out = Vec::new();
        for c in &self.methods {
            if let Some(f) = &c.failure {
                out.push(format!("methods {}: {f}", c.case));
            }
            for r in &c.runs {
                if let Some(f) = &r.result.failure {
                    out.push(format!(
                        "methods {} {} level {}: {}",
                        c.case,
                        r.method.label,
                        r.result.level,
                        f.lines().next().unwrap_or("")
                    ));
                }
                let judged = r.method.judged;
                for v in r.result.values.iter().filter(|v| judged && !v.passed) {
                    out.push(format!(
                        "methods {} {} level {}: {} error {:.3e} > tolerance {:.1e}",
                        c.case,
                        r.method.label,
                        r.result.level,
                        v.quantity,
                        v.error,
                        v.tolerance.unwrap_or(f64::NAN)
                    ));
                }
            }
            out.extend(c.penetration_failures());
        }
        if let Some(s) = &self.sweep {
            if let Some(f) = &s.failure {
                out.push(format!("penalty sweep {}: {f}", s.case));
            }
            for p in &s.points {
                if let Some(f) = &p.result.failure {
                    out.push(format!(
                        "penalty sweep {} k = {:.3e}: {}",
                        s.case,
                        p.stiffness,
                        f.lines().next().unwrap_or("")
                    ));
                }
            }
        }
        if let Some(s) = &self.scaling {
            out.extend(s.failures.iter().map(|f| format!("penalty scaling: {f}")));
        }
        if let Some(t) = &self.target {
            if let Some(f) = &t.failure {
                out.push(format!("penalty for penetration {}: {f}", t.case));
            }
        }
        out
    }
}

/// Runs the studies whose case matches `filter` (the method comparisons on
/// `hertz_cylinder` / `hertz_sphere`, the sweep on `hertz_cylinder`, the
/// scaling study on `penalty_scaling`).
pub fn run_studies(
    filter: Option<&str>,
    cases_dir: &Path,
    progress: &mut dyn FnMut(&str),
) -> Studies {
    let matches = |name: &str| filter.is_none_or(|f| name.contains(f));
    let methods = studies(METHOD_LEVELS)
        .iter()
        .filter(|s| matches(s.case.name))
        .map(|s| compare_methods(s, cases_dir, progress))
        .collect();
    let cyl = cases::hertz_cylinder();
    let sweep = matches(cyl.name)
        .then(|| penalty_sweep(&cyl, cases_dir, SWEEP_LEVEL, 0.01, &SWEEP_FACTORS, progress));
    let scaling =
        matches("penalty_scaling").then(|| penalty_scaling(cases_dir, SCALING_LEVELS, progress));
    let target = matches(cyl.name)
        .then(|| penalty_for_penetration(&cyl, cases_dir, SWEEP_LEVEL, TARGET_PENETRATION, 6));
    let quadratic = matches("hertz_quadratic").then(|| {
        progress("hertz_quadratic: quad8 vs quad4");
        quadratic_rows(QUADRATIC_LEVELS)
    });
    let quadratic_3d = matches("hertz_sphere_3d_quadratic").then(|| {
        progress("hertz_sphere_3d_quadratic: hex20 and hex27 vs hex8");
        quadratic_3d_rows(QUADRATIC_3D_LEVELS)
    });
    Studies {
        methods,
        sweep,
        scaling,
        target,
        quadratic,
        quadratic_3d,
    }
}

/// Writes the plots of the studies into `dir`; returns the files written.
pub fn study_plots(s: &Studies, dir: &Path) -> Result<Vec<PlotFile>, String> {
    let mut out = Vec::new();
    for c in &s.methods {
        out.extend(work_precision_plot(c, dir)?);
    }
    if let Some(sw) = &s.sweep {
        out.extend(sweep_plot(sw, dir)?);
    }
    if let Some(sc) = &s.scaling {
        out.extend(scaling_plot(sc, dir)?);
    }
    if let Some(Ok(rows)) = &s.quadratic {
        for deck in ["cylinder", "sphere"] {
            out.extend(crate::method_plots::quadratic_work_precision_plot(
                deck, rows, dir,
            )?);
        }
    }
    if let Some(Ok(rows)) = &s.quadratic_3d {
        out.extend(crate::method_plots::quadratic_work_precision_plot(
            "sphere_3d",
            rows,
            dir,
        )?);
    }
    Ok(out)
}

/// Table rows of the method comparison: method, level, dofs, a / p0 /
/// force errors, max penetration (and / indentation), Newton iterations,
/// contact (active-set / Uzawa) iterations, solve time.
pub fn method_rows(c: &MethodComparison) -> Vec<[String; 12]> {
    use crate::case::Quantity as Q;
    let err = |r: &crate::methods::MethodRun, q| {
        r.result
            .error_of(q)
            .map_or("-".to_string(), |e| format!("{e:.2e}"))
    };
    c.runs
        .iter()
        .map(|r| {
            let l = &r.result;
            if let Some(f) = &l.failure {
                return [
                    r.method.label.clone(),
                    l.level.to_string(),
                    l.free_dofs.to_string(),
                    "FAILED".into(),
                    f.lines().next().unwrap_or("").replace('|', "/"),
                    String::new(),
                    String::new(),
                    String::new(),
                    l.newton_total.to_string(),
                    l.contact_iterations.to_string(),
                    format!("{:.3}", l.solve_time),
                    "FAIL".into(),
                ];
            }
            [
                r.method.label.clone(),
                l.level.to_string(),
                l.free_dofs.to_string(),
                err(r, Q::HalfWidth),
                err(r, Q::PeakPressure),
                err(r, Q::ContactForce),
                format!("{:.2e}", l.max_penetration),
                format!("{:.1e}", l.max_penetration / c.indentation),
                l.newton_total.to_string(),
                l.contact_iterations.to_string(),
                format!("{:.3}", l.solve_time),
                match (l.passed(), r.method.judged) {
                    (true, _) => "pass".into(),
                    (false, true) => "FAIL".into(),
                    (false, false) => "over tol. (not judged)".into(),
                },
            ]
        })
        .collect()
}

/// Column headers of [`method_rows`].
pub const METHOD_COLUMNS: [&str; 12] = [
    "method",
    "level",
    "dofs",
    "a err",
    "p0 err",
    "force err",
    "max penetration",
    "/ indentation",
    "Newton",
    "active-set/Uzawa",
    "solve [s]",
    "case tolerances",
];

impl Studies {
    /// Plain-text tables of the studies.
    pub fn table(&self) -> String {
        use std::fmt::Write as _;
        let mut s = String::new();
        for c in &self.methods {
            let _ = writeln!(s, "method comparison: {} ({})", c.case, c.title);
            let _ = writeln!(
                s,
                "{:<30} {:>3} {:>6} {:>9} {:>9} {:>9} {:>10} {:>8} {:>6} {:>6} {:>8}  tolerances",
                "method",
                "lvl",
                "dofs",
                "a err",
                "p0 err",
                "force",
                "penetr.",
                "/indent",
                "newton",
                "contact",
                "time[s]",
            );
            for r in method_rows(c) {
                let _ = writeln!(
                    s,
                    "{:<30} {:>3} {:>6} {:>9} {:>9} {:>9} {:>10} {:>8} {:>6} {:>6} {:>8}  {}",
                    r[0], r[1], r[2], r[3], r[4], r[5], r[6], r[7], r[8], r[9], r[10], r[11]
                );
            }
            let _ = writeln!(s);
        }
        if let Some(sw) = &self.sweep {
            let _ = writeln!(
                s,
                "penalty sweep: {} level {} (E = {}, h = {:.3e}, E/h = {:.3e})",
                sw.case,
                sw.level,
                sw.young,
                sw.h,
                sw.young / sw.h
            );
            for (k, f, l) in sweep_rows(sw) {
                let _ = writeln!(s, "  {k:<28} {f:<10} {l}");
            }
            let _ = writeln!(s);
        }
        if let Some(t) = &self.target {
            let _ = writeln!(
                s,
                "penalty from an allowed penetration {:e}: {} level {}",
                t.allowed, t.case, t.level
            );
            for (i, r) in t.trials.iter().enumerate() {
                let _ = writeln!(
                    s,
                    "  run {}: k = {:.4e}  penetration {:.3e}  p0 err {:.2e}  Newton {}",
                    i + 1,
                    r.stiffness,
                    r.penetration,
                    r.p0_error,
                    r.newton
                );
            }
            if let Some(f) = &t.failure {
                let _ = writeln!(s, "  FAILED: {f}");
            }
            let _ = writeln!(s);
        }
        if let Some(sc) = &self.scaling {
            let _ = writeln!(
                s,
                "penalty mesh scaling (k = {:e}, rigid pressure {})",
                sc.stiffness, sc.rigid_pressure
            );
            for p in &sc.points {
                let _ = writeln!(
                    s,
                    "  {:<28} h = {:<8.4} penalty {:>10.3e}  middle gap {:>11.3e}  pressure error {:.3e}",
                    p.flavour.label(),
                    p.h,
                    p.penalty,
                    p.gap_middle,
                    p.pressure_error
                );
            }
            let _ = writeln!(s);
        }
        s
    }
}

/// Rows of the sweep table: (k, k / (E/h), "p0 err .. penetration ..
/// newton ..") including the Lagrange limit.
pub fn sweep_rows(sw: &PenaltySweep) -> Vec<(String, String, String)> {
    use crate::case::Quantity as Q;
    let line = |l: &crate::report::LevelReport| match &l.failure {
        Some(f) => format!("FAILED: {}", f.lines().next().unwrap_or("")),
        None => format!(
            "p0 err {:.2e}  a err {:.2e}  penetration {:.2e}  Newton {}  solve {:.3} s",
            l.error_of(Q::PeakPressure).unwrap_or(f64::NAN),
            l.error_of(Q::HalfWidth).unwrap_or(f64::NAN),
            l.max_penetration,
            l.newton_total,
            l.solve_time
        ),
    };
    let mut out: Vec<_> = sw
        .points
        .iter()
        .map(|p| {
            (
                format!("k = {:.3e}", p.stiffness),
                format!("{:.0e} E/h", p.factor),
                line(&p.result),
            )
        })
        .collect();
    if let Some(l) = &sw.lagrange {
        out.push(("lagrange".into(), "k -> inf".into(), line(l)));
    }
    out
}
