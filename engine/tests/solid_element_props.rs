//! Structural properties of the tet4 / hex8 tangents of every nonlinear law
//! (small-strain J2 with linear, Swift and Voce hardening and Perzyna;
//! finite-strain Neo-Hooke, Hencky, J2 and Perzyna), full integration and
//! B-bar / F-bar, over random distorted shapes, displacement states and
//! plastic histories (`material_tangent.rs` checks the same tangents against
//! central differences). Every property is a consequence of the continuum
//! problem, so none is tuned to the code:
//!
//! - rigid translations are in the null space: `K t = 0` (f_int depends on
//!   displacement differences only);
//! - rigid rotations: small strain, `K (w x X) = 0` (an infinitesimal
//!   rotation has no linearized strain); finite strain, the internal force
//!   of an objective law rotates with the body, `f(R phi) = R f(phi)`, so
//!   `K (w x phi) = w x f` at the current positions `phi = X + u`;
//! - symmetry: `K = K^T` where the discrete problem has a potential or an
//!   associative return (small strain, full and B-bar, every law — the
//!   radial return's consistent tangent is symmetric —, finite-strain
//!   hyperelasticity with full integration, and the finite-strain J2 of
//!   Simo's exponential update with logarithmic elastic strains, whose
//!   algorithmic tangent is symmetric for isotropic laws (Simo, CMAME 99
//!   (1992) 61-112, box 1); F-bar is unsymmetric by construction (its
//!   volumetric term couples `J` at the centre to `J` at the point), and is
//!   checked to be so: a symmetry check that passes everywhere proves
//!   nothing.
//!
//! ```text
//!   reference cell  --(I + A, |A_ij| <= 0.3)-->  jitter each node by 8 %
//!   --> scale 0.2..5, shift;  u = H (X - Xc) + nodal perturbation (finite)
//! ```

use ctc_engine::element::kernel::{HEX8, TET4};
use ctc_engine::element::recovery::virgin;
use ctc_engine::element::{CellKernel, ElementMatrix, NonlinearInput, Section};
use ctc_engine::geom::Point;
use ctc_engine::material::tensor::exp;
use ctc_engine::material::{History, NonlinearLaw};
use ctc_engine::model::{AnalysisKind, Formulation, Kinematics};
use ctc_engine::testkit::laws::nonlinear_laws;
use nalgebra::{DMatrix, DVector, Vector3};
use proptest::prelude::*;

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

/// Random inputs of one configuration.
#[derive(Debug, Clone)]
struct Draw {
    a: Vec<f64>,
    jitter: Vec<f64>,
    scale: f64,
    shift: Vec<f64>,
    grad: Vec<f64>,
    nodal: Vec<f64>,
    plastic: Vec<f64>,
    amplitude: f64,
    ep: f64,
    thermal: f64,
}

fn draw() -> impl Strategy<Value = Draw> {
    (
        (
            proptest::collection::vec(-0.3f64..0.3, 9),
            proptest::collection::vec(-0.08f64..0.08, 24),
            0.2f64..5.0,
            proptest::collection::vec(-10.0f64..10.0, 3),
        ),
        (
            proptest::collection::vec(-0.25f64..0.25, 9),
            proptest::collection::vec(-1.0f64..1.0, 24),
        ),
        (
            proptest::collection::vec(-1.0f64..1.0, 5),
            0.0f64..0.2,
            0.0f64..0.3,
            prop_oneof![Just(0.0), -0.01f64..0.01],
        ),
    )
        .prop_map(
            |((a, jitter, scale, shift), (grad, nodal), (plastic, amplitude, ep, thermal))| Draw {
                a,
                jitter,
                scale,
                shift,
                grad,
                nodal,
                plastic,
                amplitude,
                ep,
                thermal,
            },
        )
}

fn shape(reference: &[[f64; 3]], d: &Draw) -> Vec<Point<3>> {
    reference
        .iter()
        .enumerate()
        .map(|(n, c)| {
            Point::<3>::from_fn(|i, _| {
                let mapped =
                    c[i] + d.jitter[3 * n + i] + (0..3).map(|j| d.a[3 * i + j] * c[j]).sum::<f64>();
                mapped * d.scale + d.shift[i]
            })
        })
        .collect()
}

