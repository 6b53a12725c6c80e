//! Mortar between a linear and a quadratic side (issue 23, with 18): the
//! linear side's faces are taken by the quadratic routines with their own
//! shape functions (2D `ctc_engine::contact::mortar::seg3::
//! segment_pair_orders`, 3D `ctc_engine::contact::mortar::quadratic3d`
//! with tri3 / quad4 faces).
//!
//! `contact_patch_mortar_mixed` — Source: Taylor & Papadopoulos, "On a
//! patch test for contact problems in two dimensions", IJNME 31 (1991)
//! 2205; Puso & Laursen, CMAME 193 (2004) 601 and Popp, Gee & Wall, IJNME
//! 79 (2009) 1354 (dual mortar passes it to round-off); the same-order
//! version is `contact_patch_mortar_quadratic` (`programs/
//! mortar_quadratic.rs`), whose blocks, loads and closed forms these are.
//!
//! ```text
//!   top  [0,1]x[1,2], 3 | 5 cells across, 2 up; top edge pushed down by 0.1
//!   ---- interface: slave = top.bottom, master = base.top (non-matching) ----
//!   base [0,1]x[0,1], 4 | 7 cells across, 2 up; bottom fixed in y
//!   E = 2e6, nu = 0; one block linear (quad4 / tri3), the other quadratic
//!   (quad8 / quad9 / tri6), either one the slave
//! ```
//!
//! Exact state: `sigma_yy = -p`, `p = 0.1 / (2 / E + 1 / k)` (area penalty
//! `k = 1e8`) or `0.1 E / 2` (augmented Lagrangian, Lagrange multipliers).
//! Measured: the largest deviation of the closed slave nodes' pressures
//! from their mean and the mean's error against `p`; every slave node must
//! be closed (a quadratic slave's corner on the axis has no row: its
//! `int N_a 2 pi r ds` is 0; a linear slave's is positive).
//!
//! `contact_patch_mortar_mixed_3d` — the 3D patch test of
//! `contact_patch_mortar_quadratic_3d` (`programs/mortar_quadratic_3d.rs`,
//! Taylor & Papadopoulos in 3D; Puso, Laursen & Solberg, CMAME 197 (2008)
//! 555) with one block linear:
//!
//! ```text
//!   top  [0,1]^2 x [0.5,1], one layer: hex8 3x3 | hex20 2x2 | tet4 3x3
//!        (6 tets per hex), top face pushed down by d = 0.01
//!   ---- interface z = 0.5: slave = top.zmin / master = base.zmax ----
//!   base [0,1]^2 x [0,0.5], one layer: hex20 2x2 | hex8 3x3 | hex20 2x2
//!   E = 1000, nu = 0.3; x = 0 and y = 0 symmetry planes on both blocks
//! ```
//!
//! Exact: uniform `sigma_zz = -p`, `p = d / (H / E + 1 / k)` (area penalty)
//! or `E d / H`; measured the deviation of the closed slave nodes'
//! pressures from their mean and the total force through the stack
//! (`cargo test -p ctc-verification --test suite -- mortar_mixed
//! --nocapture`): penalty hex8 | hex20 1.1e-11, hex20 | hex8 9.1e-12, tet4
//! | hex20 1.3e-11, force 5.96e-6 each (the penalty's compliance per
//! current area, as the same-order pairs'); augmented Lagrangian hex8 |
//! hex20 1.2e-13, force -2.4e-8; Lagrange multipliers (hex20 | hex8, the
//! same-order 3D rows of `mortar_quadratic_3d`) see the catalogue. The 2D runs: deviation and mean error
//! <= 4.7e-13 on both levels.
//!
//! `hertz_two_cylinders_mortar_mixed` — see [`hertz_case`].

use super::contact_ntf_3d::{mortar_patch_deck, run_patch_deck, PENALTY};
use super::mortar_quadratic::{block, method, Enforce, Last, E, K, TRAVEL};
use super::{error, value};
use crate::case::{Check, Quantity};
use crate::registry::{CaseKind, ProgramCase, ProgramLevel, VerifyCase};
use ctc_engine::contact::ContactStatus;
use ctc_engine::mesh::CellKind;
use ctc_engine::model::{AnalysisKind, ContactFormulation};
use ctc_engine::testkit::{ramp, ModelBuilder};

/// Levels of the 2D patch test: (base cells, top cells) across.
const MESHES: [(usize, usize); 2] = [(4, 3), (7, 5)];

