//! A communicator, and the collective decisions ranks must agree on: under
//! MPI a rank never decides alone whether an iteration converged, a step is
//! cut back or the run failed (a lone rank going its own way deadlocks the
//! next collective call).

use crate::env::Environment;
use crate::error::PetscError;
use crate::ffi;
use mpi::collective::SystemOperation;
use mpi::topology::SimpleCommunicator;
use mpi::traits::{AsRaw, Communicator, CommunicatorCollectives, Root};
use std::marker::PhantomData;

/// An MPI communicator usable by PETSc objects and for agreement; it
/// cannot outlive the [`Environment`] (so no PETSc object outlives
/// `PetscFinalize`).
pub struct Comm<'e> {
    inner: SimpleCommunicator,
    _env: PhantomData<&'e Environment>,
}

impl<'e> Comm<'e> {
    pub(crate) fn new(inner: SimpleCommunicator) -> Comm<'e> {
        Comm {
            inner,
            _env: PhantomData,
        }
    }

    /// This process's rank.
    pub fn rank(&self) -> usize {
        self.inner.rank() as usize
    }

    /// Number of ranks.
    pub fn size(&self) -> usize {
        self.inner.size() as usize
    }

    /// The raw handle for PETSc calls.
    pub(crate) fn raw(&self) -> ffi::MPI_Comm {
        ffi::MPI_Comm(self.inner.as_raw().0 as *mut ffi::ompi_communicator_t)
    }

    /// The rsmpi communicator (for other collectives).
    pub fn mpi(&self) -> &SimpleCommunicator {
        &self.inner
    }

    /// True on every rank iff `ok` on every rank.
    pub fn all(&self, ok: bool) -> bool {
        let mut out = 0i32;
        self.inner
            .all_reduce_into(&i32::from(ok), &mut out, SystemOperation::logical_and());
        out != 0
    }

    /// True on every rank iff `flag` on at least one rank.
    pub fn any(&self, flag: bool) -> bool {
        let mut out = 0i32;
        self.inner
            .all_reduce_into(&i32::from(flag), &mut out, SystemOperation::logical_or());
        out != 0
    }

    /// The convergence decision of an iteration: converged only if every
    /// rank's local test passed.
    pub fn agree_converged(&self, local_converged: bool) -> bool {
        self.all(local_converged)
    }

    /// Makes every rank agree on a failure: each passes its local failure
    /// code (0 = none, see [`PetscError::code`] or the engine's own
    /// numbering) and all get the largest.
    pub fn agree_failure_code(&self, local: u32) -> u32 {
        let mut out = 0u32;
        self.inner
            .all_reduce_into(&local, &mut out, SystemOperation::max());
        out
    }

    /// [`Comm::agree_failure_code`] for a local result: `Ok` on every rank
    /// iff every rank succeeded; otherwise every rank returns an error (its
    /// own if it failed, or [`PetscError::OtherRank`] with the class of the
    /// failure elsewhere).
    pub fn agree_failure<T>(&self, local: Result<T, PetscError>) -> Result<T, PetscError> {
        let code = self.agree_failure_code(local.as_ref().err().map_or(0, PetscError::code));
        match (local, code) {
            (Ok(v), 0) => Ok(v),
            (Err(e), _) => Err(e),
            (Ok(_), c) => Err(PetscError::OtherRank(c)),
        }
    }

    /// Sum over the ranks.
    pub fn sum(&self, local: f64) -> f64 {
        let mut out = 0.0;
        self.inner
            .all_reduce_into(&local, &mut out, SystemOperation::sum());
        out
    }

    /// Maximum over the ranks.
    pub fn max(&self, local: f64) -> f64 {
        let mut out = 0.0;
        self.inner
            .all_reduce_into(&local, &mut out, SystemOperation::max());
        out
    }

    /// Sum over the ranks of a count.
    pub fn sum_count(&self, local: usize) -> usize {
        let mut out = 0u64;
        self.inner
            .all_reduce_into(&(local as u64), &mut out, SystemOperation::sum());
        out as usize
    }

    /// Sums `v` over the ranks in place (collective): reduced on rank 0,
    /// then broadcast, so every rank holds the same bits (an all-reduce
    /// may round differently on different ranks).
    pub fn sum_vector(&self, v: &mut [f64]) {
        let root = self.inner.process_at_rank(0);
        if self.rank() == 0 {
            let mut out = vec![0.0; v.len()];
            root.reduce_into_root(&v[..], &mut out[..], SystemOperation::sum());
            v.copy_from_slice(&out);
        } else {
            root.reduce_into(&v[..], SystemOperation::sum());
        }
        root.broadcast_into(v);
    }

    /// Every rank's `local` values (any count per rank), rank by rank, on
    /// rank 0; `None` on the others.
    pub fn gather_on_first(&self, local: &[f64]) -> Option<Vec<f64>> {
        let root = self.inner.process_at_rank(0);
        let count = i32::try_from(local.len()).expect("fewer than 2^31 values per rank");
        if self.rank() == 0 {
            let mut counts = vec![0i32; self.size()];
            root.gather_into_root(&count, &mut counts[..]);
            let displs: Vec<i32> = counts
                .iter()
                .scan(0i32, |at, &c| {
                    let d = *at;
                    *at += c;
                    Some(d)
                })
                .collect();
            let total = counts.iter().map(|&c| c as usize).sum();
            let mut out = vec![0.0; total];
            let mut partition = mpi::datatype::PartitionMut::new(&mut out[..], counts, displs);
            root.gather_varcount_into_root(local, &mut partition);
            Some(out)
        } else {
            root.gather_into(&count);
            root.gather_varcount_into(local);
            None
        }
    }

    /// Every rank's `local` values (the same count on every rank), rank by
    /// rank, on every rank.
    pub fn all_gather(&self, local: &[f64]) -> Vec<f64> {
        let mut out = vec![0.0; local.len() * self.size()];
        self.inner.all_gather_into(local, &mut out[..]);
        out
    }
}
