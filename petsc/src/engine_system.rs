//! The engine's tangent solved by PETSc over MPI: an implementation of
//! [`ctc_engine::solve::linalg::LinearSystem`], what `ctc run --solver petsc`
//! plugs into the Newton loop.
//!
//! ```text
//! distributed assembly (models ctc_engine::solve::share accepts):
//!   rank r: its METIS cells + the contact blocks of its nodes
//!     ──partial CSC──▶ MatAIJ, ADD_VALUES (the stash sends other ranks' rows;
//!                      exact preallocation from the cells around owned nodes)
//!   f_int of its cells ──sum over ranks (reduce + broadcast)──▶ the residual
//! replicated assembly (the other models):
//!   every rank: the whole free-free tangent ──its own rows, INSERT_VALUES──▶ MatAIJ
//! then:
//!   KSP (preset: MUMPS LU; `-ksp_type`/`-pc_type`.. options win)
//!   solution (PETSc order) ──scatter to all──▶ the same free vector on every rank
//! ```
//!
//! Because every rank holds the same residual (summed over the ranks) and
//! receives the same solution vector, every decision of the Newton loop
//! (convergence, line search, contact status, cutback, failure) is taken
//! identically on all ranks without further agreement; a failed
//! factorization or a diverged Krylov solve is collective in PETSc, so it
//! is an error on every rank at once, and a failed element is agreed
//! (`any_rank`).
//!
//! Distributed: the element matrices and element loop with the
//! integration-point updates of every material law (each rank its cells:
//! memory and time fall with the rank count; the committed points are
//! exchanged at each commit), the contact tangent (the owner of a node
//! adds its rows: a slave node's block against a tool, the rows of slave
//! and master nodes of a deformable pair), the matrix rows, the
//! factorization / preconditioner and the Krylov solve. Replicated: the
//! mesh and model, the contact evaluation (every rank every slave node
//! against the replicated rigid tools and master surfaces), and the
//! vectors of the Newton loop (the solution is gathered whole on every
//! rank: O(dofs) per rank).
//!
//! Row ownership: a node belongs to the lowest rank among the METIS parts
//! of its cells ([`DofLayout`]); PETSc numbers the nodes rank by rank, and
//! every node has its `D` rows (block size `D`, so AMG aggregates nodes as
//! it does for elasticity). The rows of prescribed and inactive dofs are
//! identity rows (diagonal = the mean free diagonal of the rank, right-hand
//! side 0), decoupled from the free ones, as FEniCSx does for Dirichlet
//! rows; AMG gets the rigid-body modes of the nodes as near-null space.
//!
//! With MUMPS, null-pivot detection is on (`ICNTL(24) = 1`): a singular
//! tangent (a rigid-body motion nothing holds) is an error naming the
//! number of null pivots, as the serial solver's zero-pivot test is,
//! instead of a solution with an arbitrary rigid motion.

use crate::comm::Comm;
use crate::env::{check, Environment};
use crate::error::PetscError;
use crate::ffi;
use crate::krylov::{set_near_null_space, Krylov, SolverChoice};
use crate::layout::{DofLayout, Preallocation};
use crate::matrix::{to_ints, DistMatrix};
use crate::nullspace::rigid_body_modes;
use crate::partition::partition_cells;
use ctc_engine::model::Model;
use ctc_engine::solve::dofs::DofMap;
use ctc_engine::solve::linalg::{
    peak_memory_bytes, DistributedStats, FactorStats, LinearError, LinearSystem, RankStats,
    SparsePattern,
};
use ctc_engine::solve::memory::process_cpu_seconds;
use ctc_engine::solve::share::{replicated_reason, AssemblyShare};
use ctc_engine::solve::Timings;
use std::sync::Arc;
use std::time::Instant;

/// Marks an identity row's entry in [`OwnedRows::slots`].
const DIAGONAL: usize = usize::MAX;

/// The rows of the tangent owned by this rank, and where their values are
/// in the engine's CSC value array.
struct OwnedRows {
    /// Start of each owned row in `cols` / `slots` (`rows + 1` entries).
    ptr: Vec<usize>,
    /// PETSc column index of each entry.
    cols: Vec<ffi::PetscInt>,
    /// Index into the CSC values of each entry ([`DIAGONAL`]: the one entry
    /// of an identity row).
    slots: Vec<usize>,
    /// Row values, refilled at each factorization.
    values: Vec<f64>,
}

