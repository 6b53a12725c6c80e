//! Mortar contact between deformable bodies on quadratic faces (issues 23
//! and 18; `verification/src/programs/mortar_quadratic.rs`, where the
//! references and sketches are): `contact_patch_mortar_quadratic` (Taylor
//! & Papadopoulos, IJNME 31 (1991) 2205: two blocks with non-matching
//! quad8 / quad9 / tri6 meshes across the interface carry a uniform
//! pressure, plane strain and axisymmetric, penalty, augmented Lagrangian
//! and Lagrange multipliers) and `hertz_two_cylinders_mortar_quadratic`
//! (Johnson, Contact Mechanics §4.3: quad8 seg3 mortar against quad4
//! mortar at about equal dofs).
//!
//! ```text
//!   top block  (3 | 5 quadratic cells across), pushed down
//!   ---------- non-matching interface, seg3 mortar ----------
//!   base block (4 | 7 quadratic cells across), bottom fixed
//! ```

use ctc_verification::registry;

#[test]
fn contact_patch_mortar_quadratic_gives_a_uniform_pressure() {
    let report = registry::run_passing("contact_patch_mortar_quadratic");
    // 10 runs x (deviation from uniform, mean against the closed form), both levels
    assert_eq!(report.levels.len(), 2);
    for level in &report.levels {
        assert_eq!(level.values.len(), 20);
        for v in &level.values {
            assert!(v.error < 1e-8, "{:?}: {:.2e}", v.quantity, v.error);
        }
    }
}

#[test]
fn hertz_two_cylinders_mortar_quadratic_meets_hertz() {
    let report = registry::run_passing("hertz_two_cylinders_mortar_quadratic");
    for v in &report.levels[0].values {
        println!("{:?}: {:.2e}", v.quantity, v.error);
    }
}

/// The frictional patch test on quadratic faces (`ctc verify
/// contact_patch_friction_quadratic`; Taylor & Papadopoulos, IJNME 31
/// (1991) 2205; Gitterle, Popp, Gee & Wall, IJNME 84 (2010) 543;
/// `verification/src/programs/mortar_quadratic_friction.rs`): a quad8 block
/// pressed on and pushed along a quad8 block (3 | 4 cells across, seg3
/// mortar), below `mu N` every node sticks and the shear is carried, past
/// it every node slips on the cone and the friction work is `mu N` times
/// the slide; every value within its tolerance (0.4 s debug).
///
/// ```text
///   top  quad8 3 x 2, u = (delta, -d) on top
///   ---- slave top.bottom (seg3) / master base.top, mu = 0.3 ----
///   base quad8 4 x 2, fixed bottom; side tractions of the uniform state
/// ```
#[test]
fn contact_patch_friction_quadratic_passes() {
    let report = registry::run_passing("contact_patch_friction_quadratic");
    assert_eq!(report.levels[0].values.len(), 7);
}
