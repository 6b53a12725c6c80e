//! Coulomb friction between deformable solids in 3D (node-to-facet), as
//! `ctc verify friction_blocks_ntf_3d` and `ironing_ntf_3d` run them; the
//! tables print with
//! `cargo test -p ctc-verification --test suite friction_ntf_3d:: -- --nocapture`.
//!
//! Block on a block (Coulomb's law, statics: stick below mu F_n, in slip
//! `sum |T_i| = mu sum R_N,i`):
//!
//! ```text
//!        p = 10, top face pulled along x
//!       +--------+
//!       |  top   |  slave top.zmin (3x3 facets), mu = 0.3
//!   +---+--------+-------+  master base.zmax (8x4 facets)
//!   |       base         |
//!   +--------------------+  fixed
//! ```
//!
//! Ironing: M. A. Puso, T. A. Laursen, "A mortar segment-to-segment
//! frictional contact method for large deformations", CMAME 193 (2004)
//! 4891-4913 (die-on-slab: Neo-Hookean slab 9 x 3 x 4, E = 1, nu = 0.3;
//! die R = 3, width 5.2, E = 1000, nu = 0.499; press 1.4, slide 4.0,
//! mu = 0.3, penalty 500):
//!
//! ```text
//!          .-''''''-.   die (u_y = -1.4, then u_x = 4)
//!         /          \
//!   +-----\----------/---------------+  slab top (slave)
//!   |      '--------'     slab        |
//!   +--------------------------------+  fixed
//! ```

use ctc_engine::contact::NodeContact;
use ctc_engine::solve::{
    restart::Checkpoint, run, run_from, IncrementView, IterationInfo, Observer,
};
use ctc_verification::programs::friction_ntf_3d::{
    block_run, blocks_model, ironing, BLOCK_RUNS, MU,
};
use ctc_verification::registry;

#[derive(Default)]
struct Last {
    u: Vec<[f64; 3]>,
    contact: Vec<NodeContact<3>>,
    checkpoints: Vec<Checkpoint<3>>,
    iterations: Vec<IterationInfo>,
}

impl Observer<3> for Last {
    fn iteration(&mut self, info: &IterationInfo) {
        self.iterations.push(info.clone());
    }
    fn converged(&mut self, v: &IncrementView<'_, 3>) -> Result<(), String> {
        self.u = v.displacement.to_vec();
        self.contact = v.contact[0].clone();
        Ok(())
    }
    fn wants_checkpoint(&self) -> bool {
        true
    }
    fn checkpoint(&mut self, c: &Checkpoint<3>) -> Result<(), String> {
        self.checkpoints.push(c.clone());
        Ok(())
    }
}

fn bits(l: &Last) -> Vec<u64> {
    l.u.iter()
        .flatten()
        .chain(l.contact.iter().flat_map(|c| c.force.iter()))
        .chain(l.contact.iter().flat_map(|c| c.friction.slip_vector.iter()))
        .map(|v| v.to_bits())
        .collect()
}

/// The stick points on the master facets (`[facet, xi_1, xi_2]`) and the
/// shifts survive a restart bit for bit in the slide (checkpoint 4: after
/// the press, the stick stage and two slip increments).
#[test]
fn friction_ntf_3d_restarts_bit_for_bit_in_the_slide() {
    for (strategy, method) in [
        ("single_pass", "penalty { kind = area  stiffness = 1e5 }"),
        (
            "modified_double_pass",
            "penalty { kind = area  stiffness = 1e5 }",
        ),
        (
            "single_pass",
            "augmented_lagrange { kind = area  penalty = 1e5  tolerance = 1e-6 }",
        ),
    ] {
        let model = blocks_model(strategy, method).unwrap();
        let mut first = Last::default();
        let s1 = run(&model, &mut first).unwrap();
        assert!(s1.completed);
        let mut rest = Last::default();
        let s2 = run_from(&model, &mut rest, Some(&first.checkpoints[3])).unwrap();
        assert!(s2.completed);
        assert_eq!(bits(&first), bits(&rest), "{strategy} {method}");
        assert!(s1.friction_work[0] > 0.0);
    }
}

