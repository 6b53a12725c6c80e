//! 3D mortar contact on quadratic faces (issues 23 and 18; Puso, Laursen &
//! Solberg, CMAME 197 (2008) 555): the contact patch test of `ctc verify
//! contact_patch_mortar_quadratic_3d` (Taylor & Papadopoulos, IJNME 31
//! (1991) 2205, in 3D; penalty, augmented Lagrangian and Lagrange
//! multipliers; prints the tables with
//! `cargo test -p ctc-verification --test suite mortar_quadratic_3d:: -- --nocapture`),
//! the assembled pair's tangent against central differences of its forces
//! with the pair's force and moment balance, and the Hertz case's coarse
//! level.
//!
//! ```text
//!   top  2x2 hex20 (or tet10) cells across, top face pushed down by 0.01
//!   ---- slave top.zmin (quad8 / tri6 faces) / master base.zmax (3x3 quad8) ----
//!   base 3x3 hex20 cells across, bottom on rollers
//! ```

use crate::contact_mortar_3d::forces;
use crate::contact_mortar_3d::shifted;
use ctc_engine::model::{AnyModel, Model};
use ctc_verification::programs::mortar_quadratic_3d::{patch_deck, LAGRANGE_PATCH, PATCH};
use ctc_verification::registry;

#[test]
fn contact_patch_mortar_quadratic_3d_passes() {
    let report = registry::run_passing("contact_patch_mortar_quadratic_3d");
    println!("| run | max |p - p_mean| / p_mean | F / F_exact - 1 |");
    println!("| --- | --- | --- |");
    let values = &report.levels[0].values;
    for (&(pname, fname, ..), pair) in PATCH.iter().zip(values.chunks(2)) {
        println!(
            "| {} | {:.2e} | {:.2e} |",
            pname.trim_end_matches(" p uniform"),
            pair[0].computed,
            pair[1].computed / pair[1].reference.unwrap_or(f64::NAN) - 1.0
        );
        assert!(pair[1].quantity.to_string().contains(fname), "{fname}");
    }
    // Lagrange multipliers: the deviation, the force and the largest
    // active nodal gap over the travel
    println!("| run | max |p - p_mean| / p_mean | F / F_exact - 1 | max |g~/A| / d |");
    println!("| --- | --- | --- | --- |");
    let lagrange = &values[2 * PATCH.len()..];
    assert_eq!(lagrange.len(), 3 * LAGRANGE_PATCH.len());
    for (&(pname, fname, gname, ..), v) in LAGRANGE_PATCH.iter().zip(lagrange.chunks(3)) {
        println!(
            "| {} | {:.2e} | {:.2e} | {:.2e} |",
            pname.trim_end_matches(" p uniform"),
            v[0].computed,
            v[1].computed / v[1].reference.unwrap_or(f64::NAN) - 1.0,
            v[2].computed
        );
        assert!(v[1].quantity.to_string().contains(fname), "{fname}");
        assert!(v[2].quantity.to_string().contains(gname), "{gname}");
    }
}

fn model(cell: &str) -> Model<3> {
    let text = patch_deck(cell, 2, 3, "penalty { kind = area  stiffness = 1e3 }").expect("deck");
    let src = ctc_lang::Source::new(std::path::Path::new("mortar_quadratic_3d.ctc"), &text);
    match ctc_lang::compile_any(&src) {
        Ok(AnyModel::D3(m)) => m,
        Ok(_) => panic!("the patch deck is not 3d"),
        Err(d) => panic!("{}", d.render(&src)),
    }
}

