//! Objectivity of the 2D finite-strain kernels (VERIFICATION-CASES case 6,
//! last item) as a `ctc verify` case: a 2x2 quad4 body [1, 2] x [0, 1],
//! plane strain, is pre-stressed by the homogeneous stretch
//! `F0 = [[1.06, 0.02], [0, 0.97]]` (t in [0, 1]; plastic for J2), then
//! rotated rigidly by 90 degrees about its centre in `n` increments
//! (t in [1, 2]), the motion `x = c + R(theta) F0 (X - c)` prescribed on
//! every boundary node. A rigid rotation must rotate the Cauchy stress:
//! at the end `sigma = R sigma0 R^T` (xx and yy swapped, xy negated), its
//! invariants (trace, 2D determinant, zz) unchanged, and no plastic strain
//! created. Measured, per law: `max |sigma - R sigma0 R^T|` and the
//! invariant changes over the integration points, over `max |sigma0|`; the
//! change of the equivalent plastic strain. Level l rotates in 3 x 3^l
//! increments (30, 10, 3.3 degrees each).
//! Source: rigid-rotation invariance of the finite-strain laws (Simo &
//! Hughes, Computational Inelasticity §9; the 3D case is `objectivity_3d`).
//! `verification/tests/suite/objectivity.rs` runs this entry.
//!
//! ```text
//!    y                      after 90 degrees:
//!    ^  +-----+               +--+
//!    |  |  F0 |  --R(90)-->   |  |
//!    |  +-----+               |  |
//!    +--1-----2--> x          +--+
//! ```

use super::error;
use crate::case::{Check, Quantity};
use crate::registry::{CaseKind, ProgramCase, ProgramLevel, VerifyCase};
use ctc_engine::element::MaterialPoint;
use ctc_engine::mesh::{Cell, Mesh};
use ctc_engine::model::{
    AnalysisKind, Dirichlet, Hardening, Kinematics, MaterialLaw, Model, TimeFunction,
};
use ctc_engine::solve::{run, IncrementView, Observer, RunSummary};
use ctc_engine::testkit::ModelBuilder;

/// The laws: (name of the stress error, name of the ep change (J2 only),
/// law).
fn laws() -> Vec<(&'static str, Option<&'static str>, MaterialLaw)> {
    vec![
        (
            "neo-Hookean: |sigma - R sigma0 R^T| / |sigma0|",
            None,
            MaterialLaw::NeoHookean {
                young: 200e3,
                poisson: 0.3,
            },
        ),
        (
            "Hencky: |sigma - R sigma0 R^T| / |sigma0|",
            None,
            MaterialLaw::LinearElastic {
                young: 200e3,
                poisson: 0.3,
            },
        ),
        (
            "J2 Swift: |sigma - R sigma0 R^T| / |sigma0|",
            Some("J2 Swift: ep change"),
            MaterialLaw::ElastoPlastic {
                young: 200e3,
                poisson: 0.3,
                hardening: Hardening::Swift {
                    k: 500.0,
                    eps0: 0.01,
                    n: 0.2,
                },
                viscosity: None,
            },
        ),
    ]
}

/// Rotation increments of `level`.
fn turns(level: usize) -> usize {
    3 * 3usize.pow(level as u32)
}

#[derive(Default)]
struct Points(Vec<Vec<MaterialPoint>>);

impl Observer for Points {
    fn converged(&mut self, view: &IncrementView<'_>) -> Result<(), String> {
        self.0 = view.points.to_vec();
        Ok(())
    }
}

