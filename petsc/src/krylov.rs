//! The linear solve: a PETSc `KSP` on a [`DistMatrix`], configured by a
//! [`SolverChoice`] and then by the options database (so `-ksp_type`,
//! `-pc_type`, `-ksp_rtol`, ... on the command line win, as users of PETSc
//! codes expect). Each solver has an options prefix, so several solvers in
//! one run are configured independently.

use crate::comm::Comm;
use crate::env::check;
use crate::error::PetscError;
use crate::ffi;
use crate::layout::DofLayout;
use crate::matrix::DistMatrix;
use crate::nullspace::rigid_body_modes;
use crate::vector::GhostedVector;
use std::ffi::{CStr, CString};
use std::marker::PhantomData;

/// A preset of KSP + preconditioner.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SolverChoice {
    /// Direct: `-ksp_type preonly -pc_type lu -pc_factor_mat_solver_type mumps`.
    MumpsLu,
    /// `-ksp_type cg -pc_type gamg` to relative tolerance `rtol` (give the
    /// matrix its near-null space: [`near_null_space`]).
    CgGamg {
        /// Relative residual tolerance.
        rtol: f64,
    },
    /// `-ksp_type cg -pc_type hypre -pc_hypre_type boomeramg` (only when the
    /// PETSc build has hypre: [`crate::Environment::has_package`]).
    CgHypre {
        /// Relative residual tolerance.
        rtol: f64,
    },
    /// Nothing preset: only the options database decides.
    FromOptions,
}

/// What one solve did.
#[derive(Debug, Clone, PartialEq)]
pub struct SolveReport {
    /// Krylov iterations (1 for a direct solve).
    pub iterations: usize,
    /// Final (preconditioned, for CG) residual norm as PETSc measures it.
    pub residual: f64,
    /// PETSc's converged reason, e.g. `CONVERGED_RTOL`.
    pub reason: String,
    /// `-ksp_type` and `-pc_type` actually used.
    pub ksp_type: String,
    /// The preconditioner type.
    pub pc_type: String,
}

/// A configured Krylov solver.
pub struct Krylov<'e> {
    ksp: ffi::KSP,
    _env: PhantomData<&'e ()>,
}

fn cstr(s: &str) -> Result<CString, PetscError> {
    CString::new(s).map_err(|_| PetscError::Init(format!("`{s}` contains a NUL byte")))
}

/// SAFETY: `p` is null or a NUL-terminated string owned by PETSc.
unsafe fn text(p: *const std::os::raw::c_char) -> String {
    if p.is_null() {
        String::new()
    } else {
        CStr::from_ptr(p).to_string_lossy().into_owned()
    }
}

