//! Skin pass, the coarse CI variant (`examples/skin_pass_rough.ctc`, level
//! 0 of `ctc verify skin_pass`; issue 22 example 2 after the seed slides'
//! "roughness transfer during skin-pass"; no closed form, the checks of
//! `verification/src/programs/skin_pass.rs`).
//!
//! ```text
//!        ,-~~~~~~-.   rigid roll R = 100 mm, Ra 30 um, wavelength 1 mm
//!   ____/~~~~~~~~~~\_________________  half of a 0.8 mm steel sheet
//!  |ux=0      rolled -> | bite |     |  (finite strain J2, Coulomb mu 0.15)
//!  |_________________________________|  mid-plane uy = 0
//! ```
//!
//! The crests (Ra 30 um, peak to valley 94 um) pressed 8 um into the sheet
//! (2 %) leave isolated dents: the sheet keeps a small share of the
//! roll's roughness.

use ctc_verification::programs::skin_pass;
use ctc_verification::registry;

#[test]
fn coarse_skin_pass_balances_and_transfers_a_small_share_of_the_roughness() {
    let report = registry::run_passing("skin_pass");
    let level = &report.levels[0];
    // the lines of the catalogue snapshot (cases_coarse)
    println!(
        "skin_pass level 0: {} nodes, {} free dofs, {} increments, {} Newton iterations, {} cutbacks",
        level.nodes, level.free_dofs, level.increments, level.newton_total, level.cutbacks
    );
    for v in &level.values {
        println!(
            "  {:?}: computed {} reference {} error {}",
            v.quantity,
            crate::fenicsx_snapshots::sig4(v.computed),
            v.reference
                .map_or("-".into(), crate::fenicsx_snapshots::sig4),
            crate::fenicsx_snapshots::err2(v.error)
        );
    }
    let get = |name: &str| {
        level
            .values
            .iter()
            .find(|v| format!("{}", v.quantity).starts_with(name))
            .unwrap_or_else(|| panic!("no value {name}: {:?}", level.values))
    };
    // equilibrium of every converged increment
    assert!(get("force balance").computed < 1e-6);
    // the roll's Ra measured on the deck's polyline is the profile's 30 um
    let roll = get("roll Ra");
    assert!((roll.computed - 0.030).abs() < 3e-4, "{roll:?}");
    assert!(roll.error < 0.01, "{roll:?}");
    // a small share of the roughness is transferred (measured 0.068 in
    // release on this mesh), never more than the profile
    let ratio = get("transfer ratio (coarse").computed;
    assert!((0.03..0.15).contains(&ratio), "transfer ratio {ratio}");
    assert_eq!(get("transfer ratio above").computed, 0.0);
    // the run: 2 + 14 increments, no cutback
    assert_eq!(level.increments, 16);
    assert_eq!(level.cutbacks, 0);
}

#[test]
fn the_coarsened_mesh_merges_the_full_mesh_cells_in_pairs() {
    let lets = skin_pass::coarsened("skin_pass_ra30").unwrap();
    let get = |k: &str| {
        lets.iter()
            .find(|(n, _)| *n == k)
            .unwrap()
            .1
            .parse::<f64>()
            .unwrap()
    };
    assert_eq!(get("nx"), 72.0);
    assert_eq!(get("ny"), 12.0);
    // the coarse deck compiles; its top row is the two top rows of the
    // full mesh: 0.74 um (1 + q)
    let (path, text) = skin_pass::deck("skin_pass_ra30", &lets).unwrap();
    let coarse = ctc_verification::deck::compile_text(&path, &text).unwrap();
    let (path, text) = skin_pass::deck("skin_pass_ra30", &[]).unwrap();
    let full = ctc_verification::deck::compile_text(&path, &text).unwrap();
    let top_row = |m: &ctc_engine::model::Model| {
        let h = 0.4;
        let mut ys: Vec<f64> = m.mesh.nodes.iter().map(|p| p[1]).collect();
        ys.sort_by(f64::total_cmp);
        ys.dedup_by(|a, b| (*a - *b).abs() < 1e-12);
        h - ys[ys.len() - 2]
    };
    let (e, ec) = (top_row(&full), top_row(&coarse));
    assert!((e - 0.74e-3).abs() < 1e-9, "smallest edge {e}");
    let ny = 24.0;
    let q = get_grade(&text).powf(-1.0 / (ny - 1.0));
    assert!(
        (ec - e * (1.0 + q)).abs() < 1e-9,
        "{ec} vs {}",
        e * (1.0 + q)
    );
}

fn get_grade(text: &str) -> f64 {
    text.lines()
        .find_map(|l| l.trim().strip_prefix("let grade = "))
        .and_then(|v| v.split('#').next())
        .map(|v| v.trim().parse::<f64>().unwrap())
        .unwrap()
}

#[test]
fn the_refined_mesh_splits_every_full_mesh_column_in_two() {
    let lets = skin_pass::refined("skin_pass_ra30").unwrap();
    assert_eq!(lets, vec![("nx", "288".to_string())]);
    let (path, text) = skin_pass::deck("skin_pass_ra30", &lets).unwrap();
    let fine = ctc_verification::deck::compile_text(&path, &text).unwrap();
    let (path, text) = skin_pass::deck("skin_pass_ra30", &[]).unwrap();
    let full = ctc_verification::deck::compile_text(&path, &text).unwrap();
    // every node of the full mesh is a node of the refined one (the
    // full mesh's nodes are what `sampled_ratio` reads back)
    let mut fine_nodes: Vec<[f64; 2]> = fine.mesh.nodes.clone();
    fine_nodes.sort_by(|a, b| a[0].total_cmp(&b[0]).then(a[1].total_cmp(&b[1])));
    for p in &full.mesh.nodes {
        let k = fine_nodes.partition_point(|q| q[0] < p[0] - 1e-9);
        let hit = fine_nodes[k..]
            .iter()
            .take_while(|q| q[0] <= p[0] + 1e-9)
            .any(|q| (q[1] - p[1]).abs() < 1e-12);
        assert!(hit, "full mesh node {p:?} is not a refined mesh node");
    }
    assert_eq!(
        fine.mesh.nodes.len(),
        (2 * 144 + 1) * (24 + 1),
        "288 x 24 cells"
    );
}
