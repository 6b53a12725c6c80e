//! The stress matrix (`ctc verify --stress`): stiff and extreme cases crossed
//! with parameters. Every cell must either converge to the right answer or
//! stop with a diagnosis — never NaN output, never a panic, never a hang
//! (the solver's iteration and cutback limits bound every run).
//!
//! Each cell is a deck generated here, an expectation, and a check of the
//! converged state against a reference (force balance, Hertz p0, uniform
//! compression, full release).

use crate::analytical::hertz;
use crate::capture::Capture;
use crate::deck::compile_text;
use ctc_engine::contact::ContactStatus;
use ctc_engine::solve::{IncrementView, IterationInfo, Observer};
use std::fmt::Write as _;
use std::path::Path;
use std::time::Instant;

/// Young's modulus of every stress deck.
const YOUNG: f64 = 1e3;

/// What a cell must do to pass.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Expect {
    /// Converge, and the checked quantity within the relative tolerance.
    Accurate(f64),
    /// Converge with finite results and balanced forces; the answer is known
    /// to be inaccurate by construction (e.g. a very soft penalty, locking).
    Converges,
    /// Either converge (then like `Converges`) or stop with a diagnosis.
    ConvergesOrDiagnoses,
    /// Either converge (then like `Converges`) or stop with a diagnosis
    /// whose likely cause contains the given text (e.g. a very stiff
    /// penalty must be named as the cause).
    ConvergesOrDiagnosesWith(&'static str),
}

/// Wall-time budget of one cell, seconds (dev profile). The solver's own
/// limits (`max_iter`, cutbacks down to `min_increment`) bound every run;
/// a cell over the budget is counted as a hang.
pub const CELL_BUDGET_SECONDS: f64 = 60.0;

/// How a cell ended, for the counts of the report.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Outcome {
    /// Converged and met its expectation.
    Converged,
    /// Stopped with a diagnosis, as its expectation allows.
    DiagnosedFail,
    /// Did not meet its expectation (wrong answer, NaN, panic, missing or
    /// wrong diagnosis).
    Wrong,
    /// Took longer than [`CELL_BUDGET_SECONDS`].
    Hang,
}

/// Counts of the cells per [`Outcome`].
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, serde::Serialize)]
pub struct Counts {
    /// Converged (and right).
    pub converged: usize,
    /// Stopped with the expected diagnosis.
    pub diagnosed_fail: usize,
    /// Wrong answer or missing diagnosis.
    pub wrong: usize,
    /// Over the wall-time budget.
    pub hang: usize,
}

/// One cell of the matrix.
#[derive(Debug, Clone)]
pub struct StressCase {
    /// Family of the case (e.g. `penalty`, `nu`).
    pub family: &'static str,
    /// The parameter value, as shown in the table.
    pub value: String,
    /// The deck text.
    pub deck: String,
    /// Expectation.
    pub expect: Expect,
    /// Reference check of the final state.
    pub check: Check,
}

/// How the final converged state is judged.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Check {
    /// Peak pressure vs Hertz p0 for the computed total force (plane strain,
    /// rigid/elastic cylinder of radius `radius`, plane-strain modulus).
    HertzP0 {
        /// Combined radius.
        radius: f64,
        /// Poisson's ratio of the body.
        nu: f64,
    },
    /// Total vertical contact force vs a uniform compression of a block of
    /// `width` by strain `strain` (plane strain, lateral faces free).
    UniformForce {
        /// Block width.
        width: f64,
        /// Imposed vertical strain (positive = compression).
        strain: f64,
        /// Poisson's ratio.
        nu: f64,
    },
    /// Everything released: no closed node and max |u| ~ 0.
    Released,
    /// Only force balance (contact force = -reaction).
    Balance,
}

