//! `contact_patch_mortar_quadratic`: the contact patch test between two
//! deformable blocks on quadratic faces (issues 23 and 18), mortar on seg3
//! segments with dual multipliers (`ctc_engine::contact::mortar::seg3`).
//!
//! Source: Taylor & Papadopoulos, "On a patch test for contact problems in
//! two dimensions", IJNME 31 (1991) 2205 (the test); Puso & Laursen, CMAME
//! 193 (2004) 601 and Popp, Gee & Wall, IJNME 79 (2009) 1354 (mortar with
//! dual multipliers passes it to round-off); the linear version is
//! `contact_patch_two_blocks` (`programs/mortar.rs`).
//!
//! ```text
//!   top  [0,1]x[1,2], 3 | 5 cells across, 2 up; top edge pushed down by 0.1
//!   ---- interface: slave = top.bottom, master = base.top (non-matching) ----
//!   base [0,1]x[0,1], 4 | 7 cells across, 2 up; bottom fixed in y
//!   E = 2e6, nu = 0; x = 0 fixed in x on both blocks (the axis in
//!   axisymmetry); quad8, quad9 (elevated quad4) and tri6 (elevated tri3)
//! ```
//!
//! Exact state: `sigma_yy = -p` everywhere with `p = 0.1 / (2 / E + 1 / k)`
//! (area penalty `k = 1e8`) or `p = 0.1 E / 2` (augmented Lagrangian,
//! Lagrange multipliers); `nu = 0` keeps the interface's area constant, so
//! the reported (nominal) pressure is `p`. Measured per cell kind, analysis
//! and method: the largest deviation of the closed slave nodes' pressures
//! (corners and midside nodes) from their mean, and the mean's error
//! against `p`. Every slave node with a positive tributary area must be
//! closed (in axisymmetry the corner on the axis has `int N_a 2 pi r ds =
//! 0`: no multiplier row, as its dual function vanishes).

use super::error;
use crate::case::{Check, Quantity};
use crate::registry::{CaseKind, ProgramCase, ProgramLevel, VerifyCase};
use ctc_engine::contact::{ContactStatus, NodeContact};
use ctc_engine::mesh::elevate::elevate;
use ctc_engine::mesh::generate::{generate, Grading, MeshSpec};
use ctc_engine::mesh::{CellKind, Mesh};
use ctc_engine::model::{
    AnalysisKind, ContactFormulation, ContactMethod, LagrangeFormulation, MultiplierUpdate,
    PenaltyKind,
};
use ctc_engine::solve::{IncrementView, Observer};
use ctc_engine::testkit::{ramp, ModelBuilder};

/// Levels: (base cells, top cells) across the interface.
const MESHES: [(usize, usize); 2] = [(4, 3), (7, 5)];

pub(super) const E: f64 = 2e6;
/// Area penalty.
pub(super) const K: f64 = 1e8;
/// Travel of the top edge.
pub(super) const TRAVEL: f64 = 0.1;

/// How a run enforces contact.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Enforce {
    Penalty,
    Augmented,
    Lagrange,
}

/// The runs: (deviation name, mean-error name, analysis, linear cell,
/// quadratic cell, enforcement).
type Run = (
    &'static str,
    &'static str,
    AnalysisKind,
    CellKind,
    CellKind,
    Enforce,
);

