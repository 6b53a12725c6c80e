//! Isotropic small-strain linear elasticity for plane strain, plane stress
//! and axisymmetric analyses.

use super::{Constitutive, Strain, Stress, Tangent};
use crate::model::AnalysisKind;

/// Isotropic linear elasticity with its 4x4 modulus for one 2D kind.
#[derive(Debug, Clone, PartialEq)]
pub struct LinearElastic {
    /// Young's modulus.
    pub young: f64,
    /// Poisson's ratio.
    pub poisson: f64,
    /// The 2D kind the modulus is built for.
    pub kind: AnalysisKind,
    /// Modulus `D` in `[xx, yy, zz, xy]` Voigt notation (engineering shear).
    pub d: Tangent,
}

impl LinearElastic {
    /// The law with modulus `young` > 0 and Poisson's ratio in (-1, 0.5).
    ///
    /// - plane strain and axisymmetric: the 3D isotropic modulus restricted
    ///   to `[xx, yy, zz, xy]` (plane strain elements have `eps_zz = 0`, so
    ///   `sigma_zz = lambda (eps_xx + eps_yy)`; axisymmetric elements feed the
    ///   hoop strain into `zz`);
    /// - plane stress: the reduced modulus with a zero `zz` row and column
    ///   (`sigma_zz = 0`).
    pub fn new(young: f64, poisson: f64, kind: AnalysisKind) -> Result<Self, String> {
        if !(young.is_finite() && young > 0.0) {
            return Err(format!("Young's modulus must be > 0 (got {young})"));
        }
        if !(poisson.is_finite() && poisson > -1.0 && poisson < 0.5) {
            return Err(format!(
                "Poisson's ratio must be in (-1, 0.5) (got {poisson}); for near-incompressible \
                 materials use e.g. 0.4999 with formulation = selective_reduced"
            ));
        }
        let (e, nu) = (young, poisson);
        let mut d = Tangent::zeros();
        match kind {
            AnalysisKind::PlaneStrain | AnalysisKind::Axisymmetric => {
                let lambda = e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
                let mu = e / (2.0 * (1.0 + nu));
                for i in 0..3 {
                    for j in 0..3 {
                        d[(i, j)] = lambda;
                    }
                    d[(i, i)] = lambda + 2.0 * mu;
                }
                d[(3, 3)] = mu;
            }
            AnalysisKind::PlaneStress => {
                let c = e / (1.0 - nu * nu);
                d[(0, 0)] = c;
                d[(1, 1)] = c;
                d[(0, 1)] = c * nu;
                d[(1, 0)] = c * nu;
                d[(3, 3)] = c * (1.0 - nu) / 2.0;
            }
        }
        Ok(LinearElastic {
            young,
            poisson,
            kind,
            d,
        })
    }
}

impl Constitutive for LinearElastic {
    fn stress(&self, strain: &Strain) -> Stress {
        self.d * strain
    }

    fn tangent(&self, _strain: &Strain) -> Tangent {
        self.d
    }

    fn complete_strain(&self, strain: &Strain) -> Strain {
        let mut full = *strain;
        if self.kind == AnalysisKind::PlaneStress {
            let nu = self.poisson;
            full[2] = -nu / (1.0 - nu) * (strain[0] + strain[1]);
        }
        full
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rel(a: f64, b: f64) -> f64 {
        (a - b).abs() / b.abs().max(1e-300)
    }

    #[test]
    fn plane_strain_uniaxial_strain_gives_lame_stresses() {
        let (e, nu) = (200.0, 0.3);
        let law = LinearElastic::new(e, nu, AnalysisKind::PlaneStrain).unwrap();
        let s = law.stress(&Strain::new(1e-3, 0.0, 0.0, 0.0));
        let lambda = e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
        let mu = e / (2.0 * (1.0 + nu));
        assert!(rel(s[0], (lambda + 2.0 * mu) * 1e-3) < 1e-14);
        assert!(rel(s[1], lambda * 1e-3) < 1e-14);
        assert!(rel(s[2], lambda * 1e-3) < 1e-14);
        assert_eq!(s[3], 0.0);
    }

    #[test]
    fn plane_stress_uniaxial_stress_recovers_young_and_poisson() {
        let (e, nu) = (70.0, 0.25);
        let law = LinearElastic::new(e, nu, AnalysisKind::PlaneStress).unwrap();
        // uniaxial stress state: eps_xx = s/E, eps_yy = -nu s/E
        let eps = Strain::new(2.0 / e, -nu * 2.0 / e, 0.0, 0.0);
        let s = law.stress(&eps);
        assert!(rel(s[0], 2.0) < 1e-14);
        assert!(s[1].abs() < 1e-14 && s[2] == 0.0);
        let full = law.complete_strain(&eps);
        assert!(rel(full[2], -nu * 2.0 / e) < 1e-14);
    }

    #[test]
    fn axisymmetric_hydrostatic_strain_gives_bulk_modulus() {
        let (e, nu) = (1.0, 0.2);
        let law = LinearElastic::new(e, nu, AnalysisKind::Axisymmetric).unwrap();
        let s = law.stress(&Strain::new(1.0, 1.0, 1.0, 0.0));
        let k = e / (3.0 * (1.0 - 2.0 * nu));
        for i in 0..3 {
            assert!(rel(s[i], 3.0 * k) < 1e-14);
        }
    }

    #[test]
    fn shear_modulus_uses_engineering_shear_strain() {
        let law = LinearElastic::new(2.6, 0.3, AnalysisKind::PlaneStress).unwrap();
        let s = law.stress(&Strain::new(0.0, 0.0, 0.0, 1.0));
        assert!(rel(s[3], 1.0) < 1e-14); // G = E / (2 (1 + nu)) = 1
    }

    #[test]
    fn invalid_parameters_are_rejected() {
        assert!(LinearElastic::new(0.0, 0.3, AnalysisKind::PlaneStrain).is_err());
        assert!(LinearElastic::new(f64::NAN, 0.3, AnalysisKind::PlaneStrain).is_err());
        assert!(LinearElastic::new(1.0, -1.0, AnalysisKind::PlaneStrain).is_err());
        assert!(LinearElastic::new(1.0, 0.5, AnalysisKind::Axisymmetric).is_err());
    }
}
