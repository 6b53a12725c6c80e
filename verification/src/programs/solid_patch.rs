//! Solid (3D) patch tests and objectivity as `ctc verify` cases (tag `3d`):
//! the scenes of `ctc_engine::testkit::solid`, which
//! `engine/tests/solid_patch.rs` runs too (the same function, so the cargo
//! test and the verification case cannot drift apart).
//!
//! - `patch_3d`: the patch test (Irons; MacNeal and Harder, FEAD 1 (1985)):
//!   `u = b + A x` prescribed on the boundary of a distorted 3 x 3 x 3 brick
//!   (interior nodes moved by up to 0.12 h) must be reproduced at the
//!   interior nodes, with one stress at every integration point (the exact
//!   one for linear elasticity), for tet4 and hex8 (full, B-bar / F-bar) x
//!   linear elastic and J2 at small strain (|A| ~ 1e-3, plastic) and
//!   Neo-Hooke and J2 at finite strain (|A| ~ 0.1). Measured per element and
//!   law: `max |u - u_exact| / max |u_exact|` over the nodes and `max
//!   |sigma - sigma_ref| / max |sigma_ref|` over the points.
//!
//!   ```text
//!     z
//!     |  3 x 3 x 3 cells on [0,1] x [0,2] x [0,1.5]
//!     | /y
//!     |/___ x   boundary: u = b + A x
//!   ```
//!
//! - `objectivity_3d`: a unit block stretched by `F0` (past yield for J2),
//!   then rotated rigidly by 90 degrees about `(1, 2, 3) / |..|` in 4
//!   increments: `max |sigma - R sigma_0 R^T| / |sigma_0|` over the points
//!   and the change of the equivalent plastic strain (the rotation is
//!   rigid: both must be round-off). Hex8 Neo-Hooke (full), tet4 J2 (full),
//!   hex8 J2 F-bar.

use super::error;
use crate::case::{Check, Quantity};
use crate::registry::{CaseKind, ProgramCase, ProgramLevel, VerifyCase};
use ctc_engine::mesh::CellKind;
use ctc_engine::model::{Formulation, Kinematics, MaterialLaw};
use ctc_engine::testkit::solid::{
    linear_stress, objectivity, patch, plastic, A_FINITE, A_SMALL, E, NU,
};

/// The patch runs: (u name, sigma name, cell, formulation, kinematics, law).
type PatchRun = (
    &'static str,
    &'static str,
    CellKind,
    Formulation,
    Kinematics,
    MaterialLaw,
);

fn patch_runs() -> Vec<PatchRun> {
    use CellKind::{Hex8, Tet4};
    use Formulation::{Full, SelectiveReduced as Bar};
    use Kinematics::{Finite, Small};
    let linear = MaterialLaw::LinearElastic {
        young: E,
        poisson: NU,
    };
    let neo = MaterialLaw::NeoHookean {
        young: 10.0,
        poisson: 0.45,
    };
    vec![
        (
            "u tet4 linear",
            "s tet4 linear",
            Tet4,
            Full,
            Small,
            linear.clone(),
        ),
        (
            "u hex8 linear",
            "s hex8 linear",
            Hex8,
            Full,
            Small,
            linear.clone(),
        ),
        (
            "u hex8 B-bar linear",
            "s hex8 B-bar linear",
            Hex8,
            Bar,
            Small,
            linear,
        ),
        (
            "u tet4 J2 small",
            "s tet4 J2 small",
            Tet4,
            Full,
            Small,
            plastic(),
        ),
        (
            "u hex8 J2 small",
            "s hex8 J2 small",
            Hex8,
            Full,
            Small,
            plastic(),
        ),
        (
            "u hex8 B-bar J2 small",
            "s hex8 B-bar J2 small",
            Hex8,
            Bar,
            Small,
            plastic(),
        ),
        (
            "u tet4 neo-hooke",
            "s tet4 neo-hooke",
            Tet4,
            Full,
            Finite,
            neo.clone(),
        ),
        (
            "u hex8 neo-hooke",
            "s hex8 neo-hooke",
            Hex8,
            Full,
            Finite,
            neo.clone(),
        ),
        (
            "u hex8 F-bar neo-hooke",
            "s hex8 F-bar neo-hooke",
            Hex8,
            Bar,
            Finite,
            neo,
        ),
        (
            "u tet4 J2 finite",
            "s tet4 J2 finite",
            Tet4,
            Full,
            Finite,
            plastic(),
        ),
        (
            "u hex8 J2 finite",
            "s hex8 J2 finite",
            Hex8,
            Full,
            Finite,
            plastic(),
        ),
        (
            "u hex8 F-bar J2 finite",
            "s hex8 F-bar J2 finite",
            Hex8,
            Bar,
            Finite,
            plastic(),
        ),
    ]
}

