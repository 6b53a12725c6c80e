//! History-dependent and finite-strain constitutive laws at one
//! integration point, generic over [`Scalar`] so the element kernels get
//! exact consistent tangents by forward automatic differentiation.
//!
//! Small strain (`kinematics = small`): additive split `eps = eps_e + eps_p`,
//! J2 radial return ([`super::j2`]); the history holds `eps_p`.
//!
//! Finite strain (`kinematics = finite`), all laws return the **Kirchhoff**
//! stress `tau` for a deformation gradient `F`:
//! - Neo-Hookean (compressible): `W = mu/2 (I1 - 3) - mu ln J +
//!   lambda/2 (ln J)^2`, `tau = mu (b - I) + lambda ln J I`, `b = F F^T`;
//! - Hencky elasticity (the finite-strain `elastic` law):
//!   `tau = K tr(e) I + 2 G dev(e)` with `e = 1/2 ln b` (exact for large
//!   rotations, the standard elastic part of metal plasticity);
//! - J2 elasto-plasticity (Simo 1992; Eterovic-Bathe): multiplicative split
//!   `F = F_e F_p`, trial `b_e = F C_p^-1 F^T`, logarithmic elastic strain
//!   `e_tr = 1/2 ln b_e,tr`, radial return in log space (the exponential
//!   map of the plastic flow, exactly isochoric), update
//!   `C_p^-1 = F^-1 exp(2 e) F^-T`. The history holds `C_p^-1` and `ep`.

use super::dual::Scalar;
use super::j2::{radial_return, Elastic};
use super::tensor::{constant, exp, log, values, Deformation, Sym};
use crate::model::{AnalysisKind, Hardening, Kinematics, Material, MaterialLaw, Viscosity};

/// Internal variables of one integration point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct History {
    /// Equivalent plastic strain.
    pub ep: f64,
    /// Small strain: plastic strain `[xx, yy, zz, xy, xz, yz]` (tensor
    /// shear). Finite strain: `C_p^-1 = (F_p^T F_p)^-1`.
    pub tensor: Sym<f64>,
}

impl History {
    /// The virgin state for `kinematics`.
    pub fn initial(kinematics: Kinematics) -> Self {
        History {
            ep: 0.0,
            tensor: match kinematics {
                Kinematics::Small => [0.0; 6],
                Kinematics::Finite => [1.0, 1.0, 1.0, 0.0, 0.0, 0.0],
            },
        }
    }
}

/// A constitutive law evaluated by the nonlinear element kernels.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum NonlinearLaw {
    /// Hencky (logarithmic strain) isotropic elasticity; finite strain only
    /// (small strain uses the linear elastic kernel).
    Hencky {
        /// Bulk and shear moduli.
        elastic: Elastic,
    },
    /// Compressible Neo-Hookean; finite strain only.
    NeoHookean {
        /// Shear modulus `mu`.
        mu: f64,
        /// Lame's first parameter `lambda`.
        lambda: f64,
    },
    /// J2 elasto(-visco)-plasticity with isotropic hardening.
    J2 {
        /// Bulk and shear moduli.
        elastic: Elastic,
        /// Flow stress.
        hardening: Hardening,
        /// Rate dependence of the flow, `None`: rate independent.
        viscosity: Option<Viscosity>,
    },
}

/// Stress and updated history at a point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PointUpdate<T> {
    /// Small strain: Cauchy stress; finite strain: Kirchhoff stress.
    pub stress: Sym<T>,
    /// Updated internal variables (values).
    pub history: History,
}

fn young_poisson_check(young: f64, poisson: f64) -> Result<(), String> {
    if !(young.is_finite() && young > 0.0) {
        return Err(format!("Young's modulus must be > 0 (got {young})"));
    }
    if !(poisson.is_finite() && poisson > -1.0 && poisson < 0.5) {
        return Err(format!(
            "Poisson's ratio must be in (-1, 0.5) (got {poisson})"
        ));
    }
    Ok(())
}

