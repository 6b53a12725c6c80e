//! Johnson-Cook plasticity at the material point as `ctc verify
//! johnson_cook_uniaxial` runs it (Johnson & Cook 1983, Proc. 7th Int.
//! Symp. on Ballistics, eq. 1, OFHC copper): uniaxial compression at 1000
//! /s, the stress against (A + B ep^n)(1 + C ln rate*) at every increment,
//! and with adiabatic heating the final temperature and stress against the
//! ODE integrated finely (`verification/src/programs/johnson_cook.rs`).
//!
//! ```text
//!    uy = -0.2 at 1000 /s
//!   +-------+
//!   |  JC   |  uniaxial stress, insulated
//!   +-------+
//! ```

use ctc_verification::registry;

#[test]
fn johnson_cook_uniaxial() {
    let report = registry::run_passing("johnson_cook_uniaxial");
    assert_eq!(report.levels.len(), 3, "20, 40, 80 increments");
    // the staggered heating converges with the increment
    let t: Vec<f64> = report.levels.iter().map(|l| l.values[1].error).collect();
    assert!(t[2] < t[1] && t[1] < t[0], "{t:?}");
}