/// The objectivity runs: (stress name, ep name, cell, law, formulation).
fn objectivity_runs() -> Vec<(
    &'static str,
    &'static str,
    CellKind,
    MaterialLaw,
    Formulation,
)> {
    vec![
        (
            "hex8 neo-hooke stress",
            "hex8 neo-hooke ep change",
            CellKind::Hex8,
            MaterialLaw::NeoHookean {
                young: 10.0,
                poisson: 0.3,
            },
            Formulation::Full,
        ),
        (
            "tet4 J2 stress",
            "tet4 J2 ep change",
            CellKind::Tet4,
            plastic(),
            Formulation::Full,
        ),
        (
            "hex8 F-bar J2 stress",
            "hex8 F-bar J2 ep change",
            CellKind::Hex8,
            plastic(),
            Formulation::SelectiveReduced,
        ),
    ]
}

/// The registry entries.
pub fn cases() -> Vec<VerifyCase> {
    let patch_checks = patch_runs()
        .into_iter()
        .flat_map(|(u, s, ..)| {
            [
                Check::new(Quantity::Named(u), &[1e-10]),
                Check::new(Quantity::Named(s), &[1e-10]),
            ]
        })
        .collect();
    let objectivity_checks = objectivity_runs()
        .into_iter()
        .flat_map(|(s, ep, ..)| {
            [
                Check::new(Quantity::Named(s), &[1e-12]),
                Check::new(Quantity::Named(ep), &[1e-12]),
            ]
        })
        .collect();
    vec![
        VerifyCase {
            name: "patch_3d",
            title: "Patch test, distorted 3x3x3 brick: tet4/hex8 (full, B-bar/F-bar) x every law, small and finite strain",
            source: "Irons; MacNeal & Harder, Finite Elements in Analysis and Design 1 (1985)",
            tags: &["3d", "patch", "elasticity", "plasticity", "finite_strain"],
            levels: 1,
            checks: patch_checks,
            kind: CaseKind::Program(ProgramCase {
                max_levels: 1,
                run: patch_level,
            }),
        },
        VerifyCase {
            name: "objectivity_3d",
            title: "Objectivity: pre-stressed block rotated 90 degrees about (1, 2, 3), sigma = R sigma0 R^T, ep unchanged",
            source: "rigid-rotation invariance of the finite-strain laws (Simo & Hughes, Computational Inelasticity §9)",
            tags: &["3d", "finite_strain", "plasticity", "objectivity"],
            levels: 1,
            checks: objectivity_checks,
            kind: CaseKind::Program(ProgramCase {
                max_levels: 1,
                run: objectivity_level,
            }),
        },
    ]
}

fn empty_level() -> ProgramLevel {
    ProgramLevel {
        figures: Vec::new(),
        values: Vec::new(),
        h: f64::NAN,
        nodes: 0,
        free_dofs: 0,
        increments: 0,
        newton_total: 0,
        newton_max: 0,
        cutbacks: 0,
    }
}

fn patch_level(_level: usize) -> Result<ProgramLevel, String> {
    let mut out = empty_level();
    let exact = linear_stress(E, NU, &A_SMALL);
    for (u_name, s_name, kind, formulation, kinematics, law) in patch_runs() {
        let linear = matches!(law, MaterialLaw::LinearElastic { .. });
        let a = if kinematics == Kinematics::Small {
            &A_SMALL
        } else {
            &A_FINITE
        };
        let p = patch(kind, law, formulation, kinematics, a)?;
        let s = if linear {
            p.stress_error(&exact).max(p.stress_spread)
        } else {
            p.stress_spread
        };
        out.values.push(error(u_name, p.u_error));
        out.values.push(error(s_name, s));
        out.nodes = out.nodes.max(p.summary.nodes);
        out.free_dofs = out.free_dofs.max(p.summary.free_dofs);
        out.increments += p.summary.increments.len();
        out.newton_total += p.summary.newton_iterations;
        out.newton_max = out.newton_max.max(
            p.summary
                .increments
                .iter()
                .map(|i| i.iterations)
                .max()
                .unwrap_or(0),
        );
        out.cutbacks += p.summary.cutbacks;
    }
    Ok(out)
}

fn objectivity_level(_level: usize) -> Result<ProgramLevel, String> {
    let mut out = empty_level();
    for (s_name, ep_name, kind, law, formulation) in objectivity_runs() {
        let plastic = matches!(law, MaterialLaw::ElastoPlastic { .. });
        let o = objectivity(kind, law, formulation)?;
        if plastic && o.plastic <= 1e-3 {
            return Err(format!(
                "{s_name}: the stretch did not yield (ep = {:e}): the check says nothing",
                o.plastic
            ));
        }
        out.values.push(error(s_name, o.stress));
        out.values.push(error(ep_name, o.plastic_change));
        out.nodes = out.nodes.max(8);
    }
    Ok(out)
}
