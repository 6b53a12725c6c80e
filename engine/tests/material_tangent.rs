//! Finite-difference checks of the element tangents of every nonlinear law
//! (small-strain J2 with linear, Swift and Voce hardening and Perzyna
//! visco-plasticity; finite-strain Neo-Hookean, Hencky, J2 and Perzyna),
//! for every element (tri3, quad4, tet4, hex8; full and B-bar / F-bar),
//! plane strain, axisymmetric and solid, small and finite strain, with and
//! without a thermal strain, over random shapes, displacement fields and
//! plastic histories: the automatic-differentiation tangent must match
//! central differences of the internal force to 1e-6 (relative, Frobenius
//! norm).

use ctc_engine::element::kernel::{HEX8, QUAD4, TET4, TRI3};
use ctc_engine::element::recovery::virgin;
use ctc_engine::element::{CellKernel, ElementMatrix, NonlinearInput, Section};
use ctc_engine::geom::Point;
use ctc_engine::material::tensor::{exp, Deformation};
use ctc_engine::material::{History, NonlinearLaw};
use ctc_engine::model::{AnalysisKind, Formulation, Kinematics};
use ctc_engine::testkit::laws::nonlinear_laws;
use nalgebra::DMatrix;
use proptest::prelude::*;

/// A plastic history: an isochoric plastic log strain (deviatoric, built
/// from the five numbers `p`, scaled by `a`), equivalent plastic strain
/// `ep`. Planar analyses keep `xz = yz = 0`.
fn history(finite: bool, planar: bool, a: f64, p: &[f64], ep: f64) -> History {
    let (xx, yy) = (a * p[0], a * p[1]);
    let mut e = [xx, yy, -xx - yy, a * p[2], a * p[3], a * p[4]];
    if planar {
        e[4] = 0.0;
        e[5] = 0.0;
    }
    if finite {
        // C_p^-1 = exp(-2 e_p)
        History {
            ep,
            tensor: exp(&e.map(|v| -2.0 * v)),
        }
    } else {
        History { ep, tensor: e }
    }
}

/// Everything of one evaluation but the displacement.
struct Case<'a, const D: usize> {
    kernel: &'a dyn CellKernel<D>,
    x: &'a [Point<D>],
    section: Section,
    formulation: Formulation,
    kinematics: Kinematics,
    law: &'a NonlinearLaw,
    history: Vec<History>,
    thermal_strain: f64,
}

impl<const D: usize> Case<'_, D> {
    fn eval(&self, u: &[Point<D>], with_tangent: bool) -> ElementMatrix<D> {
        let mut out = ElementMatrix::default();
        let mut states = vec![virgin(self.kinematics); self.kernel.point_count()];
        self.kernel
            .nonlinear(
                &NonlinearInput {
                    x: self.x,
                    u,
                    section: &self.section,
                    formulation: self.formulation,
                    kinematics: self.kinematics,
                    law: self.law,
                    history: &self.history,
                    dt: 0.1,
                    thermal_strain: self.thermal_strain,
                    with_tangent,
                },
                &mut out,
                &mut states,
            )
            .unwrap();
        out
    }

    /// `|K_fd - K| / |K|` at `u`.
    fn error(&self, u: &[Point<D>]) -> f64 {
        let k = self.eval(u, true);
        let nd = D * u.len();
        let kd = DMatrix::from_fn(nd, nd, |i, j| k.entry(i, j));
        let scale = u.iter().map(|p| p.amax()).fold(1e-3, f64::max);
        let h = 1e-6 * scale;
        let mut kfd = DMatrix::zeros(nd, nd);
        for j in 0..nd {
            let mut up = u.to_vec();
            let mut um = u.to_vec();
            up[j / D][j % D] += h;
            um[j / D][j % D] -= h;
            let (fp, fm) = (self.eval(&up, false), self.eval(&um, false));
            for i in 0..nd {
                kfd[(i, j)] = (fp.force_entry(i) - fm.force_entry(i)) / (2.0 * h);
            }
        }
        (kfd - &kd).norm() / kd.norm()
    }
}

/// The reference nodes of a cell mapped by `I + A` (entries of `a` in
/// [-0.3, 0.3]), jittered node by node, scaled and shifted; planar cells are
/// moved to `x >= 0.5` (axisymmetric radius).
fn shape<const D: usize>(
    reference: &[[f64; D]],
    a: &[f64],
    jitter: &[f64],
    scale: f64,
) -> Vec<Point<D>> {
    reference
        .iter()
        .enumerate()
        .map(|(n, c)| {
            let mut p = Point::<D>::zeros();
            for i in 0..D {
                p[i] = c[i] + jitter[D * n + i];
                for j in 0..D {
                    p[i] += a[D * i + j] * c[j];
                }
                p[i] *= scale;
            }
            p[0] += 2.0 * scale;
            p
        })
        .collect()
}

