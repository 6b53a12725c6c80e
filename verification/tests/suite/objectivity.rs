//! Objectivity of the 2D finite-strain kernels (VERIFICATION-CASES case 6,
//! last item) as `ctc verify` runs it: the registry entry
//! `objectivity_plane_strain`. A body pre-stressed by the homogeneous
//! stretch `F0` (plastic for J2) is rotated rigidly by 90 degrees in 3 and
//! 9 increments; the Cauchy stress must be `R sigma0 R^T` (xx and yy
//! swapped, xy negated) to 1e-9 of |sigma0|, its invariants unchanged, and
//! the rotation must create no plastic strain (1e-12), for the
//! neo-Hookean, Hencky and J2 (Swift) laws. Scene, reference and
//! tolerances: `verification/src/programs/objectivity.rs` (Simo & Hughes,
//! Computational Inelasticity §9).
//!
//! ```text
//!    y                      after 90 degrees:
//!    ^  +-----+               +--+
//!    |  |  F0 |  --R(90)-->   |  |
//!    |  +-----+               |  |
//!    +--1-----2--> x          +--+
//! ```

use ctc_verification::registry;

#[test]
fn finite_objectivity_rigid_rotation_of_prestressed_body_90_degrees() {
    let report = registry::run_passing("objectivity_plane_strain");
    assert_eq!(report.levels.len(), 2, "3 and 9 rotation increments");
    for level in &report.levels {
        for q in [
            "neo-Hookean: |sigma - R sigma0 R^T| / |sigma0|",
            "Hencky: |sigma - R sigma0 R^T| / |sigma0|",
            "J2 Swift: |sigma - R sigma0 R^T| / |sigma0|",
            "J2 Swift: ep change",
        ] {
            assert!(
                level.values.iter().any(|v| v.quantity.to_string() == q),
                "level {} does not measure {q}",
                level.level
            );
        }
    }
}
