//! Solid (3D) reference scenes shared by `engine/tests/solid_patch.rs` and
//! the `ctc verify` cases of tag `3d` (`verification/src/programs/`), so the
//! cargo test and the verification case are the same computation.
//!
//! - [`patch`]: the patch test (Irons; MacNeal and Harder, "A proposed
//!   standard set of problems to test finite element accuracy", Finite
//!   Elements in Analysis and Design 1 (1985), the patch with distorted
//!   interior nodes): a linear displacement field `u = b + A x` prescribed
//!   on the boundary of a distorted 3 x 3 x 3 brick must be reproduced at
//!   the interior nodes, with the same stress at every integration point.
//!
//!   ```text
//!     z
//!     |  3 x 3 x 3 cells on [0,1] x [0,2] x [0,1.5], the 8 interior nodes
//!     | /y   moved by up to 0.12 h in every direction
//!     |/___ x   boundary nodes: u = b + A x (all three components)
//!   ```
//!
//! - [`objectivity`]: a unit block stretched homogeneously by `F0` (step 1,
//!   past yield for J2), then rotated rigidly by 90 degrees about the axis
//!   `(1, 2, 3) / |..|` (step 2, 4 increments): the Cauchy stress must be
//!   `R sigma_0 R^T` and the plastic strain unchanged.

use super::ModelBuilder;
use crate::element::recovery::{blocks_of, cell_states};
use crate::element::{MaterialPoint, PointState, Section};
use crate::mesh::generate::{solid, Grading};
use crate::mesh::{CellKind, Mesh};
use crate::model::{Formulation, Hardening, Kinematics, MaterialLaw, Model, TimeFunction};
use crate::solve::restart::Checkpoint;
use crate::solve::{run, IncrementView, Observer, RunSummary};

/// The last converged state of a 3D run, and the checkpoints on request.
#[derive(Debug, Default)]
pub struct Last {
    /// Nodal displacements.
    pub u: Vec<[f64; 3]>,
    /// Integration points of nonlinear cells (empty for linear cells).
    pub points: Vec<Vec<MaterialPoint>>,
    /// Checkpoints, when `want_checkpoints`.
    pub checkpoints: Vec<Checkpoint<3>>,
    /// Whether checkpoints are kept.
    pub want_checkpoints: bool,
}

impl Observer<3> for Last {
    fn converged(&mut self, v: &IncrementView<'_, 3>) -> Result<(), String> {
        self.u = v.displacement.to_vec();
        self.points = v.points.to_vec();
        Ok(())
    }
    fn wants_checkpoint(&self) -> bool {
        self.want_checkpoints
    }
    fn checkpoint(&mut self, c: &Checkpoint<3>) -> Result<(), String> {
        self.checkpoints.push(c.clone());
        Ok(())
    }
}

/// The small-strain gradient `A` of the patch field.
pub const A_SMALL: [[f64; 3]; 3] = [
    [1.0e-3, 2.0e-4, -3.0e-4],
    [-1.0e-4, -5.0e-4, 4.0e-4],
    [2.5e-4, 1.5e-4, 8.0e-4],
];

/// A finite-strain gradient `A` of the patch field (`F = I + A`).
pub const A_FINITE: [[f64; 3]; 3] = [
    [0.10, 0.03, -0.02],
    [-0.04, -0.06, 0.05],
    [0.02, 0.01, 0.08],
];

/// The translation `b` of the patch field.
pub const B: [f64; 3] = [1e-3, -2e-3, 5e-4];

/// Young's modulus of the patch and objectivity laws.
pub const E: f64 = 210e3;
/// Poisson's ratio of the patch and objectivity laws.
pub const NU: f64 = 0.3;

/// J2 with linear hardening (yield 100, H = 2000): plastic in every scene.
pub fn plastic() -> MaterialLaw {
    MaterialLaw::ElastoPlastic {
        young: E,
        poisson: NU,
        hardening: Hardening::Linear {
            yield_stress: 100.0,
            modulus: 2000.0,
        },
        viscosity: None,
    }
}