/// Displacements: a homogeneous gradient `H` about the centroid plus a
/// nodal perturbation of a tenth of it (never inverts: see
/// `material_tangent.rs`), scaled down to the order of the yield strain
/// at small strain.
fn displacement(x: &[Point<3>], d: &Draw, finite: bool) -> Vec<Point<3>> {
    let factor = if finite { 1.0 } else { 0.04 };
    let h = nalgebra::Matrix3::from_fn(|i, j| d.grad[3 * i + j] * factor);
    let centroid = x.iter().fold(Point::<3>::zeros(), |s, p| s + p) / x.len() as f64;
    x.iter()
        .enumerate()
        .map(|(n, p)| {
            let q = Point::<3>::new(d.nodal[3 * n], d.nodal[3 * n + 1], d.nodal[3 * n + 2]);
            h * (p - centroid) + q * (0.1 * 0.25 * factor * d.scale)
        })
        .collect()
}

/// A plastic history (isochoric plastic log strain, equivalent plastic
/// strain `ep`).
fn history(finite: bool, d: &Draw) -> History {
    let a = d.amplitude * if finite { 1.0 } else { 0.05 };
    let p = &d.plastic;
    let (xx, yy) = (a * p[0], a * p[1]);
    let e = [xx, yy, -xx - yy, a * p[2], a * p[3], a * p[4]];
    if finite {
        History {
            ep: d.ep,
            tensor: exp(&e.map(|v| -2.0 * v)),
        }
    } else {
        History {
            ep: d.ep,
            tensor: e,
        }
    }
}

/// Measured defects of one tangent, each relative to `|K| |v|`.
#[derive(Debug, Clone, Copy, Default)]
struct Defects {
    translation: f64,
    rotation: f64,
    asymmetry: f64,
}

#[allow(clippy::too_many_arguments)]
fn defects(
    kernel: &dyn CellKernel<3>,
    x: &[Point<3>],
    u: &[Point<3>],
    formulation: Formulation,
    kinematics: Kinematics,
    law: &NonlinearLaw,
    history: &History,
    thermal: f64,
) -> Defects {
    let mut out = ElementMatrix::default();
    let mut states = vec![virgin(kinematics); kernel.point_count()];
    kernel
        .nonlinear(
            &NonlinearInput {
                x,
                u,
                section: &Section {
                    kind: AnalysisKind::Solid,
                    thickness: 1.0,
                },
                formulation,
                kinematics,
                law,
                history: &vec![*history; kernel.point_count()],
                dt: 0.1,
                thermal_strain: thermal,
                with_tangent: true,
            },
            &mut out,
            &mut states,
        )
        .unwrap();
    let nd = 3 * x.len();
    let k = DMatrix::from_fn(nd, nd, |i, j| out.entry(i, j));
    let f = DVector::from_fn(nd, |i, _| out.force_entry(i));
    let kn = k.norm();
    let mut d = Defects {
        asymmetry: (&k - k.transpose()).norm() / kn,
        ..Default::default()
    };
    for c in 0..3 {
        let t = DVector::from_fn(nd, |i, _| f64::from(i % 3 == c));
        d.translation = d.translation.max((&k * &t).norm() / (kn * t.norm()));
        let w = Vector3::from_fn(|i, _| f64::from(i == c));
        // small strain: rotate the reference; finite: the current positions
        let v = DVector::from_iterator(
            nd,
            x.iter().zip(u).flat_map(|(p, q)| {
                let phi = if kinematics == Kinematics::Finite {
                    p + q
                } else {
                    *p
                };
                let r = w.cross(&phi);
                [r[0], r[1], r[2]]
            }),
        );
        let expected = if kinematics == Kinematics::Finite {
            DVector::from_iterator(
                nd,
                out.force.iter().flat_map(|fa| {
                    let r = w.cross(fa);
                    [r[0], r[1], r[2]]
                }),
            )
        } else {
            DVector::zeros(nd)
        };
        let scale = kn * v.norm() + f.norm();
        d.rotation = d.rotation.max((&k * &v - expected).norm() / scale);
    }
    d
}

/// Whether the discrete tangent is symmetric (see the module head).
fn symmetric(kinematics: Kinematics, formulation: Formulation) -> bool {
    kinematics == Kinematics::Small || formulation == Formulation::Full
}

const TOL: f64 = 1e-10;

/// `v <= TOL` (false for NaN).
fn within(v: f64) -> bool {
    v <= TOL
}

