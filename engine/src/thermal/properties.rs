//! Temperature-dependent mechanical parameters: the factors of the
//! material's `thermal` block (tables of (T, factor), piecewise linear,
//! constant beyond the ends) scale Young's modulus (bulk and shear moduli
//! together, so Poisson's ratio is unchanged) and the whole flow-stress
//! curve of the nonlinear laws, at the cell's mean temperature.
//!
//! Only nonlinear laws (J2 plasticity, Hencky, Neo-Hookean) are scaled:
//! small-strain linear elastic cells keep their cached stiffness (the
//! validation rejects a `young` table on them).

use crate::material::NonlinearLaw;
use crate::model::thermal::MaterialThermal;
use crate::model::{Hardening, TimeFunction};

fn factor(table: &Option<Vec<(f64, f64)>>, t: f64) -> f64 {
    match table {
        Some(points) => TimeFunction::Table(points.clone()).eval(t),
        None => 1.0,
    }
}

/// Whether the material has any temperature-dependent mechanical parameter
/// (tables of its `thermal` block, or Johnson-Cook's thermal softening).
pub fn is_temperature_dependent(m: &MaterialThermal, law: &crate::model::MaterialLaw) -> bool {
    m.young_factor.is_some()
        || m.yield_factor.is_some()
        || matches!(
            law,
            crate::model::MaterialLaw::ElastoPlastic {
                hardening: Hardening::JohnsonCook { .. },
                ..
            }
        )
}

/// `law` at temperature `t`.
pub fn law_at(law: &NonlinearLaw, m: &MaterialThermal, t: f64) -> NonlinearLaw {
    let fe = factor(&m.young_factor, t);
    let fy = factor(&m.yield_factor, t);
    match *law {
        NonlinearLaw::Hencky { mut elastic } => {
            elastic.bulk *= fe;
            elastic.shear *= fe;
            NonlinearLaw::Hencky { elastic }
        }
        NonlinearLaw::NeoHookean { mu, lambda } => NonlinearLaw::NeoHookean {
            mu: mu * fe,
            lambda: lambda * fe,
        },
        NonlinearLaw::J2 {
            mut elastic,
            hardening,
            viscosity,
        } => {
            elastic.bulk *= fe;
            elastic.shear *= fe;
            let hardening = match hardening {
                Hardening::Linear {
                    yield_stress,
                    modulus,
                } => Hardening::Linear {
                    yield_stress: yield_stress * fy,
                    modulus: modulus * fy,
                },
                Hardening::Swift { k, eps0, n } => Hardening::Swift { k: k * fy, eps0, n },
                Hardening::Voce {
                    yield_stress,
                    sigma_inf,
                    delta,
                } => Hardening::Voce {
                    yield_stress: yield_stress * fy,
                    sigma_inf: sigma_inf * fy,
                    delta,
                },
                // its own thermal softening at the cell's temperature
                Hardening::JohnsonCook {
                    a,
                    b,
                    n,
                    c,
                    rate0,
                    m,
                    t_ref,
                    t_melt,
                    ..
                } => Hardening::JohnsonCook {
                    a: a * fy,
                    b: b * fy,
                    n,
                    c,
                    rate0,
                    m,
                    t_ref,
                    t_melt,
                    temperature: t,
                },
            };
            NonlinearLaw::J2 {
                elastic,
                hardening,
                viscosity,
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::j2::Elastic;

    #[test]
    fn flow_stress_and_moduli_follow_the_tables() {
        let m = MaterialThermal {
            conductivity: 1.0,
            capacity: 1.0,
            density: 1.0,
            expansion: 0.0,
            reference: 20.0,
            taylor_quinney: 0.9,
            young_factor: Some(vec![(20.0, 1.0), (520.0, 0.5)]),
            yield_factor: Some(vec![(20.0, 1.0), (220.0, 0.2)]),
        };
        let law = NonlinearLaw::J2 {
            elastic: Elastic {
                bulk: 100.0,
                shear: 50.0,
            },
            hardening: Hardening::Linear {
                yield_stress: 10.0,
                modulus: 2.0,
            },
            viscosity: None,
        };
        let NonlinearLaw::J2 {
            elastic, hardening, ..
        } = law_at(&law, &m, 120.0)
        else {
            panic!()
        };
        assert!((elastic.bulk - 90.0).abs() < 1e-12);
        assert!((elastic.shear - 45.0).abs() < 1e-12);
        assert!((hardening.flow_stress(1.0) - 0.6 * 12.0).abs() < 1e-12);
    }
}
