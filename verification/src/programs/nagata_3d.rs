//! Nagata patches on the master facets of 3D node-to-facet contact
//! (`smoothing = nagata`, `ctc_engine::contact::nagata`), tags `3d`,
//! `contact`, `smoothing`: the same sliding problem with the faceted master
//! and with the smoothed one.
//!
//! `ironing_nagata_ntf_3d` — the die-on-slab ironing problem of Puso &
//! Laursen, "A mortar segment-to-segment frictional contact method for
//! large deformations", CMAME 193 (2004) 4891-4913 (the deck of
//! `ironing_ntf_3d`, [`super::friction_ntf_3d::ironing_deck_with`]),
//! frictionless (friction on Nagata patches is not there yet): a stiff
//! cylindrical-cap die (radius 3, 28 facets over 140 degrees at level 0)
//! pressed 1.4 into a Neo-Hookean slab, then slid 4.0 along x:
//!
//! ```text
//!            die top: u_y = -1.4, then u_x = 4
//!          .-''''''-.   die (master): faceted, or Nagata patches
//!   +-----\----------/------------------+  slab top (slave)
//!   |          slab 9 x 3 x 4            |
//!   +------------------------------------+  fixed
//! ```
//!
//! Measured over the second half of the slide (t >= 1.5), with and
//! without smoothing: the oscillation amplitudes `(max - min) / mean` of
//! the die forces `F_n` (along -y) and `F_t` (along x: frictionless, the
//! ploughing of the die through the slab's bulge), and the Newton
//! iterations per increment of the slide. No published figures exist for
//! these (issue 18): the faceted run is the reference the smoothed one is
//! judged against (its amplitudes must not be larger; guards at the
//! measured figures).

use super::error;
use super::friction_ntf_3d::{ironing_deck_with, run_deck};
use crate::case::{Check, Quantity};
use crate::registry::{CaseKind, ProgramCase, ProgramLevel, VerifyCase};
use ctc_engine::solve::RunSummary;

const NAMES: [&str; 8] = [
    "faceted: F_n oscillation (max-min)/mean, t >= 1.5 (not judged)",
    "faceted: F_t oscillation (max-min)/mean, t >= 1.5 (not judged)",
    "faceted: Newton iterations per slide increment (not judged)",
    "nagata: F_n oscillation (max-min)/mean, t >= 1.5",
    "nagata: F_t oscillation (max-min)/mean, t >= 1.5",
    "nagata: Newton iterations per slide increment",
    "nagata / faceted: F_n oscillation",
    "nagata / faceted: mean F_n over the slide - 1",
];

/// The figures of one run: `[F_n amplitude, F_t amplitude, iterations per
/// slide increment, mean F_n]`.
fn figures(level: usize, smoothing: &str) -> Result<([f64; 4], RunSummary), String> {
    let (rows, summary) = run_deck(
        "ironing_nagata_ntf_3d.ctc",
        &ironing_deck_with(level, None, smoothing),
        "die.inner",
    )?;
    let late: Vec<(f64, f64)> = rows
        .rows
        .iter()
        .filter(|r| r.0 >= 1.5)
        .map(|(_, contact, _)| {
            let mut f = [0.0; 3];
            for c in contact {
                for (fk, ck) in f.iter_mut().zip(c.force) {
                    *fk += ck;
                }
            }
            (f[1].abs(), f[0].abs())
        })
        .collect();
    if late.is_empty() {
        return Err("ironing: no increment in the second half of the slide".into());
    }
    let amplitude = |v: Vec<f64>| {
        let (lo, hi) = v
            .iter()
            .fold((f64::INFINITY, 0.0f64), |(a, b), &x| (a.min(x), b.max(x)));
        let mean = v.iter().sum::<f64>() / v.len() as f64;
        (if mean > 0.0 { (hi - lo) / mean } else { f64::INFINITY }, mean)
    };
    let (an, mean_n) = amplitude(late.iter().map(|p| p.0).collect());
    let (at, _) = amplitude(late.iter().map(|p| p.1).collect());
    let slide: Vec<usize> = summary
        .increments
        .iter()
        .filter(|i| i.time > 1.0)
        .map(|i| i.iterations)
        .collect();
    let per = slide.iter().sum::<usize>() as f64 / slide.len().max(1) as f64;
    Ok(([an, at, per, mean_n], summary))
}

fn measure(level: usize) -> Result<ProgramLevel, String> {
    let mut out = ProgramLevel {
        h: 1.0 / (1usize << level) as f64,
        ..ProgramLevel::default()
    };
    let (f, sf) = figures(level, "none")?;
    let (n, sn) = figures(level, "nagata")?;
    out.add_run(&sf);
    out.add_run(&sn);
    for (k, v) in f.iter().take(3).chain(n.iter().take(3)).enumerate() {
        out.values.push(error(NAMES[k], *v));
    }
    out.values.push(error(NAMES[6], n[0] / f[0]));
    out.values.push(error(NAMES[7], (n[3] / f[3] - 1.0).abs()));
    Ok(out)
}

/// The registry entry.
pub fn cases() -> Vec<VerifyCase> {
    vec![VerifyCase {
        name: "ironing_nagata_ntf_3d",
        title: "Frictionless 3D ironing (node-to-facet), faceted die vs Nagata patches: force oscillation over the slide and Newton iterations",
        source: "Puso & Laursen, CMAME 193 (2004) 4891 (ironing); Nagata, CAGD 22 (2005) 327 (patches)",
        tags: &["3d", "contact", "smoothing"],
        levels: 1,
        checks: vec![
            Check::new(Quantity::Named(NAMES[3]), &[0.2, 0.2]),
            Check::new(Quantity::Named(NAMES[4]), &[0.5, 0.5]),
            Check::new(Quantity::Named(NAMES[5]), &[12.0, 14.0]),
            Check::new(Quantity::Named(NAMES[6]), &[1.0, 1.0]),
            Check::new(Quantity::Named(NAMES[7]), &[0.05, 0.05]),
        ],
        kind: CaseKind::Program(ProgramCase {
            max_levels: 2,
            run: measure,
        }),
    }]
}
