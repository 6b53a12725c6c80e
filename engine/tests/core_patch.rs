//! Patch tests: a constant-strain displacement field prescribed on the
//! boundary of a distorted mesh must be reproduced exactly (to round-off)
//! at the interior nodes and in the stresses, for every element, formulation
//! and 2D kind. Axisymmetric: `u_r = c r`, `u_z = d z + e` (constant
//! strain `eps_rr = eps_tt = c`, `eps_zz = d`; a constant shear `gamma_rz`
//! is *not* an equilibrium state there: `d sigma_rz / dr + sigma_rz / r != 0`).

mod support;

use ctc_engine::element::recovery::{blocks_of, cell_states, nodal_fields_of_model};
use ctc_engine::element::Section;
use ctc_engine::material::{Constitutive, Strain};
use ctc_engine::model::*;
use ctc_engine::solve::run;
use support::*;

#[derive(Clone, Copy)]
enum Element {
    Tri3,
    Quad4(Formulation),
}

/// Exact displacement and strain `[xx, yy, zz, xy]` of the patch field.
fn exact(kind: AnalysisKind, p: [f64; 2]) -> ([f64; 2], [f64; 4]) {
    let [x, y] = p;
    match kind {
        AnalysisKind::Axisymmetric => {
            let (c, d, e) = (1e-3, -2e-3, 0.5e-3);
            ([c * x, d * y + e], [c, d, c, 0.0])
        }
        _ => {
            let (a0, a1, a2) = (1e-3, 2e-3, -1e-3);
            let (b0, b1, b2) = (-2e-3, 1.5e-3, -3e-3);
            (
                [a0 + a1 * x + a2 * y, b0 + b1 * x + b2 * y],
                [a1, b2, 0.0, a2 + b1],
            )
        }
    }
}

/// Runs the patch test; returns (max relative displacement error at interior
/// nodes, max relative stress error at integration points, at nodes).
fn patch(kind: AnalysisKind, element: Element) -> (f64, f64, f64) {
    let (nx, ny) = (4, 4);
    // axisymmetric: r in [0, 2] (boundary nodes on the axis), plane: offset box
    let origin = if kind == AnalysisKind::Axisymmetric {
        [0.0, -1.0]
    } else {
        [0.5, -1.0]
    };
    let (tri, formulation) = match element {
        Element::Tri3 => (true, Formulation::Full),
        Element::Quad4(f) => (false, f),
    };
    let mesh = grid(nx, ny, origin, [2.0, 2.0], 0.3, 0x9e3779b97f4a7c15, tri);
    let mut model = one_body(kind, mesh, 210e3, 0.3, formulation);
    model.analysis.thickness = 0.7;
    let boundary = grid_boundary(nx, ny);
    for &n in &boundary {
        let (u, _) = exact(kind, model.mesh.nodes[n]);
        model.constraints.push(fix(vec![n], 0, u[0]));
        model.constraints.push(fix(vec![n], 1, u[1]));
    }
    let mut rec = Recorder::default();
    let summary = run(&model, &mut rec).expect("patch test run");
    assert_eq!(summary.increments.len(), 1);
    assert_eq!(summary.increments[0].iterations, 1, "linear: one iteration");
    let u = &rec.increments[0].displacement;

    let umax = model
        .mesh
        .nodes
        .iter()
        .map(|&p| exact(kind, p).0.iter().fold(0.0f64, |m, v| m.max(v.abs())))
        .fold(0.0, f64::max);
    let mut u_err = 0.0f64;
    for (n, &p) in model.mesh.nodes.iter().enumerate() {
        if boundary.contains(&n) {
            continue;
        }
        let (ue, _) = exact(kind, p);
        u_err = u_err.max((u[n][0] - ue[0]).abs().max((u[n][1] - ue[1]).abs()) / umax);
    }

    let blocks = blocks_of(&model).unwrap();
    let law = &blocks[0].law;
    let (_, eps) = exact(kind, [1.0, 0.0]);
    let eps = Strain::from([eps[0], eps[1], eps[2], eps[3], 0.0, 0.0]);
    let sigma = law.stress(&eps);
    let full_eps = law.complete_strain(&eps);
    let smax = sigma.amax();
    let section = Section::new(&model.analysis);
    let mut s_err = 0.0f64;
    for c in 0..model.mesh.cells.len() {
        for st in cell_states(&model.mesh, c, u, &section, &blocks[0]).unwrap() {
            s_err = s_err.max((st.stress - sigma).amax() / smax);
            s_err = s_err.max((st.strain - full_eps).amax() / full_eps.amax());
        }
    }
    let fields = nodal_fields_of_model(&model, u).unwrap();
    let mut n_err = 0.0f64;
    for n in 0..model.mesh.nodes.len() {
        for k in 0..4 {
            n_err = n_err.max((fields.stress[n][k] - sigma[k]).abs() / smax);
        }
    }
    // equilibrium of reactions along y (z): no external load
    let ry: f64 = rec.increments[0].reaction.iter().map(|r| r[1]).sum();
    let rmax = rec.increments[0]
        .reaction
        .iter()
        .fold(0.0f64, |m, r| m.max(r[1].abs()));
    assert!(ry.abs() <= 1e-10 * rmax, "reaction sum {ry} (max {rmax})");
    println!(
        "patch {kind:?} {}: u error {u_err:.2e}, point stress/strain error {s_err:.2e}, \
         nodal stress error {n_err:.2e}",
        match element {
            Element::Tri3 => "tri3".to_string(),
            Element::Quad4(f) => format!("quad4 {f:?}"),
        }
    );
    (u_err, s_err, n_err)
}

fn assert_patch(kind: AnalysisKind, element: Element) {
    let (u, s, n) = patch(kind, element);
    assert!(u <= 1e-10, "displacement error {u:e}");
    assert!(s <= 1e-10, "integration point stress error {s:e}");
    assert!(n <= 1e-10, "nodal stress error {n:e}");
}

#[test]
fn patch_test_plane_strain_distorted_tris() {
    assert_patch(AnalysisKind::PlaneStrain, Element::Tri3);
}

#[test]
fn patch_test_plane_strain_distorted_quads() {
    assert_patch(AnalysisKind::PlaneStrain, Element::Quad4(Formulation::Full));
}

#[test]
fn patch_test_plane_strain_distorted_quads_selective_reduced() {
    assert_patch(
        AnalysisKind::PlaneStrain,
        Element::Quad4(Formulation::SelectiveReduced),
    );
}

#[test]
fn patch_test_plane_stress_distorted_tris() {
    assert_patch(AnalysisKind::PlaneStress, Element::Tri3);
}

#[test]
fn patch_test_plane_stress_distorted_quads() {
    assert_patch(AnalysisKind::PlaneStress, Element::Quad4(Formulation::Full));
}

#[test]
fn patch_test_plane_stress_distorted_quads_selective_reduced() {
    assert_patch(
        AnalysisKind::PlaneStress,
        Element::Quad4(Formulation::SelectiveReduced),
    );
}

#[test]
fn patch_test_axisymmetric_distorted_tris() {
    assert_patch(AnalysisKind::Axisymmetric, Element::Tri3);
}

#[test]
fn patch_test_axisymmetric_distorted_quads() {
    assert_patch(
        AnalysisKind::Axisymmetric,
        Element::Quad4(Formulation::Full),
    );
}

#[test]
fn patch_test_axisymmetric_distorted_quads_selective_reduced() {
    assert_patch(
        AnalysisKind::Axisymmetric,
        Element::Quad4(Formulation::SelectiveReduced),
    );
}