impl<'e> Krylov<'e> {
    /// A solver for `a` on `comm` with options prefix `prefix` (`""` for
    /// none: then plain `-ksp_type ..` options apply).
    pub fn new(
        comm: &Comm<'e>,
        a: &DistMatrix<'e>,
        choice: SolverChoice,
        prefix: &str,
    ) -> Result<Krylov<'e>, PetscError> {
        let mut ksp: ffi::KSP = std::ptr::null_mut();
        // SAFETY: PETSc is initialized; strings outlive the calls.
        unsafe {
            check("KSPCreate", ffi::KSPCreate(comm.raw(), &mut ksp))?;
            let k = Krylov {
                ksp,
                _env: PhantomData,
            };
            if !prefix.is_empty() {
                let p = cstr(prefix)?;
                check(
                    "KSPSetOptionsPrefix",
                    ffi::KSPSetOptionsPrefix(ksp, p.as_ptr()),
                )?;
            }
            check("KSPSetOperators", ffi::KSPSetOperators(ksp, a.mat, a.mat))?;
            let mut pc: ffi::PC = std::ptr::null_mut();
            check("KSPGetPC", ffi::KSPGetPC(ksp, &mut pc))?;
            let tol = |rtol: f64| {
                check(
                    "KSPSetTolerances",
                    ffi::KSPSetTolerances(ksp, rtol, 1e-300, ffi::PETSC_DEFAULT as f64, 10_000),
                )
            };
            match choice {
                SolverChoice::MumpsLu => {
                    check(
                        "KSPSetType",
                        ffi::KSPSetType(ksp, ffi::KSPPREONLY.as_ptr().cast()),
                    )?;
                    check("PCSetType", ffi::PCSetType(pc, ffi::PCLU.as_ptr().cast()))?;
                    check(
                        "PCFactorSetMatSolverType",
                        ffi::PCFactorSetMatSolverType(pc, ffi::MATSOLVERMUMPS.as_ptr().cast()),
                    )?;
                }
                SolverChoice::CgGamg { rtol } => {
                    check(
                        "KSPSetType",
                        ffi::KSPSetType(ksp, ffi::KSPCG.as_ptr().cast()),
                    )?;
                    check("PCSetType", ffi::PCSetType(pc, ffi::PCGAMG.as_ptr().cast()))?;
                    tol(rtol)?;
                }
                SolverChoice::CgHypre { rtol } => {
                    check(
                        "KSPSetType",
                        ffi::KSPSetType(ksp, ffi::KSPCG.as_ptr().cast()),
                    )?;
                    check(
                        "PCSetType",
                        ffi::PCSetType(pc, ffi::PCHYPRE.as_ptr().cast()),
                    )?;
                    let boomer = cstr("boomeramg")?;
                    check("PCHYPRESetType", ffi::PCHYPRESetType(pc, boomer.as_ptr()))?;
                    tol(rtol)?;
                }
                SolverChoice::FromOptions => {}
            }
            check("KSPSetFromOptions", ffi::KSPSetFromOptions(ksp))?;
            Ok(k)
        }
    }

    /// Solves `a x = b` (collective). A diverged solve is
    /// [`PetscError::Diverged`] on every rank (the reason is global).
    pub fn solve(
        &mut self,
        b: &GhostedVector<'e>,
        x: &mut GhostedVector<'e>,
    ) -> Result<SolveReport, PetscError> {
        self.solve_vecs(b.vec, x.vec)
    }

    /// Builds the preconditioner (the factorization for a direct solver)
    /// of the current matrix values (collective); a failed set-up (a zero
    /// pivot, a singular matrix) is an error on every rank.
    pub fn set_up(&mut self) -> Result<(), PetscError> {
        // SAFETY: configured solver.
        unsafe {
            let mut pc: ffi::PC = std::ptr::null_mut();
            check("KSPGetPC", ffi::KSPGetPC(self.ksp, &mut pc))?;
            // KSPSetUp once set up does nothing; PCSetUp redoes the
            // factorization when the matrix values changed (the symbolic
            // part is kept while the pattern is the same)
            check("KSPSetUp", ffi::KSPSetUp(self.ksp))?;
            check("PCSetUp", ffi::PCSetUp(pc))?;
            let mut failed: ffi::PCFailedReason = 0;
            check("PCGetFailedReason", ffi::PCGetFailedReason(pc, &mut failed))?;
            if failed != ffi::PCFailedReason_PC_NOERROR {
                let what = match failed {
                    ffi::PCFailedReason_PC_FACTOR_STRUCT_ZEROPIVOT
                    | ffi::PCFailedReason_PC_FACTOR_NUMERIC_ZEROPIVOT => "a zero pivot",
                    ffi::PCFailedReason_PC_FACTOR_OUTMEMORY => "out of memory",
                    _ => "a failure",
                };
                return Err(PetscError::Singular(format!(
                    "the preconditioner set-up ({}) met {what} (PCFailedReason {failed}): the \
                     stiffness matrix is singular or the preconditioner does not suit it",
                    self.describe()?
                )));
            }
        }
        Ok(())
    }

    /// With a MUMPS factorization: switches on its null-pivot detection
    /// (`ICNTL(24) = 1`) and returns true; otherwise false.
    pub fn detect_null_pivots(&mut self) -> Result<bool, PetscError> {
        if !self.describe()?.ends_with("(mumps)") {
            return Ok(false);
        }
        // SAFETY: configured LU/Cholesky PC with MUMPS.
        unsafe {
            let mut pc: ffi::PC = std::ptr::null_mut();
            check("KSPGetPC", ffi::KSPGetPC(self.ksp, &mut pc))?;
            check(
                "PCFactorSetUpMatSolverType",
                ffi::PCFactorSetUpMatSolverType(pc),
            )?;
            let mut f: ffi::Mat = std::ptr::null_mut();
            check("PCFactorGetMatrix", ffi::PCFactorGetMatrix(pc, &mut f))?;
            check("MatMumpsSetIcntl", ffi::MatMumpsSetIcntl(f, 24, 1))?;
        }
        Ok(true)
    }

    /// Changes the Krylov method (`gmres`, ...), keeping the
    /// preconditioner.
    pub fn set_type(&mut self, ksp_type: &str) -> Result<(), PetscError> {
        let t = cstr(ksp_type)?;
        // SAFETY: configured solver; PETSc copies the name.
        unsafe { check("KSPSetType", ffi::KSPSetType(self.ksp, t.as_ptr())) }
    }

    /// Null pivots MUMPS met in the last factorization (`INFOG(28)`; only
    /// after [`Krylov::detect_null_pivots`] returned true).
    pub fn mumps_null_pivots(&self) -> Result<usize, PetscError> {
        let mut n: ffi::PetscInt = 0;
        // SAFETY: set-up MUMPS factorization.
        unsafe {
            let mut pc: ffi::PC = std::ptr::null_mut();
            check("KSPGetPC", ffi::KSPGetPC(self.ksp, &mut pc))?;
            let mut f: ffi::Mat = std::ptr::null_mut();
            check("PCFactorGetMatrix", ffi::PCFactorGetMatrix(pc, &mut f))?;
            check("MatMumpsGetInfog", ffi::MatMumpsGetInfog(f, 28, &mut n))?;
        }
        Ok(n.max(0) as usize)
    }

    /// `ksp <type>, pc <type>` (`(<package>)` for a factorization done by
    /// an external package such as MUMPS), as configured by the preset and
    /// the options database.
    pub fn describe(&self) -> Result<String, PetscError> {
        // SAFETY: configured solver; strings owned by PETSc.
        unsafe {
            let mut kt: ffi::KSPType = std::ptr::null();
            check("KSPGetType", ffi::KSPGetType(self.ksp, &mut kt))?;
            let mut pc: ffi::PC = std::ptr::null_mut();
            check("KSPGetPC", ffi::KSPGetPC(self.ksp, &mut pc))?;
            let mut pt: ffi::PCType = std::ptr::null();
            check("PCGetType", ffi::PCGetType(pc, &mut pt))?;
            let (kt, pt) = (text(kt), text(pt));
            let mut out = format!("petsc: ksp {kt}, pc {pt}");
            if pt == "lu" || pt == "cholesky" {
                let mut st: ffi::MatSolverType = std::ptr::null();
                check(
                    "PCFactorGetMatSolverType",
                    ffi::PCFactorGetMatSolverType(pc, &mut st),
                )?;
                let st = text(st);
                if !st.is_empty() {
                    out.push_str(&format!(" ({st})"));
                }
            }
            Ok(out)
        }
    }

    /// [`Krylov::solve`] on raw PETSc vectors of the matrix's layout.
    pub(crate) fn solve_vecs(
        &mut self,
        b: ffi::Vec,
        x: ffi::Vec,
    ) -> Result<SolveReport, PetscError> {
        // SAFETY: configured solver, compatible vectors.
        unsafe {
            check("KSPSolve", ffi::KSPSolve(self.ksp, b, x))?;
            let mut reason: ffi::KSPConvergedReason = 0;
            check(
                "KSPGetConvergedReason",
                ffi::KSPGetConvergedReason(self.ksp, &mut reason),
            )?;
            let mut its: ffi::PetscInt = 0;
            check(
                "KSPGetIterationNumber",
                ffi::KSPGetIterationNumber(self.ksp, &mut its),
            )?;
            let mut res = 0.0;
            check(
                "KSPGetResidualNorm",
                ffi::KSPGetResidualNorm(self.ksp, &mut res),
            )?;
            let mut name: *const std::os::raw::c_char = std::ptr::null();
            check(
                "KSPGetConvergedReasonString",
                ffi::KSPGetConvergedReasonString(self.ksp, &mut name),
            )?;
            let reason_name = text(name);
            if reason < 0 {
                return Err(PetscError::Diverged {
                    reason,
                    reason_name,
                    iterations: its as usize,
                });
            }
            let mut kt: ffi::KSPType = std::ptr::null();
            check("KSPGetType", ffi::KSPGetType(self.ksp, &mut kt))?;
            let mut pc: ffi::PC = std::ptr::null_mut();
            check("KSPGetPC", ffi::KSPGetPC(self.ksp, &mut pc))?;
            let mut pt: ffi::PCType = std::ptr::null();
            check("PCGetType", ffi::PCGetType(pc, &mut pt))?;
            Ok(SolveReport {
                iterations: its as usize,
                residual: res,
                reason: reason_name,
                ksp_type: text(kt),
                pc_type: text(pt),
            })
        }
    }
}

