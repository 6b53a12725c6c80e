//! Contact patch test against a rigid plane: a block of height H resting on
//! the plane y = y0 is pushed down by a uniform displacement `d` of its top,
//! frictionless, free sides, area (traction) penalty `k` (pressure per unit
//! gap). The exact discrete and continuous solution is the same uniform
//! state (`VERIFICATION-CASES.md` §3 and §7): uniaxial stress
//! `sigma_yy = -p` with
//!
//! `p = M (d / H) / (1 + M / (k H))`, gap `g = -p / k` (penetration),
//!
//! where M is the uniaxial-stress modulus of the kinematic assumption
//! (`E / (1 - nu^2)` in plane strain, `E` in plane stress and axisymmetric).
//! The displacement is linear: `u_y(y) = g - (d + g) (y - y0) / H`,
//! `u_x = eps_xx (x - x0)` (zero on the line x = x0, the symmetry plane or
//! the axis).

/// Kinematic assumption of the patch.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum PatchKind {
    /// eps_zz = 0.
    PlaneStrain,
    /// sigma_zz = 0.
    PlaneStress,
    /// x = r; free outer radius: sigma_rr = sigma_tt = 0.
    Axisymmetric,
}

/// A block pressed onto a rigid plane through an area penalty.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PenaltyPatch {
    /// Plane strain, plane stress or axisymmetric.
    pub kind: PatchKind,
    /// Young's modulus.
    pub young: f64,
    /// Poisson's ratio.
    pub poisson: f64,
    /// Height of the block H.
    pub height: f64,
    /// Downward displacement of the top `d` (> 0 presses).
    pub top_displacement: f64,
    /// Area penalty `k` (pressure per unit gap).
    pub penalty: f64,
    /// Abscissa x0 where u_x = 0 (symmetry line or axis).
    pub x0: f64,
    /// Ordinate y0 of the plane (the block's bottom in the reference state).
    pub y0: f64,
}

impl PenaltyPatch {
    /// Modulus relating sigma_yy to eps_yy in the uniaxial state.
    pub fn modulus(&self) -> f64 {
        match self.kind {
            PatchKind::PlaneStrain => self.young / (1.0 - self.poisson * self.poisson),
            PatchKind::PlaneStress | PatchKind::Axisymmetric => self.young,
        }
    }

    /// Uniform contact pressure p (> 0 in compression).
    pub fn pressure(&self) -> f64 {
        let m = self.modulus();
        m * self.top_displacement / self.height / (1.0 + m / (self.penalty * self.height))
    }

    /// Uniform normal gap `-p / k` (negative: penetration).
    pub fn gap(&self) -> f64 {
        -self.pressure() / self.penalty
    }

    /// Uniform axial stress sigma_yy (= -p).
    pub fn sigma_yy(&self) -> f64 {
        -self.pressure()
    }

    /// Lateral strain eps_xx (= eps_rr = eps_tt when axisymmetric).
    pub fn eps_xx(&self) -> f64 {
        let (e, nu, s) = (self.young, self.poisson, self.sigma_yy());
        match self.kind {
            PatchKind::PlaneStrain => -nu * (1.0 + nu) * s / e,
            PatchKind::PlaneStress | PatchKind::Axisymmetric => -nu * s / e,
        }
    }

    /// Exact displacement at reference point (x, y).
    pub fn displacement(&self, x: f64, y: f64) -> [f64; 2] {
        let g = self.gap();
        let uy = g - (self.top_displacement + g) * (y - self.y0) / self.height;
        [self.eps_xx() * (x - self.x0), uy]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn patch(kind: PatchKind, nu: f64) -> PenaltyPatch {
        PenaltyPatch {
            kind,
            young: 2e6,
            poisson: nu,
            height: 1.0,
            top_displacement: 0.05,
            penalty: 1e9,
            x0: 0.0,
            y0: 0.0,
        }
    }

    /// VERIFICATION-CASES §3: E = 2e6, nu = 0, strain -0.05 gives a uniform
    /// pressure 1e5; the penalty reduces it by the factor 1/(1 + E/(kH)).
    #[test]
    fn patch_test_uniform_pressure_1e5() {
        let p = patch(PatchKind::PlaneStrain, 0.0);
        let expected = 1e5 / (1.0 + 2e6 / 1e9);
        assert!((p.pressure() - expected).abs() < 1e-9 * expected);
        assert!((p.gap() + expected / 1e9).abs() < 1e-20);
        assert_eq!(p.eps_xx(), 0.0);
    }

    /// The displacement field reproduces the gap at the bottom, -d at the
    /// top, and the strain gives the stress through the modulus.
    #[test]
    fn patch_test_consistent_state() {
        for kind in [
            PatchKind::PlaneStrain,
            PatchKind::PlaneStress,
            PatchKind::Axisymmetric,
        ] {
            let p = patch(kind, 0.3);
            let bottom = p.displacement(0.7, 0.0);
            let top = p.displacement(0.7, 1.0);
            assert!((bottom[1] - p.gap()).abs() < 1e-18);
            assert!((top[1] + 0.05).abs() < 1e-15);
            let eps_yy = top[1] - bottom[1];
            assert!((p.modulus() * eps_yy - p.sigma_yy()).abs() < 1e-6);
            // Penalty law at the interface.
            assert!((p.penalty * -p.gap() - p.pressure()).abs() < 1e-6);
            assert!(p.eps_xx() > 0.0);
        }
        let ps = patch(PatchKind::PlaneStrain, 0.3);
        let pstress = patch(PatchKind::PlaneStress, 0.3);
        assert!(ps.pressure() > pstress.pressure());
    }
}