/// A 2D patch run: (deviation name, mean-error name, analysis, top (slave)
/// linear and final cell, base (master) linear and final cell, enforcement).
type Run = (
    &'static str,
    &'static str,
    AnalysisKind,
    [CellKind; 2],
    [CellKind; 2],
    Enforce,
);

fn runs() -> Vec<Run> {
    use AnalysisKind::{Axisymmetric as Axi, PlaneStrain as Ps};
    use CellKind::{Quad4, Quad8, Quad9, Tri3, Tri6};
    use Enforce::{Augmented as Al, Lagrange as La, Penalty as Pe};
    let (q4, q8, q9) = ([Quad4, Quad4], [Quad4, Quad8], [Quad4, Quad9]);
    let (t3, t6) = ([Tri3, Tri3], [Tri3, Tri6]);
    vec![
        (
            "dev penalty quad4 | quad8 plane strain",
            "p penalty quad4 | quad8 plane strain",
            Ps,
            q4,
            q8,
            Pe,
        ),
        (
            "dev penalty quad8 | quad4 plane strain",
            "p penalty quad8 | quad4 plane strain",
            Ps,
            q8,
            q4,
            Pe,
        ),
        (
            "dev penalty tri3 | quad9 plane strain",
            "p penalty tri3 | quad9 plane strain",
            Ps,
            t3,
            q9,
            Pe,
        ),
        (
            "dev penalty tri6 | quad4 plane strain",
            "p penalty tri6 | quad4 plane strain",
            Ps,
            t6,
            q4,
            Pe,
        ),
        (
            "dev penalty quad4 | quad8 axisymmetric",
            "p penalty quad4 | quad8 axisymmetric",
            Axi,
            q4,
            q8,
            Pe,
        ),
        (
            "dev penalty quad8 | quad4 axisymmetric",
            "p penalty quad8 | quad4 axisymmetric",
            Axi,
            q8,
            q4,
            Pe,
        ),
        (
            "dev augmented quad4 | quad8 plane strain",
            "p augmented quad4 | quad8 plane strain",
            Ps,
            q4,
            q8,
            Al,
        ),
        (
            "dev augmented quad8 | quad4 axisymmetric",
            "p augmented quad8 | quad4 axisymmetric",
            Axi,
            q8,
            q4,
            Al,
        ),
        (
            "dev lagrange quad4 | quad8 plane strain",
            "p lagrange quad4 | quad8 plane strain",
            Ps,
            q4,
            q8,
            La,
        ),
        (
            "dev lagrange quad8 | quad4 plane strain",
            "p lagrange quad8 | quad4 plane strain",
            Ps,
            q8,
            q4,
            La,
        ),
        (
            "dev lagrange tri3 | tri6 axisymmetric",
            "p lagrange tri3 | tri6 axisymmetric",
            Axi,
            t3,
            t6,
            La,
        ),
    ]
}

/// The 3D patch runs: deviation name, force name, top cell, its order
/// and cells across, base order and cells across (hex8), method, the
/// guard of the total force (the penalty's compliance acts per current
/// area: 6.0e-6 on every pair), the slave nodes (all closed).
#[allow(clippy::type_complexity)]
const PATCH_3D: &[(
    &str,
    &str,
    &str,
    usize,
    usize,
    usize,
    usize,
    &str,
    f64,
    usize,
)] = &[
    (
        "hex8 | hex20 mortar penalty p uniform",
        "hex8 | hex20 mortar penalty F",
        "hex8",
        1,
        3,
        2,
        2,
        PENALTY,
        1e-5,
        16,
    ),
    (
        "hex20 | hex8 mortar penalty p uniform",
        "hex20 | hex8 mortar penalty F",
        "hex8",
        2,
        2,
        1,
        3,
        PENALTY,
        1e-5,
        21,
    ),
    (
        "tet4 | hex20 mortar penalty p uniform",
        "tet4 | hex20 mortar penalty F",
        "tet4",
        1,
        3,
        2,
        2,
        PENALTY,
        1e-5,
        16,
    ),
    (
        "hex8 | hex20 mortar augmented p uniform",
        "hex8 | hex20 mortar augmented F",
        "hex8",
        1,
        3,
        2,
        2,
        AUGMENTED,
        1e-7,
        16,
    ),
    (
        "hex20 | hex8 mortar lagrange p uniform",
        "hex20 | hex8 mortar lagrange F",
        "hex8",
        2,
        2,
        1,
        3,
        "lagrange { }",
        1e-10,
        21,
    ),
];

const AUGMENTED: &str = "augmented_lagrange { kind = area  penalty = 1e4  tolerance = 1e-9 }";

