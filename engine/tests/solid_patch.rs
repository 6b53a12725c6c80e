//! Solid (3D) runs through the dimension-generic solver.
//!
//! Patch tests (the classic check of Irons; MacNeal and Harder, "A proposed
//! standard set of problems to test finite element accuracy", Finite
//! Elements in Analysis and Design 1 (1985), the patch with distorted
//! interior nodes): a linear displacement field `u = b + A x` prescribed on
//! the boundary of a distorted brick mesh must be reproduced at the
//! interior nodes, with the same stress at every integration point, for
//! tet4 and hex8 (full, B-bar / F-bar) and every law (small strain: linear
//! elastic and J2 plastic; finite strain: Neo-Hooke and J2 multiplicative).
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

use ctc_engine::element::recovery::{blocks_of, cell_states};
use ctc_engine::element::{MaterialPoint, PointState, Section};
use ctc_engine::mesh::generate::{solid, Grading};
use ctc_engine::mesh::{CellKind, Mesh};
use ctc_engine::model::*;
use ctc_engine::solve::restart::Checkpoint;
use ctc_engine::solve::{run, run_from, IncrementView, Observer};
use ctc_engine::testkit::ModelBuilder;

/// The last converged state of a 3D run, and the checkpoints on request.
#[derive(Default)]
struct Last {
    u: Vec<[f64; 3]>,
    points: Vec<Vec<MaterialPoint>>,
    checkpoints: Vec<Checkpoint<3>>,
    want_checkpoints: bool,
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

const A_SMALL: [[f64; 3]; 3] = [
    [1.0e-3, 2.0e-4, -3.0e-4],
    [-1.0e-4, -5.0e-4, 4.0e-4],
    [2.5e-4, 1.5e-4, 8.0e-4],
];
const B: [f64; 3] = [1e-3, -2e-3, 5e-4];

/// The distorted 3 x 3 x 3 brick.
fn distorted(kind: CellKind) -> Mesh<3> {
    let mut m = solid::brick(
        [0.0, 0.0, 0.0],
        [1.0, 2.0, 1.5],
        [3, 3, 3],
        [Grading::Uniform; 3],
        kind,
    )
    .unwrap();
    let h = [1.0 / 3.0, 2.0 / 3.0, 0.5];
    let mut seed = 0x9e37_79b9_7f4a_7c15u64;
    let mut next = || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    };
    let size = [1.0, 2.0, 1.5];
    for p in &mut m.nodes {
        let interior = (0..3).all(|k| p[k] > 1e-12 && p[k] < size[k] - 1e-12);
        if interior {
            for k in 0..3 {
                p[k] += 0.12 * h[k] * next();
            }
        }
    }
    m
}

fn field(a: &[[f64; 3]; 3], x: &[f64; 3]) -> [f64; 3] {
    std::array::from_fn(|i| B[i] + (0..3).map(|j| a[i][j] * x[j]).sum::<f64>())
}