impl Drop for Krylov<'_> {
    fn drop(&mut self) {
        // SAFETY: created by KSPCreate, destroyed once.
        unsafe {
            ffi::KSPDestroy(&mut self.ksp);
        }
    }
}

/// Gives `a` the rigid-body modes of the nodes (`coords`: `dim` values per
/// natural node, the whole mesh on every rank) as its near-null space, for
/// GAMG (collective). The modes are orthonormalised across the ranks (two
/// passes of classical Gram-Schmidt) as `MatNullSpaceCreate` requires;
/// rotations are about the mesh centroid.
pub fn near_null_space<'e>(
    comm: &Comm<'e>,
    layout: &DofLayout,
    a: &mut DistMatrix<'e>,
    coords: &[f64],
) -> Result<(), PetscError> {
    let dim = layout.dim;
    if coords.len() != dim * layout.n_nodes() {
        return Err(PetscError::Layout(format!(
            "{} coordinates for {} nodes in {dim}D",
            coords.len(),
            layout.n_nodes()
        )));
    }
    let n = layout.n_nodes().max(1) as f64;
    let centre: Vec<f64> = (0..dim)
        .map(|c| coords.iter().skip(c).step_by(dim).sum::<f64>() / n)
        .collect();
    let owned: Vec<f64> = layout
        .owned_nodes
        .iter()
        .flat_map(|&nd| coords[dim * nd..dim * nd + dim].iter().copied())
        .collect();
    let modes = rigid_body_modes(&owned, dim, &centre);
    set_near_null_space(comm, a, &modes)
}