/// PETSc objects of one sparsity pattern.
struct Objects<'e> {
    /// The distributed matrix.
    mat: DistMatrix<'e>,
    /// The configured solver.
    ksp: Krylov<'e>,
    /// Right-hand side and solution (PETSc layout of the matrix).
    b: ffi::Vec,
    x: ffi::Vec,
    /// Scatter of `x` to every rank, and its target.
    to_all: ffi::VecScatter,
    all: ffi::Vec,
}

impl Drop for Objects<'_> {
    fn drop(&mut self) {
        // SAFETY: created once in `PetscSystem::build`, destroyed once here
        // (the matrix and solver drop after, through their own wrappers).
        unsafe {
            ffi::VecScatterDestroy(&mut self.to_all);
            ffi::VecDestroy(&mut self.all);
            ffi::VecDestroy(&mut self.b);
            ffi::VecDestroy(&mut self.x);
        }
    }
}

/// The tangent of a model solved by PETSc on all the ranks of `comm`.
pub struct PetscSystem<'e> {
    comm: Comm<'e>,
    choice: SolverChoice,
    /// Options prefix of the KSP (`""`: plain `-ksp_type ..`).
    prefix: String,
    /// Dofs per node (the block size).
    dim: usize,
    /// PETSc index of each free dof (engine numbering).
    petsc_of: Vec<usize>,
    /// First PETSc row of each rank, and the total at the end.
    offsets: Vec<usize>,
    /// Engine free dof of each owned row (`None`: an identity row).
    owned: Vec<Option<usize>>,
    /// Rigid-body modes on the owned rows.
    modes: Vec<Vec<f64>>,
    /// The MUMPS factor (to read its null-pivot count), when MUMPS is used.
    mumps: bool,
    /// Whether the next matrices are symmetric.
    symmetric: bool,
    rows: Option<OwnedRows>,
    objects: Option<Objects<'e>>,
    factorized: bool,
    stats: DistributedStats,
    /// This rank's partition and halo (its entry of `per_rank`, without
    /// the times).
    share: RankStats,
    /// Distributed assembly (`ctc_engine::solve::share`): this rank's
    /// cells and nodes, the couplings of its rows from the cells around its
    /// nodes, and the exact preallocation `(d_nnz, o_nnz)` of the current
    /// pattern (those couplings and the contact couplings of the rank's
    /// partial pattern, [`PetscSystem::preallocate`]); `None`: replicated
    /// assembly.
    assembly: Option<Distributed>,
    /// Column indices of one CSC column (scratch of the insertion).
    column: Vec<ffi::PetscInt>,
    /// This rank's METIS cells, increasing (its piece of the output).
    cells: Vec<usize>,
}

/// A rank's part of a distributed assembly.
struct Distributed {
    /// Its cells and nodes.
    share: Arc<AssemblyShare>,
    /// The couplings of its rows from the cells around its nodes.
    cells: Preallocation,
    /// `(d_nnz, o_nnz)` of its rows for the current pattern.
    d_nnz: Vec<usize>,
    o_nnz: Vec<usize>,
}

/// Fields of a [`RankStats`] exchanged by [`PetscSystem::distributed`].
const RANK_FIELDS: usize = 21;

