//! The predictor's retake of a moved start (issue 20): a start that the
//! edge rule of `engine/src/solve/newton/predictor.rs` moved, whose first
//! Newton step the line search shortens, is abandoned and the increment
//! retaken from the unmoved extrapolation. Deck
//! `tests/decks/predictor_retake.ctc` (no reference solution: the check
//! is the same run without the predictor):
//!
//! ```text
//!    stepped flat punch    ______________________
//!                    _____|  upper face, DELTA up  (reaches the block
//!    lower face     |                              during the press)
//!    ==========================================  block top
//! ```
//! Under the upper face the gaps close linearly in time (the contact set
//! of the lower face fixed, the block is linear), not as the 3/2 power of
//! the distance to a smooth contact edge the rule assumes: the rule opens
//! nodes that belong closed, the retake fires (`predictor_retakes` in
//! summary.json), and the answer is the run's without the predictor
//! (`newton { predictor = false }`) to the Newton tolerance.

use super::common::run_quiet;
use std::path::Path;

fn run(deck: &Path, out: &Path) -> serde_json::Value {
    run_quiet(deck, out);
    let text = std::fs::read_to_string(out.join("summary.json")).expect("summary.json");
    serde_json::from_str(&text).expect("summary.json is JSON")
}

/// Differences allowed between the two runs' forces, relative to the
/// largest force: the Newton tolerance (`tol = 1e-10`). Measured 2.8e-13
/// (`ctc run tests/decks/predictor_retake.ctc`, and the same deck with
/// `predictor = false`, debug build, 2026-12-06: 9 iterations [2, 1, 3, 1,
/// 2] with one retake in increment 3, against 13 [2, 1, 2, 4, 4]).
const TOLERANCE_FROM_RUN: f64 = 1e-10;

/// `history.csv` as rows of numbers.
fn history(out: &Path) -> Vec<Vec<f64>> {
    let text = std::fs::read_to_string(out.join("history.csv")).unwrap();
    text.lines()
        .skip(1)
        .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
        .collect()
}

#[test]
fn a_moved_start_whose_first_step_is_shortened_is_retaken() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let deck = root.join("tests/decks/predictor_retake.ctc");
    let dir = tempfile::tempdir().unwrap();
    let with = dir.path().join("with");
    let s = run(&deck, &with);
    let retakes = s["predictor_retakes"].as_u64().unwrap_or(0);
    assert!(retakes >= 1, "no retake: {s:#}");
    // the same deck without the predictor
    let text = std::fs::read_to_string(&deck).unwrap();
    let plain_text = text.replace("max_iter = 30 }", "max_iter = 30  predictor = false }");
    assert_ne!(plain_text, text);
    let plain_deck = dir.path().join("plain.ctc");
    std::fs::write(&plain_deck, plain_text).unwrap();
    let without = dir.path().join("without");
    let p = run(&plain_deck, &without);
    assert!(p.get("predictor_retakes").is_none(), "{p:#}");
    let (a, b) = (history(&with), history(&without));
    assert_eq!(a.len(), b.len());
    // every reaction and contact force of every increment, against the
    // largest of them
    let scale = b.iter().flatten().fold(0.0f64, |m, v| m.max(v.abs()));
    for (ra, rb) in a.iter().zip(&b) {
        for (x, y) in ra.iter().zip(rb) {
            assert!(
                (x - y).abs() <= TOLERANCE_FROM_RUN * scale,
                "{ra:?} vs {rb:?}"
            );
        }
    }
}