fn displacement<const D: usize>(v: &[f64], n: usize) -> Vec<Point<D>> {
    v[..D * n]
        .chunks(D)
        .map(Point::<D>::from_column_slice)
        .collect()
}

const TRI: [[f64; 2]; 3] = [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]];
const QUAD: [[f64; 2]; 4] = [[-0.5, -0.5], [0.5, -0.5], [0.5, 0.5], [-0.5, 0.5]];
const TET: [[f64; 3]; 4] = [
    [0.0, 0.0, 0.0],
    [1.0, 0.0, 0.0],
    [0.0, 1.0, 0.0],
    [0.0, 0.0, 1.0],
];
const HEX: [[f64; 3]; 8] = [
    [-0.5, -0.5, -0.5],
    [0.5, -0.5, -0.5],
    [0.5, 0.5, -0.5],
    [-0.5, 0.5, -0.5],
    [-0.5, -0.5, 0.5],
    [0.5, -0.5, 0.5],
    [0.5, 0.5, 0.5],
    [-0.5, 0.5, 0.5],
];

/// Random inputs shared by every check.
#[derive(Debug, Clone)]
struct Draw {
    a: Vec<f64>,
    jitter: Vec<f64>,
    scale: f64,
    grad: Vec<f64>,
    plastic: Vec<f64>,
    amplitude: f64,
    ep: f64,
    thermal: f64,
    reduced: bool,
}

fn draw(max_grad: f64) -> impl Strategy<Value = Draw> {
    (
        proptest::collection::vec(-0.3f64..0.3, 9),
        proptest::collection::vec(-0.08f64..0.08, 24),
        0.2f64..5.0,
        proptest::collection::vec(-max_grad..max_grad, 24),
        proptest::collection::vec(-1.0f64..1.0, 5),
        0.0f64..0.2,
        0.0f64..0.3,
        prop_oneof![Just(0.0), -0.01f64..0.01],
        any::<bool>(),
    )
        .prop_map(
            |(a, jitter, scale, grad, plastic, amplitude, ep, thermal, reduced)| Draw {
                a,
                jitter,
                scale,
                grad,
                plastic,
                amplitude,
                ep,
                thermal,
                reduced,
            },
        )
}

/// Checks every law on one element and returns the largest error.
fn check_element<const D: usize>(
    kernel: &dyn CellKernel<D>,
    reference: &[[f64; D]],
    kind: AnalysisKind,
    kinematics: Kinematics,
    d: &Draw,
) -> Result<f64, String> {
    let x = shape(reference, &d.a, &d.jitter, d.scale);
    // small strain: displacements of the order of the yield strain times
    // the size (plastic with the histories above); finite: large
    let finite = kinematics == Kinematics::Finite;
    let nodal = displacement::<D>(&d.grad, reference.len());
    let u: Vec<Point<D>> = if finite {
        // a large homogeneous gradient H (|H_ij| <= 0.25: by Gershgorin every
        // eigenvalue of I + H has real part >= 1 - 0.25 (D - 1) - 0.25 > 0,
        // so no draw inverts the cell) plus a nodal perturbation of a tenth
        // of it: independent nodal displacements of 0.25 x size invert
        // distorted tets
        let h = nalgebra::SMatrix::<f64, D, D>::from_fn(|i, j| d.grad[D * i + j]);
        let centroid = x.iter().fold(Point::<D>::zeros(), |s, p| s + p) / x.len() as f64;
        x.iter()
            .zip(&nodal)
            .map(|(p, n)| h * (p - centroid) + n * (0.1 * d.scale))
            .collect()
    } else {
        nodal.into_iter().map(|p| p * d.scale).collect()
    };
    let mut worst = 0.0f64;
    for (name, law) in nonlinear_laws() {
        if !finite
            && matches!(
                law,
                NonlinearLaw::NeoHookean { .. } | NonlinearLaw::Hencky { .. }
            )
        {
            continue;
        }
        let h = history(
            finite,
            D == 2,
            d.amplitude * if finite { 1.0 } else { 0.05 },
            &d.plastic,
            d.ep,
        );
        let case = Case {
            kernel,
            x: &x,
            section: Section {
                kind,
                thickness: 1.0,
            },
            formulation: if d.reduced {
                Formulation::SelectiveReduced
            } else {
                Formulation::Full
            },
            kinematics,
            law: &law,
            history: vec![h; kernel.point_count()],
            thermal_strain: d.thermal,
        };
        let err = case.error(&u);
        if err.is_nan() || err > 1e-6 {
            return Err(format!(
                "{} {kind:?} {kinematics:?} {name} reduced={}: |K_fd - K| / |K| = {err:e}",
                kernel.kind().name(),
                d.reduced
            ));
        }
        worst = worst.max(err);
    }
    Ok(worst)
}

