//! ctc-petsc: distributed assembly and linear solves on the system PETSc
//! over MPI, for `mpirun -n N ctc run deck.ctc --solver petsc`.
//!
//! ```text
//! cells ──partition (METIS)──▶ cell → rank ──DofLayout──▶ owned / ghost nodes,
//!        PETSc numbering (rank blocks, natural order inside each block)
//!   ──Preallocation (exact d_nnz / o_nnz)──▶ DistMatrix (MatMPIAIJ, ADD_VALUES)
//!   ──GhostedVector (VecGhost: owned + ghost values)──▶ Krylov (KSP from options,
//!        MUMPS LU | CG + GAMG with rigid-body near-null space | hypre) ──▶ solution
//!   ranks agree on every decision through `Comm::agree_*`.
//! ```
//!
//! Without the cargo feature `petsc` (the default) only the PETSc-free parts
//! are compiled: [`layout`] (ownership and numbering from a cell partition),
//! [`nullspace`] (rigid-body modes from coordinates) and [`error`] (typed
//! errors). With it, the safe wrappers around the bindgen bindings: [`env`],
//! [`comm`], [`matrix`], [`vector`], [`krylov`], [`partition`], and
//! [`engine_system`]: the engine's `LinearSystem` on PETSc, what
//! `ctc run --solver petsc` uses.

#![warn(missing_docs)]

pub mod error;
pub mod layout;
pub mod nullspace;

#[cfg(feature = "petsc")]
pub mod comm;
#[cfg(feature = "petsc")]
pub mod engine_system;
#[cfg(feature = "petsc")]
pub mod env;
#[cfg(feature = "petsc")]
pub mod ffi;
#[cfg(feature = "petsc")]
pub mod krylov;
#[cfg(feature = "petsc")]
pub mod matrix;
#[cfg(feature = "petsc")]
pub mod partition;
#[cfg(feature = "petsc")]
pub mod vector;

pub use error::PetscError;
pub use layout::{DofLayout, Preallocation};
pub use nullspace::rigid_body_modes;

#[cfg(feature = "petsc")]
pub use comm::Comm;
#[cfg(feature = "petsc")]
pub use engine_system::PetscSystem;
#[cfg(feature = "petsc")]
pub use env::Environment;
#[cfg(feature = "petsc")]
pub use krylov::{Krylov, SolveReport, SolverChoice};
#[cfg(feature = "petsc")]
pub use matrix::DistMatrix;
#[cfg(feature = "petsc")]
pub use partition::partition_cells;
#[cfg(feature = "petsc")]
pub use vector::GhostedVector;
