//! Mesh partitioning: cells -> ranks with METIS (`METIS_PartMeshDual`,
//! the dual graph of cells sharing `n_common` nodes: a face in 3D, an edge
//! in 2D). Debian's PETSc is built without METIS (it has PT-Scotch), so the
//! partition calls Debian's libmetis directly. Every rank computes the same
//! partition of the replicated mesh (METIS with a fixed seed is
//! deterministic), so no communication is needed and the result depends only
//! on the mesh and the part count.

use crate::error::PetscError;
use crate::ffi;

/// The part (rank) of every cell, `n_parts` parts, deterministic.
pub fn partition_cells<C: AsRef<[usize]>>(
    cells: &[C],
    n_nodes: usize,
    n_parts: usize,
    n_common: usize,
) -> Result<Vec<usize>, PetscError> {
    if n_parts == 0 {
        return Err(PetscError::Partition("zero parts".into()));
    }
    if n_parts == 1 {
        return Ok(vec![0; cells.len()]);
    }
    if cells.len() < n_parts {
        return Err(PetscError::Partition(format!(
            "{} cells cannot be shared by {n_parts} ranks",
            cells.len()
        )));
    }
    let idx = |v: usize| {
        ffi::idx_t::try_from(v)
            .map_err(|_| PetscError::Partition(format!("{v} does not fit METIS's integers")))
    };
    let mut eptr = Vec::with_capacity(cells.len() + 1);
    let mut eind = Vec::new();
    eptr.push(0);
    for c in cells {
        for &n in c.as_ref() {
            if n >= n_nodes {
                return Err(PetscError::Partition(format!(
                    "a cell names node {n} of {n_nodes}"
                )));
            }
            eind.push(idx(n)?);
        }
        eptr.push(idx(eind.len())?);
    }
    let mut ne = idx(cells.len())?;
    let mut nn = idx(n_nodes)?;
    let mut ncommon = idx(n_common)?;
    let mut nparts = idx(n_parts)?;
    let mut options = [0 as ffi::idx_t; ffi::METIS_NOPTIONS as usize];
    let mut objval: ffi::idx_t = 0;
    let mut epart = vec![0 as ffi::idx_t; cells.len()];
    let mut npart = vec![0 as ffi::idx_t; n_nodes];
    // SAFETY: arrays have the sizes METIS expects (eptr ne+1, eind
    // eptr[ne], options METIS_NOPTIONS, epart ne, npart nn).
    let status = unsafe {
        ffi::METIS_SetDefaultOptions(options.as_mut_ptr());
        options[ffi::moptions_et_METIS_OPTION_NUMBERING as usize] = 0;
        options[ffi::moptions_et_METIS_OPTION_SEED as usize] = 1;
        ffi::METIS_PartMeshDual(
            &mut ne,
            &mut nn,
            eptr.as_mut_ptr(),
            eind.as_mut_ptr(),
            std::ptr::null_mut(),
            std::ptr::null_mut(),
            &mut ncommon,
            &mut nparts,
            std::ptr::null_mut(),
            options.as_mut_ptr(),
            &mut objval,
            epart.as_mut_ptr(),
            npart.as_mut_ptr(),
        )
    };
    if status != ffi::rstatus_et_METIS_OK {
        return Err(PetscError::Partition(format!("METIS returned {status}")));
    }
    Ok(epart.into_iter().map(|p| p as usize).collect())
}
