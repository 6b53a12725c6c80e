//! The registry entry `traction_patch_3d`
//! (`verification/src/programs/traction_3d.rs`, where its reference and
//! sketch are): pure shear tractions `t = sigma n` on the faces of a graded
//! brick, selected in the deck by `faces(z = ..)` / `faces(x = ..)`, give the
//! uniform stress `sigma_xz = tau` and the linear field `u = (gamma z, 0, 0)`
//! to round-off for hex8 and tet4, and the top face carries `tau x area`.
//!
//! ```text
//!   t = (tau, 0, 0) on top, (0, 0, +-tau) on x = 2 / x = 0, base held
//! ```

use ctc_verification::registry;

#[test]
fn traction_patch_3d_gives_the_uniform_shear_state() {
    let report = registry::run_passing("traction_patch_3d");
    let level = report.levels.last().expect("one level");
    assert_eq!(level.values.len(), 6);
}

/// The patch is not trivially satisfied: with the side tractions left out,
/// the stress is no longer uniform (so the check can fail).
#[test]
fn traction_patch_3d_without_the_side_tractions_is_not_uniform() {
    let deck = ctc_verification::programs::traction_3d::deck("hex8");
    let cut: String = deck
        .lines()
        .filter(|l| !l.contains("faces(x ="))
        .map(|l| format!("{l}\n"))
        .collect();
    assert_ne!(cut, deck);
    let src = ctc_lang::Source::new("cut.ctc", cut);
    let Ok(ctc_engine::model::AnyModel::D3(model)) = ctc_lang::compile_any(&src) else {
        panic!("the cut deck compiles");
    };
    let mut last = ctc_engine::testkit::solid::Last::default();
    ctc_engine::solve::run(&model, &mut last).expect("runs");
    let s = ctc_engine::testkit::solid::states(&model, &last).expect("states");
    let (lo, hi) = s
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
            (lo.min(p.stress[4]), hi.max(p.stress[4]))
        });
    assert!(hi - lo > 1.0, "sigma_xz spread {lo} .. {hi}");
}