/// The patch model: every boundary node prescribed with `u = b + A x`.
fn patch_model(
    kind: CellKind,
    law: MaterialLaw,
    formulation: Formulation,
    kinematics: Kinematics,
    a: &[[f64; 3]; 3],
) -> Model<3> {
    let mesh = distorted(kind);
    let mut b = ModelBuilder::solid()
        .material("m", law)
        .body("block", mesh.clone(), "m")
        .formulation(formulation)
        .kinematics(kinematics);
    let boundary: Vec<usize> = {
        let mut n: Vec<usize> = mesh
            .boundary_facets(0..mesh.cells.len())
            .iter()
            .flat_map(|f| f.nodes().to_vec())
            .collect();
        n.sort_unstable();
        n.dedup();
        n
    };
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
fn states(model: &Model<3>, last: &Last) -> Vec<PointState> {
    let blocks = blocks_of(model).unwrap();
    let section = Section::new(&model.analysis);
    let mut out = Vec::new();
    for (c, pts) in last.points.iter().enumerate() {
        if pts.is_empty() {
            let block = blocks.iter().find(|b| b.cells.contains(&c)).unwrap();
            out.extend(cell_states(&model.mesh, c, &last.u, &section, block).unwrap());
        } else {
            out.extend(pts.iter().map(|p| p.state));
        }
    }
    out
}

/// (displacement error at every node / |u|max, stress spread over the
/// points / |sigma|max, the first point's stress).
fn patch(
    kind: CellKind,
    law: MaterialLaw,
    formulation: Formulation,
    kinematics: Kinematics,
    a: &[[f64; 3]; 3],
) -> (f64, f64, [f64; 6], Vec<PointState>) {
    let model = patch_model(kind, law, formulation, kinematics, a);
    let mut last = Last::default();
    let summary = run(&model, &mut last).unwrap_or_else(|e| panic!("{}", e.message));
    assert!(summary.completed);
    let mut err: f64 = 0.0;
    let mut umax: f64 = 0.0;
    for (x, u) in model.mesh.nodes.iter().zip(&last.u) {
        let e = field(a, x);
        for k in 0..3 {
            err = err.max((u[k] - e[k]).abs());
            umax = umax.max(e[k].abs());
        }
    }
    let st = states(&model, &last);
    let s0: [f64; 6] = std::array::from_fn(|k| st[0].stress[k]);
    let smax = s0.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let spread = st
        .iter()
        .flat_map(|p| (0..6).map(move |k| (p.stress[k] - s0[k]).abs()))
        .fold(0.0, f64::max);
    (err / umax, spread / smax, s0, st)
}

const E: f64 = 210e3;
const NU: f64 = 0.3;

fn plastic() -> MaterialLaw {
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

#[test]
fn solid_patch_linear_elastic_tet4_and_hex8_reproduce_the_exact_stress() {
    let law = MaterialLaw::LinearElastic {
        young: E,
        poisson: NU,
    };
    let (lambda, mu) = (
        E * NU / ((1.0 + NU) * (1.0 - 2.0 * NU)),
        E / (2.0 * (1.0 + NU)),
    );
    let a = &A_SMALL;
    let tr = a[0][0] + a[1][1] + a[2][2];
    let exact = [
        lambda * tr + 2.0 * mu * a[0][0],
        lambda * tr + 2.0 * mu * a[1][1],
        lambda * tr + 2.0 * mu * a[2][2],
        mu * (a[0][1] + a[1][0]),
        mu * (a[0][2] + a[2][0]),
        mu * (a[1][2] + a[2][1]),
    ];
    for (kind, f) in [
        (CellKind::Tet4, Formulation::Full),
        (CellKind::Hex8, Formulation::Full),
        (CellKind::Hex8, Formulation::SelectiveReduced),
    ] {
        let (du, spread, _, st) = patch(kind, law.clone(), f, Kinematics::Small, a);
        let smax = exact.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let serr = st
            .iter()
            .flat_map(|p| (0..6).map(move |k| (p.stress[k] - exact[k]).abs()))
            .fold(0.0, f64::max)
            / smax;
        println!("patch linear {kind:?} {f:?}: u error {du:.2e}, stress error {serr:.2e}");
        assert!(
            du <= 1e-10 && serr <= 1e-10 && spread <= 1e-10,
            "{kind:?} {f:?}"
        );
    }
}

#[test]
fn solid_patch_j2_small_strain_yields_uniformly() {
    for (kind, f) in [
        (CellKind::Tet4, Formulation::Full),
        (CellKind::Hex8, Formulation::SelectiveReduced),
    ] {
        let (du, spread, _, st) = patch(kind, plastic(), f, Kinematics::Small, &A_SMALL);
        println!("patch J2 small {kind:?} {f:?}: u error {du:.2e}, stress spread {spread:.2e}");
        assert!(du <= 1e-10 && spread <= 1e-10, "{kind:?}");
        // the patch is plastic: the law's yield was crossed
        let q = st[0].stress;
        let m = (q[0] + q[1] + q[2]) / 3.0;
        let s2 = (q[0] - m).powi(2)
            + (q[1] - m).powi(2)
            + (q[2] - m).powi(2)
            + 2.0 * (q[3] * q[3] + q[4] * q[4] + q[5] * q[5]);
        assert!((1.5 * s2).sqrt() > 100.0);
    }
}

#[test]
fn solid_patch_finite_strain_neo_hooke_and_j2_are_homogeneous() {
    let a = [
        [0.10, 0.03, -0.02],
        [-0.04, -0.06, 0.05],
        [0.02, 0.01, 0.08],
    ];
    let neo = MaterialLaw::NeoHookean {
        young: 10.0,
        poisson: 0.45,
    };
    for (kind, f, law) in [
        (CellKind::Tet4, Formulation::Full, neo.clone()),
        (CellKind::Hex8, Formulation::Full, neo.clone()),
        (CellKind::Hex8, Formulation::SelectiveReduced, neo),
        (CellKind::Tet4, Formulation::Full, plastic()),
        (CellKind::Hex8, Formulation::SelectiveReduced, plastic()),
    ] {
        let (du, spread, _, _) = patch(kind, law, f, Kinematics::Finite, &a);
        println!("patch finite {kind:?} {f:?}: u error {du:.2e}, stress spread {spread:.2e}");
        assert!(du <= 1e-10 && spread <= 1e-10, "{kind:?} {f:?}");
    }
}

/// Rotation by `angle` about the unit axis `n` (Rodrigues).
fn rotation(n: [f64; 3], angle: f64) -> [[f64; 3]; 3] {
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

#[test]
fn solid_objectivity_rotation_of_a_prestressed_block_by_90_degrees() {
    let len = 14f64.sqrt();
    let axis = [1.0 / len, 2.0 / len, 3.0 / len];
    let f0 = [[1.08, 0.02, 0.0], [0.0, 0.95, 0.01], [0.0, 0.0, 1.03]];
    let quarter = std::f64::consts::FRAC_PI_2;
    for (kind, law) in [
        (
            CellKind::Hex8,
            MaterialLaw::NeoHookean {
                young: 10.0,
                poisson: 0.3,
            },
        ),
        (CellKind::Tet4, plastic()),
    ] {
        let mesh = solid::brick(
            [0.0; 3],
            [1.0, 1.0, 1.0],
            [1, 1, 1],
            [Grading::Uniform; 3],
            kind,
        )
        .unwrap();
        let mut b = ModelBuilder::solid()
            .material("m", law)
            .body("b", mesh.clone(), "m")
            .kinematics(Kinematics::Finite);
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
        run(&stretched, &mut s0).unwrap_or_else(|e| panic!("{}", e.message));
        let mut s1 = Last::default();
        run(&model, &mut s1).unwrap_or_else(|e| panic!("{}", e.message));
        let r = rotation(axis, quarter);
        let rt: [[f64; 3]; 3] = std::array::from_fn(|i| std::array::from_fn(|j| r[j][i]));
        let (before, after) = (states(&stretched, &s0), states(&model, &s1));
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
        let dep = ep0
            .iter()
            .zip(&ep1)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max);
        println!("objectivity {kind:?}: |sigma - R sigma0 R^T| / |sigma0| = {worst:.2e}, max ep change {dep:.2e}, ep {:.3e}", ep0.first().copied().unwrap_or(0.0));
        assert!(worst <= 1e-12, "{kind:?}: {worst:e}");
        assert!(dep <= 1e-12, "{kind:?}: {dep:e}");
    }
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
