//! VERIFICATION-CASES.md §7, penalty scaling with the mesh, as `ctc verify`
//! runs it: the registry entry `penalty_scaling`. A block pressed on a
//! rigid plane on uniform meshes h = 1/4 .. 1/32: the area penalty k
//! gives the exact uniform state `p = E (d/H) / (1 + E/(kH))`, gap `-p/k`,
//! at every h; a nodal penalty at fixed `alpha = k h0` is an area penalty
//! `alpha / h` growing as 1/h, so the gap is proportional to h and the
//! error of the pressure against rigid contact is first order in h (the
//! rate judged); `alpha = k h` keeps the gap of the area penalty
//! ("halve h, halve alpha"). Scene, references and tolerances:
//! `verification/src/programs/penalty_scaling.rs`.
//!
//! ```text
//!         u_y = -d
//!   +--------------+
//!   |    block     |  H = 1, E = 1e3, nu = 0
//!   +--------------+
//!   ////// rigid plane y = 0 //////
//! ```

use ctc_verification::registry;

#[test]
fn penalty_scaling_halve_h_halve_alpha() {
    let report = registry::run_passing("penalty_scaling");
    let judged: Vec<_> = report
        .rates
        .iter()
        .filter(|r| r.min_rate.is_some())
        .collect();
    assert_eq!(judged.len(), 2, "{:#?}", report.rates);
    for rate in judged {
        println!("{}: observed rate {:?}", rate.quantity, rate.rate);
        assert!(rate.passed, "{rate:?}");
    }
    // first order, not more: the pressure error of the fixed alpha
    let error_rate = report
        .rates
        .iter()
        .rfind(|r| r.quantity.to_string() == "alpha = k h0: |p - E d / H| / (E d / H)")
        .and_then(|r| r.rate)
        .expect("the pressure error rate");
    assert!(error_rate < 1.1, "{error_rate}");
    // the middle gap of the fixed-alpha penalty is proportional to h
    let gap = |l: usize| {
        report.levels[l]
            .values
            .iter()
            .find(|v| {
                v.quantity
                    .to_string()
                    .starts_with("alpha = k h0: middle gap")
            })
            .expect("the fixed-alpha gap")
            .computed
    };
    let (g0, g1) = (gap(0), gap(1));
    assert!((g1 / g0 - 0.5).abs() < 0.05, "gap ratio {}", g1 / g0);
}
