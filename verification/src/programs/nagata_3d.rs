//! Nagata smoothing of the master in 3D node-to-facet contact (`smoothing
//! = nagata`, `ctc_engine::contact::nagata`; issue 18), tags `3d`,
//! `contact`, `smoothing`, `node_to_segment`: each case runs the same deck
//! with the faceted master (`smoothing = none`) and with Nagata patches,
//! and reports both.
//!
//! `contact_patch_nagata_3d` — the contact patch test of
//! [`super::contact_ntf_3d`] (Taylor & Papadopoulos, IJNME 31 (1991)
//! 2205, in 3D): two blocks, hex8 and tet4, 3 x 3 | 4 x 4 facets
//! (non-matching) and 3 x 3 | 3 x 3 (matching), single pass, penalty. A
//! flat master has parallel nodal normals, so its patches are its facets;
//! the largest deviation of the nodal pressures from the exact uniform `p`
//! must not be worse than the faceted master's. Matching meshes: both pass
//! to round-off. Non-matching: node-to-facet fails the patch test, the
//! master's top face does not stay flat, and the patches follow its
//! waviness: measured 0.140 (hex8) and 0.135 (tet4) against 0.253 and
//! 0.271 faceted.
//!
//! ```text
//!   top  3 x 3 cells, pushed down d = 0.01      slave top.zmin
//!   ---------------------------------------- interface z = 0.5
//!   base 4 x 4 (or 3 x 3) cells, rollers        master base.zmax (Nagata)
//! ```
//!
//! `contact_patch_friction_nagata_3d` — the frictional patch test of
//! [`super::mortar_friction_3d`] (two hex8 blocks pressed, then sheared
//! at 30 degrees by a top displacement with the side tractions of the
//! uniform state; Coulomb mu = 0.3, area penalty `k_N = 1e8`, `k_T = 1e9`)
//! with node-to-facet contact on matching interface meshes (3 x 3 | 3 x 3
//! facets, where node-to-facet passes the frictionless patch test to
//! round-off), faceted and Nagata master: the master stays flat, its
//! nodal normals parallel, so its patches are its facets, and the friction
//! element on a flat patch is the faceted one (to 1e-13:
//! `friction_nagata::tests::a_flat_patch_gives_the_faceted_friction`).
//! Stick (`tau = mu p / 2`: every node sticks, `q` uniform) and slip (the
//! top displaced 1.05 times the stick limit: every node on the cone, `|q|
//! = mu p`). Measured per run: both masters' own figures (as
//! [`super::mortar_friction_3d`]'s) and the largest differences of the
//! nodal tractions `q` (over the mean `|q|`) and pressures (over the mean
//! `p`) between them (`ctc verify contact_patch_friction_nagata_3d`, 4
//! runs, 0.3 s CPU debug): stick `q` deviation 9.7e-6 Nagata, 2.5e-5
//! faceted (the penalty's elastic slip `g_T` moves the slave's rim off the
//! master's: an end effect of the regularization, as with mortar), slip
//! `| |q| - mu p | / (mu p)` 4.6e-16 / 1.5e-16; Nagata - faceted `q`
//! 2.1e-5 (stick), 9.2e-4 (slip), `p` 7.6e-6, 7.6e-4. Not round-off: the
//! frictionless Nagata element puts a share of `R_N` on the ring nodes
//! even on a flat master where the foot is off a node (`dg/dn_a` through
//! the edge coefficients `c_e`, zero on the plane but not their
//! derivative: `d(n . c)/dn_a = d / 2` per edge blend), so once the slip
//! moves the slave nodes off the master's nodes (matching meshes: on them
//! in the press, where the blends vanish and the two agree) the two
//! masters carry the load on slightly different nodes; the friction
//! forces take no such share (`t . (n_a + n_b) = 0`). The guards are the
//! measured figures rounded up.
//!
//! `ironing_nagata_3d` — the die-on-slab ironing of Puso & Laursen, CMAME
//! 193 (2004) 4891 (see [`super::friction_ntf_3d`]), frictionless (with friction:
//! [`super::ironing_3d`]'s `ntf nagata mu 0.3`): the Neo-Hookean slab's top nodes
//! against the die's cylindrical face, faceted (5 degree facets) or Nagata
//! patches. Measured both ways over the second half of the slide: the
//! oscillation `(max - min) / mean` of the die force `F_n` (along y) and
//! `(max - min)` of `F_t` (along x) over the mean `F_n`, and the mean
//! Newton iterations per increment of the slide, and the ratios of the
//! oscillations, Nagata over faceted. Level 0 (default): a short run (slab 6 x 3 x 2 cells,
//! press 0.5, slide 1.0); level 1 (`--max-level 2`): the full benchmark
//! (slab 9 x 3 x 4, press 1.4, slide 4.0).
//!
//! ```text
//!            die top: u_y = -press, then u_x = slide
//!          .-''''''-.   die R = 3, E = 1000 (master: facets / Nagata)
//!   +-----\----------/------------------+  slab top (slave), frictionless
//!   |      '--------'    Neo-Hooke E = 1, nu = 0.3
//!   +-----------------------------------+  fixed
//! ```

