//! Contact on quadratic faces (issue 23;
//! `verification/src/programs/quadratic_contact.rs`, where the references
//! and sketches are): `contact_patch_quadratic` (Taylor & Papadopoulos
//! 1991: a block pressed by a rigid plane carries a uniform pressure, on
//! distorted tri6 / quad8 / quad9 / tet10 / hex20 / hex27 meshes,
//! penalty, augmented Lagrangian and Lagrange multipliers),
//! `hertz_quadratic` (Johnson, Contact
//! Mechanics §4.2-4.3: quad8 against quad4 at about equal dofs) and
//! `upsetting_quadratic` (VERIFICATION-CASES case 6 on quad8), and
//! `thermal_steady_quadratic` (steady conduction on quadratic cells).
//!
//! ```text
//!   rigid plane, u = -d t
//!   =====================
//!   |  quadratic block  |  p = E' d / (H + E'/k) at every slave node
//!   +-------------------+
//! ```

use ctc_verification::programs::quadratic_contact::hertz_work_precision;
use ctc_verification::registry;

#[test]
fn contact_patch_quadratic_gives_a_uniform_pressure_on_every_quadratic_face() {
    let report = registry::run_passing("contact_patch_quadratic");
    // 9 cell kinds x (penalty, augmented, Lagrange), and the Lagrange gap
    assert_eq!(report.levels[0].values.len(), 28);
    for v in &report.levels[0].values {
        println!("{:?}: {:.2e}", v.quantity, v.error);
    }
}

#[test]
fn upsetting_quadratic_follows_the_closed_form_on_quad8() {
    let report = registry::run_passing("upsetting_quadratic");
    for v in &report.levels[0].values {
        println!("{:?}: {:.2e}", v.quantity, v.error);
    }
}

#[test]
fn hertz_quadratic_against_linear_at_equal_dofs() {
    let report = registry::run_passing("hertz_quadratic");
    assert_eq!(report.levels.len(), 3);
}

/// The work-precision rows of the issue (times printed, not judged; the
/// errors are judged by the case's checks): `cargo test -p
/// ctc-verification --test quadratic_contact -- --nocapture work_precision`.
#[test]
fn hertz_quadratic_work_precision_table() {
    for level in 0..2 {
        for r in hertz_work_precision(level).unwrap() {
            println!(
                "level {level} {:>8} {}: {} nodes, {} dofs, {:.3} s, a {:.2e}, p0 {:.2e}, L2(p) \
                 {:.2e}",
                r.deck,
                if r.quadratic { "quad8" } else { "quad4" },
                r.nodes,
                r.dofs,
                r.seconds,
                r.errors[0],
                r.errors[1],
                r.errors[2]
            );
            assert!(
                r.errors.iter().all(|e| e.is_finite() && *e < 0.2),
                "{:?}",
                r.errors
            );
        }
    }
}

/// Steady conduction on quadratic cells (`thermal_steady_quadratic`,
/// `verification/src/programs/quadratic_thermal.rs`): a harmonic quadratic
/// temperature prescribed on the boundary is carried by every interior
/// node to round-off (Strang & Fix §4.2, scalar).
#[test]
fn thermal_steady_quadratic_is_exact_on_quadratic_cells() {
    let report = registry::run_passing("thermal_steady_quadratic");
    assert_eq!(report.levels[0].values.len(), 9);
    for v in &report.levels[0].values {
        println!("{:?}: {:.2e}", v.quantity, v.error);
    }
}

/// The 3D Hertz block on hex27 / hex20 (n/2 cells) against hex8 (n cells)
/// (`hertz_sphere_3d_quadratic`; Johnson §4.2), with the work-precision
/// rows printed (dofs, time; times are not judged).
#[test]
fn hertz_sphere_3d_quadratic_against_hex8() {
    registry::run_passing("hertz_sphere_3d_quadratic");
    for level in 0..1 {
        for (kind, n, s, seconds, values) in
            ctc_verification::programs::quadratic_contact::hertz_3d_work_precision(level).unwrap()
        {
            let errors: Vec<String> = values
                .iter()
                .map(|v| format!("{:?} {:.2e}", v.quantity, v.error))
                .collect();
            println!(
                "level {level} {} n = {n}: {} dofs, {:.2} s, {}",
                kind.name(),
                s.free_dofs,
                seconds,
                errors.join(", ")
            );
        }
    }
}

/// Coulomb friction on quadratic faces (the face-integrated return map):
/// `friction_quadratic`, the inclined plane of VERIFICATION-CASES case 4
/// (`F / G = (tan a + mu) / (1 - mu tan a)`, Wriggers, Computational
/// Contact Mechanics §5.2) on quad8 / quad9 and hex20 / hex27 / tet10,
/// the stick of a block pulled below `mu N`.
///
/// ```text
///          G
///        +-------+
///  F --> | quad8 |
///        +-------+
///   ////// tan a = 0.1, mu = 0.3 //////
/// ```
#[test]
fn friction_quadratic_slides_at_the_closed_form_and_sticks_below() {
    let report = registry::run_passing("friction_quadratic");
    assert_eq!(report.levels[0].values.len(), 8);
    for v in &report.levels[0].values {
        println!("{:?}: {:.2e}", v.quantity, v.error);
    }
}

/// `upsetting_hex20`: VERIFICATION-CASES case 6 (Simo & Hughes §9, `F =
/// tau A / h`) on hex20 and hex27 cells, the die a rigid plane on the
/// quadratic top faces (sketch in `quadratic_contact.rs`).
#[test]
fn upsetting_hex20_follows_the_closed_form() {
    let report = registry::run_passing("upsetting_hex20");
    for v in &report.levels[0].values {
        println!("{:?}: {:.2e}", v.quantity, v.error);
    }
}
