//! Ghosted distributed vectors (PETSc `VecGhost`): each rank stores its
//! owned values followed by copies of its ghost values (the nodes of its
//! cells owned by another rank, [`DofLayout::ghost_nodes`]). Forward update:
//! owners -> ghost copies (before a rank evaluates its cells); reverse add:
//! ghost contributions -> owners (after a rank assembled its cells' forces).

use crate::comm::Comm;
use crate::env::check;
use crate::error::PetscError;
use crate::ffi;
use crate::layout::DofLayout;
use crate::matrix::to_ints;
use std::marker::PhantomData;

/// A distributed vector with ghost copies, on the dofs of a [`DofLayout`].
pub struct GhostedVector<'e> {
    pub(crate) vec: ffi::Vec,
    n_owned: usize,
    n_ghost: usize,
    _env: PhantomData<&'e ()>,
}

impl<'e> GhostedVector<'e> {
    /// A zero vector of `layout` with its ghosts.
    pub fn new(comm: &Comm<'e>, layout: &DofLayout) -> Result<GhostedVector<'e>, PetscError> {
        let ghosts = to_ints(&layout.ghost_dofs())?;
        let n_owned = layout.owned_dofs().len();
        let sizes = to_ints(&[n_owned, layout.n_global_dofs(), ghosts.len(), layout.dim])?;
        let mut vec: ffi::Vec = std::ptr::null_mut();
        // SAFETY: PETSc is initialized; PETSc copies the ghost indices.
        unsafe {
            check(
                "VecCreateGhost",
                ffi::VecCreateGhost(
                    comm.raw(),
                    sizes[0],
                    sizes[1],
                    sizes[2],
                    ghosts.as_ptr(),
                    &mut vec,
                ),
            )?;
            let v = GhostedVector {
                vec,
                n_owned,
                n_ghost: ghosts.len(),
                _env: PhantomData,
            };
            check("VecSetBlockSize", ffi::VecSetBlockSize(vec, sizes[3]))?;
            check("VecSet", ffi::VecSet(vec, 0.0))?;
            Ok(v)
        }
    }

    /// Number of owned values.
    pub fn n_owned(&self) -> usize {
        self.n_owned
    }

    /// Adds `values` at PETSc dof indices `dofs` (any rank's); call
    /// [`GhostedVector::assemble`] afterwards.
    pub fn add(&mut self, dofs: &[usize], values: &[f64]) -> Result<(), PetscError> {
        if dofs.len() != values.len() {
            return Err(PetscError::Layout(format!(
                "{} indices for {} values",
                dofs.len(),
                values.len()
            )));
        }
        let idx = to_ints(dofs)?;
        let n = to_ints(&[dofs.len()])?[0];
        // SAFETY: lengths checked; PETSc copies.
        unsafe {
            check(
                "VecSetValues",
                ffi::VecSetValues(
                    self.vec,
                    n,
                    idx.as_ptr(),
                    values.as_ptr(),
                    ffi::InsertMode_ADD_VALUES,
                ),
            )
        }
    }

    /// Assembly of values added with [`GhostedVector::add`] (collective).
    pub fn assemble(&mut self) -> Result<(), PetscError> {
        // SAFETY: collective on the vector's communicator.
        unsafe {
            check("VecAssemblyBegin", ffi::VecAssemblyBegin(self.vec))?;
            check("VecAssemblyEnd", ffi::VecAssemblyEnd(self.vec))
        }
    }

    /// Copies the owners' values into the ghost copies (collective).
    pub fn update_ghosts(&mut self) -> Result<(), PetscError> {
        self.ghost_update(
            ffi::InsertMode_INSERT_VALUES,
            ffi::ScatterMode_SCATTER_FORWARD,
        )
    }

    /// Adds the ghost copies into their owners' values and leaves the
    /// ghosts as they were (collective): the reverse of a cell loop that
    /// wrote into [`GhostedVector::local_mut`].
    pub fn accumulate_ghosts(&mut self) -> Result<(), PetscError> {
        self.ghost_update(ffi::InsertMode_ADD_VALUES, ffi::ScatterMode_SCATTER_REVERSE)
    }

    fn ghost_update(
        &mut self,
        insert: ffi::InsertMode,
        mode: ffi::ScatterMode,
    ) -> Result<(), PetscError> {
        // SAFETY: collective; the vector is ghosted.
        unsafe {
            check(
                "VecGhostUpdateBegin",
                ffi::VecGhostUpdateBegin(self.vec, insert, mode),
            )?;
            check(
                "VecGhostUpdateEnd",
                ffi::VecGhostUpdateEnd(self.vec, insert, mode),
            )
        }
    }

    /// Runs `f` on the local form: owned values, then ghosts, in blocks of
    /// `dim` ([`DofLayout::local_block`] gives a node's block).
    pub fn with_local<R>(&self, f: impl FnOnce(&[f64]) -> R) -> Result<R, PetscError> {
        let mut local: ffi::Vec = std::ptr::null_mut();
        let mut ptr: *const f64 = std::ptr::null();
        // SAFETY: the local form has n_owned + n_ghost entries; it is
        // restored before returning.
        unsafe {
            check(
                "VecGhostGetLocalForm",
                ffi::VecGhostGetLocalForm(self.vec, &mut local),
            )?;
            check("VecGetArrayRead", ffi::VecGetArrayRead(local, &mut ptr))?;
            let out = f(std::slice::from_raw_parts(ptr, self.n_owned + self.n_ghost));
            check(
                "VecRestoreArrayRead",
                ffi::VecRestoreArrayRead(local, &mut ptr),
            )?;
            check(
                "VecGhostRestoreLocalForm",
                ffi::VecGhostRestoreLocalForm(self.vec, &mut local),
            )?;
            Ok(out)
        }
    }

    /// Runs `f` on the mutable local form (owned values, then ghosts).
    pub fn local_mut<R>(&mut self, f: impl FnOnce(&mut [f64]) -> R) -> Result<R, PetscError> {
        let mut local: ffi::Vec = std::ptr::null_mut();
        let mut ptr: *mut f64 = std::ptr::null_mut();
        // SAFETY: as in `with_local`.
        unsafe {
            check(
                "VecGhostGetLocalForm",
                ffi::VecGhostGetLocalForm(self.vec, &mut local),
            )?;
            check("VecGetArray", ffi::VecGetArray(local, &mut ptr))?;
            let out = f(std::slice::from_raw_parts_mut(
                ptr,
                self.n_owned + self.n_ghost,
            ));
            check("VecRestoreArray", ffi::VecRestoreArray(local, &mut ptr))?;
            check(
                "VecGhostRestoreLocalForm",
                ffi::VecGhostRestoreLocalForm(self.vec, &mut local),
            )?;
            Ok(out)
        }
    }

    /// The whole vector on every rank, in PETSc order (collective; for
    /// tests and rank-0 output: use [`DofLayout::to_natural`] next).
    pub fn gather_all(&self) -> Result<Vec<f64>, PetscError> {
        let mut ctx: ffi::VecScatter = std::ptr::null_mut();
        let mut all: ffi::Vec = std::ptr::null_mut();
        // SAFETY: standard scatter-to-all; both objects destroyed here.
        unsafe {
            check(
                "VecScatterCreateToAll",
                ffi::VecScatterCreateToAll(self.vec, &mut ctx, &mut all),
            )?;
            let r = (|| {
                let (i, f) = (
                    ffi::InsertMode_INSERT_VALUES,
                    ffi::ScatterMode_SCATTER_FORWARD,
                );
                check(
                    "VecScatterBegin",
                    ffi::VecScatterBegin(ctx, self.vec, all, i, f),
                )?;
                check(
                    "VecScatterEnd",
                    ffi::VecScatterEnd(ctx, self.vec, all, i, f),
                )?;
                let mut n: ffi::PetscInt = 0;
                check("VecGetSize", ffi::VecGetSize(all, &mut n))?;
                let mut ptr: *const f64 = std::ptr::null();
                check("VecGetArrayRead", ffi::VecGetArrayRead(all, &mut ptr))?;
                let out = std::slice::from_raw_parts(ptr, n as usize).to_vec();
                check(
                    "VecRestoreArrayRead",
                    ffi::VecRestoreArrayRead(all, &mut ptr),
                )?;
                Ok(out)
            })();
            ffi::VecScatterDestroy(&mut ctx);
            ffi::VecDestroy(&mut all);
            r
        }
    }

    /// 2-norm (collective).
    pub fn norm(&self) -> Result<f64, PetscError> {
        let mut n = 0.0;
        // SAFETY: valid vector.
        unsafe {
            check(
                "VecNorm",
                ffi::VecNorm(self.vec, ffi::NormType_NORM_2, &mut n),
            )?
        };
        Ok(n)
    }

    /// `self = a x + self` (collective).
    pub fn axpy(&mut self, a: f64, x: &GhostedVector<'e>) -> Result<(), PetscError> {
        // SAFETY: compatible vectors.
        unsafe { check("VecAXPY", ffi::VecAXPY(self.vec, a, x.vec)) }
    }
}

impl Drop for GhostedVector<'_> {
    fn drop(&mut self) {
        // SAFETY: created by VecCreateGhost, destroyed once.
        unsafe {
            ffi::VecDestroy(&mut self.vec);
        }
    }
}