/// Gives `a` the near-null space spanned by `modes` (each: the values of
/// this rank's owned rows), orthonormalised across the ranks (collective).
pub fn set_near_null_space<'e>(
    comm: &Comm<'e>,
    a: &mut DistMatrix<'e>,
    modes: &[Vec<f64>],
) -> Result<(), PetscError> {
    let mut vecs: Vec<ffi::Vec> = Vec::with_capacity(modes.len());
    // SAFETY: vectors are created from the matrix, filled through their
    // owned arrays, and destroyed here (the null space keeps references).
    unsafe {
        let r = (|| {
            for m in modes {
                let mut v: ffi::Vec = std::ptr::null_mut();
                check(
                    "MatCreateVecs",
                    ffi::MatCreateVecs(a.mat, &mut v, std::ptr::null_mut()),
                )?;
                vecs.push(v);
                let mut ptr: *mut f64 = std::ptr::null_mut();
                check("VecGetArray", ffi::VecGetArray(v, &mut ptr))?;
                std::slice::from_raw_parts_mut(ptr, m.len()).copy_from_slice(m);
                check("VecRestoreArray", ffi::VecRestoreArray(v, &mut ptr))?;
            }
            for _pass in 0..2 {
                for i in 0..vecs.len() {
                    for j in 0..i {
                        let mut d = 0.0;
                        check("VecDot", ffi::VecDot(vecs[i], vecs[j], &mut d))?;
                        check("VecAXPY", ffi::VecAXPY(vecs[i], -d, vecs[j]))?;
                    }
                    check(
                        "VecNormalize",
                        ffi::VecNormalize(vecs[i], std::ptr::null_mut()),
                    )?;
                }
            }
            let mut nsp: ffi::MatNullSpace = std::ptr::null_mut();
            check(
                "MatNullSpaceCreate",
                ffi::MatNullSpaceCreate(
                    comm.raw(),
                    ffi::PetscBool_PETSC_FALSE,
                    vecs.len() as ffi::PetscInt,
                    vecs.as_ptr(),
                    &mut nsp,
                ),
            )?;
            let set = check("MatSetNearNullSpace", ffi::MatSetNearNullSpace(a.mat, nsp));
            ffi::MatNullSpaceDestroy(&mut nsp);
            set
        })();
        for v in &mut vecs {
            ffi::VecDestroy(v);
        }
        r
    }
}