fn runs() -> Vec<Run> {
    use AnalysisKind::{Axisymmetric as Axi, PlaneStrain as Ps};
    use CellKind::{Quad4, Quad8, Quad9, Tri3, Tri6};
    use Enforce::{Augmented as Al, Lagrange as La, Penalty as Pe};
    vec![
        (
            "dev penalty quad8 plane strain",
            "p penalty quad8 plane strain",
            Ps,
            Quad4,
            Quad8,
            Pe,
        ),
        (
            "dev penalty quad9 plane strain",
            "p penalty quad9 plane strain",
            Ps,
            Quad4,
            Quad9,
            Pe,
        ),
        (
            "dev penalty tri6 plane strain",
            "p penalty tri6 plane strain",
            Ps,
            Tri3,
            Tri6,
            Pe,
        ),
        (
            "dev penalty quad8 axisymmetric",
            "p penalty quad8 axisymmetric",
            Axi,
            Quad4,
            Quad8,
            Pe,
        ),
        (
            "dev penalty quad9 axisymmetric",
            "p penalty quad9 axisymmetric",
            Axi,
            Quad4,
            Quad9,
            Pe,
        ),
        (
            "dev penalty tri6 axisymmetric",
            "p penalty tri6 axisymmetric",
            Axi,
            Tri3,
            Tri6,
            Pe,
        ),
        (
            "dev augmented quad8 plane strain",
            "p augmented quad8 plane strain",
            Ps,
            Quad4,
            Quad8,
            Al,
        ),
        (
            "dev augmented tri6 axisymmetric",
            "p augmented tri6 axisymmetric",
            Axi,
            Tri3,
            Tri6,
            Al,
        ),
        (
            "dev lagrange quad8 plane strain",
            "p lagrange quad8 plane strain",
            Ps,
            Quad4,
            Quad8,
            La,
        ),
        (
            "dev lagrange quad9 axisymmetric",
            "p lagrange quad9 axisymmetric",
            Axi,
            Quad4,
            Quad9,
            La,
        ),
    ]
}

/// The registry entries of this file.
pub fn cases() -> Vec<VerifyCase> {
    vec![patch_case(), hertz_case()]
}

fn patch_case() -> VerifyCase {
    VerifyCase {
        name: "contact_patch_mortar_quadratic",
        title: "Contact patch test, two deformable blocks on quadratic faces (quad8, quad9, tri6; \
                plane strain and axisymmetric), non-matching 4|3 and 7|5: seg3 mortar, dual \
                multipliers",
        source: "Taylor & Papadopoulos IJNME 31 (1991); Puso & Laursen CMAME 193 (2004); Popp, \
                 Gee & Wall IJNME 79 (2009)",
        tags: &[
            "contact",
            "patch",
            "mortar",
            "quadratic",
            "two_bodies",
            "penalty",
            "augmented_lagrange",
            "lagrange",
            "plane_strain",
            "axisymmetric",
            "exact",
        ],
        levels: MESHES.len(),
        checks: runs()
            .into_iter()
            .flat_map(|r| {
                [
                    Check::new(Quantity::Named(r.0), &[1e-8]),
                    Check::new(Quantity::Named(r.1), &[1e-8]),
                ]
            })
            .collect(),
        kind: CaseKind::Program(ProgramCase {
            max_levels: MESHES.len(),
            run: patch_level,
        }),
    }
}

/// A block `[0, 1] x [y0, y0 + 1]` of `n` x 2 `kind` cells (the `linear`
/// cells elevated; `kind == linear`: the linear cells).
pub(super) fn block(y0: f64, n: usize, linear: CellKind, kind: CellKind) -> Result<Mesh, String> {
    let m = generate(&MeshSpec::Rectangle {
        origin: [0.0, y0],
        size: [1.0, 1.0],
        divisions: [n, 2],
        grading: [Grading::Uniform; 2],
        kind: linear,
    })
    .map_err(|e| e.message)?;
    if kind == linear {
        return Ok(m);
    }
    elevate(&m, kind).map_err(|e| e.message)
}

pub(super) fn method(enforce: Enforce) -> ContactMethod {
    match enforce {
        Enforce::Penalty => ContactMethod::Penalty {
            kind: PenaltyKind::Area,
            stiffness: K,
        },
        Enforce::Augmented => ContactMethod::AugmentedLagrange {
            kind: PenaltyKind::Area,
            penalty: K,
            tolerance: 1e-12,
            update: MultiplierUpdate::Converged,
        },
        Enforce::Lagrange => ContactMethod::Lagrange {
            formulation: LagrangeFormulation::Single,
        },
    }
}

#[derive(Default)]
pub(super) struct Last(pub(super) Vec<NodeContact>);

impl Observer for Last {
    fn converged(&mut self, v: &IncrementView<'_>) -> Result<(), String> {
        self.0 = v.contact.first().cloned().unwrap_or_default();
        Ok(())
    }
}

