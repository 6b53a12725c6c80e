//! Contact patch test between two deformable blocks with non-matching
//! interface meshes (VERIFICATION-CASES.md case 3), node-to-segment
//! contact, every strategy x method. Prints the table of the largest
//! deviation of the contact pressure from uniform
//! (`cargo test -p ctc-engine --test contact_patch_nts -- --nocapture`).
//!
//! Reference: E = 2e6, nu = 0, two blocks of height 1, top displaced by
//! -0.1: uniform pressure p = 0.1 / (2 / E + 1 / k) (1e5 for exact
//! enforcement), sigma_yy = -p everywhere.

mod contact_nts_support;

use contact_nts_support::*;
use ctc_engine::model::{ContactMethod, ContactStrategy};

const STIFFNESS: f64 = 1e10;

fn exact(method: &ContactMethod) -> f64 {
    match method {
        ContactMethod::Penalty { stiffness, .. } => DEPTH / (2.0 / E + 1.0 / stiffness),
        _ => DEPTH * E / 2.0,
    }
}

struct Outcome {
    deviation: f64,
    error: f64,
    penetration: f64,
    iterations: usize,
}

fn run_case(method: ContactMethod, strategy: ContactStrategy) -> Result<Outcome, String> {
    let model = patch(method.clone(), strategy, 4, 3, 2);
    let (summary, rec) = solve(&model)?;
    assert!(summary.completed);
    let last = rec.records.last().expect("converged increments");
    // equilibrium of every contact element: net force zero
    let net = last.net_contact_force();
    let total = last.slave_force()[1].abs();
    assert!(
        net[0].abs() <= 1e-9 * total && net[1].abs() <= 1e-9 * total,
        "net contact force {net:?} (total {total})"
    );
    let (_, deviation, error) = pressure_deviation(&last.contact, exact(&method));
    Ok(Outcome {
        deviation,
        error,
        penetration: last.max_penetration(),
        iterations: summary.increments.iter().map(|i| i.iterations).sum(),
    })
}

#[test]
fn contact_patch_test_every_strategy_and_method() {
    let methods = [
        ("penalty", penalty(STIFFNESS)),
        ("lagrange", lagrange()),
        ("augmented_lagrange", augmented(1e8, 1e-9)),
    ];
    let strategies = [
        ("single_pass", ContactStrategy::SinglePass),
        ("double_pass", ContactStrategy::DoublePass),
        ("modified_double_pass", ContactStrategy::ModifiedDoublePass),
    ];
    println!(
        "{:<22} {:<20} {:>12} {:>12} {:>12} {:>6}",
        "strategy", "method", "max dev", "max err", "penetration", "its"
    );
    for (sname, strategy) in strategies {
        for (mname, method) in &methods {
            match run_case(method.clone(), strategy) {
                Ok(o) => println!(
                    "{sname:<22} {mname:<20} {:>12.3e} {:>12.3e} {:>12.3e} {:>6}",
                    o.deviation, o.error, o.penetration, o.iterations
                ),
                Err(e) => println!("{sname:<22} {mname:<20} failed: {e}"),
            }
        }
    }
}
