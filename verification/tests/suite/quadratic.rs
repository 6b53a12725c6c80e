//! The registry entries of quadratic elements (issue 23;
//! `verification/src/programs/quadratic.rs`, where the references and
//! sketches are): `patch_quadratic` (Irons; MacNeal & Harder 1985, with the
//! quadratic fields of Strang & Fix §4.2), `lame_cylinder_quadratic`
//! (Timoshenko & Goodier §28: quad8 / tri6 against quad4 / tri3 on the same
//! meshes, rates 3 and 2 against 2 and 1) and
//! `incompressible_cylinder_quadratic` (nu = 0.4999: tet10 vs tet4, hex20
//! vs hex8).
//!
//! ```text
//!   patch: u exact on the boundary, b = -div sigma inside -> u_h = u
//!   Lame:  quarter annulus a = 1, b = 2, p = 100 on r = a
//! ```

use ctc_engine::mesh::CellKind;
use ctc_verification::programs::quadratic::plane_strain_quadratic_patch;
use ctc_verification::registry;

#[test]
fn patch_quadratic_reproduces_the_linear_and_quadratic_fields() {
    let report = registry::run_passing("patch_quadratic");
    assert_eq!(report.levels[0].values.len(), 20);
}

/// The quadratic patch can fail: without the body force the field is not
/// an equilibrium one, and the serendipity quad8 does not hold a complete
/// quadratic on distorted (non-affine) cells, while quad9 does.
#[test]
fn patch_quadratic_fails_without_body_force_and_for_quad8_on_distorted_cells() {
    let no_force = plane_strain_quadratic_patch(CellKind::Quad9, false, false).unwrap();
    assert!(no_force > 1e-3, "{no_force}");
    let quad8 = plane_strain_quadratic_patch(CellKind::Quad8, false, true).unwrap();
    assert!(quad8 > 1e-6, "{quad8}");
    let quad9 = plane_strain_quadratic_patch(CellKind::Quad9, false, true).unwrap();
    assert!(quad9 < 1e-10, "{quad9}");
    println!("no body force {no_force:.2e}, quad8 distorted {quad8:.2e}, quad9 {quad9:.2e}");
}

#[test]
fn lame_cylinder_quadratic_converges_at_order_3_in_l2_and_2_in_energy() {
    let report = registry::run_passing("lame_cylinder_quadratic");
    assert_eq!(report.levels.len(), 4);
}

#[test]
fn incompressible_cylinder_quadratic_tet10_and_hex20_do_not_lock() {
    registry::run_passing("incompressible_cylinder_quadratic");
}

/// `lame_sphere_quadratic` (`verification/src/programs/lame_sphere_quadratic.rs`,
/// Timoshenko & Goodier §137: the thick sphere octant, midside nodes on
/// the spheres): its own tolerances and rates on the default levels, and
/// the rate that the faceted sphere (straight midsides) caps at 2, against
/// ~3 with the midsides on the spheres (measured levels 1 -> 2: hex27 L2
/// 2.83 vs 2.01, tet10 2.74 vs 2.04).
#[test]
fn lame_sphere_quadratic_converges_at_order_3_and_straight_midsides_cap_it() {
    let report = registry::run_passing("lame_sphere_quadratic");
    assert_eq!(report.levels.len(), 3);
    let value = |l: usize, name: &str| {
        report.levels[l]
            .values
            .iter()
            .find(|v| v.quantity.to_string() == name)
            .unwrap_or_else(|| panic!("no {name}"))
            .computed
    };
    for kind in ["hex27", "tet10"] {
        let rate = |name: &str| (value(1, name) / value(2, name)).log2();
        let round = rate(&format!("L2(u) {kind}"));
        let flat = rate(&format!("L2(u) {kind} straight"));
        assert!(round > 2.6 && flat < 2.2, "{kind}: {round} vs {flat}");
    }
}
