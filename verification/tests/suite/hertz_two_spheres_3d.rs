//! `hertz_two_spheres_3d` (issue 18): Hertz between two elastic bodies in
//! 3D on non-matching hex8 meshes, as `ctc verify hertz_two_spheres_3d`
//! runs it (level 0; levels 1 and 2 with `--max-level 2`).
//!
//! Five variants: mortar (penalty, Lagrange), node-to-facet single pass,
//! modified double pass faceted and on Nagata patches.
//!
//! Source: K. L. Johnson, Contact Mechanics (1985) §4.2, two spheres of
//! radius R = 2 (R* = 1), E = 1000, nu = 0.3 on both sides (E* = E /
//! (2 (1 - nu^2))), Hertz at the carried load; the program is
//! `verification/src/programs/hertz_two_spheres_3d.rs`.
//!
//! ```text
//!   top body  (slave zmin, graded 20)   u_z = -0.01 on its top
//!        \___   ___/
//!            \_/      spheres touching at the origin, quarter models
//!            / \
//!    ___/   \___
//!   bottom body (master zmax, graded 30), u_z = 0 on its bottom
//! ```

use ctc_verification::registry;

#[test]
fn hertz_two_spheres_3d_meets_its_tolerances_at_level_0() {
    let report = registry::run_passing("hertz_two_spheres_3d");
    let values = &report.levels[0].values;
    let get = |name: &str| {
        values
            .iter()
            .find(|v| v.quantity.to_string() == name)
            .unwrap_or_else(|| panic!("no value {name}"))
            .error
    };
    // every variant measured: a, a (moment), p0, L2, balance, iterations
    assert_eq!(values.len(), 30);
    for variant in [
        "mortar",
        "mortar lagrange",
        "node-to-facet",
        "node-to-facet modified double pass",
        "node-to-facet modified double pass nagata",
    ] {
        assert!(get(&format!("force balance {variant}")) < 1e-7);
        assert!(get(&format!("Newton iterations {variant}")) >= 4.0);
    }
}