impl<'e> PetscSystem<'e> {
    /// The system of `model` (its dof numbering, mesh partition and
    /// rigid-body modes) on the ranks of `env`'s world, with the preset
    /// `choice` (the options database overrides it) and options prefix
    /// `prefix`.
    pub fn new<const D: usize>(
        env: &'e Environment,
        model: &Model<D>,
        choice: SolverChoice,
        prefix: &str,
    ) -> Result<PetscSystem<'e>, PetscError> {
        let comm = env.world();
        let (ranks, rank) = (comm.size(), comm.rank());
        let cells: Vec<&[usize]> = model.mesh.cells.iter().map(|c| c.nodes).collect();
        let n_nodes = model.mesh.nodes.len();
        // faces in 3D, edges in 2D (the first D nodes of a face are enough
        // for linear and quadratic cells alike)
        let part = partition_cells(&cells, n_nodes, ranks, D)?;
        ctc_engine::solve::memory::trace("partition (metis)");
        let layout = DofLayout::new(&cells, &part, n_nodes, ranks, rank, D)?;
        ctc_engine::solve::memory::trace("dof layout");
        let dofs = DofMap::<D>::new(model);
        let petsc_of: Vec<usize> = dofs
            .free
            .iter()
            .map(|&g| D * layout.node_block[g / D] + g % D)
            .collect();
        let offsets: Vec<usize> = layout.rank_offsets.iter().map(|&b| D * b).collect();
        let mut owned = vec![None; offsets[rank + 1] - offsets[rank]];
        for (f, &p) in petsc_of.iter().enumerate() {
            if p >= offsets[rank] && p < offsets[rank + 1] {
                owned[p - offsets[rank]] = Some(f);
            }
        }
        // rigid-body modes of the owned nodes about the centroid of the mesh
        let n = n_nodes.max(1) as f64;
        let centre: Vec<f64> = (0..D)
            .map(|c| model.mesh.nodes.iter().map(|x| x[c]).sum::<f64>() / n)
            .collect();
        let coords: Vec<f64> = layout
            .owned_nodes
            .iter()
            .flat_map(|&nd| model.mesh.nodes[nd])
            .collect();
        let modes = rigid_body_modes(&coords, D, &centre);
        ctc_engine::solve::memory::trace("petsc numbering, rigid modes");
        let reason = replicated_reason(model);
        let (mut halo_blocks, mut halo_ranks) = (0, 0);
        let assembly = match reason {
            Some(_) => None,
            None => {
                let mut mine = vec![false; cells.len()];
                for &c in &layout.cells {
                    mine[c] = true;
                }
                let nodes = layout.node_owner.iter().map(|&o| o == rank).collect();
                let prealloc = Preallocation::from_cells(&layout, &cells);
                let (d, o) = prealloc.nnz();
                // the halo: node blocks of other ranks coupled to owned rows
                let own = layout.rank_offsets[rank]..layout.rank_offsets[rank + 1];
                let mut halo: Vec<usize> = prealloc
                    .neighbours
                    .iter()
                    .flatten()
                    .copied()
                    .filter(|b| !own.contains(b))
                    .collect();
                halo.sort_unstable();
                halo.dedup();
                halo_blocks = halo.len();
                let mut owners: Vec<usize> = halo
                    .iter()
                    .map(|&b| layout.rank_offsets.partition_point(|&o| o <= b) - 1)
                    .collect();
                owners.dedup();
                halo_ranks = owners.len();
                let share = AssemblyShare {
                    ranks,
                    cells: mine,
                    nodes,
                    exchanged: AssemblyShare::exchanged_cells(&cells, &part, n_nodes),
                };
                Some(Distributed {
                    share: Arc::new(share),
                    cells: prealloc,
                    d_nnz: d,
                    o_nnz: o,
                })
            }
        };
        ctc_engine::solve::memory::trace("share + preallocation");
        let stats = DistributedStats {
            // replaced by the KSP's own description at the first set-up
            solver: "petsc".into(),
            ranks,
            rows_per_rank: offsets.windows(2).map(|w| w[1] - w[0]).collect(),
            assembly: match reason {
                None => "distributed".into(),
                Some(r) => format!("replicated: {r}"),
            },
            ..Default::default()
        };
        let share = RankStats {
            rank,
            cells: layout.cells.len(),
            owned_nodes: layout.owned_nodes.len(),
            ghost_nodes: layout.ghost_nodes.len(),
            rows: offsets[rank + 1] - offsets[rank],
            halo_columns: D * halo_blocks,
            neighbours: halo_ranks,
            ..Default::default()
        };
        Ok(PetscSystem {
            comm,
            choice,
            prefix: prefix.to_string(),
            dim: D,
            mumps: false,
            petsc_of,
            offsets,
            owned,
            modes,
            symmetric: true,
            rows: None,
            objects: None,
            factorized: false,
            stats,
            share,
            assembly,
            column: Vec::new(),
            cells: {
                let mut c = layout.cells.clone();
                c.sort_unstable();
                c
            },
        })
    }

    /// This rank's number (0 writes the results).
    pub fn rank(&self) -> usize {
        self.comm.rank()
    }

    /// Ranks of the run.
    pub fn ranks(&self) -> usize {
        self.comm.size()
    }

    /// This rank's cells (its METIS part, increasing): the piece of the
    /// output it writes.
    pub fn cells(&self) -> &[usize] {
        &self.cells
    }

    /// First owned PETSc row.
    fn lo(&self) -> usize {
        self.offsets[self.comm.rank()]
    }

    /// The owned rows of `pattern` (CSC, structurally symmetric: the row
    /// of a dof has the entries of its column), and identity rows.
    fn owned_rows(&self, pattern: &SparsePattern) -> Result<OwnedRows, PetscError> {
        let lo = self.lo();
        let n_owned = self.owned.len();
        let local = |f: usize| {
            let p = self.petsc_of[f];
            (p >= lo && p < lo + n_owned).then(|| p - lo)
        };
        // row i's entries, from the columns j that hold row i
        let mut count: Vec<usize> = self
            .owned
            .iter()
            .map(|o| usize::from(o.is_none()))
            .collect();
        for j in 0..pattern.n {
            for &i in &pattern.row_idx[pattern.col_ptr[j]..pattern.col_ptr[j + 1]] {
                if let Some(r) = local(i) {
                    count[r] += 1;
                }
            }
        }
        let mut ptr = vec![0; n_owned + 1];
        for r in 0..n_owned {
            ptr[r + 1] = ptr[r] + count[r];
        }
        let nnz = ptr[n_owned];
        let mut cols = vec![0usize; nnz];
        let mut slots = vec![0usize; nnz];
        let mut next = ptr.clone();
        for (r, o) in self.owned.iter().enumerate() {
            if o.is_none() {
                cols[next[r]] = lo + r;
                slots[next[r]] = DIAGONAL;
                next[r] += 1;
            }
        }
        for j in 0..pattern.n {
            for k in pattern.col_ptr[j]..pattern.col_ptr[j + 1] {
                if let Some(r) = local(pattern.row_idx[k]) {
                    cols[next[r]] = self.petsc_of[j];
                    slots[next[r]] = k;
                    next[r] += 1;
                }
            }
        }
        // PETSc prefers sorted columns within a row
        for r in 0..n_owned {
            let (a, b) = (ptr[r], ptr[r + 1]);
            let mut idx: Vec<usize> = (a..b).collect();
            idx.sort_by_key(|&e| cols[e]);
            let c: Vec<usize> = idx.iter().map(|&e| cols[e]).collect();
            let s: Vec<usize> = idx.iter().map(|&e| slots[e]).collect();
            cols[a..b].copy_from_slice(&c);
            slots[a..b].copy_from_slice(&s);
        }
        Ok(OwnedRows {
            ptr,
            cols: to_ints(&cols)?,
            slots,
            values: vec![0.0; nnz],
        })
    }

    /// Distributed assembly: the exact preallocation of the owned rows for
    /// the rank's partial `pattern`: the couplings of the cells around the
    /// owned nodes (the entries other ranks' cells send) and the entries of
    /// `pattern` in owned rows. The pattern's contact couplings are the same
    /// on every rank (`Scatter::contact_coupled`), so an entry another rank
    /// adds to an owned row (a node-to-segment element whose slave node it
    /// owns) is in this rank's pattern too.
    fn preallocate(&mut self, pattern: &SparsePattern) {
        let dim = self.dim;
        let Some(a) = self.assembly.as_mut() else {
            return;
        };
        let mut p = a.cells.clone();
        for j in 0..pattern.n {
            let col = self.petsc_of[j] / dim;
            for &i in &pattern.row_idx[pattern.col_ptr[j]..pattern.col_ptr[j + 1]] {
                p.couple_blocks(self.petsc_of[i] / dim, col);
            }
        }
        (a.d_nnz, a.o_nnz) = p.nnz();
    }

    /// Creates the matrix, vectors, scatter and solver of the current rows.
    fn build(&mut self) -> Result<Objects<'e>, PetscError> {
        let (lo, n_owned) = (self.lo(), self.owned.len());
        let hi = lo + n_owned;
        let n_global = *self.offsets.last().unwrap_or(&0);
        let mut mat = if let Some(Distributed {
            d_nnz: d, o_nnz: o, ..
        }) = &self.assembly
        {
            // distributed: the rows' entries from all the cells around the
            // owned nodes (every dof of a node, prescribed ones included)
            self.share.nonzeros = d.iter().sum::<usize>() + o.iter().sum::<usize>();
            self.share.off_rank_nonzeros = o.iter().sum();
            DistMatrix::from_nnz(&self.comm, n_owned, n_global, self.dim, d, o)?
        } else {
            let rows = self.rows.as_ref().expect("owned rows are built first");
            let mut d = vec![0usize; n_owned];
            let mut o = vec![0usize; n_owned];
            for r in 0..n_owned {
                for &c in &rows.cols[rows.ptr[r]..rows.ptr[r + 1]] {
                    let c = c as usize;
                    if c >= lo && c < hi {
                        d[r] += 1;
                    } else {
                        o[r] += 1;
                    }
                }
            }
            // the halo: distinct columns of other ranks, and the ranks
            // owning them
            let mut halo: Vec<ffi::PetscInt> = rows
                .cols
                .iter()
                .copied()
                .filter(|&c| (c as usize) < lo || (c as usize) >= hi)
                .collect();
            self.share.nonzeros = rows.cols.len();
            self.share.off_rank_nonzeros = halo.len();
            halo.sort_unstable();
            halo.dedup();
            self.share.halo_columns = halo.len();
            let mut owners: Vec<usize> = halo
                .iter()
                .map(|&c| self.offsets.partition_point(|&o| o <= c as usize) - 1)
                .collect();
            owners.dedup();
            self.share.neighbours = owners.len();
            DistMatrix::from_nnz(&self.comm, n_owned, n_global, self.dim, &d, &o)?
        };
        set_near_null_space(&self.comm, &mut mat, &self.modes)?;
        let mut ksp = Krylov::new(&self.comm, &mat, self.choice, &self.prefix)?;
        self.mumps = ksp.detect_null_pivots()?;
        let mut b: ffi::Vec = std::ptr::null_mut();
        let mut x: ffi::Vec = std::ptr::null_mut();
        let mut to_all: ffi::VecScatter = std::ptr::null_mut();
        let mut all: ffi::Vec = std::ptr::null_mut();
        // SAFETY: the matrix is created; the handles are owned by
        // `Objects`, whose Drop destroys them once.
        unsafe {
            check("MatCreateVecs", ffi::MatCreateVecs(mat.mat, &mut x, &mut b))?;
            check(
                "VecScatterCreateToAll",
                ffi::VecScatterCreateToAll(x, &mut to_all, &mut all),
            )?;
        }
        self.stats.solver = ksp.describe()?;
        Ok(Objects {
            mat,
            ksp,
            b,
            x,
            to_all,
            all,
        })
    }

    /// Inserts the owned rows of `values` and assembles (collective).
    fn fill(&mut self, values: &[f64]) -> Result<(), PetscError> {
        let lo = self.lo();
        let rows = self.rows.as_mut().expect("owned rows are built first");
        // identity rows: the mean diagonal of the free rows (conditioning)
        let (mut sum, mut n) = (0.0, 0usize);
        for (r, o) in self.owned.iter().enumerate() {
            if o.is_some() {
                for e in rows.ptr[r]..rows.ptr[r + 1] {
                    if rows.cols[e] as usize == lo + r {
                        sum += values[rows.slots[e]].abs();
                        n += 1;
                    }
                }
            }
        }
        let diagonal = if n > 0 && sum > 0.0 {
            sum / n as f64
        } else {
            1.0
        };
        for (v, &s) in rows.values.iter_mut().zip(&rows.slots) {
            *v = if s == DIAGONAL { diagonal } else { values[s] };
        }
        let obj = self.objects.as_mut().expect("objects are built first");
        for r in 0..self.owned.len() {
            let (a, b) = (rows.ptr[r], rows.ptr[r + 1]);
            let row = [(lo + r) as ffi::PetscInt];
            // SAFETY: the row is owned and its columns are in the
            // preallocated pattern; PETSc copies the values.
            unsafe {
                check(
                    "MatSetValues",
                    ffi::MatSetValues(
                        obj.mat.mat,
                        1,
                        row.as_ptr(),
                        (b - a) as ffi::PetscInt,
                        rows.cols[a..b].as_ptr(),
                        rows.values[a..b].as_ptr(),
                        ffi::InsertMode_INSERT_VALUES,
                    ),
                )?;
            }
        }
        obj.mat.assemble()?;
        obj.mat.set_symmetric(self.symmetric)
    }

    /// Distributed assembly: adds this rank's part of the tangent (the
    /// entries of its cells and contact nodes, any rank's rows) into the
    /// zeroed matrix with ADD_VALUES, the identity rows of the owned
    /// prescribed and inactive dofs, and assembles (collective: PETSc's
    /// stash sends the other ranks' rows to their owners).
    fn add_local(&mut self, pattern: &SparsePattern, values: &[f64]) -> Result<(), PetscError> {
        let lo = self.lo();
        // identity rows: the mean diagonal of the owned free rows, the
        // diagonal summed over the ranks first
        let mut diagonal: Vec<f64> = (0..pattern.n)
            .map(|j| pattern.find(j, j).map_or(f64::NAN, |k| values[k]))
            .collect();
        if self.comm.size() > 1 {
            // a dof no rank's cells touch has no diagonal: NaN stays NaN
            for v in &mut diagonal {
                if v.is_nan() {
                    *v = 0.0;
                }
            }
            self.comm.sum_vector(&mut diagonal);
        }
        let (mut sum, mut n) = (0.0, 0usize);
        for f in self.owned.iter().flatten() {
            let d = diagonal[*f];
            if !d.is_nan() {
                sum += d.abs();
                n += 1;
            }
        }
        drop(diagonal);
        let diagonal = if n > 0 && sum > 0.0 {
            sum / n as f64
        } else {
            1.0
        };
        let obj = self.objects.as_mut().expect("objects are built first");
        obj.mat.zero()?;
        for j in 0..pattern.n {
            let (a, b) = (pattern.col_ptr[j], pattern.col_ptr[j + 1]);
            if a == b {
                continue;
            }
            self.column.clear();
            for &i in &pattern.row_idx[a..b] {
                self.column.push(self.petsc_of[i] as ffi::PetscInt);
            }
            let col = [self.petsc_of[j] as ffi::PetscInt];
            // SAFETY: `column` and the values hold `b - a` entries, in the
            // preallocated pattern (the cells around the rows' nodes);
            // PETSc copies them (to its stash for other ranks' rows).
            unsafe {
                check(
                    "MatSetValues",
                    ffi::MatSetValues(
                        obj.mat.mat,
                        (b - a) as ffi::PetscInt,
                        self.column.as_ptr(),
                        1,
                        col.as_ptr(),
                        values[a..b].as_ptr(),
                        ffi::InsertMode_ADD_VALUES,
                    ),
                )?;
            }
        }
        for (r, o) in self.owned.iter().enumerate() {
            if o.is_none() {
                let row = [(lo + r) as ffi::PetscInt];
                // SAFETY: an owned row's diagonal, preallocated.
                unsafe {
                    check(
                        "MatSetValues",
                        ffi::MatSetValues(
                            obj.mat.mat,
                            1,
                            row.as_ptr(),
                            1,
                            row.as_ptr(),
                            &diagonal,
                            ffi::InsertMode_ADD_VALUES,
                        ),
                    )?;
                }
            }
        }
        obj.mat.assemble()?;
        obj.mat.set_symmetric(self.symmetric)
    }

    /// Factorization / preconditioner of the new values (collective).
    fn factorize_petsc(
        &mut self,
        pattern: &SparsePattern,
        values: &[f64],
    ) -> Result<(), PetscError> {
        let distributed = self.assembly.is_some();
        if self.rows.is_none() && !distributed {
            self.objects = None;
            self.rows = Some(self.owned_rows(pattern)?);
        }
        if self.objects.is_none() {
            if distributed {
                self.preallocate(pattern);
            }
            self.objects = Some(self.build()?);
        }
        let start = Instant::now();
        if distributed {
            self.add_local(pattern, values)?;
        } else {
            self.fill(values)?;
        }
        let mid = Instant::now();
        self.stats.assembly_seconds += (mid - start).as_secs_f64();
        let obj = self.objects.as_mut().expect("built above");
        // a failed factorization is reported by the rank that met it:
        // every rank stops with it
        self.comm.agree_failure(obj.ksp.set_up())?;
        if self.mumps {
            let null = obj.ksp.mumps_null_pivots()?;
            if null > 0 {
                return Err(PetscError::Singular(format!(
                    "the stiffness matrix is singular: MUMPS found {null} null pivot(s) (a \
                     rigid-body motion that no `fix` / `displace` condition and no closed \
                     contact holds)"
                )));
            }
        }
        self.stats.setup_seconds += mid.elapsed().as_secs_f64();
        self.stats.setups += 1;
        self.stats.krylov_per_setup.push(Vec::new());
        Ok(())
    }

    /// `K x = rhs` in place (collective).
    fn solve_petsc(&mut self, rhs: &mut [f64]) -> Result<(), PetscError> {
        let start = Instant::now();
        let obj = self.objects.as_mut().expect("factorized first");
        // SAFETY: `b` has the owned rows of this rank; `all` has every row.
        unsafe {
            let mut ptr: *mut f64 = std::ptr::null_mut();
            check("VecGetArray", ffi::VecGetArray(obj.b, &mut ptr))?;
            let b = std::slice::from_raw_parts_mut(ptr, self.owned.len());
            for (v, f) in b.iter_mut().zip(&self.owned) {
                *v = f.map_or(0.0, |f| rhs[f]);
            }
            check("VecRestoreArray", ffi::VecRestoreArray(obj.b, &mut ptr))?;
        }
        let report = match obj.ksp.solve_vecs(obj.b, obj.x) {
            // CG met an indefinite tangent (the curvature term of a convex
            // tool at a trial penetration, softening): solve it, and the
            // next ones of this pattern, by GMRES, as the serial solver
            // falls back from Cholesky to L D L^T
            Err(PetscError::Diverged { reason, .. })
                if reason == ffi::KSPConvergedReason_KSP_DIVERGED_INDEFINITE_MAT
                    || reason == ffi::KSPConvergedReason_KSP_DIVERGED_INDEFINITE_PC =>
            {
                obj.ksp.set_type("gmres")?;
                if self.stats.fallbacks == 0 {
                    self.stats.fallback_reason =
                        if reason == ffi::KSPConvergedReason_KSP_DIVERGED_INDEFINITE_MAT {
                            "indefinite matrix"
                        } else {
                            "indefinite preconditioner"
                        }
                        .into();
                }
                self.stats.fallbacks += 1;
                self.stats.solver = obj.ksp.describe()?;
                obj.ksp.solve_vecs(obj.b, obj.x)?
            }
            r => r?,
        };
        // SAFETY: scatter created for `x` -> `all`.
        unsafe {
            let (i, f) = (
                ffi::InsertMode_INSERT_VALUES,
                ffi::ScatterMode_SCATTER_FORWARD,
            );
            check(
                "VecScatterBegin",
                ffi::VecScatterBegin(obj.to_all, obj.x, obj.all, i, f),
            )?;
            check(
                "VecScatterEnd",
                ffi::VecScatterEnd(obj.to_all, obj.x, obj.all, i, f),
            )?;
            let mut ptr: *const f64 = std::ptr::null();
            check("VecGetArrayRead", ffi::VecGetArrayRead(obj.all, &mut ptr))?;
            let all = std::slice::from_raw_parts(ptr, *self.offsets.last().unwrap_or(&0));
            for (v, &p) in rhs.iter_mut().zip(&self.petsc_of) {
                *v = all[p];
            }
            check(
                "VecRestoreArrayRead",
                ffi::VecRestoreArrayRead(obj.all, &mut ptr),
            )?;
        }
        self.stats.solves += 1;
        if let Some(group) = self.stats.krylov_per_setup.last_mut() {
            group.push(report.iterations);
        }
        self.stats.krylov_iterations += report.iterations;
        self.stats.max_krylov_iterations = self.stats.max_krylov_iterations.max(report.iterations);
        self.stats.solve_seconds += start.elapsed().as_secs_f64();
        Ok(())
    }
}