fn planar_kind(axi: bool) -> AnalysisKind {
    if axi {
        AnalysisKind::Axisymmetric
    } else {
        AnalysisKind::PlaneStrain
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(16))]
    #[test]
    fn finite_strain_tangents_match_finite_differences(d in draw(0.25), axi in any::<bool>()) {
        let k = planar_kind(axi);
        check_element(&TRI3, &TRI, k, Kinematics::Finite, &d).map_err(TestCaseError::fail)?;
        check_element(&QUAD4, &QUAD, k, Kinematics::Finite, &d).map_err(TestCaseError::fail)?;
        check_element(&TET4, &TET, AnalysisKind::Solid, Kinematics::Finite, &d).map_err(TestCaseError::fail)?;
        check_element(&HEX8, &HEX, AnalysisKind::Solid, Kinematics::Finite, &d).map_err(TestCaseError::fail)?;
    }

    #[test]
    fn small_strain_tangents_match_finite_differences(d in draw(0.01), axi in any::<bool>()) {
        let k = planar_kind(axi);
        check_element(&TRI3, &TRI, k, Kinematics::Small, &d).map_err(TestCaseError::fail)?;
        check_element(&QUAD4, &QUAD, k, Kinematics::Small, &d).map_err(TestCaseError::fail)?;
        check_element(&TET4, &TET, AnalysisKind::Solid, Kinematics::Small, &d).map_err(TestCaseError::fail)?;
        check_element(&HEX8, &HEX, AnalysisKind::Solid, Kinematics::Small, &d).map_err(TestCaseError::fail)?;
    }
}

#[test]
fn tangent_checks_are_plastic() {
    // guard against a vacuous check: a stretch of 10 % is plastic at every point
    let x = shape(&HEX, &[0.0; 9], &[0.0; 24], 1.0);
    let law = &nonlinear_laws()[3].1;
    let mut out = ElementMatrix::default();
    let mut states = vec![virgin(Kinematics::Finite); 8];
    let u: Vec<Point<3>> = x
        .iter()
        .map(|p| Point::<3>::new(0.1 * (p[0] - 2.0), 0.0, 0.0))
        .collect();
    HEX8.nonlinear(
        &NonlinearInput {
            x: &x,
            u: &u,
            section: &Section {
                kind: AnalysisKind::Solid,
                thickness: 1.0,
            },
            formulation: Formulation::Full,
            kinematics: Kinematics::Finite,
            law,
            history: &[History::initial(Kinematics::Finite); 8],
            dt: 0.1,
            thermal_strain: 0.0,
            with_tangent: false,
        },
        &mut out,
        &mut states,
    )
    .unwrap();
    assert!(
        states.iter().all(|p| p.history.ep > 0.05),
        "{:?}",
        states[0].history
    );
    assert_eq!(Deformation::<f64>::identity().det(), 1.0);
}

#[test]
fn tangent_errors_per_element_and_law_are_small_and_printed() {
    // one fixed distorted, strongly deformed, plastic configuration
    let d = Draw {
        a: vec![0.1, -0.05, 0.02, 0.03, 0.08, -0.04, 0.0, 0.05, -0.1],
        jitter: (0..24)
            .map(|k| 0.05 * ((k * 7 % 11) as f64 / 11.0 - 0.5))
            .collect(),
        scale: 1.3,
        grad: (0..24)
            .map(|k| 0.2 * ((k * 5 % 13) as f64 / 13.0 - 0.5))
            .collect(),
        plastic: vec![0.5, -0.3, 0.2, 0.4, -0.1],
        amplitude: 0.05,
        ep: 0.1,
        thermal: 0.004,
        reduced: false,
    };
    for reduced in [false, true] {
        let d = Draw {
            reduced,
            ..d.clone()
        };
        let small = Draw {
            grad: d.grad.iter().map(|g| 0.05 * g).collect(),
            ..d.clone()
        };
        for (name, kinematics, draw) in [
            ("finite", Kinematics::Finite, &d),
            ("small", Kinematics::Small, &small),
        ] {
            let e = [
                check_element(&TRI3, &TRI, AnalysisKind::PlaneStrain, kinematics, draw).unwrap(),
                check_element(&QUAD4, &QUAD, AnalysisKind::Axisymmetric, kinematics, draw).unwrap(),
                check_element(&TET4, &TET, AnalysisKind::Solid, kinematics, draw).unwrap(),
                check_element(&HEX8, &HEX, AnalysisKind::Solid, kinematics, draw).unwrap(),
            ];
            println!(
                "{name:6} reduced={reduced:5}: worst |K_fd - K|/|K| over the laws: tri3 {:.1e}, \
                 quad4 (axi) {:.1e}, tet4 {:.1e}, hex8 {:.1e}",
                e[0], e[1], e[2], e[3]
            );
            assert!(e.iter().all(|&v| v > 0.0 && v < 1e-6));
        }
    }
}