impl NonlinearLaw {
    /// The nonlinear law of `material` for a body with `kinematics` in an
    /// analysis of `kind`; `None` when the linear elastic kernel applies
    /// (small-strain linear elasticity).
    pub fn build(
        material: &Material,
        kinematics: Kinematics,
        kind: AnalysisKind,
    ) -> Result<Option<Self>, String> {
        let name = &material.name;
        let err = |e: String| format!("material `{name}`: {e}");
        let law = match material.law {
            MaterialLaw::LinearElastic { young, poisson } => match kinematics {
                Kinematics::Small => return Ok(None),
                Kinematics::Finite => {
                    young_poisson_check(young, poisson).map_err(err)?;
                    NonlinearLaw::Hencky {
                        elastic: Elastic::from_young(young, poisson),
                    }
                }
            },
            MaterialLaw::NeoHookean { young, poisson } => {
                young_poisson_check(young, poisson).map_err(err)?;
                if kinematics == Kinematics::Small {
                    return Err(err(
                        "neo_hookean is a finite-strain law: use `kinematics = finite` in the body"
                            .into(),
                    ));
                }
                NonlinearLaw::NeoHookean {
                    mu: young / (2.0 * (1.0 + poisson)),
                    lambda: young * poisson / ((1.0 + poisson) * (1.0 - 2.0 * poisson)),
                }
            }
            MaterialLaw::ElastoPlastic {
                young,
                poisson,
                hardening,
                viscosity,
            } => {
                young_poisson_check(young, poisson).map_err(err)?;
                // pure Norton-Hoff: no static yield stress (sigma_y = 0)
                let pure_norton_hoff = matches!(viscosity, Some(Viscosity::NortonHoff { .. }))
                    && hardening
                        == (Hardening::Linear {
                            yield_stress: 0.0,
                            modulus: 0.0,
                        });
                if !pure_norton_hoff {
                    hardening.check().map_err(err)?;
                }
                if let Some(v) = viscosity {
                    v.check().map_err(err)?;
                }
                NonlinearLaw::J2 {
                    elastic: Elastic::from_young(young, poisson),
                    hardening,
                    viscosity,
                }
            }
        };
        if kind == AnalysisKind::PlaneStress {
            return Err(err(
                "plasticity and finite strain in plane stress are not supported yet (use \
                 plane_strain or axisymmetric)"
                    .into(),
            ));
        }
        Ok(Some(law))
    }

    /// Small strain: Cauchy stress for the total strain `eps` (tensor
    /// shear) from the history `h` at the start of the increment, over the
    /// time increment `dt`.
    pub fn small<T: Scalar>(
        &self,
        eps: &Sym<T>,
        h: &History,
        dt: f64,
    ) -> Result<PointUpdate<T>, String> {
        match self {
            NonlinearLaw::J2 {
                elastic,
                hardening,
                viscosity,
            } => {
                let p = &h.tensor;
                let e_tr: Sym<T> = std::array::from_fn(|k| eps[k] - p[k]);
                let r = radial_return(
                    elastic,
                    hardening,
                    &e_tr,
                    h.ep,
                    viscosity.map(|v| (v, dt)),
                    dt,
                )?;
                let tensor = std::array::from_fn(|k| eps[k].re() - r.elastic_strain[k].re());
                Ok(PointUpdate {
                    stress: r.stress,
                    history: History { ep: r.ep, tensor },
                })
            }
            NonlinearLaw::Hencky { elastic } => Ok(PointUpdate {
                stress: elastic.stress(eps),
                history: *h,
            }),
            NonlinearLaw::NeoHookean { .. } => Err("neo_hookean needs kinematics = finite".into()),
        }
    }

