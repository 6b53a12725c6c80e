//! Tube hydroforming before die contact, open and closed ends (`ctc
//! verify tube_hydroforming_free_bulge`, `..._closed`;
//! `verification/src/programs/tube_bulge.rs`): a quarter slice of a long
//! thin tube (r0 = 20, t0 = 1, Swift hardening) under internal pressure;
//! the end cap's load `p pi ri^2` of a closed tube makes the wall biaxial
//! and raises both the yield and the free-bulge pressure. Sources: R. Hill,
//! The Mathematical Theory of Plasticity (1950) ch. V; Z. Marciniak, J. L.
//! Duncan, S. J. Hu, Mechanics of Sheet Metal Forming (2002) ch. 7.
//!
//! ```text
//!   open:   sigma_z = 0            p_y = sigma_y t/r,  p_max = K (2n/3)^n ..
//!   closed: sigma_z = sigma_th/2   p_y = (2/sqrt 3) sigma_y t/r,
//!           (cap load p pi ri^2)   p_max = (2/sqrt 3) K (n/sqrt 3)^n ..
//! ```

use ctc_verification::registry;
use ctc_verification::report::CaseReport;

fn value(report: &CaseReport, prefix: &str) -> f64 {
    report.levels[0]
        .values
        .iter()
        .find(|v| v.quantity.to_string().starts_with(prefix))
        .unwrap_or_else(|| panic!("no value `{prefix}`"))
        .computed
}

#[test]
fn closed_ends_raise_the_yield_and_bulge_pressures_as_the_membrane_says() {
    let open = registry::run_passing("tube_hydroforming_free_bulge");
    let closed = registry::run_passing("tube_hydroforming_free_bulge_closed");
    // first yield: Lamé's closed / open ratio at the inner fibre is
    // sqrt(1 + 3 (ro/ri)^4) / (sqrt 3 (ro/ri)^2) = 1.1282; the FE's 1.1339
    // (level 0, the yielding point inside the first cell; measured by this
    // test) within 1 %
    let ratio = value(
        &closed,
        "closed ends, initial yield: FE first-yield pressure vs Lame",
    ) / value(&open, "initial yield: FE first-yield pressure vs Lame");
    let q = (20.5f64 / 19.5).powi(2);
    let lame = (1.0 + 3.0 * q * q).sqrt() / (3f64.sqrt() * q);
    assert!((ratio / lame - 1.0).abs() < 1e-2, "{ratio} vs {lame}");
    // free bulge: the membrane ratio (2/sqrt 3) (sqrt 3/2)^n exp((sqrt 3 -
    // 3/2) eps0) = 1.1247; the FE's 1.1149 (level 0, measured by
    // this test: the open run sits 0.6 % above its membrane by the thick
    // wall, the closed 0.3 % below by the elastic strains) within 1.5 %
    let ratio = value(
        &closed,
        "closed ends, free bulge: maximum pressure vs membrane",
    ) / value(&open, "free bulge: maximum pressure vs membrane");
    let n = 0.2f64;
    let membrane =
        2.0 / 3f64.sqrt() * (0.5 * 3f64.sqrt()).powf(n) * ((3f64.sqrt() - 1.5) * 0.01).exp();
    assert!(
        (ratio / membrane - 1.0).abs() < 1.5e-2,
        "{ratio} vs {membrane}"
    );
    // the closed tube bulges at a smaller strain (n/2 vs 2n/3)
    let (eo, ec) = (
        value(&open, "free bulge: hoop strain at the maximum"),
        value(
            &closed,
            "closed ends, free bulge: hoop strain at the maximum vs membrane",
        ),
    );
    assert!(ec < 0.8 * eo, "{ec} vs {eo}");
}
