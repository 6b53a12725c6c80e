//! Heat conduction and thermo-mechanical coupling.
//!
//! A scene has a thermal part ([`crate::model::thermal::ThermalScene`],
//! `Model::thermal`, plain data in the model)
//! only if its deck has a `thermal` block; otherwise nothing here is built
//! and the run has no temperature unknowns at all.
//!
//! - [`conduction`]: conductivity and lumped capacity of tri3/quad4 cells,
//!   plane and axisymmetric;
//! - [`boundary`]: edge integrals of fluxes and convection films;
//! - [`contact`]: pressure- and gap-dependent contact conductance, the
//!   conductance element against a tool or a master segment;
//! - [`contact_faces`]: the same exchange integrated at the points of
//!   quadratic slave faces against a tool (no nodal areas there);
//! - [`solver`]: the implicit (backward Euler) transient on its own scalar
//!   dof numbering, sparse Cholesky;
//! - [`expansion`]: thermal strains handed to the mechanics;
//! - [`properties`]: temperature-dependent moduli and flow stress;
//! - [`coupling`]: the staggered (isothermal split) increment: mechanics at
//!   fixed temperature, then heat with the mechanical sources.

pub mod boundary;
pub mod conduction;
pub mod contact;
pub mod contact_faces;
pub mod coupling;
pub mod expansion;
pub mod properties;
pub mod solver;
