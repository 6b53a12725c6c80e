//! ctc against the committed FEniCSx (DOLFINx) references on identical
//! meshes (issue 9): nodal displacements, nodal contact forces and the
//! total contact force must agree to 1e-6 relative (Newton tolerance level).
//! Each test runs the registry entry of the same name (`ctc verify --tag
//! fenicsx` runs them all); the last test shows the comparison fails on a
//! perturbed reference.
//! Regenerate the references with `verification/fenicsx/regenerate.sh`.

use ctc_verification::fenicsx::{cases, compare_case, crate_dir, reference_dir, table, TOLERANCE};
use ctc_verification::registry;

/// Runs the registry entry `name` (`ctc verify --tag fenicsx` runs the
/// same): it must pass, and measure the displacement and tributary-area
/// differences.
fn check(name: &str) {
    let report = registry::run_passing(name);
    let level = report.levels.last().expect("one level");
    for q in ["max |du| / max |u|", "tributary areas"] {
        assert!(
            level.values.iter().any(|v| v.quantity.to_string() == q),
            "{name} does not measure {q}"
        );
    }
}

#[test]
fn fenicsx_rigid_cylinder() {
    check("fenicsx_rigid_cylinder");
}

#[test]
fn fenicsx_rigid_cylinder_level1() {
    check("fenicsx_rigid_cylinder_level1");
}

#[test]
fn fenicsx_lame_plane_strain() {
    check("fenicsx_lame_plane_strain");
}

#[test]
fn fenicsx_hertz_sphere_tri3() {
    check("fenicsx_hertz_sphere_tri3");
}

#[test]
fn fenicsx_patch_plane_strain_tri3() {
    check("fenicsx_patch_plane_strain_tri3");
}

#[test]
fn fenicsx_rigid_sphere_block() {
    check("fenicsx_rigid_sphere_block");
}

/// Every committed reference is a registry case tagged `fenicsx`, and each
/// has a test here.
#[test]
fn fenicsx_every_case_is_registered_and_tested() {
    let mut references: Vec<_> = cases().iter().map(|c| c.name.to_string()).collect();
    let mut registered: Vec<_> = registry::list(None, &["fenicsx".into()])
        .into_iter()
        .map(|r| r.name)
        .collect();
    references.sort();
    registered.sort();
    assert_eq!(references, registered);
    let this = include_str!("fenicsx.rs");
    for n in references {
        assert!(this.contains(&format!("fn {n}()")), "case {n} has no test");
    }
}

/// Copies the committed reference files of `name` into a temporary
/// directory, letting `edit` change the parsed reference and problem.
fn edited_copy(
    name: &str,
    edit: impl FnOnce(&mut serde_json::Value, &mut serde_json::Value),
) -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    let read = |f: &str| -> serde_json::Value {
        serde_json::from_str(&std::fs::read_to_string(reference_dir().join(f)).unwrap()).unwrap()
    };
    let mut reference = read(&format!("{name}.json"));
    let mut problem = read(&format!("{name}.problem.json"));
    edit(&mut reference, &mut problem);
    std::fs::write(
        dir.path().join(format!("{name}.json")),
        reference.to_string(),
    )
    .unwrap();
    std::fs::write(
        dir.path().join(format!("{name}.problem.json")),
        problem.to_string(),
    )
    .unwrap();
    dir
}

#[test]
fn fenicsx_comparison_detects_a_perturbed_reference() {
    let name = "fenicsx_rigid_cylinder";
    let case = cases().into_iter().find(|c| c.name == name).unwrap();
    // 1e-5 of the largest displacement (0.01) on one node's uy.
    let dir = edited_copy(name, |r, _| {
        let u = &mut r["displacement"][100][1];
        *u = serde_json::json!(u.as_f64().unwrap() + 1e-7);
    });
    let cmp = compare_case(&case, &crate_dir(), dir.path()).unwrap();
    eprint!("{}", table(std::slice::from_ref(&cmp)));
    assert!(!cmp.within(TOLERANCE), "{cmp:#?}");
    assert!(cmp.max_rel_displacement > 5e-6 && cmp.max_rel_displacement < 2e-5);
    // A stale problem export (one node moved) is refused.
    let dir = edited_copy(name, |_, p| {
        let x = &mut p["nodes"][5][0];
        *x = serde_json::json!(x.as_f64().unwrap() + 1e-3);
    });
    let err = compare_case(&case, &crate_dir(), dir.path()).unwrap_err();
    assert!(err.contains("regenerate"), "{err}");
}
