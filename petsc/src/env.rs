//! The process-wide MPI + PETSc environment: one per process, alive for the
//! whole run. MPI is started by rsmpi, then PETSc inside it (so PETSc does
//! not finalize MPI); PETSc's error handler is replaced by the returning one,
//! so a failing call gives a typed [`PetscError`] instead of a printed
//! traceback.

use crate::comm::Comm;
use crate::error::PetscError;
use crate::ffi;
use std::ffi::{CStr, CString};

/// Checks a `PetscErrorCode`: 0 is success, anything else becomes
/// [`PetscError::Call`] with PETSc's text.
pub fn check(call: &'static str, code: ffi::PetscErrorCode) -> Result<(), PetscError> {
    if code == 0 {
        return Ok(());
    }
    let mut text: *const std::os::raw::c_char = std::ptr::null();
    // SAFETY: PetscErrorMessage only writes a pointer to a static string.
    let message = unsafe {
        if ffi::PetscErrorMessage(code, &mut text, std::ptr::null_mut()) == 0 && !text.is_null() {
            CStr::from_ptr(text).to_string_lossy().into_owned()
        } else {
            String::from("unknown PETSc error")
        }
    };
    Err(PetscError::Call {
        call,
        code,
        message,
    })
}

/// A started MPI + PETSc environment; dropping it finalizes PETSc, then MPI.
pub struct Environment {
    /// A duplicate of the world kept for the leaving barrier alone, so it
    /// can never match a collective call of the run (declared first: freed
    /// before `universe` finalizes MPI).
    leaving: mpi::topology::SimpleCommunicator,
    /// MPI itself (finalized when dropped).
    universe: mpi::environment::Universe,
}

impl Environment {
    /// Starts MPI and PETSc with `options` (PETSc command-line syntax, e.g.
    /// `-ksp_type cg -pc_type gamg`) in the options database. They are
    /// given to `PetscInitialize` itself (through `PETSC_OPTIONS`, after
    /// what that variable already holds), so the options PETSc reads only
    /// while it starts work too: `-log_view`, `-log_view_memory`,
    /// `-memory_view`, `-malloc_view`, `-info` (inserted after the start,
    /// they were silently ignored). Fails if MPI was already started in
    /// this process.
    pub fn initialize(options: &str) -> Result<Environment, PetscError> {
        if options.contains('\0') {
            return Err(PetscError::Init("PETSc options contain a NUL byte".into()));
        }
        if !options.trim().is_empty() {
            let all = match std::env::var("PETSC_OPTIONS") {
                Ok(before) if !before.trim().is_empty() => format!("{before} {options}"),
                _ => options.to_string(),
            };
            // read by PetscOptionsInsert inside PetscInitialize; set before
            // MPI starts any thread
            std::env::set_var("PETSC_OPTIONS", all);
        }
        let universe = mpi::initialize()
            .ok_or_else(|| PetscError::Init("MPI is already initialized".into()))?;
        // SAFETY: MPI is initialized; PETSc is initialized once per process
        // (the Universe above can only be had once).
        unsafe {
            check(
                "PetscInitializeNoArguments",
                ffi::PetscInitializeNoArguments(),
            )?;
            check(
                "PetscPushErrorHandler",
                ffi::PetscPushErrorHandler(
                    Some(ffi::PetscReturnErrorHandler),
                    std::ptr::null_mut(),
                ),
            )?;
        }
        let leaving = mpi::traits::Communicator::duplicate(&universe.world());
        Ok(Environment { leaving, universe })
    }

    /// Inserts options into PETSc's database (later ones win).
    pub fn insert_options(&self, options: &str) -> Result<(), PetscError> {
        if options.trim().is_empty() {
            return Ok(());
        }
        let c = CString::new(options)
            .map_err(|_| PetscError::Init("PETSc options contain a NUL byte".into()))?;
        // SAFETY: PETSc is initialized; the string outlives the call.
        unsafe {
            check(
                "PetscOptionsInsertString",
                ffi::PetscOptionsInsertString(std::ptr::null_mut(), c.as_ptr()),
            )
        }
    }

    /// All the ranks of the run.
    pub fn world(&self) -> Comm<'_> {
        Comm::new(self.universe.world())
    }

    /// Waits, at most `timeout`, until every rank has called this: a rank
    /// that has printed its diagnosis then leaves knowing the others did
    /// not exit (and have `mpirun` kill it) before the text was out. True
    /// if every rank arrived in time; false after `timeout` (a rank failed
    /// alone and the others are elsewhere: the caller exits anyway, and
    /// `mpirun` stops the rest). A separate communicator, so this barrier
    /// never pairs with a collective call of the run.
    pub fn leave_together(&self, timeout: std::time::Duration) -> bool {
        use mpi::traits::CommunicatorCollectives;
        let start = std::time::Instant::now();
        let mut request = self.leaving.immediate_barrier();
        loop {
            match request.test() {
                Ok(_) => return true,
                Err(pending) if start.elapsed() >= timeout => {
                    // the barrier cannot complete: leave the request
                    // behind (the process is about to exit)
                    std::mem::forget(pending);
                    return false;
                }
                Err(pending) => {
                    request = pending;
                    std::thread::sleep(std::time::Duration::from_millis(1));
                }
            }
        }
    }

    /// This process alone (a sequential PETSc object in a parallel run).
    pub fn local(&self) -> Comm<'_> {
        Comm::new(mpi::topology::SimpleCommunicator::self_comm())
    }

    /// Whether the PETSc build has an optional package (`hypre`, `mumps`, ...).
    pub fn has_package(&self, name: &str) -> bool {
        let Ok(c) = CString::new(name) else {
            return false;
        };
        let mut has = ffi::PetscBool_PETSC_FALSE;
        // SAFETY: PETSc is initialized; `has` is a valid out pointer.
        let code = unsafe { ffi::PetscHasExternalPackage(c.as_ptr(), &mut has) };
        code == 0 && has == ffi::PetscBool_PETSC_TRUE
    }
}

impl Drop for Environment {
    fn drop(&mut self) {
        // SAFETY: every PETSc object is owned by a wrapper that borrows the
        // environment's communicators, so they are destroyed before this.
        unsafe {
            ffi::PetscFinalize();
        }
        // then `universe` drops: MPI_Finalize
    }
}
