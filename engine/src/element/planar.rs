//! The planar embeddings of the 3D laws and kinematics, in one place.
//!
//! Materials are always three-dimensional (`crate::material`); a planar
//! analysis (x, y in the plane; x = r, y = z when axisymmetric) maps its
//! in-plane kinematics into 3D tensors whose `xz`, `yz` components vanish:
//!
//! - **plane strain**: `eps_zz = 0`, `F_33 = 1`;
//! - **plane stress**: `sigma_zz = 0`, solved by static condensation of the
//!   linear elastic modulus ([`plane_stress_modulus`], [`plane_stress_zz`]);
//!   nonlinear laws in plane stress are rejected by validation;
//! - **axisymmetric**: the hoop row `eps_zz = u_r / r` of the strain and
//!   `F_33 = 1 + u_r / R` of the deformation gradient; volumes are `2 pi r`
//!   per unit area (totals over the full ring).
//!
//! Solid (3D) analyses have no embedding: every function here is the
//! identity for them.

use super::{ElementError, Section};
use crate::material::{Strain, Tangent};
use crate::model::AnalysisKind;

/// Volume per unit area (2D) or per unit volume (3D) at radius `r`: the
/// thickness (plane), `2 pi r` (axisymmetric, totals over the full ring) or
/// 1 (solid).
pub fn measure(section: &Section, r: f64) -> f64 {
    match section.kind {
        AnalysisKind::Axisymmetric => 2.0 * std::f64::consts::PI * r,
        AnalysisKind::PlaneStrain | AnalysisKind::PlaneStress => section.thickness,
        AnalysisKind::Solid => 1.0,
    }
}

/// Whether the analysis has the hoop terms (`u_r / r` in the strain,
/// `F_33 = 1 + u_r / R`).
pub fn has_hoop(section: &Section) -> bool {
    section.kind == AnalysisKind::Axisymmetric
}

/// Checks that an axisymmetric integration point is off the axis (the hoop
/// strain `u_r / r` is undefined at `r <= 0`).
pub fn check_radius(section: &Section, r: f64) -> Result<(), ElementError> {
    if has_hoop(section) && (r.is_nan() || r <= 0.0) {
        return Err(ElementError::new(format!(
            "axisymmetric integration point at radius r = {r:e} <= 0: the body must lie in x = r \
             >= 0"
        )));
    }
    Ok(())
}

/// Exponent of the volumetric ratio in F-bar, `F_bar = (J_0 / J)^e F`:
/// 1/2 in plane strain (only the in-plane block is modified, `F_33 = 1`
/// stays), 1/3 otherwise (axisymmetric and solid: all of `F`).
pub fn fbar_exponent(section: &Section) -> f64 {
    match section.kind {
        AnalysisKind::PlaneStrain | AnalysisKind::PlaneStress => 0.5,
        AnalysisKind::Axisymmetric | AnalysisKind::Solid => 1.0 / 3.0,
    }
}

/// Number of rows and columns of `F` that F-bar scales: 2 in plane strain,
/// 3 otherwise.
pub fn fbar_block(section: &Section) -> usize {
    match section.kind {
        AnalysisKind::PlaneStrain | AnalysisKind::PlaneStress => 2,
        AnalysisKind::Axisymmetric | AnalysisKind::Solid => 3,
    }
}

/// The plane-stress modulus: the 3D isotropic law condensed on
/// `sigma_zz = 0` (zero `zz` row and column), in closed form.
pub fn plane_stress_modulus(young: f64, poisson: f64) -> Tangent {
    let (e, nu) = (young, poisson);
    let mut d = Tangent::zeros();
    let c = e / (1.0 - nu * nu);
    d[(0, 0)] = c;
    d[(1, 1)] = c;
    d[(0, 1)] = c * nu;
    d[(1, 0)] = c * nu;
    d[(3, 3)] = c * (1.0 - nu) / 2.0;
    // the out-of-plane shears do not exist in plane stress; their modulus
    // is the 3D one, G
    d[(4, 4)] = e / (2.0 * (1.0 + nu));
    d[(5, 5)] = e / (2.0 * (1.0 + nu));
    d
}

/// The out-of-plane strain of plane stress, from `sigma_zz = 0`:
/// `eps_zz = -nu / (1 - nu) (eps_xx + eps_yy)`.
pub fn plane_stress_zz(poisson: f64, strain: &Strain) -> f64 {
    -poisson / (1.0 - poisson) * (strain[0] + strain[1])
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::linear_elastic::isotropic_modulus;

    #[test]
    fn plane_stress_modulus_is_the_condensed_3d_modulus() {
        let (e, nu) = (70.0, 0.25);
        let d3 = isotropic_modulus(e, nu);
        let d = plane_stress_modulus(e, nu);
        for i in [0, 1, 3] {
            for j in [0, 1, 3] {
                let cond = d3[(i, j)] - d3[(i, 2)] * d3[(2, j)] / d3[(2, 2)];
                assert!((d[(i, j)] - cond).abs() < 1e-12 * e, "{i} {j}");
            }
        }
        let eps = Strain::from([1e-3, -2e-4, 0.0, 0.0, 0.0, 0.0]);
        let mut full = eps;
        full[2] = plane_stress_zz(nu, &eps);
        assert!((d3 * full)[2].abs() < 1e-14 * e);
    }

    #[test]
    fn axisymmetric_point_on_axis_is_an_error() {
        let s = Section {
            kind: AnalysisKind::Axisymmetric,
            thickness: 1.0,
        };
        let e = check_radius(&s, 0.0).unwrap_err();
        assert!(e.message.contains("r = 0"), "{}", e.message);
        assert!(check_radius(&s, 1e-3).is_ok());
        let solid = Section {
            kind: AnalysisKind::Solid,
            thickness: 1.0,
        };
        assert!(check_radius(&solid, -1.0).is_ok());
        assert_eq!(measure(&solid, -3.0), 1.0);
    }
}