use super::contact_ntf_3d::{patch_deck, run_patch_deck, PENALTY};
use super::friction_ntf_3d::{run_deck, Rows};
use super::mortar_friction_3d::{run_edited, Run, PENALTY as PATCH_PENALTY};
use super::{error, value};
use crate::case::{Check, Quantity};
use crate::registry::{CaseKind, ProgramCase, ProgramLevel, VerifyCase};
use ctc_engine::solve::RunSummary;

/// The smoothings compared, as deck text.
const SMOOTHINGS: [&str; 2] = ["none", "nagata"];

/// Patch-test runs: (label, cell, base cells across).
const PATCH_RUNS: &[(&str, &str, usize)] = &[
    ("hex8 3|4", "hex8", 4),
    ("tet4 3|4", "tet4", 4),
    ("hex8 3|3", "hex8", 3),
];

/// Quantities of the patch case, per run: nagata's pressure deviation,
/// its ratio to none's (non-matching: not worse) or difference (matching:
/// both round-off), nagata's total force.
const PATCH_NAMES: &[[&str; 3]] = &[
    [
        "hex8 3|4 nagata: max |p_i - p| / p",
        "hex8 3|4 nagata / none deviation",
        "hex8 3|4 nagata total force",
    ],
    [
        "tet4 3|4 nagata: max |p_i - p| / p",
        "tet4 3|4 nagata / none deviation",
        "tet4 3|4 nagata total force",
    ],
    [
        "hex8 3|3 nagata: max |p_i - p| / p",
        "hex8 3|3 nagata - none deviation",
        "hex8 3|3 nagata total force",
    ],
];

/// Adds `smoothing = nagata` to the contact block of a generated deck.
fn with_smoothing(deck: &str, smoothing: &str) -> Result<String, String> {
    let head = "  formulation = node_to_segment\n";
    if !deck.contains(head) {
        return Err("the deck has no node-to-segment contact block".into());
    }
    Ok(deck.replace(head, &format!("{head}  smoothing = {smoothing}\n")))
}

fn patch_level(_level: usize) -> Result<ProgramLevel, String> {
    let mut out = ProgramLevel {
        h: 1.0 / 3.0,
        ..ProgramLevel::default()
    };
    for (names, &(label, cell, base)) in PATCH_NAMES.iter().zip(PATCH_RUNS) {
        let mut dev = [0.0; 2];
        for (k, s) in SMOOTHINGS.iter().enumerate() {
            let deck = with_smoothing(&patch_deck(cell, base, "single_pass", PENALTY), s)?;
            let (o, level) = run_patch_deck(deck, PENALTY).map_err(|e| format!("{label}: {e}"))?;
            super::contact_ntf_3d::add_level(&mut out, &level);
            dev[k] = o.deviation;
            if k == 1 {
                out.values.push(error(names[0], o.deviation));
                let compared = if base == 3 {
                    (o.deviation - dev[0]).abs()
                } else {
                    o.deviation / dev[0]
                };
                out.values.push(error(names[1], compared));
                out.values.push(value(names[2], o.force, o.exact));
            }
        }
    }
    Ok(out)
}

/// The frictional patch runs (of [`super::mortar_friction_3d::RUNS`]'s
/// form): hex8, penalty, 30 degrees, stick and slip.
const FRICTION_RUNS: [Run; 2] = [
    (
        "hex8 stick penalty 30deg",
        "hex8",
        PATCH_PENALTY,
        1e9,
        false,
        30.0,
    ),
    (
        "hex8 slip penalty 30deg",
        "hex8",
        PATCH_PENALTY,
        1e9,
        true,
        30.0,
    ),
];

