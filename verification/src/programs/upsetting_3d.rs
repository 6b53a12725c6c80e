//! `upsetting_3d_vs_axi` (tag `3d`): the frictionless upsetting of
//! `upsetting_linear` (r0 = 1, h0 = 1, J2 finite strain with linear
//! hardening, 50 % height reduction in 20 increments; closed form of the
//! model `F = tau pi r0^2 h0 / h`, `tau = sigma_f(ln(h0/h) - tau/E)`,
//! Simo & Hughes §9) solved twice at the same density through the
//! thickness (4 cells over the half height):
//!
//! - axisymmetric: 4 x 4 quads, the rigid flat die by area penalty (the
//!   scene of `upsetting.rs`);
//! - 3D: the 1/8 model, a 90 degree O-grid cylinder sector (`cylinder`
//!   generator: core 6, ring 2, 4 axial layers, hex8), symmetry `u_n = 0`
//!   on `x = 0`, `y = 0`, `z = 0`, the frictionless die as `u_z` prescribed
//!   on `z = h0 / 2` with `u_x`, `u_y` free (3D has no contact yet; a
//!   frictionless flat die on a homogeneous state is exactly that), force =
//!   4 x the reactions of the top face.
//!
//! Measured over the increments past 2 % strain: the 3D force against the
//! axisymmetric one (carried from the axisymmetric height, which the
//! penalty die's penetration lowers by ~6e-5, to the 3D height by the
//! ratio of the closed form), against the closed form (the inscribed polygon of the
//! O-grid has 12 chords per quarter: its area is 0.29 % below pi r0^2 / 4),
//! and against the closed form on the polygon's own area (the homogeneous
//! state is exact for any cross-section: round-off). Iterations of both
//! runs are reported (`newton 3d`, `newton axi`); the times are those of
//! `ctc verify upsetting_3d_vs_axi` vs `ctc verify upsetting_linear` (the
//! same axisymmetric run).
//!
//! ```text
//!        z   u_z = -0.25 t on the top face (frictionless die)
//!        |_______
//!        |       \      quarter of the O-grid cylinder, r0 = 1
//!        | core   |     h0 / 2 = 0.5, u_z = 0 at z = 0
//!        o--------+-- x
//! ```

use super::error;
use super::upsetting::{axial_stress, upsetting};
use crate::case::{Check, Quantity};
use crate::registry::{CaseKind, ProgramCase, ProgramLevel, VerifyCase};
use ctc_engine::mesh::generate::solid;
use ctc_engine::mesh::CellKind;
use ctc_engine::model::{Formulation, Hardening, Kinematics, MaterialLaw};
use ctc_engine::solve::{run, IncrementView, Observer};
use ctc_engine::testkit::{ramp, ModelBuilder};
use std::f64::consts::PI;

const E: f64 = 200e3;
const NU: f64 = 0.3;
const HARDENING: Hardening = Hardening::Linear {
    yield_stress: 250.0,
    modulus: 1000.0,
};
/// O-grid core divisions (12 chords per quarter), ring divisions, layers.
const DIVISIONS: [usize; 3] = [6, 2, 4];
const INCREMENTS: usize = 20;

/// Height and die force of every converged 3D increment.
#[derive(Default)]
struct Record3 {
    top: Vec<usize>,
    rows: Vec<(f64, f64)>,
}

impl Observer<3> for Record3 {
    fn converged(&mut self, v: &IncrementView<'_, 3>) -> Result<(), String> {
        let uz =
            self.top.iter().map(|&n| v.displacement[n][2]).sum::<f64>() / self.top.len() as f64;
        let fz: f64 = self.top.iter().map(|&n| v.reaction[n][2]).sum();
        self.rows.push((2.0 * (0.5 + uz), -4.0 * fz));
        Ok(())
    }
}

/// The registry entry.
pub fn cases() -> Vec<VerifyCase> {
    vec![VerifyCase {
        name: "upsetting_3d_vs_axi",
        title:
            "Upsetting, J2 finite strain, 50 %: 1/8 3D O-grid model against the axisymmetric run",
        source: "VERIFICATION-CASES.md case 6; Simo & Hughes §9; upsetting_linear",
        tags: &[
            "3d",
            "upsetting",
            "plasticity",
            "finite_strain",
            "axisymmetric",
            "closed_form",
            "cross_check",
        ],
        levels: 1,
        checks: vec![
            Check::new(Quantity::Named("F 3d vs axi"), &[5e-3]),
            Check::new(Quantity::Named("F 3d vs exact (pi r0^2)"), &[5e-3]),
            Check::new(Quantity::Named("F 3d vs exact (polygon area)"), &[1e-9]),
            Check::new(Quantity::Named("final h / h0 3d"), &[1e-9]),
        ],
        kind: CaseKind::Program(ProgramCase {
            max_levels: 1,
            run: level,
        }),
    }]
}

