//! Heat conduction and thermal expansion against closed forms (hand-built
//! models; the deck-level cases are in `tests/thermal_*.rs`).

mod support;

use ctc_engine::model::thermal::{
    CouplingScheme, HeatFlux, MaterialThermal, PrescribedTemperature, ThermalScene,
};
use ctc_engine::model::*;
use ctc_engine::solve::{run, IncrementView, Observer};
use std::f64::consts::PI;
use support::{fix, grid, grid_node, one_body, step};

/// Keeps the displacements, temperatures and thermal reports.
#[derive(Default)]
struct Keep {
    u: Vec<[f64; 2]>,
    reaction: Vec<[f64; 2]>,
    temperature: Option<Vec<f64>>,
    times: Vec<f64>,
    stored: Vec<f64>,
}

impl Observer for Keep {
    fn converged(&mut self, v: &IncrementView<'_>) -> Result<(), String> {
        self.u = v.displacement.to_vec();
        self.reaction = v.reaction.to_vec();
        self.temperature = v.temperature.map(<[f64]>::to_vec);
        self.times.push(v.time);
        if let Some(t) = v.thermal {
            self.stored.push(t.stored);
        }
        Ok(())
    }
}

fn thermal_material(expansion: f64) -> MaterialThermal {
    MaterialThermal {
        conductivity: 2.0,
        capacity: 3.0,
        density: 0.5,
        expansion,
        reference: 20.0,
        taylor_quinney: 0.9,
        young_factor: None,
        yield_factor: None,
    }
}

fn scene(model: &Model, m: MaterialThermal, initial: f64) -> ThermalScene {
    ThermalScene {
        materials: vec![Some(m); model.materials.len()],
        initial: vec![initial; model.bodies.len()],
        temperatures: vec![],
        fluxes: vec![],
        convection: vec![],
        contacts: vec![None; model.contacts.len()],
        scheme: CouplingScheme::Staggered,
    }
}

/// Slab `0 <= x <= L` at 0, face x = 0 raised to 1 at t = 0, x = L
/// insulated: `T = 1 - sum 4 / ((2k+1) pi) sin(l_k x) exp(-l_k^2 a t)`,
/// `l_k = (2k+1) pi / (2L)`.
fn slab_series(x: f64, t: f64, l: f64, a: f64) -> f64 {
    let mut s = 0.0;
    for k in 0..200 {
        let m = (2 * k + 1) as f64;
        let lk = m * PI / (2.0 * l);
        s += 4.0 / (m * PI) * (lk * x).sin() * (-lk * lk * a * t).exp();
    }
    1.0 - s
}

/// Max nodal error of the slab at t = 0.5 with `increments` time steps on
/// an `nx` x 1 quad mesh.
fn slab_error(nx: usize, increments: usize) -> f64 {
    let (l, h) = (1.0, 0.1);
    let mesh = grid(nx, 1, [0.0, 0.0], [l, h], 0.0, 1, false);
    let mut model = one_body(AnalysisKind::PlaneStrain, mesh, 1.0, 0.3, Formulation::Full);
    let left: Vec<usize> = (0..2).map(|j| grid_node(nx, 0, j)).collect();
    model.constraints = vec![fix((0..model.mesh.nodes.len()).collect(), 0, 0.0)];
    model
        .constraints
        .push(fix((0..model.mesh.nodes.len()).collect(), 1, 0.0));
    model.steps = vec![Step {
        t_end: 0.5,
        ..step(increments)
    }];
    let mut s = scene(&model, thermal_material(0.0), 0.0);
    s.temperatures.push(PrescribedTemperature {
        label: "left".into(),
        nodes: left,
        value: TimeFunction::Constant(1.0),
    });
    model.thermal = Some(s);
    let mut keep = Keep::default();
    let summary = run(&model, &mut keep).unwrap();
    assert_eq!(summary.temperature_dofs, 2 * nx);
    let a = 2.0 / (0.5 * 3.0);
    let t = keep.temperature.unwrap();
    model
        .mesh
        .nodes
        .iter()
        .zip(&t)
        .map(|(p, v)| (v - slab_series(p[0], 0.5, l, a)).abs())
        .fold(0.0, f64::max)
}

