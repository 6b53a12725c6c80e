//! Objectivity of the finite-strain kernel (VERIFICATION-CASES case 6, last
//! item): a body is pre-stressed by a homogeneous stretch (plastic for J2),
//! then rotated rigidly by 90 degrees in increments, the motion
//! `x = R(theta) F0 X` being prescribed on all boundary nodes. At the end
//! the Cauchy stress must be the rotated initial stress `R sigma0 R^T`
//! (xx and yy swapped, xy negated), the invariants unchanged, and no
//! plastic strain created by the rotation.

use ctc_engine::element::MaterialPoint;
use ctc_engine::mesh::{Cell, Mesh};
use ctc_engine::model::{
    AnalysisKind, Dirichlet, Hardening, Kinematics, MaterialLaw, Model, TimeFunction,
};
use ctc_engine::solve::{run, IncrementView, Observer};
use ctc_engine::testkit::ModelBuilder;

#[derive(Default)]
struct Points(Vec<Vec<MaterialPoint>>);

impl Observer for Points {
    fn converged(&mut self, view: &IncrementView<'_>) -> Result<(), String> {
        self.0 = view.points.to_vec();
        Ok(())
    }
}

fn rotated_model(law: MaterialLaw, kind: AnalysisKind, rotate: bool, turns: usize) -> Model {
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
    // pre-stretch F0 (t in [0, 1]) then rotation by 90 degrees about the
    // body's centre (t in [1, 2]), table points at every increment end
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
            if rotate {
                for s in 1..=turns {
                    let th = std::f64::consts::FRAC_PI_2 * s as f64 / turns as f64;
                    let (co, si) = (th.cos(), th.sin());
                    let r = [co * fd[0] - si * fd[1], si * fd[0] + co * fd[1]];
                    table.push((1.0 + s as f64 / turns as f64, r[comp] - d[comp]));
                }
            }
            constraints.push(Dirichlet {
                label: format!("node {k}"),
                nodes: vec![k],
                component: comp,
                value: TimeFunction::Table(table),
            });
        }
    }
    let mut b = ModelBuilder::new(kind)
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
    if rotate {
        b = b
            .step("rotate", 2.0, turns)
            .min_fraction(1.0 / 64.0)
            .tol(1e-10);
    }
    b.build()
}

fn invariants(s: &[f64]) -> [f64; 3] {
    let tr = s[0] + s[1] + s[2];
    let det2 = s[0] * s[1] - s[3] * s[3];
    [tr, det2, s[2]]
}

#[test]
fn finite_objectivity_rigid_rotation_of_prestressed_body_90_degrees() {
    let laws = [
        (
            "neo_hookean",
            MaterialLaw::NeoHookean {
                young: 200e3,
                poisson: 0.3,
            },
        ),
        (
            "hencky",
            MaterialLaw::LinearElastic {
                young: 200e3,
                poisson: 0.3,
            },
        ),
        (
            "j2_swift",
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
    ];
    for (name, law) in laws {
        let model0 = rotated_model(law.clone(), AnalysisKind::PlaneStrain, false, 0);
        let mut before = Points::default();
        run(&model0, &mut before).unwrap_or_else(|e| panic!("{}", e.message));
        for turns in [3, 9] {
            let model = rotated_model(law.clone(), AnalysisKind::PlaneStrain, true, turns);
            let mut after = Points::default();
            run(&model, &mut after).unwrap_or_else(|e| panic!("{}", e.message));
            let (mut worst, mut scale, mut worst_ep) = (0.0f64, 0.0f64, 0.0f64);
            for (b, a) in before.0.iter().flatten().zip(after.0.iter().flatten()) {
                let s0 = b.state.stress;
                let s1 = a.state.stress;
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
            }
            let ep = before
                .0
                .iter()
                .flatten()
                .map(|p| p.history.ep)
                .fold(0.0, f64::max);
            println!(
                "{name}, {turns} increments of {:.0} deg: |sigma - R sigma0 R^T| / |sigma0| = {:.1e} \
                 (|sigma0| = {scale:.1}), ep before {ep:.4}, ep change {worst_ep:.1e}",
                90.0 / turns as f64,
                worst / scale
            );
            assert!(scale > 1.0);
            assert!(worst / scale < 1e-9, "{name}: {}", worst / scale);
            assert!(
                worst_ep < 1e-12,
                "{name}: plastic strain created by a rotation"
            );
            if name == "j2_swift" {
                assert!(ep > 0.01, "the pre-stress must be plastic");
            }
        }
    }
}
