//! What a verification case is: a deck, its refinement levels, the closed
//! form it is compared with, the quantities measured and their tolerances.

use crate::analytical::lame::ThickCylinder;
use crate::analytical::patch::PenaltyPatch;
use crate::profile::Abscissa;
use std::fmt;

/// A quantity extracted from a converged state and compared with a
/// reference. Errors are relative (see each variant for its normalisation).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Quantity {
    /// Hertz contact half-width (cylinder) or radius (sphere) a, from the
    /// pressure profile ([`crate::profile::ContactProfile::half_width`]),
    /// against Hertz for the computed load. Error `|a_h - a| / a`.
    HalfWidth,
    /// Hertz a from the first moment of the contact forces
    /// ([`crate::profile::ContactProfile::moment_ratio`]): an integral
    /// estimate, insensitive to where the nodes fall. Error `|a_m - a| / a`.
    HalfWidthMoment,
    /// Pressure at the node on the axis against Hertz p0 for the computed
    /// load. Error `|p_h - p0| / p0`.
    PeakPressure,
    /// Total contact force (sum of `NodeContact::force`, y) against the
    /// load carried by the supports (minus the sum of the y reactions).
    /// Error `|F_c + sum R| / |sum R|`.
    ContactForce,
    /// `sqrt(int_0^{1.5 a} (p_h - p_Hertz)^2 dx / a) / p0` (the error is the
    /// value itself).
    PressureL2,
    /// Radial displacement of the inner surface nodes:
    /// `max |u_r - u_r,exact| / |u_r,exact(a)|`; computed/reference shown at
    /// the worst node.
    InnerDisplacement,
    /// Hoop stress at every integration point (as the engine's element
    /// kernels compute it): `max |s_tt - s_tt,exact(r)| / s_tt,exact(a)`;
    /// computed/reference shown at the worst point.
    HoopStress,
    /// Axial strain (least-squares slope of u_z over z) against Lamé's
    /// eps_zz. Error `|eps_h - eps| / |eps|`.
    AxialStrain,
    /// Contact pressure of every closed slave node against the uniform
    /// patch pressure: `max |p_i - p| / p`; computed shown at the worst node.
    PatchPressure,
    /// Gap of every slave node against `-p / k`: `max |g_i - g| / |g|`.
    PatchGap,
    /// Displacement of every node against the exact linear field:
    /// `max |u - u_exact| / d`.
    PatchDisplacement,
    /// sigma_yy at every integration point against `-p`:
    /// `max |s_yy + p| / p`; computed shown at the worst point.
    PatchStress,
    /// A quantity of a program case ([`crate::registry::ProgramCase`]),
    /// named in its table (e.g. "F/G mu=0.3"); its normalisation is
    /// documented with the case.
    Named(&'static str),
}

impl Quantity {
    /// Short name used in tables, JSON and plots.
    pub fn name(self) -> &'static str {
        match self {
            Quantity::HalfWidth => "a",
            Quantity::HalfWidthMoment => "a (moment)",
            Quantity::PeakPressure => "p0",
            Quantity::ContactForce => "contact force",
            Quantity::PressureL2 => "L2(p)/p0",
            Quantity::InnerDisplacement => "u_r(a)",
            Quantity::HoopStress => "s_tt",
            Quantity::AxialStrain => "eps_zz",
            Quantity::PatchPressure => "p uniform",
            Quantity::PatchGap => "gap = -p/k",
            Quantity::PatchDisplacement => "u linear",
            Quantity::PatchStress => "s_yy uniform",
            Quantity::Named(n) => n,
        }
    }
}