/// The distorted 3 x 3 x 3 brick (deterministic jitter of the interior
/// nodes).
pub fn distorted(kind: CellKind) -> Mesh<3> {
    let mut m = solid::brick(
        [0.0, 0.0, 0.0],
        [1.0, 2.0, 1.5],
        [3, 3, 3],
        [Grading::Uniform; 3],
        kind,
    )
    .expect("a valid brick");
    let h = [1.0 / 3.0, 2.0 / 3.0, 0.5];
    let mut rng = super::Rng(0x9e37_79b9_7f4a_7c15);
    let size = [1.0, 2.0, 1.5];
    for p in &mut m.nodes {
        let interior = (0..3).all(|k| p[k] > 1e-12 && p[k] < size[k] - 1e-12);
        if interior {
            for k in 0..3 {
                p[k] += 0.12 * h[k] * rng.sym();
            }
        }
    }
    m
}

/// `b + A x`.
pub fn field(a: &[[f64; 3]; 3], x: &[f64; 3]) -> [f64; 3] {
    std::array::from_fn(|i| B[i] + (0..3).map(|j| a[i][j] * x[j]).sum::<f64>())
}

/// The patch model: every boundary node prescribed with `u = b + A x`.
pub fn patch_model(
    kind: CellKind,
    law: MaterialLaw,
    formulation: Formulation,
    kinematics: Kinematics,
    a: &[[f64; 3]; 3],
) -> Model<3> {
    patch_model_on(distorted(kind), law, formulation, kinematics, a)
}

/// The patch model on `mesh` (any cell kinds): every boundary node
/// prescribed with `u = b + A x`.
pub fn patch_model_on(
    mesh: Mesh<3>,
    law: MaterialLaw,
    formulation: Formulation,
    kinematics: Kinematics,
    a: &[[f64; 3]; 3],
) -> Model<3> {
    let mut b = ModelBuilder::solid()
        .material("m", law)
        .body("block", mesh.clone(), "m")
        .formulation(formulation)
        .kinematics(kinematics);
    let mut boundary: Vec<usize> = mesh
        .boundary_facets(0..mesh.cells.len())
        .iter()
        .flat_map(|f| f.nodes().to_vec())
        .collect();
    boundary.sort_unstable();
    boundary.dedup();
    for &n in &boundary {
        let u = field(a, &mesh.nodes[n]);
        for (c, uc) in u.iter().enumerate() {
            b = b.displace([n], c, TimeFunction::Constant(*uc));
        }
    }
    b.step("load", 1.0, 1).tol(1e-12).build()
}

/// Integration point states of the last increment (stored points of
/// nonlinear laws, recomputed for linear cells).
pub fn states(model: &Model<3>, last: &Last) -> Result<Vec<PointState>, String> {
    let blocks = blocks_of(model)?;
    let section = Section::new(&model.analysis);
    let mut out = Vec::new();
    for (c, pts) in last.points.iter().enumerate() {
        if pts.is_empty() {
            let block = blocks
                .iter()
                .find(|b| b.cells.contains(&c))
                .ok_or_else(|| format!("cell {c} in no block"))?;
            out.extend(
                cell_states(&model.mesh, c, &last.u, &section, block).map_err(|e| e.message)?,
            );
        } else {
            out.extend(pts.iter().map(|p| p.state));
        }
    }
    Ok(out)
}

/// The measured result of one patch run.
#[derive(Debug, Clone)]
pub struct Patch {
    /// `max |u - u_exact|` over every node and component / `max |u_exact|`.
    pub u_error: f64,
    /// `max |sigma - sigma_0|` over the points and components / `max
    /// |sigma_0|` (`sigma_0` the first point's stress).
    pub stress_spread: f64,
    /// The stress of every integration point.
    pub states: Vec<PointState>,
    /// The run's summary.
    pub summary: RunSummary,
}

impl Patch {
    /// `max |sigma - exact|` over the points and components / `max |exact|`.
    pub fn stress_error(&self, exact: &[f64; 6]) -> f64 {
        let smax = exact.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        self.states
            .iter()
            .flat_map(|p| (0..6).map(move |k| (p.stress[k] - exact[k]).abs()))
            .fold(0.0, f64::max)
            / smax
    }

