//! ctc-engine: the finite-element engine of ctc.
//!
//! - [`geom`]: points, node blocks, the dimension bound, boxes, rotations;
//! - [`model`]: the lowered scene a deck compiles into;
//! - [`mesh`]: storage, generators, gmsh import, selections, checks;
//! - [`element`] and [`material`]: element kernels and constitutive laws;
//! - [`contact`]: rigid analytical tools, search, penalty enforcement;
//! - [`solve`]: assembly, sparse linear solvers, the Newton loop, stepping;
//! - [`output`]: VTU/PVD, CSV histories, JSON run summary;
//! - [`thermal`]: heat conduction, thermal contact, thermo-mechanical coupling;
//! - [`testkit`]: the model builder and recording observer shared by tests.

pub mod contact;
pub mod element;
pub mod geom;
pub mod material;
pub mod mesh;
pub mod model;
pub mod output;
pub mod solve;
pub mod testkit;
pub mod thermal;
