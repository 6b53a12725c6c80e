//! A penalty relative to the mesh reaches the engine node by node
//! (`tests/decks/hertz_relative_penalty.ctc`: Hertz line contact of
//! `examples/hertz_cylinder.ctc`, Hertz (1882) as in VERIFICATION-CASES.md
//! case 1, with `stiffness = 10 * E / h`).
//!
//! ```text
//!        ____ flat (pressed down) ____
//!       \                            /
//!         \__  arc, graded: h small near the bottom, large at the sides
//!  ===========*****=============  floor (rigid plane)
//! ```
//! At every closed node the area-weighted penalty gives
//! `pressure = alpha_i (-gap)`, so `pressure / -gap` read from the contact
//! CSV must be the node's `10 E / h_i` from the lowered model (not the
//! pair's single stiffest value): checked to 1e-9, over nodes whose
//! coefficients differ. The total force is within 0.5% of the absolute
//! penalty of the example (2e4, close to the relative one at the bottom).

use super::common::run_quiet as run;
use ctc_engine::model::AnyModel;
use std::path::Path;

/// Last line of `history.csv`, as numbers.
fn last_history(out: &Path) -> Vec<f64> {
    let text = std::fs::read_to_string(out.join("history.csv")).unwrap();
    let line = text.lines().last().unwrap();
    line.split(',').map(|v| v.parse().unwrap()).collect()
}

#[test]
fn relative_penalty_is_applied_per_node_in_the_run() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let deck = root.join("tests/decks/hertz_relative_penalty.ctc");
    let src = ctc_lang::Source::read(&deck).unwrap();
    let Ok(AnyModel::D2(model)) = ctc_lang::compile_any(&src) else {
        panic!("deck compiles");
    };
    let local: std::collections::BTreeMap<usize, f64> =
        model.contacts[0].local_penalty.iter().copied().collect();
    let dir = tempfile::tempdir().unwrap();
    let rel = dir.path().join("rel");
    run(&deck, &rel);
    let csv = std::fs::read_to_string(rel.join("contact_0_0004.csv")).unwrap();
    let hs: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
    let find = |n: &str| hs.iter().position(|c| *c == n).unwrap();
    let (inode, igap, ipress) = (find("node"), find("gap"), find("pressure"));
    let mut closed = Vec::new();
    for line in csv.lines().skip(1) {
        let f: Vec<&str> = line.split(',').collect();
        let (Ok(gap), Ok(p)) = (f[igap].parse::<f64>(), f[ipress].parse::<f64>()) else {
            continue;
        };
        if gap < 0.0 && p > 0.0 {
            let node: usize = f[inode].parse().unwrap();
            closed.push((node, p / -gap));
        }
    }
    assert!(closed.len() >= 5, "{} closed nodes", closed.len());
    let mut worst = 0.0f64;
    for &(node, ratio) in &closed {
        worst = worst.max((ratio / local[&node] - 1.0).abs());
    }
    assert!(
        worst < 1e-9,
        "pressure / penetration vs 10 E / h: {worst:e}"
    );
    let ks: Vec<f64> = closed.iter().map(|&(n, _)| local[&n]).collect();
    let spread =
        ks.iter().cloned().fold(0.0, f64::max) / ks.iter().cloned().fold(f64::INFINITY, f64::min);
    assert!(
        spread > 1.01,
        "closed nodes have distinct coefficients: {spread}"
    );
    // the force against the example's absolute penalty
    let abs = dir.path().join("abs");
    run(&root.join("examples/hertz_cylinder.ctc"), &abs);
    let (fr, fa) = (last_history(&rel), last_history(&abs));
    let (fr, fa) = (fr.last().unwrap(), fa.last().unwrap());
    assert!((fr / fa - 1.0).abs() < 5e-3, "force {fr} vs {fa}");
}
