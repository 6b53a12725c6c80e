//! Contact patch test with mortar segment-to-segment contact
//! (VERIFICATION-CASES.md case 3; Puso & Laursen, CMAME 193 (2004) 601,
//! "A mortar segment-to-segment contact method for large deformation
//! solid mechanics": mortar passes the patch test that node-to-segment
//! fails). Two blocks with 4 and 3, then 7 and 5 quads across the
//! interface; the pressure must be uniform to round-off, and the contact
//! tangent must be the derivative of the contact forces (finite
//! differences, random configurations).
//!
//! ```text
//!   top (3 | 5 quads)    slave = top.bottom
//!   ---------------- interface, non-matching nodes
//!   base (4 | 7 quads)   master = base.top
//! ```
//!
//! Reference: E = 2e6, nu = 0, blocks of height 1, top displaced by -0.1:
//! `p = 0.1 / (2 / E + 1 / k)` (penalty), `0.1 E / 2` exactly enforced.

mod support;

use ctc_engine::contact::{evaluate_pair, PairState};
use ctc_engine::model::{ContactFormulation, ContactMethod, ContactStrategy, Model};
use proptest::prelude::*;
use support::nts::*;
use support::solve;

const STIFFNESS: f64 = 1e8;

fn mortar(method: ContactMethod, n_base: usize, n_top: usize) -> Model {
    let mut m = patch(method, ContactStrategy::SinglePass, n_base, n_top, 2);
    m.contacts[0].formulation = ContactFormulation::Mortar;
    m
}

fn exact(method: &ContactMethod) -> f64 {
    match method {
        ContactMethod::Penalty { stiffness, .. } => DEPTH / (2.0 / E + 1.0 / stiffness),
        _ => DEPTH * E / 2.0,
    }
}

#[test]
fn mortar_passes_the_patch_test() {
    println!("| mesh | method | closed | mean p | max dev | max err | iterations |");
    println!("| --- | --- | --- | --- | --- | --- | --- |");
    for (n_base, n_top) in [(4, 3), (7, 5)] {
        for (name, method, err_tol) in [
            ("penalty", penalty(STIFFNESS), 1e-8),
            ("augmented", augmented(STIFFNESS, 1e-9), 1e-4),
        ] {
            let model = mortar(method.clone(), n_base, n_top);
            let (summary, rec) = solve(&model).expect("run");
            assert!(summary.completed, "{name} {n_base}/{n_top}");
            let last = rec.increments.last().expect("increments");
            let closed = last.closed(0).len();
            assert_eq!(closed, n_top + 1, "every slave node closed");
            let (mean, dev, err) = pressure_deviation(&last.contact[0], exact(&method));
            let iterations: usize = rec.increments.iter().map(|i| i.iterations()).sum();
            println!(
                "| {n_base} vs {n_top} | {name} | {closed} | {mean:.6e} | {dev:.2e} | {err:.2e} | {iterations} |"
            );
            assert!(dev <= 1e-8, "{name} {n_base}/{n_top}: deviation {dev:e}");
            assert!(err <= err_tol, "{name} {n_base}/{n_top}: error {err:e}");
        }
    }
}

/// Forces of the mortar rows of pair 0 at coordinates `x`, and the tangent
/// applied to `v`.
fn forces(model: &Model, x: &[[f64; 2]], v: &[[f64; 2]]) -> (Vec<f64>, Vec<f64>, usize) {
    let mut state = PairState::new(model, 0);
    let res = evaluate_pair(model, 0, x, 0.0, &mut state);
    let mut f = vec![0.0; 2 * x.len()];
    let mut kv = vec![0.0; 2 * x.len()];
    for c in state.couplings.as_ref().expect("mortar rows") {
        let nd = 2 * c.nodes.len();
        for (a, &na) in c.nodes.iter().enumerate() {
            for i in 0..2 {
                f[2 * na + i] += c.force[2 * a + i];
                for (b, &nb) in c.nodes.iter().enumerate() {
                    for (j, vj) in v[nb].iter().enumerate() {
                        kv[2 * na + i] += c.tangent[(2 * a + i) * nd + 2 * b + j] * vj;
                    }
                }
            }
        }
    }
    let closed = res
        .iter()
        .filter(|c| c.status == ctc_engine::contact::ContactStatus::Closed)
        .count();
    (f, kv, closed)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]
    /// `K v = -(f(x + h v) - f(x - h v)) / 2h` on randomly deformed,
    /// penetrating interfaces (rotated and wavy), penalty enforcement.
    #[test]
    fn mortar_tangent_matches_finite_differences(
        seed in 0u64..1_000_000,
        depth in 0.005f64..0.05,
        angle in -0.4f64..0.4,
    ) {
        let model = mortar(penalty(1e3), 4, 3);
        let mut rng = support::Rng(seed * 2 + 1);
        let (c, s) = (angle.cos(), angle.sin());
        let x: Vec<[f64; 2]> = model
            .mesh
            .nodes
            .iter()
            .enumerate()
            .map(|(k, p)| {
                // top block pushed down into the base, both jittered
                let top = p[1] > 1.0 - 1e-12 && k >= model.bodies[1].nodes.start;
                let y = if top { p[1] - depth } else { p[1] };
                let q = [p[0] + 0.03 * rng.sym(), y + 0.01 * rng.sym()];
                [c * q[0] - s * q[1], s * q[0] + c * q[1]]
            })
            .collect();
        let v: Vec<[f64; 2]> = x.iter().map(|_| [rng.sym(), rng.sym()]).collect();
        let (_, kv, closed) = forces(&model, &x, &v);
        prop_assume!(closed > 0);
        let h = 1e-7;
        let shift = |sign: f64| -> Vec<[f64; 2]> {
            x.iter().zip(&v).map(|(p, d)| [p[0] + sign * h * d[0], p[1] + sign * h * d[1]]).collect()
        };
        let (fp, _, cp) = forces(&model, &shift(1.0), &v);
        let (fm, _, cm) = forces(&model, &shift(-1.0), &v);
        prop_assume!(cp == closed && cm == closed);
        let scale = kv.iter().fold(1.0f64, |a, b| a.max(b.abs()));
        for k in 0..kv.len() {
            let fd = -(fp[k] - fm[k]) / (2.0 * h);
            prop_assert!((fd - kv[k]).abs() <= 1e-5 * scale, "dof {k}: fd {fd} vs K v {}", kv[k]);
        }
    }
}
