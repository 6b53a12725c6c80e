//! Finite-difference checks of the element tangents of every nonlinear law
//! (small-strain J2, finite-strain Neo-Hookean, Hencky and J2 with linear,
//! Swift and Voce hardening, Perzyna visco-plasticity), for quad4 (full and
//! F-bar / B-bar) and tri3, plane strain and axisymmetric, over random
//! shapes, displacement fields and plastic histories: the automatic
//! differentiation tangent must match central differences of the internal
//! force to 1e-6 (relative, Frobenius norm).

use ctc_engine::element::finite::FiniteElement;
use ctc_engine::element::{inelastic, quad4, tri3, Section};
use ctc_engine::material::j2::Elastic;
use ctc_engine::material::tensor::{exp, Deformation};
use ctc_engine::material::{History, NonlinearLaw};
use ctc_engine::model::{AnalysisKind, Formulation, Hardening};
use nalgebra::{SMatrix, SVector};
use proptest::prelude::*;

fn laws() -> Vec<(&'static str, NonlinearLaw)> {
    let elastic = Elastic::from_young(200e3, 0.3);
    let j2 = |hardening, viscosity| NonlinearLaw::J2 {
        elastic,
        hardening,
        viscosity,
    };
    vec![
        (
            "neo_hookean",
            NonlinearLaw::NeoHookean {
                mu: 80e3,
                lambda: 120e3,
            },
        ),
        ("hencky", NonlinearLaw::Hencky { elastic }),
        (
            "j2_linear",
            j2(
                Hardening::Linear {
                    yield_stress: 250.0,
                    modulus: 1000.0,
                },
                None,
            ),
        ),
        (
            "j2_swift",
            j2(
                Hardening::Swift {
                    k: 500.0,
                    eps0: 0.01,
                    n: 0.2,
                },
                None,
            ),
        ),
        (
            "j2_voce",
            j2(
                Hardening::Voce {
                    yield_stress: 200.0,
                    sigma_inf: 400.0,
                    delta: 10.0,
                },
                None,
            ),
        ),
        (
            "perzyna",
            j2(
                Hardening::Linear {
                    yield_stress: 250.0,
                    modulus: 1000.0,
                },
                Some(2000.0),
            ),
        ),
    ]
}

/// A plastic history: isochoric plastic stretch with principal log strain
/// `a` at angle `th`, equivalent plastic strain `ep`.
fn history(finite: bool, a: f64, th: f64, ep: f64) -> History {
    let (c, s) = (th.cos(), th.sin());
    // plastic log strain: diag(a, -a/2 - b, ...) rotated; keep trace 0
    let e = [
        a * c * c - 0.5 * a * s * s,
        a * s * s - 0.5 * a * c * c,
        -0.5 * a,
        1.5 * a * c * s,
    ];
    if finite {
        // C_p^-1 = exp(-2 e_p)
        History {
            ep,
            tensor: exp(&[-2.0 * e[0], -2.0 * e[1], -2.0 * e[2], -2.0 * e[3]]),
        }
    } else {
        History { ep, tensor: e }
    }
}

/// Internal force and tangent of an element at a displacement.
type ForceAndTangent<const ND: usize> = (SVector<f64, ND>, SMatrix<f64, ND, ND>);

fn check<const ND: usize>(
    eval: &dyn Fn(&SVector<f64, ND>, bool) -> ForceAndTangent<ND>,
    u: &SVector<f64, ND>,
    what: &str,
) -> Result<f64, String> {
    let (_, k) = eval(u, true);
    let scale = u.amax().max(1e-3);
    let h = 1e-6 * scale;
    let mut kfd = SMatrix::<f64, ND, ND>::zeros();
    for j in 0..ND {
        let mut up = *u;
        let mut um = *u;
        up[j] += h;
        um[j] -= h;
        let col = (eval(&up, false).0 - eval(&um, false).0) / (2.0 * h);
        kfd.set_column(j, &col);
    }
    let err = (kfd - k).norm() / k.norm();
    if err > 1e-6 {
        return Err(format!("{what}: |K_fd - K| / |K| = {err:e}"));
    }
    Ok(err)
}