/// The registry entries of this file.
pub fn cases() -> Vec<VerifyCase> {
    vec![patch_case(), patch_3d_case(), hertz_case()]
}

fn patch_case() -> VerifyCase {
    VerifyCase {
        name: "contact_patch_mortar_mixed",
        title: "Contact patch test, a linear block on a quadratic one and the reverse (quad4 | \
                quad8, quad8 | quad4, tri3 | quad9, tri6 | quad4, tri3 | tri6; plane strain and \
                axisymmetric), non-matching 4|3 and 7|5: mixed-order mortar, dual multipliers",
        source: "Taylor & Papadopoulos IJNME 31 (1991); Puso & Laursen CMAME 193 (2004); Popp, \
                 Gee & Wall IJNME 79 (2009)",
        tags: &[
            "contact",
            "patch",
            "mortar",
            "quadratic",
            "mixed_order",
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

/// One 2D run's figures: the largest `|p_i - mean| / mean` over the
/// closed slave nodes, the mean's error against the closed form, the run.
fn patch_run(
    n_base: usize,
    n_top: usize,
    analysis: AnalysisKind,
    top: [CellKind; 2],
    base: [CellKind; 2],
    enforce: Enforce,
) -> Result<(f64, f64, ctc_engine::solve::RunSummary), String> {
    let mut b = ModelBuilder::new(analysis)
        .elastic("m", E, 0.0)
        .body("base", block(0.0, n_base, base[0], base[1])?, "m")
        .body("top", block(1.0, n_top, top[0], top[1])?, "m");
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
    // a quadratic slave: corners and midside nodes, less the corner on the
    // axis in axisymmetry; a linear slave: its corners
    let expected = if top[0] == top[1] {
        n_top + 1
    } else {
        2 * n_top + 1 - usize::from(analysis == AnalysisKind::Axisymmetric)
    };
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
    for (dev, mean, analysis, top, base, enforce) in runs() {
        let (d, m, s) = patch_run(n_base, n_top, analysis, top, base, enforce)
            .map_err(|e| format!("{dev}: {e}"))?;
        out.add_run(&s);
        out.values.push(error(dev, d));
        out.values.push(error(mean, m));
    }
    Ok(out)
}

fn patch_3d_case() -> VerifyCase {
    VerifyCase {
        name: "contact_patch_mortar_mixed_3d",
        title: "3D contact patch test, a linear block on a quadratic one and the reverse (hex8 | \
                hex20, hex20 | hex8, tet4 | hex20), non-matching, one layer each: mixed-order \
                mortar, penalty, augmented Lagrangian and Lagrange multipliers",
        source: "Taylor & Papadopoulos IJNME 31 (1991), in 3D; Puso, Laursen & Solberg CMAME \
                 197 (2008) 555",
        tags: &[
            "3d",
            "contact",
            "mortar",
            "quadratic",
            "mixed_order",
            "patch",
            "two_bodies",
            "penalty",
            "augmented_lagrange",
            "exact",
        ],
        levels: 1,
        checks: PATCH_3D
            .iter()
            .flat_map(|c| {
                [
                    Check::new(Quantity::Named(c.0), &[1e-8]),
                    Check::new(Quantity::Named(c.1), &[c.8]),
                ]
            })
            .collect(),
        kind: CaseKind::Program(ProgramCase {
            max_levels: 1,
            run: patch_3d_level,
        }),
    }
}

/// The 3D patch deck: the linear mortar patch deck with its top block of
/// `top_n` x `top_n` x 1 `cell` cells of order `top_order` and its base of
/// `base_n` x `base_n` x 1 hex8 cells of order `base_order`.
pub fn patch_3d_deck(
    cell: &str,
    top_order: usize,
    top_n: usize,
    base_order: usize,
    base_n: usize,
    method: &str,
) -> Result<String, String> {
    let linear = mortar_patch_deck("hex8", 4, method);
    let base_old = "divisions = (4, 4, 2)  element = hex8 }";
    let top_old = "divisions = (3, 3, 2)  element = hex8 }";
    if !linear.contains(base_old) || !linear.contains(top_old) {
        return Err("the linear patch deck has changed: no mesh line to replace".into());
    }
    Ok(linear
        .replace(
            base_old,
            &format!(
                "divisions = ({base_n}, {base_n}, 1)  element = hex8  order = {base_order} }}"
            ),
        )
        .replace(
            top_old,
            &format!("divisions = ({top_n}, {top_n}, 1)  element = {cell}  order = {top_order} }}"),
        ))
}

fn patch_3d_level(_level: usize) -> Result<ProgramLevel, String> {
    let mut out = ProgramLevel {
        h: 0.5,
        ..ProgramLevel::default()
    };
    for &(pname, fname, cell, top_order, top_n, base_order, base_n, method, _, slaves) in PATCH_3D {
        let text = patch_3d_deck(cell, top_order, top_n, base_order, base_n, method)?;
        let (o, level) = run_patch_deck(text, method).map_err(|e| format!("{pname}: {e}"))?;
        if o.closed != slaves {
            return Err(format!(
                "{pname}: {} of {slaves} slave nodes closed",
                o.closed
            ));
        }
        super::contact_ntf_3d::add_level(&mut out, &level);
        out.values.push(error(pname, o.uniformity));
        out.values.push(value(fname, o.force, o.exact));
    }
    Ok(out)
}

// ------------------------------- Hertz, a quad8 cylinder on a quad4 one

/// The deck of `ctc verify hertz_two_cylinders_mortar` (quad4).
const HERTZ_DECK: &str = "hertz_two_cylinders_mortar.ctc";

/// The measured quantities and their tolerances per level: the measured
/// figures of [`hertz_case`] times about 1.5.
const HERTZ_CHECKS: [(&str, &[f64]); 10] = [
    ("p0 quad8 | quad4", &[0.04, 0.03, 0.016]),
    ("a (moment) quad8 | quad4", &[0.03, 0.023, 0.007]),
    ("L2(p) quad8 | quad4", &[0.08, 0.04, 0.018]),
    ("p0 quad4 | quad8", &[0.009, 0.012, 0.007]),
    ("a (moment) quad4 | quad8", &[0.009, 0.008, 0.0035]),
    ("L2(p) quad4 | quad8", &[0.13, 0.065, 0.034]),
    ("P quad8 | quad4 vs quad4 | quad4", &[0.012, 0.008, 0.002]),
    ("P quad8 | quad4 vs quad8 | quad8", &[0.008, 0.003, 0.001]),
    ("P quad4 | quad8 vs quad4 | quad4", &[0.008, 0.0035, 0.001]),
    ("P quad4 | quad8 vs quad8 | quad8", &[0.012, 0.008, 0.002]),
];

/// Hertz, two elastic cylinders on non-matching arcs with mixed orders:
/// the top cylinder (slave) on quad8 cells (`order = 2`, half the
/// divisions: about the dofs of the quad4 body) pressed on the bottom one
/// on quad4 cells, and the reverse; against Hertz and against the two
/// same-order runs of the same decks (all quad4; all quad8).
///
/// ```text
///          |  top quarter cylinder R = 1 (arc grading 0.02), flat pushed 0.02
///          | .-'
///   -------+---- interface: slave top.arc -> master bottom.arc (mortar)
///          | '-.
///          |  bottom quarter cylinder R = 1 (arc grading 0.03), flat fixed
///   x = 0: symmetry; one body quad8 (tri6 at the hub), the other quad4
/// ```
///
/// Reference: K. L. Johnson, Contact Mechanics (1985) §4.3 (identical
/// cylinders: `a = sqrt(4 P R / (pi E'))`, `p0 = 2 P / (pi a)`), the deck
/// `verification/cases/hertz_two_cylinders_mortar.ctc`; the total force
/// `P` (the reaction on the pushed flat) against the same-order runs.
///
/// Measured (`ctc verify hertz_two_cylinders_mortar_mixed --max-level 2`,
/// debug build; levels 0-2, 320 / 1,158 / 4,464 free dofs of the mixed
/// runs; slave | master):
///
/// | level | p0 quad8 \| quad4 | a | L2(p) | p0 quad4 \| quad8 | a | L2(p) |
/// | --- | --- | --- | --- | --- | --- | --- |
/// | 0 | 2.7e-2 | 1.8e-2 | 5.2e-2 | 5.4e-3 | 5.9e-3 | 8.7e-2 |
/// | 1 | 2.1e-2 | 1.5e-2 | 2.7e-2 | 7.5e-3 | 5.2e-3 | 4.4e-2 |
/// | 2 | 1.1e-2 | 4.5e-3 | 1.2e-2 | 4.7e-3 | 2.2e-3 | 2.3e-2 |
///
/// (same-order, `hertz_two_cylinders_mortar_quadratic`: p0 quad8 4.4e-2 /
/// 2.7e-3 / 1.7e-3, quad4 3.1e-2 / 1.7e-2 / 9.4e-3; L2(p) quad8 5.6e-2 /
/// 4.2e-2 / 1.4e-2, quad4 8.4e-2 / 4.5e-2 / 2.3e-2: the mixed pairs land
/// between the two, the L2 error near the slave's own order). The force
/// of a mixed run lies between the two same-order runs' at every level:
/// quad8 | quad4 against quad4 | quad4 / quad8 | quad8 7.5e-3 / 5.2e-3,
/// 5.4e-3 / 1.9e-3, 1.2e-3 / 5.9e-4; quad4 | quad8 5.2e-3 / 7.6e-3, 2.3e-3
/// / 5.1e-3, 5.8e-4 / 1.2e-3 (the same-order runs differ by 1.3 %, 0.7 %,
/// 0.18 %).
fn hertz_case() -> VerifyCase {
    VerifyCase {
        name: "hertz_two_cylinders_mortar_mixed",
        title: "Hertz: two elastic cylinders, non-matching arcs, a quad8 cylinder on a quad4 one \
                and the reverse (mixed-order mortar) vs Hertz and vs the same-order runs",
        source: "VERIFICATION-CASES.md §1; Johnson, Contact Mechanics §4.3; deck \
                 hertz_two_cylinders_mortar.ctc",
        tags: &[
            "contact",
            "hertz",
            "mortar",
            "quadratic",
            "mixed_order",
            "two_bodies",
            "penalty",
            "plane_strain",
            "closed_form",
            "cross_check",
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

/// `text` with every `from` replaced by `to`, which must occur once.
fn replace_once(text: &str, from: &str, to: &str) -> Result<String, String> {
    let found = text.matches(from).count();
    if found != 1 {
        return Err(format!(
            "{HERTZ_DECK}: `{from}` found {found} times, not once"
        ));
    }
    Ok(text.replace(from, to))
}

/// The body block `part` of the Hertz deck on quad8 cells: `order = 2`
/// and half the divisions `r` / `c`.
fn quadratic_body(part: &str, r: usize, c: usize) -> Result<String, String> {
    let part = replace_once(
        part,
        &format!("radial = {r}  circumferential = {c}"),
        &format!("radial = {}  circumferential = {}", r / 2, c / 2),
    )?;
    replace_once(&part, "element = quad4", "element = quad4  order = 2")
}

fn hertz_level(level: usize) -> Result<ProgramLevel, String> {
    let (path, text) = super::read_case_deck(HERTZ_DECK)?;
    let deck = crate::refine::RefinableDeck::parse(&text)?;
    if level >= deck.levels() {
        return Err(format!("{HERTZ_DECK} has no level {level}"));
    }
    let linear = deck.render(level)?;
    let (r, c) = (8 << level, 16 << level);
    let cut = linear
        .find("body bottom")
        .ok_or_else(|| format!("{HERTZ_DECK}: no `body bottom`"))?;
    let (top, bottom) = linear.split_at(cut);
    let (top8, bottom8) = (quadratic_body(top, r, c)?, quadratic_body(bottom, r, c)?);
    let decks = [
        format!("{top8}{bottom}"),
        format!("{top}{bottom8}"),
        linear.clone(),
        format!("{top8}{bottom8}"),
    ];
    let mut out = ProgramLevel {
        h: 1.0 / c as f64,
        ..ProgramLevel::default()
    };
    let mut measured = Vec::new();
    for text in &decks {
        let (m, _, summary) = super::mortar::hertz_run(&path, text)?;
        out.add_run(&summary);
        measured.push(m);
    }
    let of = |k: usize, q: Quantity| {
        measured[k]
            .values
            .iter()
            .find(|v| v.quantity == q)
            .cloned()
            .ok_or_else(|| format!("{q:?} not measured"))
    };
    for (k, names) in [(0, &HERTZ_CHECKS[..3]), (1, &HERTZ_CHECKS[3..6])] {
        for (q, (name, _)) in [
            Quantity::PeakPressure,
            Quantity::HalfWidthMoment,
            Quantity::PressureL2,
        ]
        .into_iter()
        .zip(names)
        {
            out.values.push(error(name, of(k, q)?.error));
        }
    }
    // the total force: the reaction on the pushed flat (the reference of
    // the measured contact force)
    let force = |k: usize| -> Result<f64, String> {
        of(k, Quantity::ContactForce)?
            .reference
            .ok_or_else(|| "no reaction measured".to_string())
    };
    for (k, same, name) in [
        (0, 2, HERTZ_CHECKS[6].0),
        (0, 3, HERTZ_CHECKS[7].0),
        (1, 2, HERTZ_CHECKS[8].0),
        (1, 3, HERTZ_CHECKS[9].0),
    ] {
        out.values.push(value(name, force(k)?, force(same)?));
    }
    Ok(out)
}
