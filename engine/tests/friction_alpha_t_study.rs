//! Effect of the tangential penalty `alpha_T` (regularized Coulomb law) on
//! the error and on the Newton iterations.
//!
//! - Error: a block pressed with `N` and pulled with `Q = 0.9 mu N` sticks;
//!   exact Coulomb friction keeps the base in place, the regularized law
//!   lets it creep elastically by `R_T / alpha_T` (area penalty: `Q /
//!   (alpha_T width)`), so the error falls as `1 / alpha_T`. Lagrange
//!   multipliers give 0.
//! - Iterations: the inclined-plane push (case 4, mu = 0.3: stick, partial
//!   slip, then full slip), Newton iterations of the whole run; the slip
//!   threshold stays exact at every `alpha_T`.
//!
//! Run with `--nocapture` for the table.

mod support;

use ctc_engine::model::{ContactMethod, LagrangeFormulation, PenaltyKind};
use support::friction::{solve, Block, Drive};

const MU: f64 = 0.3;
const ALPHA_N: f64 = 1e7;

/// Largest |u_x| of the base under Q = 0.9 mu N (sticking block).
fn creep(method: ContactMethod, stiffness: Option<f64>, squeeze: Option<f64>) -> (f64, f64) {
    let q = 0.9 * MU * 100.0;
    let mut b = Block::new(0.0, MU, Drive::Force(q));
    b.method = method;
    b.friction_stiffness = stiffness;
    b.squeeze = squeeze;
    b.poisson = 0.0;
    let (rec, _) = solve(&b).unwrap_or_else(|e| panic!("{e}"));
    let last = rec.rows.last().unwrap();
    let u = last
        .contact
        .iter()
        .map(|c| c.friction.tangential_gap.abs())
        .fold(0.0, f64::max);
    (u, q)
}

#[test]
fn alpha_t_error_and_iterations() {
    let alpha = 0.1f64.atan();
    let reference = (0.1 + MU) / (1.0 - MU * 0.1);
    println!("| alpha_T / alpha_N | stick creep (base u_T) | creep x alpha_T | case 4 F/G error | Newton iterations (case 4) |");
    println!("| --- | --- | --- | --- | --- |");
    let mut products = Vec::new();
    for ratio in [1e-3, 1e-2, 1e-1, 1.0, 1e1] {
        let at = ratio * ALPHA_N;
        let penalty = ContactMethod::Penalty {
            kind: PenaltyKind::Area,
            stiffness: ALPHA_N,
        };
        let (u, q) = creep(penalty.clone(), Some(at), None);
        // expected creep: uniform shear traction q / width over alpha_T
        let expected = q / at;
        let mut b = Block::new(alpha, MU, Drive::LeftSide(0.01));
        b.friction_stiffness = Some(at);
        let (rec, summary) = solve(&b).unwrap_or_else(|e| panic!("{e}"));
        let last = rec.rows.last().unwrap();
        let err = (last.push / b.weight - reference).abs() / reference;
        println!(
            "| {ratio:.0e} | {u:.3e} | {:.4e} | {err:.1e} | {} |",
            u * at,
            summary.newton_iterations
        );
        if ratio == 1e-1 {
            for r in &rec.rows {
                let seq: Vec<String> = r.residuals.iter().map(|x| format!("{x:.1e}")).collect();
                println!("    t = {:.2}: residuals [{}]", r.time, seq.join(", "));
            }
        }
        assert!(
            (u - expected).abs() < 1e-6 * expected,
            "creep {u} vs {expected}"
        );
        assert!(err < 1e-8, "alpha_T = {at}: F/G error {err}");
        products.push(u * at);
    }
    // the creep is exactly inversely proportional to alpha_T
    for p in &products {
        assert!((p - products[0]).abs() < 1e-6 * products[0]);
    }
    let (u, _) = creep(
        ContactMethod::Lagrange {
            formulation: LagrangeFormulation::Single,
        },
        None,
        Some(1e-3),
    );
    println!("Lagrange multipliers: stick creep {u:.1e}");
    assert!(u < 1e-12, "Lagrange stick is exact: {u}");
}