/// Quantities of the frictional patch case and their tolerances: per run
/// Nagata's figure (stick: the traction's deviation from uniform; slip:
/// `| |q| - mu p | / (mu p)`), then the differences Nagata - faceted of
/// the nodal tractions and pressures.
const FRICTION_CHECKS: [(&str, f64); 8] = [
    ("hex8 stick penalty 30deg none: q deviation", 5e-5),
    ("hex8 stick penalty 30deg nagata: q deviation", 2e-5),
    (
        "hex8 stick penalty 30deg: max |q_nagata - q_faceted| / |q|",
        5e-5,
    ),
    (
        "hex8 stick penalty 30deg: max |p_nagata - p_faceted| / p",
        2e-5,
    ),
    (
        "hex8 slip penalty 30deg none: max ||q| - mu p| / (mu p)",
        1e-12,
    ),
    (
        "hex8 slip penalty 30deg nagata: max ||q| - mu p| / (mu p)",
        1e-12,
    ),
    (
        "hex8 slip penalty 30deg: max |q_nagata - q_faceted| / |q|",
        2e-3,
    ),
    (
        "hex8 slip penalty 30deg: max |p_nagata - p_faceted| / p",
        2e-3,
    ),
];

/// The patch deck of [`super::mortar_friction_3d`] with node-to-facet
/// contact and `smoothing`, the base meshed as the top (3 x 3 cells
/// across: matching interface).
fn friction_patch_deck(deck: String, smoothing: &str) -> String {
    deck.replace(
        "  formulation = mortar\n",
        &format!("  formulation = node_to_segment\n  smoothing = {smoothing}\n"),
    )
    .replace("divisions = (4, 4, 2)", "divisions = (3, 3, 2)")
}

