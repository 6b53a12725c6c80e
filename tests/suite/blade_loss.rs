//! `examples/blade_loss.ctc` (issue 19): the catalogue case `blade_loss`
//! (`ctc_verification::programs::blade_loss`: its reference, the Jeffcott
//! rotor, Genta 2005 section 4.2, and its probe and checks are there) at
//! its level 0, the flight ended at 10 ms, run once for this test and the
//! examples test's summary ([`crate::examples::SharedRun`]); the
//! catalogue test of ctc-verification leaves the case out
//! (`registry::RUN_BY_THE_CTC_SUITE`), so `cargo test` flies it once.
//!
//! ```text
//!          casing (springs outside)
//!        .-~~~~~~~~~~~-.   0.6 mm clearance
//!      /   \   |   /    \      blade 1 (released at 6 ms) --> flies off
//!     |  ---( (o) )---   |     shaft: rigid body, k, c bearings, omega
//!      \   /   |   \    /
//!        '-~~~~~~~~~~~-'
//! ```

use crate::examples::{run_example_with, SharedRun};
use ctc_verification::programs::blade_loss::{self, Probe};
use ctc_verification::{registry, runner};
use std::sync::OnceLock;

/// The example's first 10 ms (the case's level 0), run once for this
/// file's test and the examples test ([`crate::examples::SharedRun`]).
pub(crate) fn shared_10_ms() -> &'static SharedRun<Probe> {
    static RUN: OnceLock<SharedRun<Probe>> = OnceLock::new();
    RUN.get_or_init(|| {
        let src = blade_loss::deck(0).expect("the deck");
        let model = blade_loss::model(0).unwrap_or_else(|e| panic!("{e}"));
        let probe = blade_loss::probe_of(&model).unwrap_or_else(|e| panic!("{e}"));
        run_example_with(&src.path, &model, probe)
    })
}

#[test]
fn blade_loss_whirl_friction_and_energy() {
    let model = blade_loss::model(0).unwrap_or_else(|e| panic!("{e}"));
    let run = shared_10_ms();
    let m = blade_loss::measure(&model, &run.probe, &run.summary).unwrap_or_else(|e| panic!("{e}"));
    eprintln!("blade loss: {}; {:.1} s", m.line(), run.seconds);
    for ((name, _, _), d) in run.probe.rotor.iter().zip(&run.probe.penetration) {
        eprintln!("  {name}: {d:.3e}");
    }
    // the catalogue case's checks at level 0 (`ctc verify blade_loss`)
    let case = registry::find("blade_loss").expect("the case");
    let judged = runner::judge(&case.checks, 0, m.values());
    for v in &judged {
        eprintln!(
            "  {:?}: {:.4e} (tolerance {:?})",
            v.quantity, v.error, v.tolerance
        );
    }
    let failed: Vec<_> = judged.iter().filter(|v| !v.passed).collect();
    assert!(failed.is_empty(), "{failed:#?}");
    assert_eq!(
        judged.iter().filter(|v| v.tolerance.is_some()).count(),
        case.checks.len(),
        "every check judged"
    );
    // beyond the checks: the tips rub, the released blade touches the
    // rotor, and rho_inf = 0.9 dissipates over the run (the balance
    // alone reaches 1.57e-3 of the largest K, the numerical dissipation
    // 1.42e-3, the error 2.15e-5)
    assert!(m.friction_total > 0.0, "the tips rub");
    assert!(m.p_rotor > 0.0, "the released blade touches the rotor");
    assert!(m.numerical > 0.0, "numerical dissipation {:e}", m.numerical);
    let lines = [
        format!("increments {}", m.increments),
        format!(
            "release at increment {}, first rub at increment {}, omega {:.1}",
            m.release_increment, m.first_rub, m.omega
        ),
        format!("whirl vs Jeffcott ODE until the rub: {:.1e}", m.whirl_error),
        format!("max orbit radius: {:.3}", m.radius_max),
        format!("friction work: {:.3e}", m.friction_total),
        format!("released blade root mean radius min: {:.2}", m.root_min),
        format!("released blade deepest in the rotor: {:.1e}", m.deepest),
    ];
    insta::assert_snapshot!("summary", lines.join("\n"));
}