/// One run's figures: the largest `|p_i - mean| / mean` over the closed
/// slave nodes, the mean's relative error against the closed form, and the
/// run's summary.
fn patch_run(
    n_base: usize,
    n_top: usize,
    analysis: AnalysisKind,
    linear: CellKind,
    kind: CellKind,
    enforce: Enforce,
) -> Result<(f64, f64, ctc_engine::solve::RunSummary), String> {
    let mut b = ModelBuilder::new(analysis)
        .elastic("m", E, 0.0)
        .body("base", block(0.0, n_base, linear, kind)?, "m")
        .body("top", block(1.0, n_top, linear, kind)?, "m");
    let (base_bottom, base_left) = (b.node_set("base.bottom"), b.node_set("base.left"));
    let (top_left, top_top) = (b.node_set("top.left"), b.node_set("top.top"));
    let (slave, master) = (b.edge_set("top.bottom"), b.edge_set("base.top"));
    b = b
        .fix(base_bottom, 1)
        .fix(base_left, 0)
        .fix(top_left, 0)
        .displace(top_top, 1, ramp(0.0, 1.0, -TRAVEL));
    let model = b
        .contact_surface(
            "top.bottom -> base.top",
            ("top", slave),
            ("base", master),
            method(enforce),
        )
        .formulation_of_pair(ContactFormulation::Mortar)
        .step("press", 1.0, 2)
        .tol(1e-10)
        .build();
    let mut last = Last::default();
    let s = ctc_engine::solve::run(&model, &mut last).map_err(|e| e.message)?;
    if !s.completed {
        return Err("the run did not complete".into());
    }
    // corners and midside nodes of the slave edges, less the corner on
    // the axis in axisymmetry (zero tributary area)
    let expected = 2 * n_top + 1 - usize::from(analysis == AnalysisKind::Axisymmetric);
    let p: Vec<f64> = last
        .0
        .iter()
        .filter(|c| c.status == ContactStatus::Closed)
        .map(|c| c.pressure)
        .collect();
    if p.len() != expected {
        return Err(format!(
            "{} of {expected} slave nodes are closed in the patch test",
            p.len()
        ));
    }
    let mean = p.iter().sum::<f64>() / p.len() as f64;
    let deviation = p.iter().map(|x| (x - mean).abs()).fold(0.0, f64::max) / mean;
    let exact = match enforce {
        Enforce::Penalty => TRAVEL / (2.0 / E + 1.0 / K),
        _ => TRAVEL * E / 2.0,
    };
    Ok((deviation, ((mean - exact) / exact).abs(), s))
}

fn patch_level(level: usize) -> Result<ProgramLevel, String> {
    let (n_base, n_top) = *MESHES.get(level).ok_or("no such level")?;
    let mut out = ProgramLevel {
        h: 1.0 / n_top as f64,
        ..ProgramLevel::default()
    };
    for (dev, mean, analysis, linear, kind, enforce) in runs() {
        let (d, m, s) = patch_run(n_base, n_top, analysis, linear, kind, enforce)
            .map_err(|e| format!("{dev}: {e}"))?;
        out.add_run(&s);
        out.values.push(error(dev, d));
        out.values.push(error(mean, m));
    }
    Ok(out)
}

// ---------------------------------------- Hertz, two cylinders on quad8

/// The deck of `ctc verify hertz_two_cylinders_mortar` (quad4).
const HERTZ_DECK: &str = "hertz_two_cylinders_mortar.ctc";

/// The measured quantities: (name, tolerance per level); the quad4 ones
/// are the same deck's (`hertz_two_cylinders_mortar`) at about the same
/// number of dofs.
const HERTZ_CHECKS: [(&str, &[f64]); 6] = [
    ("p0 quad8", &[0.05, 0.005, 0.003]),
    ("a (moment) quad8", &[0.005, 0.012, 0.005]),
    ("L2(p) quad8", &[0.07, 0.05, 0.018]),
    ("p0 quad4", &[0.035, 0.02, 0.011]),
    ("a (moment) quad4", &[0.03, 0.012, 0.005]),
    ("L2(p) quad4", &[0.09, 0.05, 0.026]),
];