    /// Von Mises stress of the first point.
    pub fn mises(&self) -> f64 {
        let q = self.states[0].stress;
        let m = (q[0] + q[1] + q[2]) / 3.0;
        let s2 = (q[0] - m).powi(2)
            + (q[1] - m).powi(2)
            + (q[2] - m).powi(2)
            + 2.0 * (q[3] * q[3] + q[4] * q[4] + q[5] * q[5]);
        (1.5 * s2).sqrt()
    }
}

/// Runs the patch test of `kind` / `law` / `formulation` / `kinematics`
/// with the field gradient `a`.
pub fn patch(
    kind: CellKind,
    law: MaterialLaw,
    formulation: Formulation,
    kinematics: Kinematics,
    a: &[[f64; 3]; 3],
) -> Result<Patch, String> {
    patch_on(distorted(kind), law, formulation, kinematics, a)
}

/// [`patch`] on the mesh `mesh` (e.g. the distorted brick elevated to
/// quadratic cells by `crate::mesh::elevate`).
pub fn patch_on(
    mesh: Mesh<3>,
    law: MaterialLaw,
    formulation: Formulation,
    kinematics: Kinematics,
    a: &[[f64; 3]; 3],
) -> Result<Patch, String> {
    let model = patch_model_on(mesh, law, formulation, kinematics, a);
    let mut last = Last::default();
    let summary = run(&model, &mut last).map_err(|e| e.message)?;
    if !summary.completed {
        return Err("the patch run did not complete".into());
    }
    let mut err: f64 = 0.0;
    let mut umax: f64 = 0.0;
    for (x, u) in model.mesh.nodes.iter().zip(&last.u) {
        let e = field(a, x);
        for k in 0..3 {
            err = err.max((u[k] - e[k]).abs());
            umax = umax.max(e[k].abs());
        }
    }
    let states = states(&model, &last)?;
    let s0 = states[0].stress;
    let smax = s0.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let spread = states
        .iter()
        .flat_map(|p| (0..6).map(move |k| (p.stress[k] - s0[k]).abs()))
        .fold(0.0, f64::max);
    Ok(Patch {
        u_error: err / umax,
        stress_spread: spread / smax,
        states,
        summary,
    })
}

/// The exact small-strain linear elastic stress of the field gradient `a`.
pub fn linear_stress(young: f64, poisson: f64, a: &[[f64; 3]; 3]) -> [f64; 6] {
    let (lambda, mu) = (
        young * poisson / ((1.0 + poisson) * (1.0 - 2.0 * poisson)),
        young / (2.0 * (1.0 + poisson)),
    );
    let tr = a[0][0] + a[1][1] + a[2][2];
    [
        lambda * tr + 2.0 * mu * a[0][0],
        lambda * tr + 2.0 * mu * a[1][1],
        lambda * tr + 2.0 * mu * a[2][2],
        mu * (a[0][1] + a[1][0]),
        mu * (a[0][2] + a[2][0]),
        mu * (a[1][2] + a[2][1]),
    ]
}

/// Rotation by `angle` about the unit axis `n` (Rodrigues).
pub fn rotation(n: [f64; 3], angle: f64) -> [[f64; 3]; 3] {
    let (s, c) = angle.sin_cos();
    let k = [[0.0, -n[2], n[1]], [n[2], 0.0, -n[0]], [-n[1], n[0], 0.0]];
    std::array::from_fn(|i| {
        std::array::from_fn(|j| {
            let kk: f64 = (0..3).map(|m| k[i][m] * k[m][j]).sum();
            f64::from(u8::from(i == j)) + s * k[i][j] + (1.0 - c) * kk
        })
    })
}

fn matmul(a: &[[f64; 3]; 3], b: &[[f64; 3]; 3]) -> [[f64; 3]; 3] {
    std::array::from_fn(|i| std::array::from_fn(|j| (0..3).map(|m| a[i][m] * b[m][j]).sum()))
}

fn tensor(s: &[f64]) -> [[f64; 3]; 3] {
    [[s[0], s[3], s[4]], [s[3], s[1], s[5]], [s[4], s[5], s[2]]]
}