    /// Finite strain: Kirchhoff stress for the deformation gradient `f`
    /// from the history `h` at the start of the increment.
    pub fn finite<T: Scalar>(
        &self,
        f: &Deformation<T>,
        h: &History,
        dt: f64,
    ) -> Result<PointUpdate<T>, String> {
        let j = f.det();
        if !(j.re() > 0.0 && j.re().is_finite()) {
            return Err(format!("inverted material (det F = {:e})", j.re()));
        }
        match self {
            NonlinearLaw::NeoHookean { mu, lambda } => {
                let b = f.left_cauchy_green();
                let p = j.ln() * *lambda;
                Ok(PointUpdate {
                    stress: [
                        (b[0] - 1.0) * *mu + p,
                        (b[1] - 1.0) * *mu + p,
                        (b[2] - 1.0) * *mu + p,
                        b[3] * *mu,
                        b[4] * *mu,
                        b[5] * *mu,
                    ],
                    history: *h,
                })
            }
            NonlinearLaw::Hencky { elastic } => {
                let b = f.left_cauchy_green();
                let e = log(&b).map(|l| l * 0.5);
                Ok(PointUpdate {
                    stress: elastic.stress(&e),
                    history: *h,
                })
            }
            NonlinearLaw::J2 {
                elastic,
                hardening,
                viscosity,
            } => {
                let be = f.push(&constant(&h.tensor));
                let e_tr = log(&be).map(|l| l * 0.5);
                let r = radial_return(
                    elastic,
                    hardening,
                    &e_tr,
                    h.ep,
                    viscosity.map(|v| (v, dt)),
                    dt,
                )?;
                let tensor = if r.dgamma > 0.0 {
                    let be_new = exp(&values(&r.elastic_strain).map(|e| 2.0 * e));
                    f.re().inverse().push(&be_new)
                } else {
                    h.tensor
                };
                Ok(PointUpdate {
                    stress: r.stress,
                    history: History { ep: r.ep, tensor },
                })
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finite_laws_reduce_to_linear_elasticity_at_small_strain() {
        let (e, nu) = (200e3, 0.3);
        let elastic = Elastic::from_young(e, nu);
        let lambda = e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
        let mu = e / (2.0 * (1.0 + nu));
        let g = [
            [2e-7, -1e-7, 0.5e-7],
            [3e-7, -4e-7, 1e-7],
            [-2e-7, 0.0, 1e-7],
        ];
        let f = Deformation {
            f: std::array::from_fn(|i| {
                std::array::from_fn(|j| if i == j { 1.0 } else { 0.0 } + g[i][j])
            }),
        };
        let eps: Sym<f64> = crate::material::tensor::PAIRS.map(|(i, j)| 0.5 * (g[i][j] + g[j][i]));
        let tr = eps[0] + eps[1] + eps[2];
        let linear: Sym<f64> = std::array::from_fn(|k| {
            if k < 3 {
                lambda * tr + 2.0 * mu * eps[k]
            } else {
                2.0 * mu * eps[k]
            }
        });
        let fin = Kinematics::Finite;
        let laws = [
            NonlinearLaw::NeoHookean { mu, lambda },
            NonlinearLaw::Hencky { elastic },
            NonlinearLaw::J2 {
                elastic,
                hardening: Hardening::Linear {
                    yield_stress: 250.0,
                    modulus: 0.0,
                },
                viscosity: None,
            },
        ];
        for law in laws {
            let s = law.finite(&f, &History::initial(fin), 0.0).unwrap().stress;
            for k in 0..6 {
                assert!(
                    (s[k] - linear[k]).abs() < 1e-6 * 0.1,
                    "{law:?} {s:?} {linear:?}"
                );
            }
        }
        // and the small-strain J2 law is linear elastic below yield
        let j2 = laws[2];
        let s = j2
            .small(&eps, &History::initial(Kinematics::Small), 0.0)
            .unwrap()
            .stress;
        for k in 0..6 {
            assert!((s[k] - linear[k]).abs() < 1e-12);
        }
    }

    #[test]
    fn neo_hookean_on_small_strain_body_is_rejected() {
        let m = Material {
            name: "rubber".into(),
            density: 0.0,
            law: MaterialLaw::NeoHookean {
                young: 1.0,
                poisson: 0.3,
            },
        };
        let e = NonlinearLaw::build(&m, Kinematics::Small, AnalysisKind::PlaneStrain).unwrap_err();
        assert!(e.contains("kinematics = finite"), "{e}");
        let e = NonlinearLaw::build(&m, Kinematics::Finite, AnalysisKind::PlaneStress).unwrap_err();
        assert!(e.contains("not supported yet"), "{e}");
    }
}
