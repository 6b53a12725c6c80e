//! Mortar between a linear and a quadratic side (issue 23, with 18;
//! `verification/src/programs/mortar_mixed.rs`, where the references and
//! sketches are): the 2D and 3D contact patch tests with mixed orders
//! (Taylor & Papadopoulos, IJNME 31 (1991) 2205: a uniform pressure across
//! non-matching interfaces, one block linear, the other quadratic, either
//! one the slave), the assembled 3D pair's tangent against central
//! differences with its force and moment balance, and Hertz with a quad8
//! cylinder on a quad4 one (Johnson, Contact Mechanics §4.3).
//!
//! ```text
//!   top block  (linear | quadratic cells), pushed down
//!   ---------- non-matching interface, mixed-order mortar ----------
//!   base block (quadratic | linear cells), bottom fixed
//! ```

use crate::contact_mortar_3d::forces;
use crate::contact_mortar_3d::shifted;
use crate::fenicsx_snapshots::{err2, sig4};
use ctc_engine::model::{AnyModel, Model};
use ctc_verification::programs::mortar_mixed::patch_3d_deck;
use ctc_verification::registry;

#[test]
fn contact_patch_mortar_mixed_gives_a_uniform_pressure() {
    let report = registry::run_passing("contact_patch_mortar_mixed");
    assert_eq!(report.levels.len(), 2);
    for level in &report.levels {
        assert_eq!(level.values.len(), 22);
        for v in &level.values {
            assert!(v.error < 1e-8, "{:?}: {:.2e}", v.quantity, v.error);
        }
    }
}

#[test]
fn contact_patch_mortar_mixed_3d_passes() {
    let report = registry::run_passing("contact_patch_mortar_mixed_3d");
    println!("| run | max |p - p_mean| / p_mean | F / F_exact - 1 |");
    println!("| --- | --- | --- |");
    for pair in report.levels[0].values.chunks(2) {
        println!(
            "| {} | {:.2e} | {:.2e} |",
            pair[0].quantity,
            pair[0].computed,
            pair[1].computed / pair[1].reference.unwrap_or(f64::NAN) - 1.0
        );
    }
}

fn model(cell: &str, top_order: usize, top_n: usize, base_order: usize, base_n: usize) -> Model<3> {
    let text = patch_3d_deck(
        cell,
        top_order,
        top_n,
        base_order,
        base_n,
        "penalty { kind = area  stiffness = 1e3 }",
    )
    .expect("deck");
    let src = ctc_lang::Source::new(std::path::Path::new("mortar_mixed_3d.ctc"), &text);
    match ctc_lang::compile_any(&src) {
        Ok(AnyModel::D3(m)) => m,
        Ok(_) => panic!("the patch deck is not 3d"),
        Err(d) => panic!("{}", d.render(&src)),
    }
}

