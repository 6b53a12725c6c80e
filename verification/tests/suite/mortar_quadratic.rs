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
