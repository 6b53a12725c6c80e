//! The distributed sparse matrix: PETSc `MATAIJ` (`MatMPIAIJ` on several
//! ranks, `MatSeqAIJ` on one), block size = dofs per node, preallocated
//! exactly from a [`Preallocation`] and locked to that pattern (a value
//! outside it is an error, never a silent reallocation). Values are added
//! (`ADD_VALUES`) by every rank for its own cells, then assembled: rows
//! owned by another rank travel there during the assembly.

use crate::comm::Comm;
use crate::env::check;
use crate::error::PetscError;
use crate::ffi;
use crate::layout::{DofLayout, Preallocation};
use crate::vector::GhostedVector;
use std::marker::PhantomData;

/// A distributed square matrix on the dofs of a [`DofLayout`].
pub struct DistMatrix<'e> {
    pub(crate) mat: ffi::Mat,
    _env: PhantomData<&'e ()>,
}

fn to_int(v: usize) -> Result<ffi::PetscInt, PetscError> {
    ffi::PetscInt::try_from(v).map_err(|_| {
        PetscError::Layout(format!(
            "index {v} does not fit PETSc's {}-bit integers",
            8 * std::mem::size_of::<ffi::PetscInt>()
        ))
    })
}

/// `usize` indices -> PETSc integers.
pub(crate) fn to_ints(v: &[usize]) -> Result<Vec<ffi::PetscInt>, PetscError> {
    v.iter().map(|&i| to_int(i)).collect()
}