fn square(scale: f64, r0: f64, jitter: &[f64]) -> [[f64; 2]; 4] {
    [
        [r0 + jitter[0], jitter[1]],
        [r0 + scale + jitter[2], jitter[3]],
        [r0 + scale + jitter[4], scale + jitter[5]],
        [r0 + jitter[6], scale + jitter[7]],
    ]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]
    #[test]
    fn finite_quad4_tangent_matches_finite_differences(
        jitter in proptest::collection::vec(-0.15f64..0.15, 8),
        grad in proptest::collection::vec(-0.25f64..0.25, 8),
        a in -0.2f64..0.2, th in 0.0f64..3.0, ep in 0.0f64..0.3,
        axi in any::<bool>(), fbar in any::<bool>(),
    ) {
        let kind = if axi { AnalysisKind::Axisymmetric } else { AnalysisKind::PlaneStrain };
        let x = square(1.0, 0.5, &jitter);
        let sec = Section { kind, thickness: 1.0 };
        let (pts, center) = quad4::reference_points(&x, &sec).unwrap();
        let u = SVector::<f64, 8>::from_row_slice(&grad);
        for (name, law) in laws() {
            let hist = [history(true, a, th, ep); 4];
            let eval = |u: &SVector<f64, 8>, t: bool| {
                let el = FiniteElement { points: &pts, center: fbar.then_some(&center), kind, law: &law, history: &hist, dt: 0.1 };
                let (r, _) = el.response(u, t).unwrap();
                (r.force, r.stiffness)
            };
            check(&eval, &u, &format!("quad4 finite {name} axi={axi} fbar={fbar}")).map_err(TestCaseError::fail)?;
        }
    }

    #[test]
    fn finite_tri3_tangent_matches_finite_differences(
        jitter in proptest::collection::vec(-0.1f64..0.1, 6),
        grad in proptest::collection::vec(-0.25f64..0.25, 6),
        a in -0.2f64..0.2, th in 0.0f64..3.0, ep in 0.0f64..0.3,
        axi in any::<bool>(),
    ) {
        let kind = if axi { AnalysisKind::Axisymmetric } else { AnalysisKind::PlaneStrain };
        let x = [[0.5 + jitter[0], jitter[1]], [1.5 + jitter[2], jitter[3]], [0.7 + jitter[4], 1.0 + jitter[5]]];
        let sec = Section { kind, thickness: 1.0 };
        let pts = tri3::reference_points(&x, &sec).unwrap();
        let u = SVector::<f64, 6>::from_row_slice(&grad);
        for (name, law) in laws() {
            let hist = [history(true, a, th, ep)];
            let eval = |u: &SVector<f64, 6>, t: bool| {
                let el = FiniteElement { points: &pts, center: None, kind, law: &law, history: &hist, dt: 0.1 };
                let (r, _) = el.response(u, t).unwrap();
                (r.force, r.stiffness)
            };
            check(&eval, &u, &format!("tri3 finite {name} axi={axi}")).map_err(TestCaseError::fail)?;
        }
    }

    #[test]
    fn small_strain_j2_tangent_matches_finite_differences(
        jitter in proptest::collection::vec(-0.15f64..0.15, 8),
        grad in proptest::collection::vec(-0.02f64..0.02, 8),
        a in -0.01f64..0.01, th in 0.0f64..3.0, ep in 0.0f64..0.1,
        axi in any::<bool>(), bbar in any::<bool>(),
    ) {
        let kind = if axi { AnalysisKind::Axisymmetric } else { AnalysisKind::PlaneStrain };
        let x = square(1.0, 0.5, &jitter);
        let sec = Section { kind, thickness: 1.0 };
        let f = if bbar { Formulation::SelectiveReduced } else { Formulation::Full };
        let pts = quad4::integration_points(&x, &sec, f).unwrap();
        let u = SVector::<f64, 8>::from_row_slice(&grad);
        for (name, law) in laws().into_iter().skip(2) {
            let hist = [history(false, a, th, ep); 4];
            let eval = |u: &SVector<f64, 8>, t: bool| {
                let (r, _) = inelastic::response(&pts, u, &law, &hist, 0.1, t).unwrap();
                (r.force, r.stiffness)
            };
            check(&eval, &u, &format!("quad4 small {name} axi={axi} bbar={bbar}")).map_err(TestCaseError::fail)?;
        }
    }
}

#[test]
fn finite_tangent_check_reports_plastic_points() {
    // guard against a vacuous check: the random fields above are plastic
    let x = square(1.0, 0.5, &[0.0; 8]);
    let sec = Section {
        kind: AnalysisKind::PlaneStrain,
        thickness: 1.0,
    };
    let (pts, _) = quad4::reference_points(&x, &sec).unwrap();
    let law = &laws()[3].1;
    let hist = [History::initial(ctc_engine::model::Kinematics::Finite); 4];
    let u = SVector::<f64, 8>::from_row_slice(&[0.0, 0.0, 0.1, 0.0, 0.1, -0.1, 0.0, -0.1]);
    let el = FiniteElement {
        points: &pts,
        center: None,
        kind: sec.kind,
        law,
        history: &hist,
        dt: 0.1,
    };
    let (_, p) = el.response(&u, false).unwrap();
    assert!(p.iter().all(|p| p.history.ep > 0.05), "{:?}", p[0].history);
    let f = Deformation::<f64>::identity();
    assert_eq!(f.det(), 1.0);
}

#[test]
fn tangent_errors_per_law_are_small_and_printed() {
    // one fixed distorted, strongly deformed, plastic configuration per law
    let x = square(1.0, 0.5, &[0.05, -0.03, 0.1, 0.02, -0.04, 0.08, 0.0, -0.1]);
    let u = SVector::<f64, 8>::from_row_slice(&[0.01, -0.02, 0.15, 0.03, 0.12, -0.2, -0.05, -0.18]);
    for kind in [AnalysisKind::PlaneStrain, AnalysisKind::Axisymmetric] {
        let sec = Section {
            kind,
            thickness: 1.0,
        };
        let (pts, center) = quad4::reference_points(&x, &sec).unwrap();
        for (name, law) in laws() {
            for fbar in [false, true] {
                let hist = [history(true, 0.05, 0.4, 0.1); 4];
                let eval = |u: &SVector<f64, 8>, t: bool| {
                    let el = FiniteElement {
                        points: &pts,
                        center: fbar.then_some(&center),
                        kind,
                        law: &law,
                        history: &hist,
                        dt: 0.1,
                    };
                    let (r, _) = el.response(u, t).unwrap();
                    (r.force, r.stiffness)
                };
                let err = check(&eval, &u, name).unwrap();
                assert!(err > 0.0);
                println!("finite {kind:?} {name:12} fbar={fbar:5}: |K_fd - K|/|K| = {err:.2e}");
            }
        }
    }
}
