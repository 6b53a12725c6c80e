//! Typed errors of the distributed backend: what a caller (and every rank)
//! must decide on. A PETSc error code becomes [`PetscError::Call`] with the
//! name of the call and PETSc's own message; a Krylov solve that stopped on a
//! divergence reason becomes [`PetscError::Diverged`].

use std::fmt;

/// A failure of the distributed backend.
#[derive(Debug, Clone, PartialEq)]
pub enum PetscError {
    /// A PETSc (or MPI) call returned a non-zero `PetscErrorCode`.
    Call {
        /// The C function that failed (`MatSetValues`, ...).
        call: &'static str,
        /// The `PetscErrorCode` it returned.
        code: i32,
        /// PETSc's text for the code (`PetscErrorMessage`).
        message: String,
    },
    /// The Krylov solver stopped without converging.
    Diverged {
        /// PETSc's `KSPConvergedReason` (negative).
        reason: i32,
        /// Its name (`DIVERGED_ITS`, `DIVERGED_INDEFINITE_PC`, ...).
        reason_name: String,
        /// Iterations done.
        iterations: usize,
    },
    /// The mesh or the partition handed to the layout is inconsistent.
    Layout(String),
    /// METIS could not partition the mesh.
    Partition(String),
    /// The MPI/PETSc environment could not start.
    Init(String),
    /// The factorization found the matrix singular (MUMPS null pivots, a
    /// failed preconditioner set-up): what, in words.
    Singular(String),
    /// This rank was fine but another one failed with this error class
    /// (see [`PetscError::code`]); every rank stops together.
    OtherRank(u32),
}

impl PetscError {
    /// A small integer per variant, for the all-reduce that makes every rank
    /// agree on a failure ([`crate::comm::Comm::agree_failure`] keeps the
    /// largest): 0 is "no failure".
    pub fn code(&self) -> u32 {
        match self {
            PetscError::Diverged { .. } => 1,
            PetscError::Layout(_) => 2,
            PetscError::Partition(_) => 3,
            PetscError::Call { .. } => 4,
            PetscError::Init(_) => 5,
            PetscError::Singular(_) => 6,
            PetscError::OtherRank(c) => *c,
        }
    }
}

impl fmt::Display for PetscError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            PetscError::Call {
                call,
                code,
                message,
            } => write!(f, "PETSc error {code} in {call}: {message}"),
            PetscError::Diverged {
                reason,
                reason_name,
                iterations,
            } => write!(
                f,
                "the Krylov solver did not converge: {reason_name} ({reason}) after {iterations} iterations"
            ),
            PetscError::Layout(m) => write!(f, "distributed layout: {m}"),
            PetscError::Partition(m) => write!(f, "mesh partition: {m}"),
            PetscError::Init(m) => write!(f, "MPI/PETSc start: {m}"),
            PetscError::Singular(m) => f.write_str(m),
            PetscError::OtherRank(c) => write!(f, "another rank failed (error class {c})"),
        }
    }
}

impl std::error::Error for PetscError {}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn codes_are_distinct_and_non_zero() {
        let all = [
            PetscError::Diverged {
                reason: -3,
                reason_name: "DIVERGED_ITS".into(),
                iterations: 10,
            },
            PetscError::Layout(String::new()),
            PetscError::Partition(String::new()),
            PetscError::Call {
                call: "MatSetValues",
                code: 63,
                message: "Argument out of range".into(),
            },
            PetscError::Init(String::new()),
        ];
        let mut codes: Vec<u32> = all.iter().map(PetscError::code).collect();
        codes.sort_unstable();
        codes.dedup();
        assert_eq!(codes.len(), all.len());
        assert!(codes.iter().all(|&c| c > 0));
        assert_eq!(
            all[3].to_string(),
            "PETSc error 63 in MatSetValues: Argument out of range"
        );
    }
}