/// The assembled mixed-order pair (hex8 | hex20, hex20 | hex8, tet4 |
/// hex20) on a jittered, bent interface: its tangent along a random
/// direction against central differences of its forces, and its force and
/// moment balance.
#[test]
fn mixed_mortar_pair_tangent_matches_finite_differences_and_balances() {
    let mut seed: u64 = 0x2545_f491_4f6c_dd1d;
    let mut rnd = move || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    };
    for (name, cell, top_order, top_n, base_order, base_n) in [
        ("hex8 | hex20", "hex8", 1, 3, 2, 2),
        ("hex20 | hex8", "hex8", 2, 2, 1, 3),
        ("tet4 | hex20", "tet4", 1, 3, 2, 2),
    ] {
        let model = model(cell, top_order, top_n, base_order, base_n);
        let top = model.bodies[1].nodes.start;
        let depth = 0.01 + 0.005 * rnd().abs();
        let x: Vec<[f64; 3]> = model
            .mesh
            .nodes
            .iter()
            .enumerate()
            .map(|(k, p)| {
                let bulge = 0.01 * (1.0 - (p[0] - 0.5).powi(2) - (p[1] - 0.5).powi(2));
                let dz = if k >= top { -depth - bulge } else { 0.0 };
                [
                    p[0] + 0.01 * rnd(),
                    p[1] + 0.01 * rnd(),
                    p[2] + dz + 0.002 * rnd(),
                ]
            })
            .collect();
        let v: Vec<[f64; 3]> = x.iter().map(|_| [rnd(), rnd(), rnd()]).collect();
        let (f, kv, closed) = forces(&model, &x, &v);
        assert!(closed > 0, "{name}");
        let (mut sum, mut moment, mut scale) = ([0.0f64; 3], [0.0f64; 3], 0.0f64);
        for (k, p) in x.iter().enumerate() {
            let fk = [f[3 * k], f[3 * k + 1], f[3 * k + 2]];
            scale = scale.max(fk.iter().fold(0.0f64, |a, b| a.max(b.abs())));
            for c in 0..3 {
                sum[c] += fk[c];
            }
            moment[0] += p[1] * fk[2] - p[2] * fk[1];
            moment[1] += p[2] * fk[0] - p[0] * fk[2];
            moment[2] += p[0] * fk[1] - p[1] * fk[0];
        }
        let imbalance = sum
            .iter()
            .chain(&moment)
            .fold(0.0f64, |a, b| a.max(b.abs()))
            / scale;
        let h = 1e-7;
        let shift = |sign: f64| shifted(&x, &v, sign * h);
        let (fp, _, cp) = forces(&model, &shift(1.0), &v);
        let (fm, _, cm) = forces(&model, &shift(-1.0), &v);
        assert!(cp == closed && cm == closed, "{name}");
        let kscale = kv.iter().fold(1e-300f64, |a, b| a.max(b.abs()));
        let e = (0..kv.len())
            .map(|k| (-(fp[k] - fm[k]) / (2.0 * h) - kv[k]).abs() / kscale)
            .fold(0.0, f64::max);
        println!(
            "{name}: {closed} closed, max |K v - FD| / max |K v| = {e:.2e}, \
             force / moment imbalance {imbalance:.1e}"
        );
        assert!(e <= 1e-5, "{name}: {e}");
        assert!(imbalance <= 1e-10, "{name}: {imbalance}");
    }
}

#[test]
fn hertz_two_cylinders_mortar_mixed_meets_hertz_and_the_same_order_runs() {
    let report = registry::run_passing("hertz_two_cylinders_mortar_mixed");
    for v in &report.levels[0].values {
        println!(
            "{:?}: {:.4e} vs {:?}: {:.2e}",
            v.quantity, v.computed, v.reference, v.error
        );
    }
}

/// The catalogue snapshot's lines of this file's cases
/// (`cases_coarse::verification_catalogue_on_default_levels`), to splice
/// into its snapshot (`cargo test -p ctc-verification --test suite
/// mortar_mixed::catalogue_lines -- --ignored --nocapture`).
#[test]
#[ignore]
fn catalogue_lines() {
    for name in [
        "contact_patch_mortar_mixed",
        "contact_patch_mortar_mixed_3d",
        "hertz_two_cylinders_mortar_mixed",
    ] {
        let case = registry::find(name).expect("registered");
        let c = registry::run_default(&case, &mut |l| eprintln!("{l}"));
        let l = &c.levels[0];
        println!(
            "SNAP {} level {}: {} nodes, {} free dofs, {} increments, {} Newton iterations, {} cutbacks",
            c.name, l.level, l.nodes, l.free_dofs, l.increments, l.newton_total, l.cutbacks
        );
        for v in &l.values {
            println!(
                "SNAP   {:?}: computed {} reference {} error {}",
                v.quantity,
                sig4(v.computed),
                v.reference.map_or("-".into(), sig4),
                err2(v.error)
            );
        }
    }
}