impl<'e> DistMatrix<'e> {
    /// Creates the matrix of `layout` with the exact pattern `prealloc`.
    pub fn new(
        comm: &Comm<'e>,
        layout: &DofLayout,
        prealloc: &Preallocation,
    ) -> Result<DistMatrix<'e>, PetscError> {
        let (d, o) = prealloc.nnz();
        let n_local = layout.owned_dofs().len();
        DistMatrix::from_nnz(comm, n_local, layout.n_global_dofs(), layout.dim, &d, &o)
    }

    /// Creates a matrix of `n_local` owned rows (`n_global` in all) with
    /// block size `block` and the exact per-row counts of entries in the
    /// owned columns (`d`) and the others (`o`).
    pub fn from_nnz(
        comm: &Comm<'e>,
        n_local: usize,
        n_global: usize,
        block: usize,
        d: &[usize],
        o: &[usize],
    ) -> Result<DistMatrix<'e>, PetscError> {
        if d.len() != n_local || o.len() != n_local {
            return Err(PetscError::Layout(format!(
                "{} and {} row counts for {n_local} rows",
                d.len(),
                o.len()
            )));
        }
        let (d, o) = (to_ints(d)?, to_ints(o)?);
        let n_local = to_int(n_local)?;
        let n_global = to_int(n_global)?;
        let mut mat: ffi::Mat = std::ptr::null_mut();
        // SAFETY: PETSc is initialized (the Comm borrows the Environment);
        // the arrays outlive the calls, which copy them.
        unsafe {
            check("MatCreate", ffi::MatCreate(comm.raw(), &mut mat))?;
            let m = DistMatrix {
                mat,
                _env: PhantomData,
            };
            check(
                "MatSetSizes",
                ffi::MatSetSizes(mat, n_local, n_local, n_global, n_global),
            )?;
            check(
                "MatSetType",
                ffi::MatSetType(mat, ffi::MATAIJ.as_ptr().cast()),
            )?;
            check("MatSetBlockSize", ffi::MatSetBlockSize(mat, to_int(block)?))?;
            check(
                "MatSeqAIJSetPreallocation",
                ffi::MatSeqAIJSetPreallocation(mat, 0, d.as_ptr()),
            )?;
            check(
                "MatMPIAIJSetPreallocation",
                ffi::MatMPIAIJSetPreallocation(mat, 0, d.as_ptr(), 0, o.as_ptr()),
            )?;
            check(
                "MatSetOption",
                ffi::MatSetOption(
                    mat,
                    ffi::MatOption_MAT_NEW_NONZERO_ALLOCATION_ERR,
                    ffi::PetscBool_PETSC_TRUE,
                ),
            )?;
            Ok(m)
        }
    }

    /// Adds a dense block `values` (row-major, `rows.len() x cols.len()`) at
    /// the PETSc dof indices `rows` x `cols` (any rank's rows).
    pub fn add(
        &mut self,
        rows: &[usize],
        cols: &[usize],
        values: &[f64],
    ) -> Result<(), PetscError> {
        if values.len() != rows.len() * cols.len() {
            return Err(PetscError::Layout(format!(
                "a {} x {} block with {} values",
                rows.len(),
                cols.len(),
                values.len()
            )));
        }
        let (r, c) = (to_ints(rows)?, to_ints(cols)?);
        // SAFETY: sizes checked above; PETSc copies the values.
        unsafe {
            check(
                "MatSetValues",
                ffi::MatSetValues(
                    self.mat,
                    to_int(rows.len())?,
                    r.as_ptr(),
                    to_int(cols.len())?,
                    c.as_ptr(),
                    values.as_ptr(),
                    ffi::InsertMode_ADD_VALUES,
                ),
            )
        }
    }

    /// Final assembly (collective): sends off-rank rows to their owners.
    /// After it the pattern is locked: adding a value at a new location is
    /// an error (a grown contact pattern needs a new matrix).
    pub fn assemble(&mut self) -> Result<(), PetscError> {
        // SAFETY: collective on the matrix's communicator.
        unsafe {
            check(
                "MatAssemblyBegin",
                ffi::MatAssemblyBegin(self.mat, ffi::MatAssemblyType_MAT_FINAL_ASSEMBLY),
            )?;
            check(
                "MatAssemblyEnd",
                ffi::MatAssemblyEnd(self.mat, ffi::MatAssemblyType_MAT_FINAL_ASSEMBLY),
            )?;
            check(
                "MatSetOption",
                ffi::MatSetOption(
                    self.mat,
                    ffi::MatOption_MAT_NEW_NONZERO_LOCATION_ERR,
                    ffi::PetscBool_PETSC_TRUE,
                ),
            )
        }
    }

    /// Tells PETSc whether the (assembled) matrix is symmetric, for
    /// solvers that exploit it (CG, Cholesky, GAMG smoothers).
    pub fn set_symmetric(&mut self, symmetric: bool) -> Result<(), PetscError> {
        let flag = if symmetric {
            ffi::PetscBool_PETSC_TRUE
        } else {
            ffi::PetscBool_PETSC_FALSE
        };
        // SAFETY: the matrix is valid.
        unsafe {
            check(
                "MatSetOption",
                ffi::MatSetOption(self.mat, ffi::MatOption_MAT_SYMMETRIC, flag),
            )
        }
    }

    /// Zeroes all values, keeping the pattern (a new Newton iteration).
    pub fn zero(&mut self) -> Result<(), PetscError> {
        // SAFETY: the matrix is valid.
        unsafe { check("MatZeroEntries", ffi::MatZeroEntries(self.mat)) }
    }

    /// Prescribed dofs (collective; each rank passes the rows it owns):
    /// zeroes their rows and columns with `diag` on the diagonal, and sets
    /// `b = diag * x` there and `b -= A x` elsewhere, so the solution takes
    /// the values of `x` at these dofs.
    pub fn zero_rows_columns(
        &mut self,
        rows: &[usize],
        diag: f64,
        x: &GhostedVector<'e>,
        b: &mut GhostedVector<'e>,
    ) -> Result<(), PetscError> {
        let r = to_ints(rows)?;
        // SAFETY: the matrix is assembled; vectors are compatible.
        unsafe {
            check(
                "MatZeroRowsColumns",
                ffi::MatZeroRowsColumns(
                    self.mat,
                    to_int(rows.len())?,
                    r.as_ptr(),
                    diag,
                    x.vec,
                    b.vec,
                ),
            )
        }
    }

    /// `y = A x` (collective).
    pub fn mult(&self, x: &GhostedVector<'e>, y: &mut GhostedVector<'e>) -> Result<(), PetscError> {
        // SAFETY: assembled matrix, compatible vectors.
        unsafe { check("MatMult", ffi::MatMult(self.mat, x.vec, y.vec)) }
    }

    /// Mallocs done during the assembly on this rank (0 when the
    /// preallocation was exact) and the stored non-zeros.
    pub fn allocation(&self) -> Result<(usize, usize), PetscError> {
        let mut info = ffi::MatInfo::default();
        // SAFETY: `info` is a valid out struct.
        unsafe {
            check(
                "MatGetInfo",
                ffi::MatGetInfo(self.mat, ffi::MatInfoType_MAT_LOCAL, &mut info),
            )?;
        }
        Ok((info.mallocs as usize, info.nz_used as usize))
    }
}

impl Drop for DistMatrix<'_> {
    fn drop(&mut self) {
        // SAFETY: the matrix was created by MatCreate and is destroyed once.
        unsafe {
            ffi::MatDestroy(&mut self.mat);
        }
    }
}