/// The result of one cell.
#[derive(Debug, Clone, serde::Serialize)]
pub struct StressResult {
    /// Family.
    pub family: String,
    /// Parameter value.
    pub value: String,
    /// Expectation.
    pub expect: Expect,
    /// Did the analysis reach its end.
    pub converged: bool,
    /// Newton iterations (all attempts).
    pub iterations: usize,
    /// Cutbacks.
    pub cutbacks: usize,
    /// Deepest penetration seen at any converged increment (>= 0).
    pub worst_penetration: f64,
    /// Relative force balance |F_contact + R| / |F_contact| at the end.
    pub balance: f64,
    /// Relative error of the checked quantity (None: not applicable).
    pub error: Option<f64>,
    /// Residual sequence of the last converged increment.
    pub last_residuals: Vec<f64>,
    /// The solver's diagnosis when it stopped early, or the panic message.
    pub diagnosis: Option<String>,
    /// The diagnosis' "likely cause" line, when it has one.
    pub cause: Option<String>,
    /// Whether the expectation was met.
    pub ok: bool,
    /// Wall time, seconds.
    pub seconds: f64,
    /// Converged / diagnosed-fail / wrong / hang.
    pub outcome: Outcome,
}

/// The whole matrix.
#[derive(Debug, Clone, serde::Serialize)]
pub struct StressReport {
    /// One row per cell.
    pub cells: Vec<StressResult>,
}

impl StressReport {
    /// True when every cell met its expectation within the time budget.
    pub fn passed(&self) -> bool {
        self.cells
            .iter()
            .all(|c| c.ok && c.outcome != Outcome::Hang)
    }

    /// Cells per outcome.
    pub fn counts(&self) -> Counts {
        let mut k = Counts::default();
        for c in &self.cells {
            match c.outcome {
                Outcome::Converged => k.converged += 1,
                Outcome::DiagnosedFail => k.diagnosed_fail += 1,
                Outcome::Wrong => k.wrong += 1,
                Outcome::Hang => k.hang += 1,
            }
        }
        k
    }

    /// The counts line shown under the tables.
    pub fn counts_line(&self) -> String {
        let k = self.counts();
        format!(
            "{} cells: {} converged, {} diagnosed-fail, {} wrong, {} hang (budget {CELL_BUDGET_SECONDS} s per cell)",
            self.cells.len(),
            k.converged,
            k.diagnosed_fail,
            k.wrong,
            k.hang
        )
    }

    /// The matrix as a Markdown section (for the verification report:
    /// `stress.md`).
    pub fn markdown(&self) -> String {
        let mut s = String::from("## Stress matrix (stiff and extreme cases)\n\n");
        let _ = writeln!(s, "**{}**\n", self.counts_line());
        s.push_str(
            "| family | value | outcome | iterations | cutbacks | worst penetration | balance | error | time [s] | likely cause (failed cells) |\n\
             |---|---|---|---:|---:|---:|---:|---:|---:|---|\n",
        );
        for c in &self.cells {
            let err = c.error.map_or("-".to_string(), |e| format!("{e:.2e}"));
            let cause = c
                .cause
                .as_deref()
                .or(c.diagnosis.as_deref().filter(|_| !c.converged))
                .unwrap_or("")
                .replace('|', "\\|");
            let _ = writeln!(
                s,
                "| {} | {} | {} | {} | {} | {:.2e} | {:.1e} | {} | {:.3} | {} |",
                c.family,
                c.value,
                outcome_name(c.outcome),
                c.iterations,
                c.cutbacks,
                c.worst_penetration,
                c.balance,
                err,
                c.seconds,
                cause
            );
        }
        s
    }

    /// A fixed-width table.
    pub fn table(&self) -> String {
        let mut s = String::new();
        let _ = writeln!(
            s,
            "{:<14} {:<22} {:<9} {:>5} {:>4} {:>10} {:>9} {:>9} {:>8}  verdict",
            "family", "value", "result", "iters", "cut", "penetr.", "balance", "error", "time[s]"
        );
        for c in &self.cells {
            let err = c.error.map_or("-".to_string(), |e| format!("{e:.2e}"));
            let _ = writeln!(
                s,
                "{:<14} {:<22} {:<9} {:>5} {:>4} {:>10.2e} {:>9.1e} {:>9} {:>8.3}  {}",
                c.family,
                c.value,
                if c.converged { "converged" } else { "stopped" },
                c.iterations,
                c.cutbacks,
                c.worst_penetration,
                c.balance,
                err,
                c.seconds,
                if c.ok { "ok" } else { "FAIL" }
            );
            if let Some(d) = &c.diagnosis {
                let first = d.lines().next().unwrap_or("");
                let _ = writeln!(s, "{:<14} diagnosis: {first}", "");
            }
            if let Some(cause) = &c.cause {
                let _ = writeln!(s, "{:<14} {cause}", "");
            }
        }
        let _ = writeln!(s, "{}", self.counts_line());
        let failed = self.cells.iter().filter(|c| !c.ok).count();
        let _ = writeln!(
            s,
            "{} of {} cells met their expectation",
            self.cells.len() - failed,
            self.cells.len()
        );
        s
    }
}