/// The exact tangent: in the slip stage of the single-pass penalty run,
/// once the relative residual is below 1e-3 and above round-off, each
/// Newton iteration squares it (`r_k+1 <= 30 r_k^2`; measured: e.g.
/// 2.7e-4 -> 1.3e-7 -> 4.0e-13, 4.3e-5 -> 1.4e-8 -> 2.9e-13; the first
/// iterations of an increment switch nodes from stick to slip). The
/// constant was 10 before the free-edge band's fade: the upper block's
/// nodes crossing the lower block's rim now lose their force over the band
/// (`node_to_facet::edge_fade`), a sharper but smooth (C2) nonlinearity:
/// increment 8 4.4e-4 -> 2.8e-6 -> 4.0e-12 (constants 14.4, then 0.5),
/// increment 10 3.3e-4 -> 2.0e-6 -> 1.5e-12 (18.2, 0.4).
#[test]
fn newton_converges_quadratically_while_the_block_slides() {
    let model = blocks_model("single_pass", "penalty { kind = area  stiffness = 1e5 }").unwrap();
    let mut last = Last::default();
    run(&model, &mut last).unwrap();
    let slip: Vec<&IterationInfo> = last.iterations.iter().filter(|i| i.step == 2).collect();
    let mut checked = 0;
    for w in slip.windows(2) {
        let (a, b) = (w[0], w[1]);
        if a.increment != b.increment || b.iteration != a.iteration + 1 {
            continue;
        }
        if a.residual < 1e-3 && b.residual > 1e-12 {
            assert!(
                b.residual <= 30.0 * a.residual * a.residual,
                "increment {} iteration {}: {:.3e} -> {:.3e}",
                a.increment,
                a.iteration,
                a.residual,
                b.residual
            );
            checked += 1;
        }
    }
    assert!(checked >= 8, "{checked} iterations checked");
}

#[test]
fn friction_blocks_ntf_3d_passes() {
    registry::run_passing("friction_blocks_ntf_3d");
}

#[test]
fn table_of_the_block_runs() {
    println!(
        "| run | stick: slipping nodes | slip: sum|T| / (mu sum R_N) - 1 | |F_t| / (mu F_n) - 1 | \
         F_n | Newton | increments |"
    );
    println!("| --- | --- | --- | --- | --- | --- | --- |");
    for &(label, strategy, method, ..) in BLOCK_RUNS {
        let (f, s) = block_run(strategy, method).expect("run");
        println!(
            "| {label} | {} | {:.2e} | {:.2e} | {:.12} | {} | {} |",
            f[0],
            f[1] - 1.0,
            f[2] - 1.0,
            f[3],
            s.newton_iterations,
            s.increments.len()
        );
    }
}

/// The ironing histories at the coarse level: `F_t`, `F_n` per increment,
/// the ratio against mu, the oscillation amplitudes, Newton iterations per
/// increment.
#[test]
fn ironing_coarse_histories() {
    let start = std::time::Instant::now();
    let r = ironing(0).expect("ironing level 0");
    println!("| t | F_t | F_n | F_t / F_n |");
    println!("| --- | --- | --- | --- |");
    for (t, ft, fn_) in &r.history {
        println!(
            "| {t:.4} | {ft:.5} | {:.5} | {:.4} |",
            fn_.abs(),
            (ft / fn_).abs()
        );
    }
    let s = &r.summary;
    println!(
        "level 0: F_t / F_n (slide mean) {:.4} vs mu {MU}; oscillation F_n {:.3}, F_t {:.3}; \
         sum|T| / (mu sum R_N) - 1 = {:.2e}; balance {:.2e}; {} increments, {} Newton \
         iterations ({:.2} per increment), {} cutbacks; {:.1} s",
        r.ratio,
        r.oscillation[0],
        r.oscillation[1],
        r.coulomb - 1.0,
        r.balance,
        s.increments.len(),
        s.newton_iterations,
        s.newton_iterations as f64 / s.increments.len().max(1) as f64,
        s.cutbacks,
        start.elapsed().as_secs_f64()
    );
    assert!((r.coulomb - 1.0).abs() <= 1e-9);
    assert!(r.balance <= 1e-6);
}