/// The stretched body, rotated in `turns` increments (`None`: stretch
/// only).
fn model(law: MaterialLaw, turns: Option<usize>) -> Model {
    let n = 2;
    let mut nodes = Vec::new();
    for j in 0..=n {
        for i in 0..=n {
            nodes.push([1.0 + i as f64 / n as f64, j as f64 / n as f64]);
        }
    }
    let id = |i: usize, j: usize| j * (n + 1) + i;
    let mut cells = Vec::new();
    for j in 0..n {
        for i in 0..n {
            cells.push(Cell::quad(
                id(i, j),
                id(i + 1, j),
                id(i + 1, j + 1),
                id(i, j + 1),
            ));
        }
    }
    // table points at every increment end
    let f0 = [[1.06, 0.02], [0.0, 0.97]];
    let c = [1.5, 0.5];
    let mut constraints = Vec::new();
    for (k, x) in nodes.iter().enumerate() {
        let (i, j) = (k % (n + 1), k / (n + 1));
        if !(i == 0 || j == 0 || i == n || j == n) {
            continue;
        }
        let d = [x[0] - c[0], x[1] - c[1]];
        let fd = [
            f0[0][0] * d[0] + f0[0][1] * d[1],
            f0[1][0] * d[0] + f0[1][1] * d[1],
        ];
        for comp in 0..2 {
            let mut table = vec![(0.0, 0.0), (1.0, fd[comp] - d[comp])];
            let n_rot = turns.unwrap_or(0);
            for s in 1..=n_rot {
                let th = std::f64::consts::FRAC_PI_2 * s as f64 / n_rot as f64;
                let (co, si) = (th.cos(), th.sin());
                let r = [co * fd[0] - si * fd[1], si * fd[0] + co * fd[1]];
                table.push((1.0 + s as f64 / n_rot as f64, r[comp] - d[comp]));
            }
            constraints.push(Dirichlet {
                label: format!("node {k}"),
                nodes: vec![k],
                component: comp,
                value: TimeFunction::Table(table),
            });
        }
    }
    let mut b = ModelBuilder::new(AnalysisKind::PlaneStrain)
        .material("m", law)
        .body("b", Mesh::new(nodes, cells), "m")
        .kinematics(Kinematics::Finite);
    for c in constraints {
        b = b.constraint(c);
    }
    b = b
        .step("stretch", 1.0, 4)
        .min_fraction(1.0 / 64.0)
        .tol(1e-10);
    if let Some(turns) = turns {
        b = b
            .step("rotate", 2.0, turns)
            .min_fraction(1.0 / 64.0)
            .tol(1e-10);
    }
    b.build()
}

/// Trace, 2D determinant and zz of a stress (xx, yy, zz, xy).
fn invariants(s: &[f64]) -> [f64; 3] {
    [s[0] + s[1] + s[2], s[0] * s[1] - s[3] * s[3], s[2]]
}

fn solve(model: &Model) -> Result<(Points, RunSummary), String> {
    let mut points = Points::default();
    let summary = run(model, &mut points).map_err(|e| format!("solver: {}", e.message))?;
    Ok((points, summary))
}

fn objectivity_level(level: usize) -> Result<ProgramLevel, String> {
    let turns = turns(level);
    let mut out = ProgramLevel {
        h: f64::NAN,
        ..ProgramLevel::default()
    };
    for (s_name, ep_name, law) in laws() {
        let (before, _) = solve(&model(law.clone(), None))?;
        let (after, summary) = solve(&model(law, Some(turns)))?;
        let (mut worst, mut scale, mut worst_ep, mut ep) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
        for (b, a) in before.0.iter().flatten().zip(after.0.iter().flatten()) {
            let (s0, s1) = (b.state.stress, a.state.stress);
            // R(90) sigma R^T: xx <- yy, yy <- xx, xy <- -xy
            let rot = [s0[1], s0[0], s0[2], -s0[3]];
            for k in 0..4 {
                worst = worst.max((s1[k] - rot[k]).abs());
            }
            let (i0, i1) = (invariants(s0.as_slice()), invariants(s1.as_slice()));
            for k in 0..3 {
                worst = worst.max((i0[k] - i1[k]).abs() / s0.norm().max(1.0));
            }
            scale = scale.max(s0.norm());
            worst_ep = worst_ep.max((a.history.ep - b.history.ep).abs());
            ep = ep.max(b.history.ep);
        }
        if scale <= 1.0 {
            return Err(format!("{s_name}: the stretch left no stress ({scale:e})"));
        }
        out.values.push(error(s_name, worst / scale));
        if let Some(ep_name) = ep_name {
            if ep <= 0.01 {
                return Err(format!(
                    "{ep_name}: the stretch did not yield (ep = {ep:e}): the check says nothing"
                ));
            }
            out.values.push(error(ep_name, worst_ep));
        }
        out.add_run(&summary);
    }
    Ok(out)
}

/// The registry entry.
pub fn cases() -> Vec<VerifyCase> {
    let checks = laws()
        .into_iter()
        .flat_map(|(s, ep, _)| {
            // measured 0.9e-14 .. 1.8e-14 at levels 0-2 (round-off); ep
            // change exactly 0
            let mut c = vec![Check::new(Quantity::Named(s), &[1e-11])];
            c.extend(ep.map(|e| Check::new(Quantity::Named(e), &[1e-12])));
            c
        })
        .collect();
    vec![VerifyCase {
        name: "objectivity_plane_strain",
        title: "Objectivity: pre-stressed body rotated 90 degrees, plane strain, sigma = R sigma0 R^T, ep unchanged (neo-Hookean, Hencky, J2)",
        source: "rigid-rotation invariance of the finite-strain laws (Simo & Hughes, Computational Inelasticity §9)",
        tags: &["finite_strain", "objectivity", "plasticity", "plane_strain"],
        levels: 2,
        checks,
        kind: CaseKind::Program(ProgramCase {
            max_levels: 3,
            run: objectivity_level,
        }),
    }]
}