#[test]
fn transient_slab_converges_at_first_order_in_dt_to_the_series_solution() {
    // fine mesh: the error is dominated by backward Euler
    let errors: Vec<f64> = [10, 20, 40].iter().map(|&n| slab_error(80, n)).collect();
    eprintln!("slab: max nodal error at t = 0.5 for dt = 0.05, 0.025, 0.0125: {errors:?}");
    for w in errors.windows(2) {
        let rate = (w[0] / w[1]).log2();
        assert!((0.8..1.3).contains(&rate), "{errors:?}");
    }
    assert!(errors[2] < 1e-2, "{errors:?}");
}

#[test]
fn steady_radial_conduction_in_a_hollow_cylinder_matches_the_log_profile() {
    // rho c = 0: steady; axisymmetric ring r in [1, 3], T(1) = 10, flux
    // q = 5 into r = 3: T = 10 + q r_o / k ln(r / r_i)
    let nx = 16;
    let mut model = one_body(
        AnalysisKind::Axisymmetric,
        grid(nx, 2, [1.0, 0.0], [2.0, 0.5], 0.0, 1, true),
        1.0,
        0.3,
        Formulation::Full,
    );
    let all: Vec<usize> = (0..model.mesh.nodes.len()).collect();
    model.constraints = vec![fix(all.clone(), 0, 0.0), fix(all, 1, 0.0)];
    let mut m = thermal_material(0.0);
    m.density = 0.0;
    let mut s = scene(&model, m, 0.0);
    let left: Vec<usize> = (0..3).map(|j| grid_node(nx, 0, j)).collect();
    let right: Vec<ctc_engine::mesh::Facet> = (0..2)
        .map(|j| ctc_engine::mesh::Facet::new(&[grid_node(nx, nx, j), grid_node(nx, nx, j + 1)]))
        .collect();
    s.temperatures.push(PrescribedTemperature {
        label: "inner".into(),
        nodes: left,
        value: TimeFunction::Constant(10.0),
    });
    s.fluxes.push(HeatFlux {
        label: "outer".into(),
        facets: right,
        value: TimeFunction::Constant(5.0),
    });
    model.thermal = Some(s);
    let mut keep = Keep::default();
    run(&model, &mut keep).unwrap();
    let t = keep.temperature.unwrap();
    // axisymmetric radial conduction, r in [1, 3]: T = T_i + q r_o / k ln(r / r_i)
    let mut worst: f64 = 0.0;
    for (p, v) in model.mesh.nodes.iter().zip(&t) {
        let exact = 10.0 + 5.0 * 3.0 / 2.0 * (p[0] / 1.0).ln();
        worst = worst.max((v - exact).abs() / exact);
    }
    eprintln!("steady radial conduction: max relative nodal error {worst:.2e}");
    // linear elements on 16 cells: nodal values of the log profile within 2e-3 (9e-4 measured)
    assert!(worst < 2e-3, "{worst:e}");
}

/// Bar `[0, L] x [0, H]` at a uniform temperature `T_ref + dT` from the
/// start (initial temperature), held at x = 0 in x (and one node in y).
fn heated_bar(
    kind: AnalysisKind,
    law: MaterialLaw,
    kinematics: Kinematics,
    clamp_right: bool,
) -> (Model, Keep) {
    let (nx, ny, l, h) = (6, 2, 3.0, 1.0);
    let origin = [0.0, 0.0];
    let mut model = one_body(
        kind,
        grid(nx, ny, origin, [l, h], 0.0, 1, false),
        200e3,
        0.3,
        Formulation::Full,
    );
    model.materials[0].law = law;
    model.bodies[0].kinematics = kinematics;
    let left: Vec<usize> = (0..=ny).map(|j| grid_node(nx, 0, j)).collect();
    let right: Vec<usize> = (0..=ny).map(|j| grid_node(nx, nx, j)).collect();
    let bottom: Vec<usize> = (0..=nx).map(|i| grid_node(nx, i, 0)).collect();
    model.constraints = vec![fix(left, 0, 0.0), fix(bottom, 1, 0.0)];
    if clamp_right {
        model.constraints.push(fix(right, 0, 0.0));
    }
    model.steps = vec![step(2)];
    // alpha dT = 1e-4: elastic everywhere (plane strain sigma_zz = -20)
    model.thermal = Some(scene(&model, thermal_material(1e-6), 120.0));
    let mut keep = Keep::default();
    run(&model, &mut keep).unwrap();
    (model, keep)
}