/// Rigid cylinder (R = 1) pushed `depth` into a block [-2,2]x[-2,0].
fn cylinder_on_block(
    divisions: (usize, usize),
    grading_y: f64,
    stiffness: f64,
    nu: f64,
    depth: f64,
    increments: usize,
) -> String {
    format!(
        "analysis {{ dimension = plane_strain }}\n\
         material m {{ elastic {{ E = {YOUNG:e}  nu = {nu} }} }}\n\
         body block {{\n  mesh = rectangle {{ origin = (-2, -2)  size = (4, 2)  divisions = ({}, {})\n    grading = (center(6), geometric({grading_y:e}))  element = quad4 }}\n  material = m\n}}\n\
         tool punch = circle {{ center = (0, 1)  radius = 1  motion {{ uy = ramp(0, {}) }} }}\n\
         contact block.top -> punch {{ method = penalty {{ kind = area  stiffness = {stiffness:e} }} }}\n\
         fix block.bottom {{ ux uy }}\n\
         step s {{ time = 0 .. 1  increments = {increments} }}\n",
        divisions.0, divisions.1, -depth
    )
}

/// Elastic half cylinder (R = 8) pressed onto a rigid floor.
fn cylinder_on_floor(nu: f64, formulation: &str, stiffness: f64) -> String {
    format!(
        "analysis {{ dimension = plane_strain }}\n\
         material m {{ elastic {{ E = {YOUNG:e}  nu = {nu} }} }}\n\
         body disc {{\n  mesh = half_disc {{ center = (0, 8)  radius = 8  radial = 12  circumferential = 48\n    radial_grading = geometric(0.15)  circumferential_grading = center(10)  upper = false }}\n  material = m\n  formulation = {formulation}\n}}\n\
         tool floor = plane {{ point = (0, 0)  normal = (0, 1) }}\n\
         contact disc.arc -> floor {{ method = penalty {{ kind = area  stiffness = {stiffness:e} }} }}\n\
         fix disc.flat {{ ux }}\n\
         displace disc.flat {{ uy = ramp(0, -0.08) }}\n\
         step s {{ time = 0 .. 1  increments = 4 }}\n"
    )
}

/// A unit block pressed onto a rigid `floor` tool (deck text of the tool
/// given) by displacing its top by -0.01.
fn block_on_tool(tool: &str, divisions: usize) -> String {
    format!(
        "analysis {{ dimension = plane_strain }}\n\
         material m {{ elastic {{ E = {YOUNG:e}  nu = 0.3 }} }}\n\
         body block {{\n  mesh = rectangle {{ origin = (-0.5, 0)  size = (1, 1)  divisions = ({divisions}, {divisions})  element = quad4 }}\n  material = m\n}}\n\
         tool floor = {tool}\n\
         contact block.bottom -> floor {{ method = penalty {{ kind = area  stiffness = 1e8 }} }}\n\
         fix block.node(near(0, 1)) {{ ux }}\n\
         displace block.top {{ uy = ramp(0, -0.01) }}\n\
         step s {{ time = 0 .. 1  increments = 2 }}\n"
    )
}

