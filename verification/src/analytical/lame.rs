//! Lamé: thick-walled cylinder (inner radius a, outer radius b) under an
//! internal pressure p, linear elastic, small strain.
//!
//! With `A = p a^2 / (b^2 - a^2)` and `B = p a^2 b^2 / (b^2 - a^2)`:
//! `sigma_rr = A - B / r^2`, `sigma_tt = A + B / r^2`, and
//! `u_r = r eps_tt = (r / E) (sigma_tt - nu (sigma_rr + sigma_zz))`, where
//! the axial stress depends on the end condition ([`EndCondition`]).
//! Reference: S. Timoshenko, J. N. Goodier, *Theory of Elasticity*, §33.

/// Axial (z) condition of the cylinder.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum EndCondition {
    /// eps_zz = 0 (plane strain; also an axisymmetric model with both ends
    /// fixed axially): `sigma_zz = 2 nu A`.
    PlaneStrain,
    /// Free ends (generalised plane strain, uniform eps_zz):
    /// `sigma_zz = 0`.
    OpenEnds,
    /// Capped ends carrying the pressure on the caps: `sigma_zz = A`.
    ClosedEnds,
}

/// Thick cylinder under internal pressure.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ThickCylinder {
    /// Inner radius a > 0.
    pub inner: f64,
    /// Outer radius b > a.
    pub outer: f64,
    /// Internal pressure p (positive pushes the bore outwards).
    pub pressure: f64,
    /// Young's modulus.
    pub young: f64,
    /// Poisson's ratio.
    pub poisson: f64,
    /// Axial condition.
    pub ends: EndCondition,
}

impl ThickCylinder {
    /// Constant A of the Lamé solution.
    fn a_coef(&self) -> f64 {
        let (a, b) = (self.inner, self.outer);
        self.pressure * a * a / (b * b - a * a)
    }

    /// Constant B of the Lamé solution.
    fn b_coef(&self) -> f64 {
        let (a, b) = (self.inner, self.outer);
        self.pressure * a * a * b * b / (b * b - a * a)
    }

    /// Radial stress at radius `r`.
    pub fn sigma_rr(&self, r: f64) -> f64 {
        self.a_coef() - self.b_coef() / (r * r)
    }

    /// Hoop stress at radius `r`.
    pub fn sigma_tt(&self, r: f64) -> f64 {
        self.a_coef() + self.b_coef() / (r * r)
    }

    /// Axial stress (uniform).
    pub fn sigma_zz(&self) -> f64 {
        match self.ends {
            EndCondition::PlaneStrain => 2.0 * self.poisson * self.a_coef(),
            EndCondition::OpenEnds => 0.0,
            EndCondition::ClosedEnds => self.a_coef(),
        }
    }

    /// Axial strain (uniform; 0 in plane strain).
    pub fn eps_zz(&self) -> f64 {
        (self.sigma_zz() - 2.0 * self.poisson * self.a_coef()) / self.young
    }

    /// Radial displacement at radius `r`.
    pub fn u_r(&self, r: f64) -> f64 {
        r / self.young * (self.sigma_tt(r) - self.poisson * (self.sigma_rr(r) + self.sigma_zz()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cyl(ends: EndCondition) -> ThickCylinder {
        ThickCylinder {
            inner: 1.0,
            outer: 2.0,
            pressure: 1.0,
            young: 1.0,
            poisson: 0.3,
            ends,
        }
    }

    #[test]
    fn lame_boundary_tractions() {
        for ends in [
            EndCondition::PlaneStrain,
            EndCondition::OpenEnds,
            EndCondition::ClosedEnds,
        ] {
            let c = cyl(ends);
            assert!((c.sigma_rr(1.0) + 1.0).abs() < 1e-14);
            assert!(c.sigma_rr(2.0).abs() < 1e-14);
        }
    }

    /// Plane strain, a = 1, b = 2, p = 1, E = 1, nu = 0.3:
    /// u_r(a) = (1 + nu)/E [(1 - 2 nu) A a + B / a] = 1.3 (0.4/3 + 4/3).
    #[test]
    fn lame_plane_strain_inner_displacement() {
        let c = cyl(EndCondition::PlaneStrain);
        let expected = 1.3 * (0.4 / 3.0 + 4.0 / 3.0);
        assert!(
            (c.u_r(1.0) - expected).abs() < 1e-14,
            "u_r = {}",
            c.u_r(1.0)
        );
        assert!((c.sigma_tt(1.0) - 5.0 / 3.0).abs() < 1e-14);
        assert_eq!(c.eps_zz(), 0.0);
    }

    /// Open ends: sigma_zz = 0, eps_zz = -2 nu A / E, and
    /// u_r = [(1 - nu) A r + (1 + nu) B / r] / E.
    #[test]
    fn lame_open_ends_axial_strain() {
        let c = cyl(EndCondition::OpenEnds);
        let (a, b) = (1.0 / 3.0, 4.0 / 3.0);
        assert!((c.eps_zz() + 2.0 * 0.3 * a).abs() < 1e-14);
        let r = 1.5;
        let expected = 0.7 * a * r + 1.3 * b / r;
        assert!((c.u_r(r) - expected).abs() < 1e-14);
    }

    /// The displacement field satisfies Hooke's law with eps_rr = du/dr and
    /// the stresses satisfy radial equilibrium, for all end conditions.
    #[test]
    fn lame_compatibility_and_equilibrium() {
        for ends in [
            EndCondition::PlaneStrain,
            EndCondition::OpenEnds,
            EndCondition::ClosedEnds,
        ] {
            let c = cyl(ends);
            for &r in &[1.1, 1.5, 1.9] {
                let h = 1e-5;
                let du = (c.u_r(r + h) - c.u_r(r - h)) / (2.0 * h);
                let eps_rr = (c.sigma_rr(r) - c.poisson * (c.sigma_tt(r) + c.sigma_zz())) / c.young;
                assert!(
                    (du - eps_rr).abs() < 1e-8,
                    "{ends:?} r={r}: {du} vs {eps_rr}"
                );
                let ds = (c.sigma_rr(r + h) - c.sigma_rr(r - h)) / (2.0 * h);
                let eq = ds + (c.sigma_rr(r) - c.sigma_tt(r)) / r;
                assert!(eq.abs() < 1e-8, "{ends:?} equilibrium residual {eq}");
                let eps_zz = (c.sigma_zz() - c.poisson * (c.sigma_rr(r) + c.sigma_tt(r))) / c.young;
                assert!((eps_zz - c.eps_zz()).abs() < 1e-14);
            }
        }
    }
}
