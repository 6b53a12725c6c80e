//! The nonlinear material laws the kernel property tests sweep: one
//! representative of every law (Neo-Hooke, Hencky, J2 with linear, Swift,
//! Voce and Johnson-Cook hardening, Perzyna linear and power, Norton-Hoff
//! with and without static yield), steel-like constants in MPa.

use crate::material::j2::Elastic;
use crate::material::NonlinearLaw;
use crate::model::{Hardening, Viscosity};

/// Every nonlinear law with its name, as the tangent, rigid-mode and
/// symmetry property tests iterate over them.
pub fn nonlinear_laws() -> Vec<(&'static str, NonlinearLaw)> {
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
            // OFHC copper's A B n C m (Johnson & Cook 1983) at 500 K, the
            // reference rate low enough for the rate term to act at the
            // tests' dt = 0.1
            "j2_johnson_cook",
            j2(
                Hardening::JohnsonCook {
                    a: 90.0,
                    b: 292.0,
                    n: 0.31,
                    c: 0.025,
                    rate0: 1e-3,
                    m: 1.09,
                    t_ref: 298.0,
                    t_melt: 1356.0,
                    temperature: 500.0,
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
                Some(Viscosity::Perzyna { eta: 2000.0 }),
            ),
        ),
        (
            "perzyna_power",
            j2(
                Hardening::Linear {
                    yield_stress: 250.0,
                    modulus: 1000.0,
                },
                Some(Viscosity::PerzynaPower {
                    rate: 0.5,
                    exponent: 3.0,
                }),
            ),
        ),
        (
            "norton_hoff",
            j2(
                Hardening::Linear {
                    yield_stress: 0.0,
                    modulus: 0.0,
                },
                Some(Viscosity::NortonHoff {
                    stress: 50.0,
                    rate: 1e-3,
                    m: 0.5,
                }),
            ),
        ),
        (
            "norton_hoff_yield",
            j2(
                Hardening::Swift {
                    k: 500.0,
                    eps0: 0.01,
                    n: 0.2,
                },
                Some(Viscosity::NortonHoff {
                    stress: 80.0,
                    rate: 1.0,
                    m: 0.3,
                }),
            ),
        ),
    ]
}