/// The cells of the matrix; `reduced` keeps a quick subset for the tests.
pub fn cases(reduced: bool) -> Vec<StressCase> {
    let mut v = Vec::new();
    let hertz_block = Check::HertzP0 {
        radius: 1.0,
        nu: 0.3,
    };
    // Penalty over ten decades, in units of E / h_min (h_min ~ 0.04 here).
    let h_min = 0.04;
    let factors: &[f64] = if reduced {
        &[1.0, 1e4]
    } else {
        &[1e-2, 1.0, 1e2, 1e4, 1e6, 1e8]
    };
    for &f in factors {
        let expect = if f < 10.0 {
            Expect::Converges
        } else if f <= 1e4 {
            Expect::Accurate(0.15)
        } else {
            Expect::ConvergesOrDiagnosesWith("penalty too high for this mesh")
        };
        v.push(StressCase {
            family: "penalty",
            value: format!("{f:e} E/h"),
            deck: cylinder_on_block((32, 16), 0.2, f * YOUNG / h_min, 0.3, 0.02, 4),
            expect,
            check: hertz_block,
        });
    }
    // Near incompressibility, full vs selective reduced integration.
    let nus: &[f64] = if reduced {
        &[0.4999]
    } else {
        &[0.49, 0.499, 0.4999]
    };
    for &nu in nus {
        for (form, expect) in [
            ("selective_reduced", Expect::Accurate(0.05)),
            ("full", Expect::Converges),
        ] {
            if reduced && form == "full" {
                continue;
            }
            v.push(StressCase {
                family: "nu",
                value: format!("{nu} {form}"),
                deck: cylinder_on_floor(nu, form, 1e6),
                expect,
                check: Check::HertzP0 { radius: 8.0, nu },
            });
        }
    }
    if !reduced {
        // Element size ratio 1e3 through the thickness under the contact.
        v.push(StressCase {
            family: "size ratio",
            value: "1e3 (geometric 1e-3)".into(),
            deck: cylinder_on_block((32, 24), 1e-3, 1e2 * YOUNG / h_min, 0.3, 0.02, 4),
            expect: Expect::Accurate(0.15),
            check: hertz_block,
        });
        // The whole indentation in one increment, five times deeper.
        v.push(StressCase {
            family: "load step",
            value: "d = 0.1 in 1 increment".into(),
            deck: cylinder_on_block((32, 16), 0.2, 1e2 * YOUNG / h_min, 0.3, 0.1, 1),
            expect: Expect::Converges,
            check: Check::Balance,
        });
    }
    let uniform = Check::UniformForce {
        width: 1.0,
        strain: 0.01,
        nu: 0.3,
    };
    // Large sliding of a finely segmented floor under the block.
    let mut pts = String::new();
    for i in 0..=400 {
        let x = -3.0 + 6.0 * i as f64 / 400.0;
        let _ = write!(pts, "{}({x}, 0)", if i == 0 { "" } else { ", " });
    }
    v.push(StressCase {
        family: "sliding",
        value: "400-segment floor moves 2".into(),
        deck: block_on_tool(
            &format!("polyline {{ points = [{pts}]  motion {{ ux = ramp(0, 2) }} }}"),
            8,
        ),
        expect: Expect::Accurate(0.02),
        check: uniform,
    });
    // A node exactly on the vertex between two segments.
    v.push(StressCase {
        family: "vertex",
        value: "node on segment end".into(),
        deck: block_on_tool("polyline { points = [(-2, 0), (0, 0), (2, 0)] }", 8),
        expect: Expect::Accurate(0.02),
        check: uniform,
    });
    v.push(StressCase {
        family: "kink",
        value: "convex kink 2 deg".into(),
        deck: block_on_tool(
            "polyline { points = [(-2, -0.0349), (0, 0), (2, -0.0349)] }",
            8,
        ),
        expect: Expect::Converges,
        check: Check::Balance,
    });
    // A flat punch with sharp corners narrower than the block.
    v.push(StressCase {
        family: "sharp corner",
        value: "flat punch, 90 deg corners".into(),
        deck: "analysis { dimension = plane_strain }\n\
               material m { elastic { E = 1e3  nu = 0.3 } }\n\
               body block {\n  mesh = rectangle { origin = (-2, -2)  size = (4, 2)  divisions = (32, 16)  element = quad4 }\n  material = m\n}\n\
               tool punch = polyline { points = [(0.5, 1), (0.5, 0), (-0.5, 0), (-0.5, 1)]  motion { uy = ramp(0, -0.01) } }\n\
               contact block.top -> punch { method = penalty { kind = area  stiffness = 1e6 } }\n\
               fix block.bottom { ux uy }\n\
               step s { time = 0 .. 1  increments = 2 }\n"
            .into(),
        expect: Expect::Converges,
        check: Check::Balance,
    });
    // Initially penetrating by 0.01, no motion.
    v.push(StressCase {
        family: "initial overlap",
        value: "penetrating 0.01".into(),
        deck: "analysis { dimension = plane_strain }\n\
               material m { elastic { E = 1e3  nu = 0.3 } }\n\
               body block {\n  mesh = rectangle { origin = (-2, -2)  size = (4, 2)  divisions = (32, 16)  grading = (center(6), geometric(0.2))  element = quad4 }\n  material = m\n}\n\
               tool punch = circle { center = (0, 0.99)  radius = 1 }\n\
               contact block.top -> punch { method = penalty { kind = area  stiffness = 2.5e6 } }\n\
               fix block.bottom { ux uy }\n\
               step s { time = 0 .. 1  increments = 1 }\n"
            .into(),
        expect: Expect::Converges,
        check: Check::Balance,
    });
    // Press, then pull the tool back beyond first contact: everything releases.
    v.push(StressCase {
        family: "release",
        value: "down 0.02 then up 0.01".into(),
        deck: "analysis { dimension = plane_strain }\n\
               material m { elastic { E = 1e3  nu = 0.3 } }\n\
               body block {\n  mesh = rectangle { origin = (-2, -2)  size = (4, 2)  divisions = (32, 16)  grading = (center(6), geometric(0.2))  element = quad4 }\n  material = m\n}\n\
               tool punch = circle { center = (0, 1)  radius = 1  motion { uy = table((0, 0), (0.5, -0.02), (1, 0.01)) } }\n\
               contact block.top -> punch { method = penalty { kind = area  stiffness = 2.5e6 } }\n\
               fix block.bottom { ux uy }\n\
               step s { time = 0 .. 1  increments = 8 }\n"
            .into(),
        expect: Expect::Accurate(1e-9),
        check: Check::Released,
    });
    if !reduced {
        // A tool that only ever moves away from the body.
        v.push(StressCase {
            family: "moving away",
            value: "gap 0.01 growing".into(),
            deck: "analysis { dimension = plane_strain }\n\
                   material m { elastic { E = 1e3  nu = 0.3 } }\n\
                   body block {\n  mesh = rectangle { origin = (-2, -2)  size = (4, 2)  divisions = (16, 8)  element = quad4 }\n  material = m\n}\n\
                   tool punch = circle { center = (0, 1.01)  radius = 1  motion { uy = ramp(0, 0.5) } }\n\
                   contact block.top -> punch { method = penalty { kind = area  stiffness = 2.5e6 } }\n\
                   fix block.bottom { ux uy }\n\
                   step s { time = 0 .. 1  increments = 2 }\n"
                .into(),
            expect: Expect::Accurate(1e-9),
            check: Check::Released,
        });
    }
    v
}

