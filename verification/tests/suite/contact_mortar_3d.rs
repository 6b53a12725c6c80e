//! The 3D contact patch test between two deformable blocks (Taylor &
//! Papadopoulos, IJNME 31 (1991) 2205, in 3D) with mortar
//! segment-to-segment contact (Puso & Laursen, CMAME 193 (2004) 601), as
//! `ctc verify contact_patch_mortar_3d` runs it; prints the table of the
//! mortar runs next to node-to-facet's single pass
//! (`cargo test -p ctc-verification --test suite contact_mortar_3d:: -- --nocapture`),
//! and checks the tangent of the assembled mortar pair against finite
//! differences of its forces.
//!
//! ```text
//!   top  3x3 cells across, top face pushed down by 0.01
//!   ---- slave top.zmin (3x3 facets) / master base.zmax (4x4 facets) ----
//!   base 4x4 cells across, bottom on rollers
//! ```

use ctc_engine::contact::surface::{evaluate_pair, SurfacePair};
use ctc_engine::contact::ContactStatus;
use ctc_engine::model::{AnyModel, Model};
use ctc_verification::programs::contact_ntf_3d::{
    mortar_patch_deck, run_combination, run_mortar, MORTAR,
};
use ctc_verification::registry;

#[test]
fn contact_patch_mortar_3d_passes() {
    registry::run_passing("contact_patch_mortar_3d");
}

#[test]
fn table_of_mortar_and_node_to_facet() {
    println!(
        "| formulation | cell | base | method | max |p - p_mean| / p_mean | max |p - p_exact| / p \
         | F / F_exact - 1 | closed | Newton |"
    );
    println!("| --- | --- | --- | --- | --- | --- | --- | --- | --- |");
    for &(_, _, cell, base, method, _) in MORTAR {
        let (o, _) = run_mortar(cell, base, method).expect("run");
        let m = method.split_whitespace().next().unwrap_or("");
        println!(
            "| mortar | {cell} | {base}x{base} | {m} | {:.2e} | {:.2e} | {:.2e} | {} | {} |",
            o.uniformity,
            o.deviation,
            o.force / o.exact - 1.0,
            o.closed,
            o.iterations
        );
        assert!(o.uniformity <= 1e-8, "{cell} {m}: {}", o.uniformity);
    }
    for cell in ["hex8", "tet4"] {
        let method = "penalty { kind = area  stiffness = 1e6 }";
        let (o, _) = run_combination(cell, 4, "single_pass", method).expect("run");
        println!(
            "| node-to-facet single | {cell} | 4x4 | penalty | {:.2e} | {:.2e} | {:.2e} | {} | {} |",
            o.uniformity,
            o.deviation,
            o.force / o.exact - 1.0,
            o.closed,
            o.iterations
        );
    }
}

fn model(cell: &str) -> Model<3> {
    let text = mortar_patch_deck(cell, 4, "penalty { kind = area  stiffness = 1e3 }");
    let src = ctc_lang::Source::new(std::path::Path::new("mortar_3d.ctc"), &text);
    match ctc_lang::compile_any(&src) {
        Ok(AnyModel::D3(m)) => m,
        _ => panic!("the mortar patch deck does not compile to a 3d model"),
    }
}

/// `max |K v - FD| / max |K v|`: the pair's tangent along the direction `v`
/// against central differences of its forces at `x` (the contact set must
/// not change over the step).
fn directional_fd_error(model: &Model<3>, x: &[[f64; 3]], v: &[[f64; 3]]) -> f64 {
    let (_, kv, closed) = forces(model, x, v);
    assert!(closed > 0);
    let h = 1e-7;
    let shift = |sign: f64| shifted(x, v, sign * h);
    let (fp, _, cp) = forces(model, &shift(1.0), v);
    let (fm, _, cm) = forces(model, &shift(-1.0), v);
    assert!(cp == closed && cm == closed);
    let scale = kv.iter().fold(1e-300f64, |a, b| a.max(b.abs()));
    (0..kv.len())
        .map(|k| (-(fp[k] - fm[k]) / (2.0 * h) - kv[k]).abs() / scale)
        .fold(0.0, f64::max)
}

/// The pair's forces at `x`, the tangent applied to `v` (`K v`), and the
/// closed nodes (also of the quadratic pairs' tests).
pub fn forces(model: &Model<3>, x: &[[f64; 3]], v: &[[f64; 3]]) -> (Vec<f64>, Vec<f64>, usize) {
    let mut state = SurfacePair::new(model, 0);
    let (res, _) = evaluate_pair(model, 0, x, 0.0, &mut state);
    let closed = res
        .iter()
        .filter(|c| c.status == ContactStatus::Closed)
        .count();
    let (f, kv) = scatter(&state, x.len(), v);
    (f, kv, closed)
}

/// The points `x + step v` (a central difference's two sides, `step = +-h`).
pub fn shifted(x: &[[f64; 3]], v: &[[f64; 3]], step: f64) -> Vec<[f64; 3]> {
    x.iter()
        .zip(v)
        .map(|(p, d)| std::array::from_fn(|c| p[c] + step * d[c]))
        .collect()
}

/// The forces of the pair's couplings (`state` evaluated) and their
/// tangent times `v`, over `nodes` nodes.
pub fn scatter(state: &SurfacePair, nodes: usize, v: &[[f64; 3]]) -> (Vec<f64>, Vec<f64>) {
    let pair = state.deformable.as_ref().expect("a deformable pair");
    pair.forces_and_tangent_times(nodes, v)
}

