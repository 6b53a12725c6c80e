//! The thermal part of a lowered scene ([`crate::model::Model::thermal`]):
//! plain data, lowered from the deck, used by [`crate::thermal`].
//!
//! It exists only when the deck has a `thermal` block somewhere: a scene
//! without one carries `Model::thermal = None` and no temperature unknowns
//! at all. Temperatures are nodal; units are the user's (consistent). The
//! same data serves planar and solid models (boundary conditions on
//! [`Facet`]s: edges in 2D, faces in 3D).

use super::TimeFunction;
use crate::mesh::Facet;

/// Everything thermal of a scene.
#[derive(Debug, Clone, PartialEq)]
pub struct ThermalScene {
    /// Thermal properties per material (index = `Model::materials`); a body
    /// whose material has `None` carries no temperature unknowns.
    pub materials: Vec<Option<MaterialThermal>>,
    /// Initial temperature per body (index = `Model::bodies`).
    pub initial: Vec<f64>,
    /// Prescribed nodal temperatures.
    pub temperatures: Vec<PrescribedTemperature>,
    /// Prescribed heat fluxes into the body through boundary edges.
    pub fluxes: Vec<HeatFlux>,
    /// Convection (film) conditions on boundary edges.
    pub convection: Vec<Convection>,
    /// Thermal contact settings per contact pair (index = `Model::contacts`);
    /// `None`: the pair exchanges no heat.
    pub contacts: Vec<Option<ContactThermal>>,
    /// How mechanics and heat are coupled.
    pub scheme: CouplingScheme,
}

/// Thermal and thermo-mechanical properties of a material.
#[derive(Debug, Clone, PartialEq)]
pub struct MaterialThermal {
    /// Conductivity `k` (power / length / temperature), > 0.
    pub conductivity: f64,
    /// Specific heat capacity `c` (energy / mass / temperature), >= 0.
    pub capacity: f64,
    /// Mass density `rho`, >= 0 (`rho c = 0`: steady conduction).
    pub density: f64,
    /// Linear thermal expansion coefficient `alpha`, >= 0.
    pub expansion: f64,
    /// Temperature at which the thermal strain is zero.
    pub reference: f64,
    /// Taylor-Quinney factor: fraction of the plastic work turned into heat,
    /// in [0, 1].
    pub taylor_quinney: f64,
    /// Young's modulus factor as a function of temperature (multiplies the
    /// mechanical law's `E`); `None`: independent of temperature.
    pub young_factor: Option<Vec<(f64, f64)>>,
    /// Flow stress factor as a function of temperature (multiplies the
    /// whole hardening curve); `None`: independent of temperature.
    pub yield_factor: Option<Vec<(f64, f64)>>,
}

/// Fixed nodal temperatures.
#[derive(Debug, Clone, PartialEq)]
pub struct PrescribedTemperature {
    /// Human-readable origin, e.g. `temperature bar.left`.
    pub label: String,
    /// Global node numbers.
    pub nodes: Vec<usize>,
    /// Temperature as a function of time.
    pub value: TimeFunction,
}

/// Heat flux entering the body through boundary facets (power / area;
/// positive heats the body).
#[derive(Debug, Clone, PartialEq)]
pub struct HeatFlux {
    /// Human-readable origin.
    pub label: String,
    /// Boundary facets: edges `[a, b]` of a planar mesh (body on the left)
    /// or faces of a solid (outward).
    pub facets: Vec<Facet>,
    /// Flux as a function of time.
    pub value: TimeFunction,
}

/// Convection `q = h (T_ambient - T)` entering the body through boundary
/// facets.
#[derive(Debug, Clone, PartialEq)]
pub struct Convection {
    /// Human-readable origin.
    pub label: String,
    /// Boundary facets: edges `[a, b]` of a planar mesh (body on the left)
    /// or faces of a solid (outward).
    pub facets: Vec<Facet>,
    /// Film coefficient `h` (power / area / temperature), >= 0.
    pub film: f64,
    /// Ambient temperature as a function of time.
    pub ambient: TimeFunction,
}

/// Conductance of a closed contact as a function of the contact pressure.
#[derive(Debug, Clone, PartialEq)]
pub enum Conductance {
    /// `h = h0 + h1 p^n`.
    Power {
        /// `h0`, >= 0.
        h0: f64,
        /// `h1`, >= 0.
        h1: f64,
        /// Exponent `n`, > 0.
        n: f64,
    },
    /// Piecewise linear in the pressure through (p, h) points, constant
    /// beyond the ends.
    Table(Vec<(f64, f64)>),
}

impl Conductance {
    /// Conductance at contact pressure `p >= 0`.
    pub fn at(&self, p: f64) -> f64 {
        let p = p.max(0.0);
        match self {
            Conductance::Power { h0, h1, n } => h0 + h1 * p.powf(*n),
            Conductance::Table(points) => TimeFunction::Table(points.clone()).eval(p),
        }
    }
}

/// Thermal settings of a contact pair.
#[derive(Debug, Clone, PartialEq)]
pub struct ContactThermal {
    /// Conductance of the closed contact.
    pub conductance: Conductance,
    /// Open contact: gas conductivity `k_gap`, conductance `k_gap / g` for a
    /// gap `g` within the pair's `prof` (the gap is floored at
    /// `gap_min`); 0: no heat across an open contact.
    pub gap_conductivity: f64,
    /// Smallest gap used in `k_gap / g` (length), > 0.
    pub gap_min: f64,
    /// Fraction of the frictional heat that goes to the slave side, in
    /// [0, 1] (the rest goes to the master surface or the tool).
    pub friction_split: f64,
    /// Temperature of the rigid tool of the pair (its own prescribed
    /// temperature); `None` for a deformable master, or an adiabatic tool.
    pub tool_temperature: Option<TimeFunction>,
}

/// Coupling scheme between mechanics and heat.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum CouplingScheme {
    /// Isothermal split: each increment solves mechanics at the temperatures
    /// of the last converged increment, then heat conduction on the
    /// converged configuration with the increment's mechanical heat sources
    /// and contact conductances (the default).
    #[default]
    Staggered,
}