fn level(_level: usize) -> Result<ProgramLevel, String> {
    // axisymmetric
    let (axi, _, sa) = upsetting(
        HARDENING,
        Formulation::Full,
        Kinematics::Finite,
        0.25,
        4,
        INCREMENTS,
    )?;
    // 3D, 1/8
    let mesh = solid::cylinder(1.0, 90.0, 0.5, DIVISIONS, CellKind::Hex8).map_err(|e| e.message)?;
    let chords = 2 * DIVISIONS[0];
    let polygon = 0.5 * chords as f64 * (PI / 2.0 / chords as f64).sin() * 4.0;
    let mut b = ModelBuilder::solid()
        .material(
            "steel",
            MaterialLaw::ElastoPlastic {
                young: E,
                poisson: NU,
                hardening: HARDENING,
                viscosity: None,
            },
        )
        .body("billet", mesh, "steel")
        .kinematics(Kinematics::Finite);
    for (set, c) in [("start", 1), ("end", 0), ("zmin", 2)] {
        let nodes = b.node_set(&format!("billet.{set}"));
        b = b.fix(nodes, c);
    }
    let top = b.node_set("billet.zmax");
    let model = b
        .displace(top.clone(), 2, ramp(0.0, 1.0, -0.25))
        .step("upset", 1.0, INCREMENTS)
        .min_fraction(1.0 / 64.0)
        .tol(1e-10)
        .build();
    let mut rec = Record3 {
        top,
        ..Default::default()
    };
    let s3 = run(&model, &mut rec).map_err(|e| e.message)?;
    if !s3.completed || rec.rows.len() != axi.rows.len() {
        return Err(format!(
            "the runs did not complete on the same increments (3d {}, axi {})",
            rec.rows.len(),
            axi.rows.len()
        ));
    }
    let (mut vs_axi, mut vs_exact, mut vs_polygon) = (0.0f64, 0.0f64, 0.0f64);
    for ((h3, f3), (ha, fa, _)) in rec.rows.iter().zip(&axi.rows) {
        let eps = (1.0 / h3).ln();
        if eps < 0.02 {
            continue;
        }
        // the penalty die penetrates (h differs by ~6e-5): the axisymmetric
        // force is carried to the 3D height by the closed form's ratio
        if ((h3 - ha) / ha).abs() > 1e-3 {
            return Err(format!("the runs are at different heights: {h3} vs {ha}"));
        }
        let exact_at = |h: f64| axial_stress(&HARDENING, (1.0 / h).ln()) * PI / h;
        let exact = exact_at(*h3);
        let fa = fa * exact / exact_at(*ha);
        vs_axi = vs_axi.max(((f3 - fa) / fa).abs());
        vs_exact = vs_exact.max(((f3 - exact) / exact).abs());
        let on_polygon = exact * polygon / PI;
        vs_polygon = vs_polygon.max(((f3 - on_polygon) / on_polygon).abs());
    }
    let final_h = rec.rows.last().map_or(f64::NAN, |r| r.0);
    Ok(ProgramLevel {
        figures: Vec::new(),
        values: vec![
            error("F 3d vs axi", vs_axi),
            error("F 3d vs exact (pi r0^2)", vs_exact),
            error("F 3d vs exact (polygon area)", vs_polygon),
            super::value("final h / h0 3d", final_h, 0.5),
            error("newton 3d", s3.newton_iterations as f64),
            error("newton axi", sa.newton_iterations as f64),
        ],
        h: 0.5 / DIVISIONS[2] as f64,
        nodes: model.mesh.nodes.len(),
        free_dofs: s3.free_dofs,
        increments: s3.increments.len() + sa.increments.len(),
        newton_total: s3.newton_iterations + sa.newton_iterations,
        newton_max: s3
            .increments
            .iter()
            .chain(&sa.increments)
            .map(|i| i.iterations)
            .max()
            .unwrap_or(0),
        cutbacks: s3.cutbacks + sa.cutbacks,
    })
}