#[test]
fn free_thermal_expansion_of_a_bar_matches_the_closed_form() {
    let da = 1e-6 * 100.0;
    let plastic = MaterialLaw::ElastoPlastic {
        young: 200e3,
        poisson: 0.3,
        hardening: Hardening::Linear {
            yield_stress: 250.0,
            modulus: 1000.0,
        },
        viscosity: None,
    };
    let elastic = MaterialLaw::LinearElastic {
        young: 200e3,
        poisson: 0.3,
    };
    let cases = [
        // plane stress: eps_xx = eps_yy = alpha dT
        (
            AnalysisKind::PlaneStress,
            elastic.clone(),
            Kinematics::Small,
            da,
            da,
        ),
        // plane strain (eps_zz = 0): eps_xx = eps_yy = (1 + nu) alpha dT
        (
            AnalysisKind::PlaneStrain,
            elastic.clone(),
            Kinematics::Small,
            1.3 * da,
            1.3 * da,
        ),
        (
            AnalysisKind::PlaneStrain,
            plastic.clone(),
            Kinematics::Small,
            1.3 * da,
            1.3 * da,
        ),
        // axisymmetric solid cylinder: u_r = alpha dT r, u_z = alpha dT z
        (
            AnalysisKind::Axisymmetric,
            elastic,
            Kinematics::Small,
            da,
            da,
        ),
        (
            AnalysisKind::Axisymmetric,
            plastic.clone(),
            Kinematics::Small,
            da,
            da,
        ),
        // finite strain, multiplicative split: u = alpha dT X exactly
        (
            AnalysisKind::Axisymmetric,
            plastic,
            Kinematics::Finite,
            da,
            da,
        ),
    ];
    for (kind, law, kin, ex, ey) in cases {
        let (model, keep) = heated_bar(kind, law.clone(), kin, false);
        let mut worst: f64 = 0.0;
        for (p, u) in model.mesh.nodes.iter().zip(&keep.u) {
            worst = worst
                .max((u[0] - ex * p[0]).abs())
                .max((u[1] - ey * p[1]).abs());
        }
        let rel = worst / (ex * 3.0);
        eprintln!("free expansion {kind:?} {kin:?}: max relative displacement error {rel:.2e}");
        assert!(rel < 1e-8, "{kind:?} {law:?} {kin:?}: {rel:e}");
    }
}

#[test]
fn constrained_thermal_expansion_of_a_bar_gives_the_closed_form_reaction() {
    // plane stress, clamped in x at both ends, free in y: sigma_xx = -E alpha dT
    let law = MaterialLaw::LinearElastic {
        young: 200e3,
        poisson: 0.3,
    };
    let (model, keep) = heated_bar(AnalysisKind::PlaneStress, law, Kinematics::Small, true);
    let right_sum: f64 = model
        .mesh
        .nodes
        .iter()
        .zip(&keep.reaction)
        .filter(|(p, _)| (p[0] - 3.0).abs() < 1e-12)
        .map(|(_, r)| r[0])
        .sum();
    // the wall pushes back: reaction on the body -sigma A = E alpha dT H t
    let expect = 200e3 * 1e-6 * 100.0 * 1.0 * 1.0;
    let rel = (-right_sum - expect).abs() / expect;
    eprintln!("constrained expansion: reaction {right_sum} vs {expect}: relative error {rel:.2e}");
    assert!(rel < 1e-8, "{right_sum} vs {expect}");
    // free in y: u_y = (1 + nu) alpha dT y (plane stress: eps_yy = alpha dT - nu sigma_xx / E)
    for (p, u) in model.mesh.nodes.iter().zip(&keep.u) {
        let ey = 1.3 * 1e-4;
        assert!((u[1] - ey * p[1]).abs() < 1e-12, "{p:?} {u:?}");
    }
}

#[test]
fn a_scene_without_thermal_blocks_has_no_temperature_unknowns() {
    let mut model = one_body(
        AnalysisKind::PlaneStrain,
        grid(2, 2, [0.0, 0.0], [1.0, 1.0], 0.0, 1, false),
        1.0,
        0.3,
        Formulation::Full,
    );
    let all: Vec<usize> = (0..model.mesh.nodes.len()).collect();
    model.constraints = vec![fix(all.clone(), 0, 0.0), fix(all, 1, 0.0)];
    assert!(model.thermal.is_none());
    assert!(ctc_engine::thermal::coupling::Coupling::new(&model)
        .unwrap()
        .is_none());
    let mut keep = Keep::default();
    let summary = run(&model, &mut keep).unwrap();
    assert_eq!(summary.temperature_dofs, 0);
    assert!(keep.temperature.is_none());
    assert!(keep.stored.is_empty());
    assert!(summary.increments.iter().all(|i| i.thermal.is_none()));
}
