//! 3D contact with rigid surface tools as `ctc verify` runs it: the
//! registry entries `contact_patch_3d` (the contact patch test of Taylor &
//! Papadopoulos 1991 in 3D: uniform pressure to round-off for penalty,
//! Lagrange multipliers and augmented Lagrangian, hex8 and tet4, and a
//! plane brought to its place by a rigid rotation) and `hertz_sphere_3d`
//! (Hertz point contact, K. L. Johnson, Contact Mechanics §4.2: peak
//! pressure and profile against Hertz at the force the model carries).
//! Scenes, references and tolerances:
//! `verification/src/programs/contact_3d.rs`.
//!
//! ```text
//!   rigid plane / rigid sphere, lowered by 0.01
//!   ======================        .-"""-.
//!   |  block 1 x 1 x 1   |   _____/_______\_____
//!   |____________________|   | quarter block |
//! ```

use ctc_verification::registry;

#[test]
fn contact_patch_3d_is_uniform_to_round_off() {
    let report = registry::run_passing("contact_patch_3d");
    let level = report.levels.last().expect("one level");
    let spread = level
        .values
        .iter()
        .find(|v| v.quantity.to_string() == "pressure spread")
        .expect("the spread is measured");
    assert!(spread.error < 1e-10, "{spread:?}");
}

#[test]
fn hertz_sphere_3d_peak_pressure_converges_to_hertz() {
    let report = registry::run_passing("hertz_sphere_3d");
    let p0: Vec<f64> = report
        .levels
        .iter()
        .map(|l| {
            l.values
                .iter()
                .find(|v| v.quantity.to_string() == "p0 vs Hertz(P)")
                .expect("p0 is measured")
                .error
        })
        .collect();
    assert_eq!(p0.len(), 2, "two default levels");
    assert!(
        p0[1] < p0[0],
        "the peak pressure error must fall with refinement: {p0:?}"
    );
}

#[test]
fn cad_patch_3d_nurbs_face_is_exact_and_the_hole_is_free() {
    registry::run_passing("cad_patch_3d");
}

#[test]
fn cad_sphere_3d_matches_the_analytical_sphere() {
    registry::run_passing("cad_sphere_3d");
}

/// `stl_sphere_3d`: the STL sphere's force and peak pressure approach the
/// analytical sphere's as the facets shrink, at second order in the facet
/// size (the chords' sagitta).
#[test]
fn stl_sphere_3d_converges_to_the_analytical_sphere() {
    let report = registry::run_passing("stl_sphere_3d");
    for l in &report.levels {
        for v in &l.values {
            eprintln!("level {} h {:.4e} {}: {:.3e}", l.level, l.h, v.quantity, v.error);
        }
    }
    assert_eq!(report.levels.len(), 3, "three default levels");
}
