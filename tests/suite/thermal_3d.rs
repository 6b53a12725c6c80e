//! Heat and thermo-mechanics in 3D (issue 15) as `ctc verify` runs them:
//! the registry entries of `verification/src/programs/thermal_3d.rs`, which
//! open with their references and sketches (Incropera & DeWitt §3.1,
//! Carslaw & Jaeger §3.3, Timoshenko & Goodier §150, VERIFICATION-CASES.md
//! §8, Simo & Hughes §2.3), judged against their tolerances.
//!
//! ```text
//!   T0 +--------+ h, T_inf      brick on a hot/cold rigid plane tool:
//!      |  k     |               q = (T_hot - T_tool) / (L/k + 1/h(p))
//!      +--------+
//! ```

use ctc_verification::registry;

/// Runs the registry case `name` (every level) and asserts it passes.
fn passes(name: &str) {
    registry::run_passing(name);
}

#[test]
fn steady_conduction_3d_is_exact_on_tet4_and_distorted_hex8() {
    passes("thermal_steady_3d");
}

#[test]
fn transient_conduction_3d_converges_to_the_slab_series() {
    passes("thermal_transient_3d");
}

#[test]
fn thermal_expansion_3d_free_and_held_bricks() {
    passes("thermal_expansion_3d");
}

#[test]
fn thermal_contact_with_a_3d_rigid_tool_matches_closed_form_and_2d() {
    passes("thermal_contact_tool_3d");
}

#[test]
fn adiabatic_heating_3d_matches_beta_w_and_the_axisymmetric_run() {
    passes("adiabatic_heating_3d");
}

/// Runs a 3D deck whose body is the unit brick of 2 x 2 x 2 hex8 heated
/// uniformly from 20 to 120 (E = 200e3, nu = 0.3, alpha = 1e-5) with the
/// supports `fixes`, and returns every nodal and cell stress of the VTU.
fn heated_brick_stresses(fixes: &str) -> Vec<[f64; 6]> {
    use ctc_engine::output::vtu_read::Vtu;
    let deck = format!(
        "analysis {{ dimension = 3d }}
material m {{
  elastic {{ E = 200e3  nu = 0.3 }}
  thermal {{ conductivity = 50  capacity = 4.6e8  density = 7.85e-9  expansion = 1e-5  reference = 20 }}
}}
body b {{
  mesh = box {{ size = (1, 1, 1)  divisions = (2, 2, 2) }}
  material = m
  thermal {{ initial = 120 }}
}}
{fixes}
step s {{ time = 0 .. 1  increments = 1 }}
output {{ fields = [displacement, stress] }}
"
    );
    let source = ctc_lang::Source::new(std::path::Path::new("heated.ctc"), deck);
    let Ok(ctc_engine::model::AnyModel::D3(model)) = ctc_lang::compile_any(&source) else {
        panic!("the heated brick deck does not compile to a 3D model")
    };
    let tmp = tempfile::tempdir().unwrap();
    let mut w = ctc_engine::output::ResultWriter::create(tmp.path(), &model).unwrap();
    let summary = ctc_engine::solve::run(&model, &mut w).unwrap();
    w.finish(&summary).unwrap();
    let vtu = Vtu::read_file(&tmp.path().join("inc_0001.vtu")).unwrap();
    let mut out = Vec::new();
    for array in [vtu.point("stress"), vtu.cell("stress")] {
        let s = array.expect("stress array");
        assert_eq!(s.components, 6);
        out.extend(s.values.chunks(6).map(|v| std::array::from_fn(|k| v[k])));
    }
    out
}

fn assert_stresses(stresses: &[[f64; 6]], expected: [f64; 6]) {
    let scale = expected.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    for v in stresses {
        for (k, (a, b)) in v.iter().zip(expected).enumerate() {
            assert!(
                (a - b).abs() <= 1e-9 * scale,
                "stress component {k}: {a} vs {b} ({v:?})"
            );
        }
    }
}

/// The VTU stress of a heated linear elastic body is `D (eps - eps_th I)`
/// (the thermal strain the increment was solved with), not `D eps`.
///
/// Reference: Timoshenko & Goodier, Theory of Elasticity, §150: a brick
/// heated uniformly by `dT`, free in x and y, held in z, carries the
/// uniaxial `sigma_zz = -E alpha dT`, `sigma_xx = sigma_yy = 0`, nodal and
/// cell stresses alike.
///
/// ```text
///      z held (uz = 0)
///   +---------+
///   |  T0+dT  |  -> free to expand in x, y
///   +---------+
///      z held (uz = 0);  sigma_zz = -E alpha dT, everything else 0
/// ```
#[test]
fn vtu_stress_of_a_heated_linear_elastic_brick_subtracts_the_thermal_strain() {
    let stresses = heated_brick_stresses(
        "fix b.xmin { ux }\nfix b.ymin { uy }\nfix b.zmin { uz }\nfix b.zmax { uz }",
    );
    let sigma = -200e3 * 1e-5 * 100.0;
    assert_stresses(&stresses, [0.0, 0.0, sigma, 0.0, 0.0, 0.0]);
}

/// A heated brick held on every face does not move (`u = 0` exactly, the
/// interior node by symmetry): the increment converges in one iteration
/// (the residual is at its round-off floor, which counts the thermal
/// forces; the correction is small against the model's size, there being
/// no displacement to compare it with) and the stress is the hydrostatic
/// `-E alpha dT / (1 - 2 nu)` (Timoshenko & Goodier §150).
///
/// ```text
///   +=========+  every face held (ux = uy = uz = 0)
///   ||T0+dT  ||  sigma_xx = sigma_yy = sigma_zz = -E alpha dT / (1 - 2 nu)
///   +=========+
/// ```
#[test]
fn a_fully_held_heated_brick_converges_with_the_hydrostatic_stress() {
    let fixes = ["xmin", "xmax", "ymin", "ymax", "zmin", "zmax"]
        .map(|f| format!("fix b.{f} {{ ux uy uz }}"))
        .join("\n");
    let stresses = heated_brick_stresses(&fixes);
    let p = -200e3 * 1e-5 * 100.0 / (1.0 - 2.0 * 0.3);
    assert_stresses(&stresses, [p, p, p, 0.0, 0.0, 0.0]);
}
