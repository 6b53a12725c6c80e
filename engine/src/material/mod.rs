//! Constitutive laws, always three-dimensional.
//!
//! One 6-component Voigt notation, ordered `[xx, yy, zz, xy, xz, yz]`:
//! - strain: `[eps_xx, eps_yy, eps_zz, gamma_xy, gamma_xz, gamma_yz]` with
//!   the **engineering** shears `gamma_ij = 2 eps_ij`;
//! - stress: `[sigma_xx, .., sigma_xy, sigma_xz, sigma_yz]`.
//!
//! Planar analyses embed into these tensors (`crate::element::planar`):
//! their `xz`, `yz` components vanish, `zz` is the out-of-plane component
//! (plane strain: `eps_zz = 0`; plane stress: `sigma_zz = 0`) or, for
//! axisymmetric analyses (x = r, y = z), the hoop component
//! `theta theta`. The first four components are those of the planar
//! outputs.
//!
//! A law maps a strain to a stress and a consistent tangent `d sigma / d eps`,
//! so that elements compute `f_int = int B^T sigma` and `K = int B^T D B`
//! whatever the law (nonlinear laws plug in behind the same trait).

pub mod dual;
pub mod hardening;
pub mod j2;
pub mod law;
pub mod linear_elastic;
pub mod tensor;

pub use law::{History, NonlinearLaw};
pub use linear_elastic::LinearElastic;

use crate::model::{AnalysisKind, Material, MaterialLaw};
use nalgebra::{SMatrix, SVector};

/// Strain in Voigt notation `[xx, yy, zz, xy, xz, yz]` (engineering shear).
pub type Strain = SVector<f64, 6>;
/// Stress in Voigt notation `[xx, yy, zz, xy, xz, yz]`.
pub type Stress = SVector<f64, 6>;
/// Tangent modulus `d sigma / d eps` (6x6).
pub type Tangent = SMatrix<f64, 6, 6>;

/// A small-strain constitutive law for a given analysis kind.
pub trait Constitutive {
    /// Stress for the kinematic strain `strain` (for plane stress the `zz`
    /// entry of `strain` is ignored; the law enforces `sigma_zz = 0`).
    fn stress(&self, strain: &Strain) -> Stress;
    /// Consistent tangent at `strain`.
    fn tangent(&self, strain: &Strain) -> Tangent;
    /// The full strain for output: the kinematic strain with the
    /// out-of-plane component completed where the law determines it
    /// (plane stress: `eps_zz` from `sigma_zz = 0`).
    fn complete_strain(&self, strain: &Strain) -> Strain;
}

/// Von Mises equivalent stress of `[xx, yy, zz, xy, xz, yz]`.
pub fn von_mises(s: &Stress) -> f64 {
    let (xx, yy, zz) = (s[0], s[1], s[2]);
    (0.5 * ((xx - yy).powi(2) + (yy - zz).powi(2) + (zz - xx).powi(2))
        + 3.0 * s[3] * s[3]
        + 3.0 * s[4] * s[4]
        + 3.0 * s[5] * s[5])
        .sqrt()
}

/// Builds the (small-strain, linear) elastic law of `material` for
/// analyses of `kind` — for nonlinear materials, their initial elastic
/// response; checks its parameters and explains what is wrong. The full law
/// of nonlinear materials is [`NonlinearLaw::build`].
pub fn build(material: &Material, kind: AnalysisKind) -> Result<LinearElastic, String> {
    let (young, poisson) = match material.law {
        MaterialLaw::LinearElastic { young, poisson }
        | MaterialLaw::NeoHookean { young, poisson }
        | MaterialLaw::ElastoPlastic { young, poisson, .. } => (young, poisson),
    };
    LinearElastic::new(young, poisson, kind)
        .map_err(|e| format!("material `{}`: {e}", material.name))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn von_mises_of_uniaxial_and_pure_shear() {
        let uni = Stress::from([3.0, 0.0, 0.0, 0.0, 0.0, 0.0]);
        assert!((von_mises(&uni) - 3.0).abs() < 1e-14);
        let shear = Stress::from([0.0, 0.0, 0.0, 0.0, 0.0, 2.0]);
        assert!((von_mises(&shear) - 2.0 * 3f64.sqrt()).abs() < 1e-14);
        let hydro = Stress::from([-5.0, -5.0, -5.0, 0.0, 0.0, 0.0]);
        assert!(von_mises(&hydro).abs() < 1e-14);
    }

    #[test]
    fn build_rejects_invalid_poisson_with_the_material_name() {
        let m = Material {
            name: "rubber".into(),
            density: 0.0,
            law: MaterialLaw::LinearElastic {
                young: 1.0,
                poisson: 0.5,
            },
        };
        let err = build(&m, AnalysisKind::PlaneStrain).unwrap_err();
        assert!(err.contains("rubber") && err.contains("Poisson"), "{err}");
    }
}