#[test]
fn quadratic_mortar_pair_tangent_matches_finite_differences_and_balances() {
    let mut seed: u64 = 0x9e37_79b9_7f4a_7c15;
    let mut rnd = move || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    };
    for cell in ["hex8", "tet4"] {
        let model = model(cell);
        let top = model.bodies[1].nodes.start;
        // jittered (a flat interface puts master vertices on slave edges,
        // a kink of the segmentation that central differences straddle)
        // and bent: the top block's bottom bulges down by up to 0.01
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
        assert!(closed > 0);
        // force and moment balance of the pair's forces
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
        // the tangent along v against central differences
        let h = 1e-7;
        let shift = |sign: f64| shifted(&x, &v, sign * h);
        let (fp, _, cp) = forces(&model, &shift(1.0), &v);
        let (fm, _, cm) = forces(&model, &shift(-1.0), &v);
        assert!(cp == closed && cm == closed);
        let kscale = kv.iter().fold(1e-300f64, |a, b| a.max(b.abs()));
        let e = (0..kv.len())
            .map(|k| (-(fp[k] - fm[k]) / (2.0 * h) - kv[k]).abs() / kscale)
            .fold(0.0, f64::max);
        println!(
            "{cell} order 2: {closed} closed, max |K v - FD| / max |K v| = {e:.2e}, \
             force / moment imbalance {imbalance:.1e}"
        );
        assert!(e <= 1e-5, "{cell}: {e}");
        assert!(imbalance <= 1e-10, "{cell}: {imbalance}");
    }
}

#[test]
fn hertz_sphere_block_mortar_quadratic_3d_passes() {
    let report = registry::run_passing("hertz_sphere_block_mortar_quadratic_3d");
    for v in &report.levels[0].values {
        println!(
            "{:?}: {:.4e} vs {:?}: {:.2e}",
            v.quantity, v.computed, v.reference, v.error
        );
    }
}

/// The Hertz runs of one level (`QM_LEVEL`, default 1) side by side: the
/// rigid plane, the stiff and the equal block (mortar on quadratic faces),
/// total force, peak pressure and free dofs (`cargo test -p
/// ctc-verification --test suite hertz_quadratic_level -- --ignored
/// --nocapture`; minutes in debug, not run by CI).
#[test]
#[ignore]
fn hertz_quadratic_level() {
    use ctc_verification::programs::mortar_quadratic_3d::hertz_run;
    let level: usize = std::env::var("QM_LEVEL")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(1);
    let runs = [None, Some(1e6), Some(1000.0)];
    let out: Vec<_> = std::thread::scope(|s| {
        let handles: Vec<_> = runs
            .iter()
            .map(|&e| s.spawn(move || (e, hertz_run(level, e).expect("hertz run"))))
            .collect();
        handles.into_iter().map(|h| h.join().unwrap()).collect()
    });
    for (e, (force, p0, s)) in out {
        println!(
            "level {level}: block E {e:?}: P {force:.6e}, p0 {p0:.6e}, {} free dofs, {} Newton, {} increments",
            s.free_dofs, s.newton_iterations, s.increments.len()
        );
    }
}

/// The equal-block Hertz runs of one level (`QM_LEVEL`, default 1) with
/// the penalty and with Lagrange multipliers side by side: total force,
/// peak pressure, largest active nodal gap, Newton iterations (`cargo
/// test -p ctc-verification --test suite hertz_quadratic_lagrange_level
/// -- --ignored --nocapture`; minutes in debug, not run by CI).
#[test]
#[ignore]
fn hertz_quadratic_lagrange_level() {
    use ctc_verification::programs::mortar_quadratic_3d::hertz_run_lagrange;
    let level: usize = std::env::var("QM_LEVEL")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(1);
    let out: Vec<_> = std::thread::scope(|s| {
        let handles: Vec<_> = [false, true]
            .into_iter()
            .map(|l| {
                s.spawn(move || {
                    (
                        l,
                        hertz_run_lagrange(level, Some(1000.0), l).expect("hertz run"),
                    )
                })
            })
            .collect();
        handles.into_iter().map(|h| h.join().unwrap()).collect()
    });
    for (lagrange, (force, p0, gap, s)) in out {
        println!(
            "level {level}: lagrange {lagrange}: P {force:.6e}, p0 {p0:.6e}, max |g~/A| {gap:.2e}, {} free dofs, {} Newton, {} increments",
            s.free_dofs, s.newton_iterations, s.increments.len()
        );
    }
}

