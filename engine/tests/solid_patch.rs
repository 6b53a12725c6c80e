//! Solid (3D) runs through the dimension-generic solver: the scenes of
//! `ctc_engine::testkit::solid` (their references and sketches are there;
//! `ctc verify --tag 3d` runs the same functions as `patch_3d` and
//! `objectivity_3d`).
//!
//! Patch tests (Irons; MacNeal and Harder, FEAD 1 (1985)): a linear field
//! `u = b + A x` prescribed on the boundary of a distorted 3 x 3 x 3 brick
//! is reproduced at the interior nodes with the same stress at every
//! integration point, for tet4 and hex8 (full, B-bar / F-bar) and every law
//! (small strain: linear elastic and J2 plastic; finite strain: Neo-Hooke
//! and J2 multiplicative).
//!
//! ```text
//!   z
//!   |  3 x 3 x 3 cells on [0,1] x [0,2] x [0,1.5], the 8 interior nodes
//!   | /y   moved by up to 0.12 h in every direction
//!   |/___ x   boundary nodes: u = b + A x (all three components)
//! ```
//!
//! Objectivity (finite strain): a block stretched homogeneously (step 1,
//! past yield for J2) then rotated rigidly by 90 degrees about the axis
//! `(1, 2, 3) / |..|` (step 2, in 4 increments): the Cauchy stress must be
//! `R sigma_0 R^T` and the plastic strain unchanged.
//!
//! Determinism and restart: the same model twice gives bit-identical
//! results; a run restarted from the checkpoint of increment 1 ends bit for
//! bit where the uninterrupted one ends.

use ctc_engine::mesh::CellKind;
use ctc_engine::model::*;
use ctc_engine::solve::{run, run_from};
use ctc_engine::testkit::solid::{
    linear_stress, objectivity, patch, patch_model, plastic, Last, A_FINITE, A_SMALL, E, NU,
};

#[test]
fn solid_patch_linear_elastic_tet4_and_hex8_reproduce_the_exact_stress() {
    let law = MaterialLaw::LinearElastic {
        young: E,
        poisson: NU,
    };
    let exact = linear_stress(E, NU, &A_SMALL);
    for (kind, f) in [
        (CellKind::Tet4, Formulation::Full),
        (CellKind::Hex8, Formulation::Full),
        (CellKind::Hex8, Formulation::SelectiveReduced),
    ] {
        let p = patch(kind, law.clone(), f, Kinematics::Small, &A_SMALL).unwrap();
        let serr = p.stress_error(&exact);
        println!(
            "patch linear {kind:?} {f:?}: u error {:.2e}, stress error {serr:.2e}",
            p.u_error
        );
        assert!(
            p.u_error <= 1e-10 && serr <= 1e-10 && p.stress_spread <= 1e-10,
            "{kind:?} {f:?}"
        );
    }
}

#[test]
fn solid_patch_j2_small_strain_yields_uniformly() {
    for (kind, f) in [
        (CellKind::Tet4, Formulation::Full),
        (CellKind::Hex8, Formulation::Full),
        (CellKind::Hex8, Formulation::SelectiveReduced),
    ] {
        let p = patch(kind, plastic(), f, Kinematics::Small, &A_SMALL).unwrap();
        println!(
            "patch J2 small {kind:?} {f:?}: u error {:.2e}, stress spread {:.2e}",
            p.u_error, p.stress_spread
        );
        assert!(p.u_error <= 1e-10 && p.stress_spread <= 1e-10, "{kind:?}");
        // the patch is plastic: the law's yield was crossed
        assert!(p.mises() > 100.0);
    }
}

#[test]
fn solid_patch_finite_strain_neo_hooke_and_j2_are_homogeneous() {
    let neo = MaterialLaw::NeoHookean {
        young: 10.0,
        poisson: 0.45,
    };
    for (kind, f, law) in [
        (CellKind::Tet4, Formulation::Full, neo.clone()),
        (CellKind::Hex8, Formulation::Full, neo.clone()),
        (CellKind::Hex8, Formulation::SelectiveReduced, neo),
        (CellKind::Tet4, Formulation::Full, plastic()),
        (CellKind::Hex8, Formulation::Full, plastic()),
        (CellKind::Hex8, Formulation::SelectiveReduced, plastic()),
    ] {
        let p = patch(kind, law, f, Kinematics::Finite, &A_FINITE).unwrap();
        println!(
            "patch finite {kind:?} {f:?}: u error {:.2e}, stress spread {:.2e}",
            p.u_error, p.stress_spread
        );
        assert!(
            p.u_error <= 1e-10 && p.stress_spread <= 1e-10,
            "{kind:?} {f:?}"
        );
    }
}

#[test]
fn solid_objectivity_rotation_of_a_prestressed_block_by_90_degrees() {
    for (kind, law, f) in [
        (
            CellKind::Hex8,
            MaterialLaw::NeoHookean {
                young: 10.0,
                poisson: 0.3,
            },
            Formulation::Full,
        ),
        (CellKind::Tet4, plastic(), Formulation::Full),
        (CellKind::Hex8, plastic(), Formulation::SelectiveReduced),
    ] {
        let o = objectivity(kind, law, f).unwrap();
        println!(
            "objectivity {kind:?} {f:?}: |sigma - R sigma0 R^T| / |sigma0| = {:.2e}, max ep change {:.2e}, ep {:.3e}",
            o.stress, o.plastic_change, o.plastic
        );
        assert!(o.stress <= 1e-12, "{kind:?}: {o:?}");
        assert!(o.plastic_change <= 1e-12, "{kind:?}: {o:?}");
    }
    // the J2 scenes are plastic (else "ep unchanged" says nothing)
    assert!(
        objectivity(CellKind::Tet4, plastic(), Formulation::Full)
            .unwrap()
            .plastic
            > 1e-3
    );
}