/// Tracks the deepest penetration and non-finite values over the run.
#[derive(Default)]
struct Watch {
    capture: Capture,
    worst_penetration: f64,
    non_finite: bool,
    cutbacks: usize,
}

impl Observer for Watch {
    fn iteration(&mut self, info: &IterationInfo) {
        self.capture.iteration(info);
    }

    fn converged(&mut self, view: &IncrementView<'_>) -> Result<(), String> {
        for pair in view.contact {
            for n in pair {
                if n.status == ContactStatus::Closed {
                    self.worst_penetration = self.worst_penetration.max(-n.gap);
                }
            }
        }
        if view
            .displacement
            .iter()
            .any(|u| !u[0].is_finite() || !u[1].is_finite())
        {
            self.non_finite = true;
        }
        self.capture.converged(view)
    }

    fn cutback(&mut self, reason: &str, new_dt: f64) {
        self.cutbacks += 1;
        self.capture.cutback(reason, new_dt);
    }
}

fn outcome_name(o: Outcome) -> &'static str {
    match o {
        Outcome::Converged => "converged",
        Outcome::DiagnosedFail => "diagnosed-fail",
        Outcome::Wrong => "WRONG",
        Outcome::Hang => "HANG",
    }
}

/// Whether a cell that stopped early met `expect` with `diagnosis`.
fn diagnosis_meets(expect: Expect, diagnosis: Option<&str>) -> bool {
    match (expect, diagnosis) {
        (_, Some(d)) if d.starts_with("PANIC") => false,
        (Expect::ConvergesOrDiagnoses, Some(_)) => true,
        (Expect::ConvergesOrDiagnosesWith(text), Some(d)) => d
            .lines()
            .any(|l| l.trim_start().starts_with("likely cause:") && l.contains(text)),
        _ => false,
    }
}