fn friction_patch_level(_level: usize) -> Result<ProgramLevel, String> {
    let mut out = ProgramLevel {
        h: 1.0 / 3.0,
        ..ProgramLevel::default()
    };
    for (k, r) in FRICTION_RUNS.iter().enumerate() {
        let mut runs = Vec::new();
        for s in SMOOTHINGS {
            let edit = |d: String| friction_patch_deck(d, s);
            let (o, l) = run_edited(r, &edit).map_err(|e| format!("{s}: {e}"))?;
            super::contact_ntf_3d::add_level(&mut out, &l);
            runs.push(o);
        }
        let (faceted, nagata) = (&runs[0], &runs[1]);
        let own = |o: &super::mortar_friction_3d::Outcome| {
            o.values.first().map_or(f64::INFINITY, |v| v.1.abs())
        };
        let n = nagata.nodes.len() as f64;
        let len = |v: [f64; 3]| (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
        let q_mean = nagata.nodes.iter().map(|c| len(c.1)).sum::<f64>() / n;
        let p_mean = nagata.nodes.iter().map(|c| c.2).sum::<f64>() / n;
        let (mut dq, mut dp) = (0.0f64, 0.0f64);
        for c in &nagata.nodes {
            let Some(f) = faceted.nodes.iter().find(|f| f.0 == c.0) else {
                return Err(format!("{}: node {} closed on Nagata only", r.0, c.0));
            };
            dq = dq.max(len([c.1[0] - f.1[0], c.1[1] - f.1[1], c.1[2] - f.1[2]]) / q_mean);
            dp = dp.max((c.2 - f.2).abs() / p_mean);
        }
        let values = [own(faceted), own(nagata), dq, dp];
        for (v, (name, _)) in values.into_iter().zip(&FRICTION_CHECKS[4 * k..]) {
            out.values.push(error(name, v));
        }
    }
    Ok(out)
}

/// The frictionless ironing deck at `level` with `smoothing` (0: slab 6 x
/// 3 x 2 cells, die 28 x 3, press 0.5 in 3 and slide 1.0 in 8 increments;
/// 1: the benchmark's slab 9 x 3 x 4, die 28 x 5, press 1.4 in 7 and slide
/// 4.0 in 20).
pub fn ironing_deck(level: usize, smoothing: &str) -> String {
    let (length, width, sx, sz, layers, press, slide, n_press, n_slide) = if level == 0 {
        (6, 2, 6, 2, 3, 0.5, 1.0, 3, 8)
    } else {
        (9, 4, 9, 4, 5, 1.4, 4.0, 7, 20)
    };
    let die = width as f64 + 1.2;
    format!(
        "# Frictionless ironing with smoothing = {smoothing}, generated by \
         verification/src/programs/nagata_3d.rs\n\
         analysis {{ dimension = 3d }}\n\
         material slab_mat {{ neo_hookean {{ E = 1  nu = 0.3 }} }}\n\
         material die_mat {{ neo_hookean {{ E = 1000  nu = 0.499 }} }}\n\
         body slab {{\n  mesh = box {{ origin = (0, 0, 0.6)  size = ({length}, 3, {width})  divisions = ({sx}, 3, {sz}) }}\n  material = slab_mat\n  kinematics = finite\n}}\n\
         body die {{\n  mesh = extrude {{\n    base = annulus {{ center = (2, 6)  inner = 2  outer = 3  start = 200  end = 340  radial = 1  circumferential = 28 }}\n    length = {die}\n    layers = {layers}\n  }}\n  material = die_mat\n  kinematics = finite\n}}\n\
         contact slab.ymax -> die.outer {{\n  method = penalty {{ kind = area  stiffness = 500 }}\n  smoothing = {smoothing}\n}}\n\
         fix slab.ymin {{ ux uy uz }}\n\
         displace die.inner {{\n  ux = table((0, 0), (1, 0), (2, {slide}))\n  uy = table((0, 0), (1, -{press}), (2, -{press}))\n  uz = 0\n}}\n\
         step press {{ time = 0 .. 1  increments = {n_press}  newton {{ tol = 1e-8  max_iter = 30 }} }}\n\
         step slide {{ time = 1 .. 2  increments = {n_slide}  newton {{ tol = 1e-8  max_iter = 30 }} }}\n"
    )
}

/// Ironing figures of one smoothing.
#[derive(Debug, Clone)]
pub struct IroningFigures {
    /// `(time, F_t, F_n)` per converged increment.
    pub history: Vec<(f64, f64, f64)>,
    /// `(max - min) / mean` of `F_n`, and `(max - min)` of `F_t` over the
    /// mean `F_n` (frictionless: `F_t` is the die's tilt, small), over the
    /// second half of the slide.
    pub oscillation: [f64; 2],
    /// Mean Newton iterations per converged increment of the slide.
    pub iterations: f64,
    /// The run.
    pub summary: RunSummary,
}

/// Runs the frictionless ironing deck.
pub fn ironing_run(level: usize, smoothing: &str) -> Result<IroningFigures, String> {
    let (rows, s): (Rows, RunSummary) = run_deck(
        "ironing_nagata_3d.ctc",
        &ironing_deck(level, smoothing),
        "die.inner",
    )?;
    let history: Vec<(f64, f64, f64)> = rows
        .rows
        .iter()
        .map(|(t, contact, _)| {
            let mut f = [0.0; 3];
            for c in contact {
                for (fk, ck) in f.iter_mut().zip(c.force) {
                    *fk += ck;
                }
            }
            (*t, f[0], f[1])
        })
        .collect();
    let late: Vec<&(f64, f64, f64)> = history.iter().filter(|h| h.0 >= 1.5 - 1e-9).collect();
    if late.len() < 2 {
        return Err("ironing: fewer than two increments in the second half of the slide".into());
    }
    let mean = late.iter().map(|h| h.2.abs()).sum::<f64>() / late.len() as f64;
    let amplitude = |pick: fn(&(f64, f64, f64)) -> f64| {
        let (lo, hi) = late
            .iter()
            .map(|h| pick(h).abs())
            .fold((f64::INFINITY, 0.0f64), |(a, b), x| (a.min(x), b.max(x)));
        if mean > 0.0 {
            (hi - lo) / mean
        } else {
            f64::INFINITY
        }
    };
    let slide: Vec<usize> = s
        .increments
        .iter()
        .filter(|i| i.time > 1.0 + 1e-12)
        .map(|i| i.iterations)
        .collect();
    let iterations = slide.iter().sum::<usize>() as f64 / slide.len().max(1) as f64;
    Ok(IroningFigures {
        oscillation: [amplitude(|h| h.2), amplitude(|h| h.1)],
        history,
        iterations,
        summary: s,
    })
}

/// The comparisons of the ironing case: nagata over none.
const IRONING_RATIOS: [&str; 2] = [
    "F_n oscillation nagata / none",
    "F_t (max-min) nagata / none",
];

const IRONING_NAMES: [[&str; 3]; 2] = [
    [
        "none: F_n oscillation (max-min)/mean",
        "none: F_t (max-min) / mean F_n",
        "none: Newton iterations per slide increment",
    ],
    [
        "nagata: F_n oscillation (max-min)/mean",
        "nagata: F_t (max-min) / mean F_n",
        "nagata: Newton iterations per slide increment",
    ],
];

fn ironing_level(level: usize) -> Result<ProgramLevel, String> {
    let mut out = ProgramLevel {
        h: 1.0 / (1usize << level) as f64,
        ..ProgramLevel::default()
    };
    let mut osc = [[0.0; 2]; 2];
    for (k, (names, s)) in IRONING_NAMES.iter().zip(SMOOTHINGS).enumerate() {
        let r = ironing_run(level, s)?;
        out.add_run(&r.summary);
        out.values.push(error(names[0], r.oscillation[0]));
        out.values.push(error(names[1], r.oscillation[1]));
        out.values.push(error(names[2], r.iterations));
        osc[k] = r.oscillation;
    }
    for (c, name) in IRONING_RATIOS.iter().enumerate() {
        out.values.push(error(name, osc[1][c] / osc[0][c]));
    }
    Ok(out)
}

/// The registry entries of this file.
pub fn cases() -> Vec<VerifyCase> {
    vec![
        VerifyCase {
            name: "contact_patch_nagata_3d",
            title: "3D contact patch test with Nagata patches on the flat master: the nodal \
                    pressures as with the faceted master (node-to-facet, single pass, penalty)",
            source: "Taylor & Papadopoulos IJNME 31 (1991), in 3D; Nagata, CAGD 22 (2005) 327",
            tags: &[
                "3d",
                "contact",
                "smoothing",
                "node_to_segment",
                "patch",
                "penalty",
            ],
            levels: 1,
            // non-matching: the measured 0.140 / 0.135 (faceted 0.253 /
            // 0.271) rounded up, and not worse than faceted; matching:
            // round-off
            checks: PATCH_NAMES
                .iter()
                .zip([(0.15, 1.0), (0.15, 1.0), (1e-9, 1e-9)])
                .flat_map(|(q, (dev, cmp))| {
                    [
                        Check::new(Quantity::Named(q[0]), &[dev]),
                        Check::new(Quantity::Named(q[1]), &[cmp]),
                        Check::new(Quantity::Named(q[2]), &[0.02]),
                    ]
                })
                .collect(),
            kind: CaseKind::Program(ProgramCase {
                max_levels: 1,
                run: patch_level,
            }),
        },
        VerifyCase {
            name: "contact_patch_friction_nagata_3d",
            title: "3D frictional contact patch test with Nagata patches on the flat master \
                    (matching meshes): stick and slip against the faceted master (node-to-facet, \
                    single pass, penalty)",
            source: "Taylor & Papadopoulos IJNME 31 (1991), in 3D; Nagata, CAGD 22 (2005) 327",
            tags: &[
                "3d",
                "contact",
                "smoothing",
                "node_to_segment",
                "patch",
                "friction",
                "penalty",
            ],
            levels: 1,
            checks: FRICTION_CHECKS
                .iter()
                .map(|(n, t)| Check::new(Quantity::Named(n), &[*t]))
                .collect(),
            kind: CaseKind::Program(ProgramCase {
                max_levels: 1,
                run: friction_patch_level,
            }),
        },
        VerifyCase {
            name: "ironing_nagata_3d",
            title: "Frictionless ironing (Puso & Laursen 2004 die-on-slab), faceted vs Nagata \
                    die: force oscillation over the slide and Newton iterations per increment",
            source: "M. A. Puso, T. A. Laursen, CMAME 193 (2004) 4891-4913, ironing example",
            tags: &[
                "3d",
                "contact",
                "smoothing",
                "node_to_segment",
                "penalty",
                "finite_strain",
                "benchmark",
            ],
            levels: 1,
            // the measured figures rounded up (level 0 / level 1):
            // F_n oscillation 0.104 / 0.115 faceted, 0.105 / 0.027 Nagata;
            // F_t (max - min) / F_n 0.030 / 0.038 faceted, 0.009 / 0.030
            // Nagata; iterations per slide increment 5.75 / 5.43 faceted,
            // 6.88 / 6.56 Nagata
            checks: vec![
                Check::new(Quantity::Named(IRONING_NAMES[0][0]), &[0.15, 0.2]),
                Check::new(Quantity::Named(IRONING_NAMES[0][1]), &[0.05, 0.06]),
                Check::new(Quantity::Named(IRONING_NAMES[0][2]), &[8.0, 8.0]),
                Check::new(Quantity::Named(IRONING_NAMES[1][0]), &[0.15, 0.05]),
                Check::new(Quantity::Named(IRONING_NAMES[1][1]), &[0.015, 0.05]),
                Check::new(Quantity::Named(IRONING_NAMES[1][2]), &[9.0, 9.0]),
                Check::new(Quantity::Named(IRONING_RATIOS[0]), &[1.1, 0.5]),
                Check::new(Quantity::Named(IRONING_RATIOS[1]), &[0.5, 1.0]),
            ],
            kind: CaseKind::Program(ProgramCase {
                max_levels: 2,
                run: ironing_level,
            }),
        },
    ]
}