#[test]
fn solid_runs_are_deterministic_and_restart_bit_for_bit() {
    // J2 finite strain on the distorted tet4 patch, loaded in 3 increments
    let a = [[0.04, 0.01, 0.0], [0.0, -0.02, 0.01], [0.01, 0.0, 0.03]];
    let mut model = patch_model(
        CellKind::Tet4,
        plastic(),
        Formulation::Full,
        Kinematics::Finite,
        &a,
    );
    for d in &mut model.constraints {
        let TimeFunction::Constant(v) = d.value else {
            unreachable!()
        };
        d.value = TimeFunction::Ramp {
            t0: 0.0,
            t1: 1.0,
            v0: 0.0,
            v1: v,
        };
    }
    model.steps[0].increments = 3;
    let bits = |l: &Last| -> Vec<u64> {
        l.u.iter()
            .flatten()
            .copied()
            .chain(
                l.points
                    .iter()
                    .flatten()
                    .flat_map(|p| p.state.stress.iter().copied()),
            )
            .map(f64::to_bits)
            .collect()
    };
    let mut first = Last {
        want_checkpoints: true,
        ..Default::default()
    };
    run(&model, &mut first).unwrap();
    let mut second = Last::default();
    run(&model, &mut second).unwrap();
    assert_eq!(bits(&first), bits(&second));
    assert_eq!(first.checkpoints.len(), 3);
    let mut rest = Last::default();
    run_from(&model, &mut rest, Some(&first.checkpoints[0])).unwrap();
    assert_eq!(bits(&first), bits(&rest));
}

/// Patch test (Irons; MacNeal and Harder 1985) on quadratic cells: the
/// distorted 3 x 3 x 3 brick of the linear patch, elevated to tet10, hex20,
/// hex20r and hex27 (straight edges, midpoints where the distorted linear
/// map puts them), `u = b + A x` on every boundary node: the interior
/// nodes (corner, midside, face and body) and the stress at every
/// integration point are exact to 1e-10.
#[test]
fn solid_patch_linear_elastic_quadratic_cells_reproduce_the_exact_stress() {
    use ctc_engine::mesh::elevate::elevate;
    use ctc_engine::testkit::solid::distorted;
    let law = MaterialLaw::LinearElastic {
        young: E,
        poisson: NU,
    };
    let exact = linear_stress(E, NU, &A_SMALL);
    for (linear, kind, f) in [
        (CellKind::Tet4, CellKind::Tet10, Formulation::Full),
        (CellKind::Hex8, CellKind::Hex20, Formulation::Full),
        (
            CellKind::Hex8,
            CellKind::Hex20,
            Formulation::SelectiveReduced,
        ),
        (CellKind::Hex8, CellKind::Hex20R, Formulation::Full),
        (CellKind::Hex8, CellKind::Hex27, Formulation::Full),
    ] {
        let mesh = elevate(&distorted(linear), kind).unwrap();
        let p =
            ctc_engine::testkit::solid::patch_on(mesh, law.clone(), f, Kinematics::Small, &A_SMALL)
                .unwrap();
        let serr = p.stress_error(&exact);
        println!(
            "patch linear {kind:?} {f:?}: u error {:.2e}, stress error {serr:.2e}",
            p.u_error
        );
        assert!(
            p.u_error <= 1e-10 && serr <= 1e-10 && p.stress_spread <= 1e-10,
            "{kind:?} {f:?}: {} {serr} {}",
            p.u_error,
            p.stress_spread
        );
    }
}

/// The quadratic patch (as above) with the nonlinear laws: J2 small strain
/// past yield, Neo-Hooke and J2 multiplicative at finite strain (F-bar on
/// hex20): the same homogeneous field everywhere to 1e-10.
#[test]
fn solid_patch_quadratic_cells_nonlinear_laws_are_homogeneous() {
    use ctc_engine::mesh::elevate::elevate;
    use ctc_engine::testkit::solid::{distorted, patch_on};
    let neo = MaterialLaw::NeoHookean {
        young: 10.0,
        poisson: 0.45,
    };
    for (linear, kind, f) in [
        (CellKind::Tet4, CellKind::Tet10, Formulation::Full),
        (
            CellKind::Hex8,
            CellKind::Hex20,
            Formulation::SelectiveReduced,
        ),
        (CellKind::Hex8, CellKind::Hex20R, Formulation::Full),
    ] {
        let mesh = elevate(&distorted(linear), kind).unwrap();
        let runs = [
            (plastic(), Kinematics::Small, &A_SMALL),
            (neo.clone(), Kinematics::Finite, &A_FINITE),
            (plastic(), Kinematics::Finite, &A_FINITE),
        ];
        for (law, kinematics, a) in runs {
            let p = patch_on(mesh.clone(), law, f, kinematics, a).unwrap();
            println!(
                "patch {kinematics:?} {kind:?} {f:?}: u error {:.2e}, stress spread {:.2e}",
                p.u_error, p.stress_spread
            );
            assert!(
                p.u_error <= 1e-10 && p.stress_spread <= 1e-10,
                "{kind:?} {f:?} {kinematics:?}"
            );
        }
    }
}
