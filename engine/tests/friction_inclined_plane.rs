//! VERIFICATION-CASES case 4 (NAFEMS CGS-4 as used by other codes): a block
//! on a rigid plane inclined at tan(alpha) = 0.1, loaded normally, then
//! pushed horizontally up the slope. Once every contact node slides, the
//! horizontal force over the vertical load is
//! `F / G = (tan a + mu) / (1 - mu tan a)` (0.412371 for mu = 0.3), for
//! every normal method (penalty, augmented Lagrangian, Lagrange).

mod support;

use ctc_engine::contact::friction::FrictionStatus;
use ctc_engine::model::{ContactMethod, LagrangeFormulation, MultiplierUpdate, PenaltyKind};
use support::friction::{count, solve, Block, Drive};

fn reference(mu: f64) -> f64 {
    (0.1 + mu) / (1.0 - mu * 0.1)
}

/// F/G at the end of the push and the Newton iterations of the run.
fn threshold(block: Block) -> (f64, usize) {
    let (rec, summary) = solve(&block).unwrap_or_else(|e| panic!("{block:?}: {e}"));
    let last = rec.rows.last().unwrap();
    let n = last.contact.len();
    assert_eq!(
        count(&last.contact, FrictionStatus::Slip),
        n,
        "mu = {}: every node slides at the end: {:?}",
        block.mu,
        last.contact.iter().map(|c| c.friction).collect::<Vec<_>>()
    );
    let g = match block.squeeze {
        Some(_) => -last.lift,
        None => block.weight,
    };
    (last.push / g, summary.newton_iterations)
}

#[test]
fn case4_inclined_plane_slip_threshold_all_methods() {
    let alpha = 0.1f64.atan();
    // (name, method, squeeze, friction stiffness)
    let methods: [(&str, ContactMethod, Option<f64>, Option<f64>); 4] = [
        (
            "penalty (weight)",
            ContactMethod::Penalty {
                kind: PenaltyKind::Area,
                stiffness: 1e7,
            },
            None,
            None,
        ),
        (
            "penalty (squeeze)",
            ContactMethod::Penalty {
                kind: PenaltyKind::Area,
                stiffness: 1e7,
            },
            Some(1e-3),
            None,
        ),
        (
            "augmented Lagrangian",
            ContactMethod::AugmentedLagrange {
                kind: PenaltyKind::Area,
                penalty: 1e6,
                tolerance: 1e-8,
                update: MultiplierUpdate::Converged,
            },
            Some(1e-3),
            // Uzawa contracts the stick gaps at about K / (K + alpha_T):
            // alpha_T = alpha_N keeps the number of updates small
            Some(1e6),
        ),
        (
            "Lagrange",
            ContactMethod::Lagrange {
                formulation: LagrangeFormulation::Single,
            },
            Some(1e-3),
            None,
        ),
    ];
    println!("| method | mu | F/G | reference | rel. error | Newton iterations |");
    println!("| --- | --- | --- | --- | --- | --- |");
    for (name, method, squeeze, stiffness) in methods {
        for mu in [0.0, 0.1, 0.2, 0.3] {
            let mut b = Block::new(alpha, mu, Drive::LeftSide(0.01));
            b.method = method.clone();
            b.squeeze = squeeze;
            b.friction_stiffness = stiffness;
            let (ratio, iterations) = threshold(b);
            let err = (ratio - reference(mu)).abs() / reference(mu);
            println!(
                "| {name} | {mu} | {ratio:.6} | {:.6} | {err:.1e} | {iterations} |",
                reference(mu)
            );
            assert!(
                err < 1e-6,
                "{name} mu = {mu}: F/G = {ratio} vs {}",
                reference(mu)
            );
        }
    }
    assert!((reference(0.3) - 0.412371).abs() < 5e-7);
}