impl fmt::Display for Quantity {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// The closed form a case is compared with, with the constants the deck
/// must use (checked against the compiled model before comparing).
#[derive(Debug, Clone, PartialEq)]
pub enum Reference {
    /// Elastic cylinder on a rigid plane, or rigid cylinder on an elastic
    /// body, plane strain: Hertz line contact.
    HertzCylinder {
        /// Young's modulus of the elastic body.
        young: f64,
        /// Poisson's ratio of the elastic body.
        poisson: f64,
        /// Radius of the cylinder.
        radius: f64,
        /// Contact pair index in the model.
        pair: usize,
        /// Abscissa of the axis of symmetry (the centre of the contact).
        axis: f64,
        /// Whether the model is the half x >= axis (load doubled).
        half_model: bool,
        /// Coordinate the profile is read in (reference for a curved body on
        /// a plane tool, current for a circle tool on a flat body).
        abscissa: Abscissa,
    },
    /// Elastic sphere on a rigid plane, axisymmetric: Hertz point contact.
    HertzSphere {
        /// Young's modulus.
        young: f64,
        /// Poisson's ratio.
        poisson: f64,
        /// Radius of the sphere.
        radius: f64,
        /// Contact pair index in the model.
        pair: usize,
    },
    /// Thick cylinder under internal pressure.
    Lame {
        /// The closed form (geometry, load, material, end condition).
        cylinder: ThickCylinder,
        /// Centre of the cross-section (plane strain annulus); for an
        /// axisymmetric model the radius is x and this is ignored.
        center: [f64; 2],
        /// Whether the model is axisymmetric (r = x) or a plane section.
        axisymmetric: bool,
    },
    /// Block pressed onto a rigid plane through an area penalty.
    Patch {
        /// The uniform exact state.
        patch: PenaltyPatch,
        /// Contact pair index in the model.
        pair: usize,
    },
}

/// A pass/fail criterion on one quantity.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Check {
    /// What is measured.
    pub quantity: Quantity,
    /// Largest relative error accepted at each level (level 0 first; the
    /// last entry applies to any further level).
    pub tolerance: Vec<f64>,
    /// Smallest observed convergence rate accepted between the last two
    /// levels run (`None`: rates are reported, not checked).
    pub min_rate: Option<f64>,
}

impl Check {
    /// A check with per-level tolerances and no rate requirement.
    pub fn new(quantity: Quantity, tolerance: &[f64]) -> Self {
        Check {
            quantity,
            tolerance: tolerance.to_vec(),
            min_rate: None,
        }
    }

    /// Adds a minimum observed rate between the last two levels.
    pub fn with_min_rate(mut self, rate: f64) -> Self {
        self.min_rate = Some(rate);
        self
    }

    /// The tolerance at `level`.
    pub fn tolerance_at(&self, level: usize) -> f64 {
        self.tolerance
            .get(level)
            .or(self.tolerance.last())
            .copied()
            .unwrap_or(f64::INFINITY)
    }
}

/// A verification case.
#[derive(Debug, Clone, PartialEq)]
pub struct Case {
    /// Identifier (filters match on it), e.g. `hertz_cylinder`.
    pub name: &'static str,
    /// One-line description of what the case shows.
    pub title: &'static str,
    /// Where the reference comes from (section of VERIFICATION-CASES.md,
    /// textbook).
    pub source: &'static str,
    /// Deck file name, relative to the cases directory.
    pub deck: &'static str,
    /// Tags `ctc verify --tag` selects on (method, physics, reference kind).
    pub tags: &'static [&'static str],
    /// Number of refinement levels `ctc verify` runs by default (the deck
    /// may define more).
    pub levels: usize,
    /// The closed form.
    pub reference: Reference,
    /// Pass/fail criteria.
    pub checks: Vec<Check>,
}

impl Case {
    /// Whether the case matches a user filter (substring of the name).
    pub fn matches(&self, filter: Option<&str>) -> bool {
        filter.is_none_or(|f| self.name.contains(f))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn check_tolerance_per_level_repeats_last() {
        let c = Check::new(Quantity::HalfWidth, &[0.1, 0.05, 0.02]);
        assert_eq!(c.tolerance_at(0), 0.1);
        assert_eq!(c.tolerance_at(2), 0.02);
        assert_eq!(c.tolerance_at(7), 0.02);
        assert_eq!(
            Check::new(Quantity::HalfWidth, &[]).tolerance_at(0),
            f64::INFINITY
        );
    }
}
