//! Dynamic axial buckling of a steel tube (Alexander 1960, Q. J. Mech.
//! Appl. Math. 13:10; Abramowicz & Jones 1984, Int. J. Impact Engng
//! 2:263): a tube carrying a 20 kg striker hits a rigid die at 10 m/s and
//! folds in the concertina mode; the folds close on themselves (self
//! contact of the wall's inner and outer faces), the end rubs on the die
//! (Coulomb friction). Scene, references and tolerances:
//! `verification/src/programs/dynamic_buckling.rs`.
//!
//! ```text
//!        striker M, v0
//!        ___|___
//!       |       |          )   a fold: the wall bulges out and its
//!       |       |          )   inner face closes on itself
//!   ====|=======|====  rigid die, mu = 0.2
//! ```

use ctc_verification::registry;

#[test]
fn dynamic_buckling_tube_axi() {
    let report = registry::run_passing("dynamic_buckling_tube_axi");
    let values = &report.levels[0].values;
    // a fold formed and closed on its inner face, friction did work, the
    // striker stopped within the tube's length
    assert!(values[0].computed >= 1.0, "{values:?}");
    assert!(values[8].computed > 0.0, "friction work: {values:?}");
    assert!(values[10].computed < 1.0, "crush / L: {values:?}");
    assert!(report.levels[0].cutbacks <= 2, "{:?}", report.levels[0]);
}