/// The linear mortar Hertz deck (`hertz_sphere_block_mortar_3d`'s, the
/// equal block, Lagrange multipliers) on a finer mesh: sphere `tangential
/// = QM_TANGENTIAL` (default 24) cells per patch edge, `radial = 3
/// tangential / 16` (rounded), block `tangential / 2` cells across and
/// `tangential / 8` thick; total force (the reaction on the sphere's base)
/// against Hertz's, to tell the finite bodies from the discretization in
/// the +16 % of `hertz_sphere_block_mortar_quadratic_3d` (`cargo test -p
/// ctc-verification --test suite hertz_linear_refinement -- --ignored
/// --nocapture`; minutes, not run by CI).
#[test]
#[ignore]
fn hertz_linear_refinement() {
    use ctc_engine::solve::run;
    use ctc_verification::programs::contact_ntf_3d::hertz_deck_with;
    let t: usize = std::env::var("QM_TANGENTIAL")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(24);
    let radial = (3 * t + 8) / 16;
    let text = hertz_deck_with(Some(1000.0), "mortar")
        .replace("penalty { kind = area  stiffness = 1e7 }", "lagrange")
        .replace(
            "radial = 3  tangential = 16 }",
            &format!("radial = {radial}  tangential = {t} }}"),
        )
        .replace(
            "divisions = (8, 8, 2) }",
            &format!("divisions = ({}, {}, {}) }}", t / 2, t / 2, (t / 8).max(1)),
        );
    assert!(text.contains(&format!("tangential = {t} ")), "{text}");
    let src = ctc_lang::Source::new(std::path::Path::new("hertz_linear.ctc"), &text);
    let model = match ctc_lang::compile_any(&src) {
        Ok(AnyModel::D3(m)) => m,
        Ok(_) => panic!("not 3d"),
        Err(d) => panic!("{}", d.render(&src)),
    };
    let mut base: Vec<usize> = model
        .mesh
        .node_sets
        .get("ball.zmin")
        .cloned()
        .unwrap_or_else(|| {
            model.mesh.face_sets["ball.zmin"]
                .iter()
                .flat_map(|f| f.nodes().to_vec())
                .collect()
        });
    base.sort_unstable();
    base.dedup();
    struct Base(Vec<usize>, f64);
    impl ctc_engine::solve::Observer<3> for Base {
        fn converged(&mut self, v: &ctc_engine::solve::IncrementView<'_, 3>) -> Result<(), String> {
            self.1 = self.0.iter().map(|&n| v.reaction[n][2]).sum();
            Ok(())
        }
    }
    let mut rec = Base(base, 0.0);
    let start = std::time::Instant::now();
    let s = run(&model, &mut rec).expect("run");
    assert!(s.completed);
    let force = rec.1;
    let e_star = 0.5 * 1000.0 / (1.0 - 0.09);
    let hertz = 4.0 / 3.0 * e_star * 0.01f64.powf(1.5) / 4.0;
    println!(
        "linear mortar lagrange tangential {t} radial {radial}: {} free dofs, P {force:.6e}, P / Hertz - 1 = {:+.4}, {} Newton, {:.0} s",
        s.free_dofs,
        force / hertz - 1.0,
        s.newton_iterations,
        start.elapsed().as_secs_f64()
    );
}

/// The catalogue snapshot's lines of this file's cases
/// (`cases_coarse::verification_catalogue_on_default_levels`), to splice
/// into its snapshot (`cargo test -p ctc-verification --test suite
/// catalogue_lines -- --ignored --nocapture`).
#[test]
#[ignore]
fn catalogue_lines() {
    use crate::fenicsx_snapshots::{err2, sig4};
    for name in [
        "contact_patch_mortar_quadratic_3d",
        "hertz_sphere_block_mortar_quadratic_3d",
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