/// Hertz, two elastic cylinders on non-matching arcs, seg3 mortar on
/// quad8 cells (tri6 in the hubs, midside nodes on the arcs) against the
/// quad4 mortar run of the same deck with twice the divisions (about the
/// same dofs).
///
/// ```text
///          |  top quarter cylinder R = 1 (arc grading 0.02), flat pushed 0.02
///          | .-'
///   -------+---- interface: slave top.arc -> master bottom.arc (mortar)
///          | '-.
///          |  bottom quarter cylinder R = 1 (arc grading 0.03), flat fixed
///   x = 0: symmetry
/// ```
///
/// Reference: K. L. Johnson, Contact Mechanics (1985) §4.3 (identical
/// cylinders: `a = sqrt(4 P R / (pi E'))`, `p0 = 2 P / (pi a)`), the deck
/// `verification/cases/hertz_two_cylinders_mortar.ctc` with `order = 2` and
/// half its `radial` / `circumferential` divisions.
///
/// Measured (`ctc verify hertz_two_cylinders_mortar_quadratic --max-level
/// 2`; levels 0-2, 320 / 1,158 / 4,464 dofs, quad8 | quad4): p0 4.4e-2 |
/// 3.1e-2, 2.7e-3 | 1.7e-2, 1.7e-3 | 9.4e-3; a (first moment) 1.5e-3 |
/// 2.6e-2, 8.9e-3 | 1.0e-2, 3.1e-3 | 3.6e-3; L2(p) 5.6e-2 | 8.4e-2, 4.2e-2
/// | 4.5e-2, 1.4e-2 | 2.3e-2.
fn hertz_case() -> VerifyCase {
    VerifyCase {
        name: "hertz_two_cylinders_mortar_quadratic",
        title: "Hertz: two elastic cylinders, non-matching arcs, seg3 mortar on quad8 cells vs \
                quad4 mortar at about equal dofs",
        source: "VERIFICATION-CASES.md §1; Johnson, Contact Mechanics §4.3; deck \
                 hertz_two_cylinders_mortar.ctc",
        tags: &[
            "contact",
            "hertz",
            "mortar",
            "quadratic",
            "two_bodies",
            "penalty",
            "plane_strain",
            "closed_form",
        ],
        levels: 2,
        checks: HERTZ_CHECKS
            .iter()
            .map(|(n, t)| Check::new(Quantity::Named(n), t))
            .collect(),
        kind: CaseKind::Program(ProgramCase {
            max_levels: 3,
            run: hertz_level,
        }),
    }
}

/// `text` with every `from` replaced by `to`, which must occur `count`
/// times.
fn replace_n(text: &str, from: &str, to: &str, count: usize) -> Result<String, String> {
    let found = text.matches(from).count();
    if found != count {
        return Err(format!(
            "{HERTZ_DECK}: `{from}` found {found} times, not {count}"
        ));
    }
    Ok(text.replace(from, to))
}

fn hertz_level(level: usize) -> Result<ProgramLevel, String> {
    let (path, text) = super::read_case_deck(HERTZ_DECK)?;
    let deck = crate::refine::RefinableDeck::parse(&text)?;
    if level >= deck.levels() {
        return Err(format!("{HERTZ_DECK} has no level {level}"));
    }
    let linear = deck.render(level)?;
    let (r, c) = (8 << level, 16 << level);
    let quadratic = replace_n(
        &linear,
        &format!("radial = {r}  circumferential = {c}"),
        &format!("radial = {}  circumferential = {}", r / 2, c / 2),
        2,
    )?;
    let quadratic = replace_n(
        &quadratic,
        "element = quad4",
        "element = quad4  order = 2",
        2,
    )?;
    let mut out = ProgramLevel {
        h: 1.0 / c as f64,
        ..ProgramLevel::default()
    };
    let of = |m: &crate::measure::Measured, q: Quantity| {
        m.values
            .iter()
            .find(|v| v.quantity == q)
            .map(|v| v.error)
            .ok_or_else(|| format!("{q:?} not measured"))
    };
    for (text, names) in [
        (quadratic, &HERTZ_CHECKS[..3]),
        (linear, &HERTZ_CHECKS[3..]),
    ] {
        let (measured, _, summary) = super::mortar::hertz_run(&path, &text)?;
        out.add_run(&summary);
        for (q, (name, _)) in [
            Quantity::PeakPressure,
            Quantity::HalfWidthMoment,
            Quantity::PressureL2,
        ]
        .into_iter()
        .zip(names)
        {
            out.values.push(error(name, of(&measured, q)?));
        }
    }
    Ok(out)
}
