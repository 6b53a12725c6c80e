//! The 3D contact patch test between two deformable blocks (Taylor &
//! Papadopoulos, IJNME 31 (1991) 2205, in 3D), node-to-facet contact, as
//! `ctc verify contact_patch_ntf_3d` runs it; prints the table of every
//! cell kind x strategy x method
//! (`cargo test -p ctc-verification --test suite contact_ntf_3d:: -- --nocapture`).
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

#[derive(Default)]
struct Last {
    u: Vec<[f64; 3]>,
    contact: Vec<ctc_engine::contact::NodeContact<3>>,
    checkpoints: Vec<ctc_engine::solve::restart::Checkpoint<3>>,
}

impl ctc_engine::solve::Observer<3> for Last {
    fn converged(&mut self, v: &ctc_engine::solve::IncrementView<'_, 3>) -> Result<(), String> {
        self.u = v.displacement.to_vec();
        self.contact = v.contact[0].clone();
        Ok(())
    }
    fn wants_checkpoint(&self) -> bool {
        true
    }
    fn checkpoint(&mut self, c: &ctc_engine::solve::restart::Checkpoint<3>) -> Result<(), String> {
        self.checkpoints.push(c.clone());
        Ok(())
    }
}

fn bits(l: &Last) -> Vec<u64> {
    l.u.iter()
        .flatten()
        .chain(l.contact.iter().flat_map(|c| c.force.iter()))
        .chain(l.contact.iter().map(|c| &c.pressure))
        .map(|v| v.to_bits())
        .collect()
}

/// A node-to-facet run restarted after its second increment (of four)
/// ends bit for bit where the uninterrupted run ends: the pattern
/// couplings, the double-pass side (an odd number of increments resumed),
/// the multipliers and the active set come back from the checkpoint.
#[test]
fn node_to_facet_restarts_bit_for_bit() {
    use ctc_verification::programs::contact_ntf_3d::patch_deck;
    for (cell, strategy, method) in [
        ("hex8", "double_pass", "lagrange { }"),
        (
            "tet4",
            "single_pass",
            "augmented_lagrange { kind = area  penalty = 1e4  tolerance = 1e-9 }",
        ),
        (
            "hex8",
            "modified_double_pass",
            "penalty { kind = area  stiffness = 1e6 }",
        ),
    ] {
        let text =
            patch_deck(cell, 4, strategy, method).replace("increments = 2", "increments = 4");
        let src = ctc_lang::Source::new("restart.ctc", &text);
        let model = match ctc_lang::compile_any(&src) {
            Ok(ctc_engine::model::AnyModel::D3(m)) => m,
            Ok(_) => panic!("not a 3d deck"),
            Err(d) => panic!("{}", d.render(&src)),
        };
        let mut first = Last::default();
        let s1 = ctc_engine::solve::run(&model, &mut first).unwrap();
        assert!(s1.completed && s1.increments.len() == 4);
        assert!(
            !first.checkpoints[1].couplings.is_empty(),
            "{cell} {strategy}: the pattern never grew"
        );
        let mut rest = Last::default();
        let s2 =
            ctc_engine::solve::run_from(&model, &mut rest, Some(&first.checkpoints[1])).unwrap();
        assert!(s2.completed);
        assert_eq!(bits(&first), bits(&rest), "{cell} {strategy} {method}");
    }
}