/// Runs one cell. A panic is caught and reported as a failed cell.
pub fn run_case(case: &StressCase) -> StressResult {
    let mut r = run_case_inner(case);
    r.cause = r.diagnosis.as_deref().and_then(|d| {
        d.lines()
            .find(|l| l.trim_start().starts_with("likely cause:"))
            .map(|l| l.trim().to_string())
    });
    r.outcome = if r.seconds > CELL_BUDGET_SECONDS {
        Outcome::Hang
    } else if !r.ok {
        Outcome::Wrong
    } else if r.converged {
        Outcome::Converged
    } else {
        Outcome::DiagnosedFail
    };
    r
}

fn run_case_inner(case: &StressCase) -> StressResult {
    let started = Instant::now();
    let mut result = StressResult {
        family: case.family.into(),
        value: case.value.clone(),
        expect: case.expect,
        converged: false,
        iterations: 0,
        cutbacks: 0,
        worst_penetration: 0.0,
        balance: f64::NAN,
        error: None,
        last_residuals: Vec::new(),
        diagnosis: None,
        cause: None,
        ok: false,
        seconds: 0.0,
        outcome: Outcome::Wrong,
    };
    let model = match compile_text(Path::new("stress.ctc"), &case.deck) {
        Ok(m) => m,
        Err(e) => {
            result.diagnosis = Some(format!("deck did not compile: {e}"));
            return result;
        }
    };
    let mut watch = Watch::default();
    let outcome = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
        ctc_engine::solve::run(&model, &mut watch)
            .map(|_| ())
            .map_err(|e| e.message)
    }));
    result.seconds = started.elapsed().as_secs_f64();
    result.iterations = watch.capture.iterations;
    result.cutbacks = watch.cutbacks;
    result.worst_penetration = watch.worst_penetration;
    match outcome {
        Err(panic) => {
            let msg = panic
                .downcast_ref::<String>()
                .cloned()
                .or_else(|| panic.downcast_ref::<&str>().map(|s| s.to_string()))
                .unwrap_or_default();
            result.diagnosis = Some(format!("PANIC: {msg}"));
            return result;
        }
        Ok(Err(message)) => result.diagnosis = Some(message),
        Ok(Ok(())) => result.converged = true,
    }
    let Some(last) = &watch.capture.last else {
        result.ok = !result.converged && diagnosis_meets(case.expect, result.diagnosis.as_deref());
        return result;
    };
    result.last_residuals = last.residuals.clone();
    let mut contact = [0.0f64; 2];
    let mut closed = 0usize;
    let mut p_max = 0.0f64;
    for pair in &last.contact {
        for n in pair {
            contact[0] += n.force[0];
            contact[1] += n.force[1];
            if n.status == ContactStatus::Closed {
                closed += 1;
                p_max = p_max.max(n.pressure);
            }
        }
    }
    let mut reaction = [0.0f64; 2];
    for r in &last.reaction {
        reaction[0] += r[0];
        reaction[1] += r[1];
    }
    let f_norm = contact[0].hypot(contact[1]);
    let imbalance = (contact[0] + reaction[0]).hypot(contact[1] + reaction[1]);
    result.balance = if f_norm > 0.0 {
        imbalance / f_norm
    } else {
        imbalance
    };
    let finite = !watch.non_finite && result.balance.is_finite();
    let balanced = result.balance <= 1e-6;
    result.error = match case.check {
        Check::HertzP0 { radius, nu } => {
            let e_star = YOUNG / (1.0 - nu * nu);
            let p = contact[1].abs();
            (p > 0.0).then(|| {
                let p0 = hertz::HertzCylinder {
                    e_star,
                    radius,
                    load: p,
                }
                .peak_pressure();
                (p_max - p0).abs() / p0
            })
        }
        Check::UniformForce { width, strain, nu } => {
            let exact = YOUNG / (1.0 - nu * nu) * strain * width;
            Some((contact[1].abs() - exact).abs() / exact)
        }
        Check::Released => {
            let umax = last
                .displacement
                .iter()
                .map(|u| u[0].hypot(u[1]))
                .fold(0.0, f64::max);
            Some(if closed > 0 { 1.0 } else { umax })
        }
        Check::Balance => None,
    };
    let within = |tol: f64| result.error.is_none_or(|e| e <= tol);
    result.ok = match case.expect {
        _ if !result.converged => {
            diagnosis_meets(case.expect, result.diagnosis.as_deref()) && finite
        }
        Expect::Accurate(tol) => finite && balanced && within(tol),
        Expect::Converges | Expect::ConvergesOrDiagnoses | Expect::ConvergesOrDiagnosesWith(_) => {
            finite && balanced
        }
    };
    result
}