/// The measured result of one objectivity run.
#[derive(Debug, Clone, Copy)]
pub struct Objectivity {
    /// `max over the points |sigma - R sigma_0 R^T| / |sigma_0|` (Frobenius).
    pub stress: f64,
    /// `max |ep - ep_0|` over the points.
    pub plastic_change: f64,
    /// The equivalent plastic strain of the first point after the stretch.
    pub plastic: f64,
}

/// The objectivity scene of `kind` / `law` / `formulation` (finite strain):
/// stretch by `F0`, then a rigid rotation by 90 degrees about `(1, 2, 3)`.
pub fn objectivity(
    kind: CellKind,
    law: MaterialLaw,
    formulation: Formulation,
) -> Result<Objectivity, String> {
    let len = 14f64.sqrt();
    let axis = [1.0 / len, 2.0 / len, 3.0 / len];
    let f0 = [[1.08, 0.02, 0.0], [0.0, 0.95, 0.01], [0.0, 0.0, 1.03]];
    let quarter = std::f64::consts::FRAC_PI_2;
    let mesh = solid::brick(
        [0.0; 3],
        [1.0, 1.0, 1.0],
        [1, 1, 1],
        [Grading::Uniform; 3],
        kind,
    )
    .map_err(|e| e.message)?;
    let mut b = ModelBuilder::solid()
        .material("m", law)
        .body("b", mesh.clone(), "m")
        .kinematics(Kinematics::Finite)
        .formulation(formulation);
    // u(t) = R(theta(t)) F(t) X - X: stretch over [0, 1], rotate over [1, 2]
    let times: Vec<f64> = (0..=8).map(|k| f64::from(k) * 0.25).collect();
    for (n, x) in mesh.nodes.iter().enumerate() {
        for c in 0..3 {
            let table = times
                .iter()
                .map(|&t| {
                    let s = t.min(1.0);
                    let f: [[f64; 3]; 3] = std::array::from_fn(|i| {
                        std::array::from_fn(|j| {
                            f64::from(u8::from(i == j))
                                + s * (f0[i][j] - f64::from(u8::from(i == j)))
                        })
                    });
                    let r = rotation(axis, quarter * (t - 1.0).max(0.0));
                    let rf = matmul(&r, &f);
                    let y: f64 = (0..3).map(|j| rf[c][j] * x[j]).sum();
                    (t, y - x[c])
                })
                .collect();
            b = b.displace([n], c, TimeFunction::Table(table));
        }
    }
    let model = b
        .step("stretch", 1.0, 4)
        .tol(1e-12)
        .step("rotate", 2.0, 4)
        .tol(1e-12)
        .build();
    // state after the stretch alone
    let mut stretched = model.clone();
    stretched.steps.truncate(1);
    let mut s0 = Last::default();
    run(&stretched, &mut s0).map_err(|e| e.message)?;
    let mut s1 = Last::default();
    run(&model, &mut s1).map_err(|e| e.message)?;
    let r = rotation(axis, quarter);
    let rt: [[f64; 3]; 3] = std::array::from_fn(|i| std::array::from_fn(|j| r[j][i]));
    let (before, after) = (states(&stretched, &s0)?, states(&model, &s1)?);
    let mut worst: f64 = 0.0;
    for (p0, p1) in before.iter().zip(&after) {
        let expect = matmul(&matmul(&r, &tensor(p0.stress.as_slice())), &rt);
        let got = tensor(p1.stress.as_slice());
        let norm0 = tensor(p0.stress.as_slice())
            .iter()
            .flatten()
            .map(|v| v * v)
            .sum::<f64>()
            .sqrt();
        let diff = (0..3)
            .flat_map(|i| (0..3).map(move |j| (i, j)))
            .map(|(i, j)| (got[i][j] - expect[i][j]).powi(2))
            .sum::<f64>()
            .sqrt();
        worst = worst.max(diff / norm0);
    }
    let ep = |l: &Last| {
        l.points
            .iter()
            .flatten()
            .map(|p| p.history.ep)
            .collect::<Vec<_>>()
    };
    let (ep0, ep1) = (ep(&s0), ep(&s1));
    let change = ep0
        .iter()
        .zip(&ep1)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    Ok(Objectivity {
        stress: worst,
        plastic_change: change,
        plastic: ep0.first().copied().unwrap_or(0.0),
    })
}