/// Checks every law on one element; returns the worst defects.
fn check(
    kernel: &dyn CellKernel<3>,
    reference: &[[f64; 3]],
    formulation: Formulation,
    kinematics: Kinematics,
    d: &Draw,
) -> Result<Defects, String> {
    let finite = kinematics == Kinematics::Finite;
    let x = shape(reference, d);
    let u = displacement(&x, d, finite);
    let h = history(finite, d);
    let mut worst = Defects::default();
    for (name, law) in nonlinear_laws() {
        if !finite
            && matches!(
                law,
                NonlinearLaw::NeoHookean { .. } | NonlinearLaw::Hencky { .. }
            )
        {
            continue;
        }
        let e = defects(kernel, &x, &u, formulation, kinematics, &law, &h, d.thermal);
        let what = format!(
            "{} {formulation:?} {kinematics:?} {name}: {e:?}",
            kernel.kind().name()
        );
        if !(within(e.translation) && within(e.rotation)) {
            return Err(format!("rigid mode not in the null space: {what}"));
        }
        if symmetric(kinematics, formulation) && !within(e.asymmetry) {
            return Err(format!("tangent not symmetric: {what}"));
        }
        worst.translation = worst.translation.max(e.translation);
        worst.rotation = worst.rotation.max(e.rotation);
        if symmetric(kinematics, formulation) {
            worst.asymmetry = worst.asymmetry.max(e.asymmetry);
        }
    }
    Ok(worst)
}

const CASES: [(Formulation, Kinematics); 4] = [
    (Formulation::Full, Kinematics::Small),
    (Formulation::SelectiveReduced, Kinematics::Small),
    (Formulation::Full, Kinematics::Finite),
    (Formulation::SelectiveReduced, Kinematics::Finite),
];

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]
    #[test]
    fn solid_tangents_rigid_modes_and_symmetry(d in draw()) {
        for (formulation, kinematics) in CASES {
            if formulation == Formulation::Full {
                check(&TET4, &TET, formulation, kinematics, &d).map_err(TestCaseError::fail)?;
            }
            check(&HEX8, &HEX, formulation, kinematics, &d).map_err(TestCaseError::fail)?;
        }
    }
}

#[test]
fn solid_tangent_properties_are_measured_and_fbar_is_unsymmetric() {
    // one fixed distorted, strongly deformed, plastic configuration
    let d = Draw {
        a: vec![0.1, -0.05, 0.02, 0.03, 0.08, -0.04, 0.0, 0.05, -0.1],
        jitter: (0..24)
            .map(|k| 0.05 * ((k * 7 % 11) as f64 / 11.0 - 0.5))
            .collect(),
        scale: 1.3,
        shift: vec![0.5, -2.0, 3.0],
        grad: (0..9)
            .map(|k| 0.4 * ((k * 5 % 13) as f64 / 13.0 - 0.5))
            .collect(),
        nodal: (0..24)
            .map(|k| 2.0 * ((k * 3 % 7) as f64 / 7.0 - 0.5))
            .collect(),
        plastic: vec![0.5, -0.3, 0.2, 0.4, -0.1],
        amplitude: 0.05,
        ep: 0.1,
        thermal: 0.004,
    };
    for (formulation, kinematics) in CASES {
        for (kernel, reference) in [(&TET4 as &dyn CellKernel<3>, &TET[..]), (&HEX8, &HEX[..])] {
            if kernel.kind().name() == "tet4" && formulation != Formulation::Full {
                continue;
            }
            let w = check(kernel, reference, formulation, kinematics, &d).unwrap();
            println!(
                "{} {formulation:?} {kinematics:?}: worst over the laws |K t|/|K||t| {:.1e}, \
                 rotation {:.1e}, |K - K^T|/|K| {:.1e}",
                kernel.kind().name(),
                w.translation,
                w.rotation,
                w.asymmetry
            );
        }
    }
    // F-bar at finite strain is unsymmetric: the check above can fail
    let x = shape(&HEX, &d);
    let u = displacement(&x, &d, true);
    for (name, law) in nonlinear_laws() {
        let e = defects(
            &HEX8,
            &x,
            &u,
            Formulation::SelectiveReduced,
            Kinematics::Finite,
            &law,
            &history(true, &d),
            d.thermal,
        );
        println!("hex8 F-bar {name}: |K - K^T|/|K| {:.1e}", e.asymmetry);
        assert!(e.asymmetry > 1e-6, "{name}: {e:?}");
    }
}