#[test]
fn mortar_pair_tangent_matches_finite_differences() {
    let mut seed: u64 = 0x2545_f491_4f6c_dd1d;
    let mut rnd = move || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    };
    for cell in ["hex8", "tet4"] {
        let model = model(cell);
        let top = model.bodies[1].nodes.start;
        let mut worst = 0.0f64;
        // jittered: the flat interface of the patch test puts master
        // vertices on the slave edges (x = 0, ...), a kink of the
        // segmentation that central differences straddle
        for trial in 0..4 {
            let depth = 0.01 + 0.01 * rnd().abs();
            let x: Vec<[f64; 3]> = model
                .mesh
                .nodes
                .iter()
                .enumerate()
                .map(|(k, p)| {
                    let dz = if k >= top { -depth } else { 0.0 };
                    [
                        p[0] + 0.02 * rnd(),
                        p[1] + 0.02 * rnd(),
                        p[2] + dz + 0.004 * rnd(),
                    ]
                })
                .collect();
            let v: Vec<[f64; 3]> = x.iter().map(|_| [rnd(), rnd(), rnd()]).collect();
            let e = directional_fd_error(&model, &x, &v);
            println!("{cell} trial {trial}: {e:.2e}");
            worst = worst.max(e);
        }
        println!("{cell}: max |K v - FD| / max |K v| = {worst:.2e}");
        assert!(worst <= 1e-5, "{cell}: {worst}");
    }
}

#[test]
fn hertz_sphere_block_mortar_3d_passes() {
    registry::run_passing("hertz_sphere_block_mortar_3d");
}

/// Prints the Hertz forces of mortar and node-to-facet and the Newton
/// iterations.
#[test]
fn hertz_mortar_forces() {
    use ctc_verification::programs::contact_ntf_3d::hertz_force_with;
    for formulation in ["mortar", "node_to_segment"] {
        for e in [Some(1e6), Some(1000.0)] {
            let (p, s) = hertz_force_with(e, formulation).expect("hertz");
            println!(
                "{formulation}: block E {e:?}: P {p:.6e}, Newton {}, increments {}",
                s.newton_iterations,
                s.increments.len()
            );
        }
    }
}

/// The frictional 3D patch test with mortar (`ctc verify
/// contact_patch_friction_3d`; Taylor & Papadopoulos, IJNME 31 (1991) 2205,
/// in 3D; Gitterle, Popp, Gee & Wall, IJNME 84 (2010) 543): two blocks,
/// 3x3 | 4x4 facets, pressed then sheared below and past `mu N`, along x
/// and at 30 degrees; every value within its tolerance (stick with the
/// augmented Lagrangian uniform to 1e-8, slip `|q| = mu p` at every node).
///
/// ```text
///   top  3x3 cells, u = (delta cos th, delta sin th, -d) on top
///   ---- slave top.zmin (3x3) / master base.zmax (4x4), mu = 0.3 ----
///   base 4x4 cells, fixed bottom; side tractions of the uniform state
/// ```
#[test]
fn contact_patch_friction_3d_passes() {
    registry::run_passing("contact_patch_friction_3d");
}

/// The assembled frictional mortar pair: its tangent applied to random
/// directions against central differences of its forces, on jittered
/// interfaces pressed and slid from the mesh's configuration (the
/// committed one), in stick (`mu = 0.9`) and in slip (`mu = 0.05`).
#[test]
fn frictional_mortar_pair_tangent_matches_finite_differences() {
    use ctc_verification::programs::mortar_friction_3d::deck;
    let mut seed: u64 = 0x2545_f491_4f6c_dd1d;
    let mut rnd = move || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    };
    // (mu, k_T): stick (the trial force 0.1 below mu R_N), slip
    for (cell, mu, k_t) in [
        ("hex8", 0.9, 1e2),
        ("hex8", 0.05, 1e4),
        ("tet4", 0.9, 1e2),
        ("tet4", 0.05, 1e4),
    ] {
        let text = deck(
            cell,
            "penalty { kind = area  stiffness = 1e3 }",
            k_t,
            0.0,
            0.0,
            2.0,
            0.0,
        )
        .replace("mu = 0.3", &format!("mu = {mu}"));
        let src = ctc_lang::Source::new(std::path::Path::new("mortar_friction_3d.ctc"), &text);
        let Ok(AnyModel::D3(model)) = ctc_lang::compile_any(&src) else {
            panic!("the frictional patch deck does not compile to a 3d model");
        };
        let top = model.bodies[1].nodes.start;
        let mut worst = 0.0f64;
        for _ in 0..2 {
            let depth = 0.01 + 0.01 * rnd().abs();
            let x: Vec<[f64; 3]> = model
                .mesh
                .nodes
                .iter()
                .enumerate()
                .map(|(k, p)| {
                    let (dx, dz) = if k >= top { (0.01, -depth) } else { (0.0, 0.0) };
                    [
                        p[0] + dx + 0.02 * rnd(),
                        p[1] + 0.5 * dx + 0.02 * rnd(),
                        p[2] + dz + 0.004 * rnd(),
                    ]
                })
                .collect();
            let v: Vec<[f64; 3]> = x.iter().map(|_| [rnd(), rnd(), rnd()]).collect();
            let e = directional_fd_error(&model, &x, &v);
            worst = worst.max(e);
        }
        println!("{cell} mu {mu}: max |K v - FD| / max |K v| = {worst:.2e}");
        assert!(worst <= 1e-5, "{cell} mu {mu}: {worst}");
    }
}