/// A PETSc failure as the engine sees it: a Krylov solve that stopped
/// before its tolerance (`DIVERGED_ITS`, a breakdown: the same reason on
/// every rank) is [`LinearError::NotConverged`], so the run's diagnosis
/// names the linear solver; a failed set-up (a singular matrix met by the
/// factorization) and the other failures are [`LinearError::Singular`].
fn to_linear(e: PetscError) -> LinearError {
    match e {
        PetscError::Diverged { .. } => LinearError::NotConverged(format!("PETSc: {e}")),
        e => LinearError::Singular(format!("PETSc: {e}")),
    }
}

impl LinearSystem for PetscSystem<'_> {
    fn set_symmetric(&mut self, symmetric: bool) {
        self.symmetric = symmetric;
    }

    fn factorize(&mut self, pattern: &SparsePattern, values: &[f64]) -> Result<(), LinearError> {
        self.factorized = false;
        self.factorize_petsc(pattern, values).map_err(to_linear)?;
        self.factorized = true;
        Ok(())
    }

    fn solve(&mut self, rhs: &mut [f64]) -> Result<(), LinearError> {
        if !self.factorized {
            return Err(LinearError::NotFactorized);
        }
        self.solve_petsc(rhs).map_err(to_linear)
    }

    fn is_factorized(&self) -> bool {
        self.factorized
    }

    fn reset_pattern(&mut self) {
        self.objects = None;
        self.rows = None;
        self.factorized = false;
    }

    fn stats(&self) -> FactorStats {
        FactorStats::default()
    }

    fn share(&self) -> Option<Arc<AssemblyShare>> {
        self.assembly.as_ref().map(|a| a.share.clone())
    }

    fn sum_over_ranks(&self, v: &mut [f64]) {
        if self.comm.size() > 1 {
            self.comm.sum_vector(v);
        }
    }

    fn any_rank(&self, flag: bool) -> bool {
        self.comm.any(flag)
    }

    fn gather_on_first(&self, local: &[f64]) -> Option<Vec<f64>> {
        self.comm.gather_on_first(local)
    }

    fn distributed(&self, timings: &Timings) -> Option<DistributedStats> {
        let s = &self.share;
        // counts travel as f64: exact below 2^53
        let local: [f64; RANK_FIELDS] = [
            s.cells as f64,
            s.owned_nodes as f64,
            s.ghost_nodes as f64,
            s.rows as f64,
            s.nonzeros as f64,
            s.off_rank_nonzeros as f64,
            s.halo_columns as f64,
            s.neighbours as f64,
            timings.assembly,
            timings.contact,
            timings.factorization,
            timings.solve,
            self.stats.assembly_seconds,
            self.stats.setup_seconds,
            peak_memory_bytes() as f64,
            timings.cells_assembled as f64,
            timings.cpu[0],
            timings.cpu[1],
            timings.cpu[2],
            timings.cpu[3],
            process_cpu_seconds(),
        ];
        let all = self.comm.all_gather(&local);
        let mut stats = self.stats.clone();
        stats.per_rank = all
            .chunks(RANK_FIELDS)
            .enumerate()
            .map(|(rank, v)| RankStats {
                rank,
                cells: v[0] as usize,
                owned_nodes: v[1] as usize,
                ghost_nodes: v[2] as usize,
                rows: v[3] as usize,
                nonzeros: v[4] as usize,
                off_rank_nonzeros: v[5] as usize,
                halo_columns: v[6] as usize,
                neighbours: v[7] as usize,
                assembly_seconds: v[8],
                contact_seconds: v[9],
                tangent_seconds: v[10],
                solve_seconds: v[11],
                insertion_seconds: v[12],
                setup_seconds: v[13],
                peak_memory_bytes: v[14] as u64,
                assembled_cells: v[15] as usize,
                assembly_cpu_seconds: v[16],
                contact_cpu_seconds: v[17],
                tangent_cpu_seconds: v[18],
                solve_cpu_seconds: v[19],
                process_cpu_seconds: v[20],
            })
            .collect();
        Some(stats)
    }
}
