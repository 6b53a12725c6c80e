//! The 3D contact patch test between two deformable blocks (Taylor &
//! Papadopoulos, IJNME 31 (1991) 2205, in 3D), node-to-facet contact, as
//! `ctc verify contact_patch_ntf_3d` runs it; prints the table of every
//! cell kind x strategy x method
//! (`cargo test -p ctc-verification --test contact_ntf_3d -- --nocapture`).
//!
//! ```text
//!   top  3x3 cells across, top face pushed down by 0.01
//!   ---- slave top.zmin (3x3 facets) / master base.zmax (4x4 facets) ----
//!   base 4x4 cells across, bottom on rollers
//! ```

use ctc_verification::programs::contact_ntf_3d::{
    run_combination, run_loaded, COMBINATIONS, LOADED,
};
use ctc_verification::registry;

#[test]
fn contact_patch_ntf_3d_passes() {
    registry::run_passing("contact_patch_ntf_3d");
}

#[test]
fn table_of_every_combination() {
    println!(
        "| cell | base | strategy | method | max |p - p_exact| / p | F / F_exact - 1 | closed | \
         Newton |"
    );
    println!("| --- | --- | --- | --- | --- | --- | --- | --- |");
    for &(_, _, cell, base, strategy, method, _, _) in COMBINATIONS {
        let (o, _) = run_combination(cell, base, strategy, method).expect("run");
        let m = method.split_whitespace().next().unwrap_or("");
        println!(
            "| {cell} | {base}x{base} | {strategy} | {m} | {:.3e} | {:.3e} | {} | {} |",
            o.deviation,
            o.force / o.exact - 1.0,
            o.closed,
            o.iterations
        );
    }
    println!("load-controlled (traction 10 on the top, the top block held only by contact):");
    for &(_, cell, strategy, method) in LOADED {
        let (o, _) = run_loaded(cell, strategy, method).expect("run");
        let m = method.split_whitespace().next().unwrap_or("");
        println!(
            "| {cell} | {strategy} | {m} | contact force / load - 1 = {:.3e} | p deviation {:.3e} | \
             Newton {} |",
            o.contact_force / o.exact - 1.0,
            o.deviation,
            o.iterations
        );
    }
}

#[test]
fn hertz_sphere_block_ntf_3d_passes() {
    registry::run_passing("hertz_sphere_block_ntf_3d");
}

/// Prints the three Hertz forces and Newton iterations.
#[test]
fn hertz_forces() {
    for e in [None, Some(1e6), Some(1000.0)] {
        let (p, s) = ctc_verification::programs::contact_ntf_3d::hertz_force(e).expect("hertz");
        println!(
            "block E {e:?}: P {p:.6e}, Newton {}, increments {}",
            s.newton_iterations,
            s.increments.len()
        );
    }
}