/// Runs every cell (or the reduced set).
pub fn run_stress(reduced: bool) -> StressReport {
    StressReport {
        cells: cases(reduced).iter().map(run_case).collect(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn penalty_1e6_e_over_h_stops_naming_the_penalty_and_a_remedy() {
        let case = cases(false)
            .into_iter()
            .find(|c| c.family == "penalty" && c.value == "1e6 E/h")
            .expect("cell");
        let r = run_case(&case);
        assert!(!r.converged);
        let cause = r.cause.as_deref().unwrap_or("");
        assert!(cause.contains("penalty too high for this mesh"), "{cause}");
        assert!(cause.contains("chattering on nodes"), "{cause}");
        let d = r.diagnosis.as_deref().unwrap();
        assert!(d.contains("try stiffness <="), "{d}");
        assert_eq!(r.outcome, Outcome::DiagnosedFail);
        assert!(r.ok);
    }

    #[test]
    fn a_generic_diagnosis_does_not_satisfy_a_specific_expectation() {
        let want = Expect::ConvergesOrDiagnosesWith("penalty too high");
        assert!(!diagnosis_meets(
            want,
            Some("could not advance\n  likely cause: other")
        ));
        assert!(diagnosis_meets(
            want,
            Some("could not advance\n  likely cause: penalty too high for this mesh")
        ));
        assert!(!diagnosis_meets(
            Expect::ConvergesOrDiagnoses,
            Some("PANIC: x")
        ));
        assert!(!diagnosis_meets(Expect::Converges, Some("stopped")));
    }

    #[test]
    fn stress_markdown_shows_the_counts_and_every_cell() {
        let report = StressReport {
            cells: vec![StressResult {
                family: "penalty".into(),
                value: "1e8 E/h".into(),
                expect: Expect::ConvergesOrDiagnoses,
                converged: false,
                iterations: 3,
                cutbacks: 1,
                worst_penetration: 0.0,
                balance: f64::NAN,
                error: None,
                last_residuals: vec![],
                diagnosis: Some("stopped".into()),
                cause: Some("likely cause: a | b".into()),
                ok: true,
                seconds: 0.1,
                outcome: Outcome::DiagnosedFail,
            }],
        };
        let md = report.markdown();
        assert!(md.contains("1 cells: 0 converged, 1 diagnosed-fail, 0 wrong, 0 hang"));
        assert!(md.contains("| penalty | 1e8 E/h | diagnosed-fail |"));
        assert!(md.contains("a \\| b"));
    }
}
