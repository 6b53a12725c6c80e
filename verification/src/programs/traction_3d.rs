//! `traction_patch_3d` (tag `3d`, `patch`, `loads`): a patch test of dead
//! face tractions in 3D, through a deck (geometric face selections
//! `faces(z = ..)` / `faces(x = ..)` and `traction` items), after the
//! traction form of the patch test (Irons; MacNeal and Harder, Finite
//! Elements in Analysis and Design 1 (1985)): boundary tractions of a
//! uniform stress state must give that state to round-off.
//!
//! Pure shear `sigma_xz = tau` (all other components zero) on the graded
//! brick `[0, 2] x [0, 1] x [0, 1.5]`, base `z = 0` held: the exact field
//! `u = (gamma z, 0, 0)`, `gamma = tau / G`, is linear, so tet4 and hex8
//! reproduce it exactly. The tractions `t = sigma n` of that state:
//!
//! ```text
//!          t = (tau, 0, 0) on z = 1.5
//!        -------->
//!       +---------+
//!   |   |         |  ^
//!   v   |  block  |  |   t = (0, 0, +tau) on x = 2
//!       |         |      t = (0, 0, -tau) on x = 0
//!       +---------+
//!      /// z = 0: ux = uy = uz = 0 (reaction -tau A in x)
//! ```
//!
//! Measured per element (hex8, tet4): `max |sigma - sigma_exact| / tau` over
//! the integration points, `max |u - u_exact| / (gamma H)` over the nodes,
//! and the total external force on the top face against `tau x area`
//! (the consistent face quadrature integrates `int N_a dA` exactly).

use super::error;
use crate::case::{Check, Quantity};
use crate::registry::{CaseKind, ProgramCase, ProgramLevel, VerifyCase};
use ctc_engine::model::AnyModel;
use ctc_engine::solve::{run, RunSummary};
use ctc_engine::testkit::solid::{states, Last};

const E: f64 = 200e3;
const NU: f64 = 0.3;
const TAU: f64 = 50.0;
/// Brick size.
const SIZE: [f64; 3] = [2.0, 1.0, 1.5];

/// The deck of the patch with cells `element` (`hex8` or `tet4`).
pub fn deck(element: &str) -> String {
    format!(
        "analysis {{ dimension = 3d }}\n\
         material steel {{ elastic {{ E = {E}  nu = {NU} }} }}\n\
         body block {{\n\
           mesh = box {{ size = ({}, {}, {})  divisions = (4, 3, 3)\n\
                        grading = (geometric(3), uniform, geometric(0.4))  element = {element} }}\n\
           material = steel\n\
         }}\n\
         fix block.faces(z = 0) {{ ux uy uz }}\n\
         traction block.faces(z = {}) {{ tx = ramp(0, {TAU}) }}\n\
         traction block.faces(x = {}) {{ tz = ramp(0, {TAU}) }}\n\
         traction block.faces(x = 0) {{ tz = ramp(0, -{TAU}) }}\n\
         step load {{ time = 0 .. 1  increments = 1 }}\n",
        SIZE[0], SIZE[1], SIZE[2], SIZE[2], SIZE[0]
    )
}

/// The measured errors of one element kind: (stress, displacement, top
/// force) errors, and the run's summary.
pub fn measure(element: &str) -> Result<([f64; 3], RunSummary), String> {
    let src = ctc_lang::Source::new("traction_patch_3d.ctc", deck(element));
    let model = match ctc_lang::compile_any(&src) {
        Ok(AnyModel::D3(m)) => m,
        Ok(AnyModel::D2(_)) => return Err("the deck lowered to a planar model".into()),
        Err(d) => return Err(d.render(&src)),
    };
    let mut last = Last::default();
    let summary = run(&model, &mut last).map_err(|e| e.message)?;
    if !summary.completed {
        return Err("the traction patch run did not complete".into());
    }
    let g = E / (2.0 * (1.0 + NU));
    let gamma = TAU / g;
    let mut exact = [0.0; 6];
    exact[4] = TAU; // Voigt [xx, yy, zz, xy, xz, yz]
    let stress = states(&model, &last)?
        .iter()
        .flat_map(|p| (0..6).map(move |k| (p.stress[k] - exact[k]).abs()))
        .fold(0.0, f64::max)
        / TAU;
    let u = model
        .mesh
        .nodes
        .iter()
        .zip(&last.u)
        .flat_map(|(x, u)| {
            let e = [gamma * x[2], 0.0, 0.0];
            (0..3).map(move |k| (u[k] - e[k]).abs())
        })
        .fold(0.0, f64::max)
        / (gamma * SIZE[2]);
    // the external force of the top traction alone, at t = 1
    let mut top = model.clone();
    top.loads.truncate(1);
    let mut f = vec![0.0; 3 * top.mesh.nodes.len()];
    ctc_engine::solve::loads::external_forces(&top, 1.0, &mut f);
    let fx: f64 = f.iter().step_by(3).sum();
    let area = SIZE[0] * SIZE[1];
    let force = (fx - TAU * area).abs() / (TAU * area);
    Ok(([stress, u, force], summary))
}

/// The registry entry.
pub fn cases() -> Vec<VerifyCase> {
    let mut checks = Vec::new();
    for q in NAMES.iter().flatten() {
        checks.push(Check::new(Quantity::Named(q), &[1e-10]));
    }
    vec![VerifyCase {
        name: "traction_patch_3d",
        title: "Traction patch test: pure shear tractions on a graded brick (deck, face selections), tet4/hex8",
        source: "Irons; MacNeal & Harder, Finite Elements in Analysis and Design 1 (1985); t = sigma n",
        tags: &["3d", "patch", "elasticity", "loads"],
        levels: 1,
        checks,
        kind: CaseKind::Program(ProgramCase {
            max_levels: 1,
            run: level,
        }),
    }]
}

/// Quantity names per element: stress, displacement, top force.
const NAMES: [[&str; 3]; 2] = [
    ["s hex8", "u hex8", "force hex8"],
    ["s tet4", "u tet4", "force tet4"],
];

fn level(_level: usize) -> Result<ProgramLevel, String> {
    let mut out = ProgramLevel {
        figures: Vec::new(),
        values: Vec::new(),
        h: f64::NAN,
        nodes: 0,
        free_dofs: 0,
        increments: 0,
        newton_total: 0,
        newton_max: 0,
        cutbacks: 0,
    };
    for (element, names) in ["hex8", "tet4"].into_iter().zip(NAMES) {
        let (errors, summary) = measure(element)?;
        for (name, e) in names.into_iter().zip(errors) {
            out.values.push(error(name, e));
        }
        out.nodes = out.nodes.max(summary.nodes);
        out.free_dofs = out.free_dofs.max(summary.free_dofs);
        out.increments += summary.increments.len();
        out.newton_total += summary.newton_iterations;
        let most = summary.increments.iter().map(|i| i.iterations).max();
        out.newton_max = out.newton_max.max(most.unwrap_or(0));
        out.cutbacks += summary.cutbacks;
    }
    Ok(out)
}
