//! Isotropic small-strain linear elasticity: the 3D modulus, and its
//! plane-stress condensation for planar analyses
//! (`crate::element::planar`).

use super::{Constitutive, Strain, Stress, Tangent};
use crate::model::AnalysisKind;

/// Isotropic linear elasticity with its 6x6 modulus for one analysis kind.
#[derive(Debug, Clone, PartialEq)]
pub struct LinearElastic {
    /// Young's modulus.
    pub young: f64,
    /// Poisson's ratio.
    pub poisson: f64,
    /// The analysis kind the modulus is built for.
    pub kind: AnalysisKind,
    /// Modulus `D` in `[xx, yy, zz, xy, xz, yz]` Voigt notation
    /// (engineering shear).
    pub d: Tangent,
}

/// Checks Young's modulus and Poisson's ratio; explains what is wrong.
pub fn check_young_poisson(young: f64, poisson: f64) -> Result<(), String> {
    if !(young.is_finite() && young > 0.0) {
        return Err(format!("Young's modulus must be > 0 (got {young})"));
    }
    if !(poisson.is_finite() && poisson > -1.0 && poisson < 0.5) {
        return Err(format!(
            "Poisson's ratio must be in (-1, 0.5) (got {poisson}); for near-incompressible \
             materials use e.g. 0.4999 with formulation = selective_reduced"
        ));
    }
    Ok(())
}

/// The isotropic 3D modulus of `young` and `poisson` (engineering shear).
pub fn isotropic_modulus(young: f64, poisson: f64) -> Tangent {
    let (e, nu) = (young, poisson);
    let lambda = e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
    let mu = e / (2.0 * (1.0 + nu));
    let mut d = Tangent::zeros();
    for i in 0..3 {
        for j in 0..3 {
            d[(i, j)] = lambda;
        }
        d[(i, i)] = lambda + 2.0 * mu;
        d[(i + 3, i + 3)] = mu;
    }
    d
}

impl LinearElastic {
    /// The law with modulus `young` > 0 and Poisson's ratio in (-1, 0.5):
    /// the 3D isotropic modulus (solid, plane strain and axisymmetric
    /// analyses: their elements feed `eps_zz = 0` or the hoop strain into
    /// `zz`), or its plane-stress condensation (`sigma_zz = 0`,
    /// `crate::element::planar::plane_stress_modulus`).
    pub fn new(young: f64, poisson: f64, kind: AnalysisKind) -> Result<Self, String> {
        check_young_poisson(young, poisson)?;
        let d = match kind {
            AnalysisKind::PlaneStress => {
                crate::element::planar::plane_stress_modulus(young, poisson)
            }
            AnalysisKind::PlaneStrain | AnalysisKind::Axisymmetric | AnalysisKind::Solid => {
                isotropic_modulus(young, poisson)
            }
        };
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
            full[2] = crate::element::planar::plane_stress_zz(self.poisson, strain);
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

    fn strain(v: [f64; 6]) -> Strain {
        Strain::from(v)
    }

    #[test]
    fn plane_strain_uniaxial_strain_gives_lame_stresses() {
        let (e, nu) = (200.0, 0.3);
        let law = LinearElastic::new(e, nu, AnalysisKind::PlaneStrain).unwrap();
        let s = law.stress(&strain([1e-3, 0.0, 0.0, 0.0, 0.0, 0.0]));
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
        let eps = strain([2.0 / e, -nu * 2.0 / e, 0.0, 0.0, 0.0, 0.0]);
        let s = law.stress(&eps);
        assert!(rel(s[0], 2.0) < 1e-14);
        assert!(s[1].abs() < 1e-14 && s[2] == 0.0);
        let full = law.complete_strain(&eps);
        assert!(rel(full[2], -nu * 2.0 / e) < 1e-14);
    }

    #[test]
    fn hydrostatic_strain_gives_bulk_modulus_and_shears_the_shear_modulus() {
        let (e, nu) = (1.0, 0.2);
        for kind in [AnalysisKind::Axisymmetric, AnalysisKind::Solid] {
            let law = LinearElastic::new(e, nu, kind).unwrap();
            let s = law.stress(&strain([1.0, 1.0, 1.0, 0.0, 0.0, 0.0]));
            let k = e / (3.0 * (1.0 - 2.0 * nu));
            for i in 0..3 {
                assert!(rel(s[i], 3.0 * k) < 1e-14);
            }
        }
        let law = LinearElastic::new(2.6, 0.3, AnalysisKind::Solid).unwrap();
        let s = law.stress(&strain([0.0, 0.0, 0.0, 1.0, 2.0, 3.0]));
        // G = E / (2 (1 + nu)) = 1, engineering shear
        assert!(rel(s[3], 1.0) < 1e-14 && rel(s[4], 2.0) < 1e-14 && rel(s[5], 3.0) < 1e-14);
    }

    #[test]
    fn invalid_parameters_are_rejected() {
        assert!(LinearElastic::new(0.0, 0.3, AnalysisKind::PlaneStrain).is_err());
        assert!(LinearElastic::new(f64::NAN, 0.3, AnalysisKind::PlaneStrain).is_err());
        assert!(LinearElastic::new(1.0, -1.0, AnalysisKind::PlaneStrain).is_err());
        assert!(LinearElastic::new(1.0, 0.5, AnalysisKind::Axisymmetric).is_err());
    }
}
