//! Element loop: internal forces and tangent stiffness of every cell,
//! scattered into the global force vector and the sparse value array.
//! Serial, in cell order: results are bit-for-bit reproducible.
//!
//! Bodies with history-dependent or finite-strain laws keep their
//! integration-point internal variables here: each evaluation computes
//! trial points from the **committed** ones (so a rejected or cut-back
//! attempt leaves no trace); [`Assembler::commit`] makes the last evaluated
//! points the committed ones at a converged increment, and
//! [`Assembler::begin_increment`] sets the time increment seen by
//! rate-dependent laws.
//!
//! Small-strain linear elastic cells have a constant stiffness and
//! `f_int = K_e u_e` exactly: their element matrices are computed once in
//! [`Assembler::new`] and each assembly is a matrix-vector product and a
//! scatter. When every cell is one, the loop runs once per scatter map
//! for the tangent and once per run for the stiffness over all dofs
//! ([`super::bulk_tangent`]): an evaluation is then a copy of the
//! assembled tangent and `f_int = K u` (the slow part of a linear contact
//! iteration is the solve, as it should be).

use super::bulk_tangent::{BulkTangent, DofMatrix};
use super::linalg::{Scatter, NO_SLOT};
use crate::element::kernel::{kernel_of, NonlinearInput};
use crate::element::recovery::{blocks_of, cell_input, virgin, CellBlock};
use crate::element::{ElementMatrix, MaterialPoint, Section};
use crate::geom::{Dimension, Point};
use crate::material::History;
use crate::mesh::Mesh;
use crate::model::Model;
use crate::solve::share::AssemblyShare;
use nalgebra::Const;
use std::sync::Arc;

/// The element kernels of a model of dimension `D`.
#[derive(Debug, Clone)]
pub struct Assembler<const D: usize = 2> {
    /// One block of cells per body, with its law and formulation.
    pub blocks: Vec<CellBlock>,
    /// Cross-section (kind, thickness).
    pub section: Section,
    /// Committed integration points per global cell (empty for
    /// small-strain linear elastic cells, and under a split distributed
    /// assembly for the cells this rank does not hold: [`Assembler::holds`]).
    committed: Vec<Vec<MaterialPoint>>,
    /// Points of the last evaluation.
    trial: Vec<Vec<MaterialPoint>>,
    /// Time of the committed state.
    t_committed: f64,
    /// Time increment of the current attempt.
    dt: f64,
    /// Element stiffness matrices (column-major, element dof order
    /// `a D + c`) of the small-strain linear elastic cells, concatenated.
    linear_k: Vec<f64>,
    /// Offset of each cell's matrix in `linear_k` (`NO_MATRIX` for cells
    /// with a nonlinear law).
    linear_offset: Vec<usize>,
    /// Thermal strain of each global cell (`crate::thermal::expansion`);
    /// empty without thermal coupling.
    thermal_strain: Vec<f64>,
    /// Nodal force of a unit thermal strain of each small-strain linear
    /// elastic cell (computed when thermal strains are first set).
    thermal_unit: Vec<Vec<Point<D>>>,
    /// Law of each cell at its temperature (temperature-dependent
    /// materials, `crate::thermal::properties`); empty otherwise.
    cell_law: Vec<Option<crate::material::NonlinearLaw>>,
    /// Norm of the element thermal forces `eps_th f_unit` (unassembled):
    /// a force scale for the convergence test of thermally loaded bodies.
    thermal_scale: f64,
    /// The cells this rank assembles (distributed assembly,
    /// [`crate::solve::share`]); `None`: all cells.
    share: Option<Arc<AssemblyShare>>,
    /// Whether every rank holds the committed points of every cell (a
    /// heat step or a pressure control reads them all,
    /// [`points_held_whole`]); otherwise a rank of a split share holds
    /// those of its cells and of the exchanged cells only.
    whole_points: bool,
    /// Cells evaluated by the last [`Assembler::assemble`].
    assembled: usize,
    /// The partition of the cells among threads for the last thread count
    /// and scatter map ([`Plan`]).
    plan: Option<Arc<Plan>>,
    /// The element tangent of a model without integration points,
    /// assembled once per scatter map ([`BulkTangent`]).
    bulk: BulkTangent,
}

/// Cells below which the element loop stays serial.
pub const PARALLEL_MIN_CELLS: usize = 4096;

/// Marks a value slot or force entry written by cells of several chunks.
const SHARED: u32 = u32::MAX;

/// The partition of the element loop among threads, for one thread count
/// and one scatter map, such that the parallel loop adds every value
/// slot's and force entry's contributions in the serial order (the bits do
/// not depend on the thread count):
/// - the cells, in the serial order (block by block), are cut into
///   contiguous chunks, one per thread;
/// - a slot (or force entry) that the cells of one chunk only touch is
///   *owned* by it: that chunk's thread adds its contributions, in cell
///   order, straight into the output;
/// - a slot touched by several chunks is *shared*: the cells touching one
///   (the *interface* cells) keep their element results, and the shared
///   entries are added after the threads, chunk by chunk, in cell order.
#[derive(Debug)]
struct Plan {
    /// Thread count and scatter map this plan is for.
    key: (usize, u64),
    /// (block, global cell) in the serial order.
    seq: Vec<(usize, usize)>,
    /// Chunks: ranges of `seq`.
    chunks: Vec<std::ops::Range<usize>>,
    /// Per `seq` entry: an interface cell.
    interface: Vec<bool>,
    /// Owner chunk of each value slot, or [`SHARED`].
    slot_owner: Vec<u32>,
    /// Owner chunk of each force entry (`D` per node), or [`SHARED`].
    force_owner: Vec<u32>,
}

/// Values of one packed [`MaterialPoint`] ([`pack_point`]): position (3),
/// volume, strain (6), stress (6), equivalent plastic strain, history
/// tensor (6).
const POINT_VALUES: usize = 23;

/// `p` as [`POINT_VALUES`] numbers (the order of the restart file).
fn pack_point(p: &MaterialPoint, out: &mut [f64]) {
    let s = &p.state;
    out[..3].copy_from_slice(&s.position);
    out[3] = s.volume;
    out[4..10].copy_from_slice(s.strain.as_slice());
    out[10..16].copy_from_slice(s.stress.as_slice());
    out[16] = p.history.ep;
    out[17..23].copy_from_slice(&p.history.tensor);
}

/// The point [`pack_point`] packed into `v`.
fn unpack_point(v: &[f64], p: &mut MaterialPoint) {
    let s = &mut p.state;
    s.position.copy_from_slice(&v[..3]);
    s.volume = v[3];
    s.strain.copy_from_slice(&v[4..10]);
    s.stress.copy_from_slice(&v[10..16]);
    p.history.ep = v[16];
    p.history.tensor.copy_from_slice(&v[17..23]);
}

/// Marks a cell without a cached stiffness matrix.
const NO_MATRIX: usize = usize::MAX;

/// Whether every rank keeps the committed points of every cell: the heat
/// step of a thermal coupling (the plastic dissipation of every point)
/// and a pressure control (the plastic strain rate of its cells) read
/// them all on every rank.
fn points_held_whole<const D: usize>(model: &Model<D>) -> bool {
    model.thermal.is_some() || !super::control::controls(model).is_empty()
}

/// Whether a rank of `share` holds the committed points of cell `c`: every
/// cell without a split share or when they are held whole, else its own
/// cells and the exchanged ones.
fn holds(share: Option<&AssemblyShare>, whole: bool, c: usize) -> bool {
    match share {
        Some(s) if s.split() && !whole => s.owns_cell(c) || s.exchanged(c),
        _ => true,
    }
}

/// Most dofs of a cell (a 27-node hexahedron).
const MAX_DOFS: usize = 81;

impl<const D: usize> Assembler<D>
where
    Const<D>: Dimension<D>,
{
    /// Builds the kernels of `model` (materials must be valid).
    pub fn new(model: &Model<D>) -> Result<Self, String> {
        Self::with_share(model, None)
    }

    /// Like [`Assembler::new`] for the cells of a rank's `share` only
    /// (distributed assembly): element matrices and integration points of
    /// its cells, the others skipped by [`Assembler::assemble`].
    pub fn with_share(model: &Model<D>, share: Option<Arc<AssemblyShare>>) -> Result<Self, String> {
        let blocks = blocks_of(model)?;
        // the committed points of the cells this rank holds: every cell
        // (serial, or a heat step or pressure control reading them all),
        // or, under a split share, its own cells and the exchanged ones
        // (kept current by `Assembler::exchange_points`: the output's
        // nodal averages on either side of a part's border); a restart
        // file gathers them (`Assembler::gathered_points`)
        let whole_points = points_held_whole(model);
        let holds = |c: usize| holds(share.as_deref(), whole_points, c);
        let mut committed = vec![Vec::new(); model.mesh.cells.len()];
        for b in &blocks {
            if b.nonlinear.is_some() {
                for c in b.cells.clone().filter(|&c| holds(c)) {
                    let kernel = kernel_of::<D>(model.mesh.cells.kind(c))
                        .map_err(|e| format!("cell {c}: {}", e.message))?;
                    committed[c] = vec![virgin(b.kinematics); kernel.point_count()];
                }
            }
        }
        let t0 = model.steps.first().map_or(0.0, |s| s.t_start);
        let section = Section::new(&model.analysis);
        let (linear_k, linear_offset) = linear_matrices(
            &model.mesh,
            &blocks,
            &section,
            share.as_deref(),
            (super::parallel::threads(), PARALLEL_MIN_CELLS),
        )?;
        Ok(Assembler {
            blocks,
            section,
            trial: committed.clone(),
            committed,
            t_committed: t0,
            dt: 0.0,
            linear_k,
            linear_offset,
            thermal_strain: Vec::new(),
            thermal_unit: Vec::new(),
            cell_law: Vec::new(),
            thermal_scale: 0.0,
            share,
            whole_points,
            assembled: 0,
            plan: None,
            bulk: BulkTangent::default(),
        })
    }

    /// Cells evaluated by the last [`Assembler::assemble`] (this rank's
    /// cells under a distributed assembly).
    pub fn assembled_cells(&self) -> usize {
        self.assembled
    }

    /// The tangent stiffness of every cell in the reference configuration
    /// (column-major `D NN x D NN`; nonlinear laws at zero strain with
    /// virgin internal variables, that is their elastic stiffness): the
    /// stiffness-proportional part of Rayleigh damping
    /// (`crate::solve::dynamics`).
    pub fn reference_stiffness(&self, mesh: &Mesh<D>) -> Result<Vec<Vec<f64>>, String> {
        let mut out = vec![Vec::new(); mesh.cells.len()];
        let mut scratch = ElementMatrix::<D>::default();
        for block in &self.blocks {
            for c in block.cells.clone() {
                if self.share.as_ref().is_some_and(|s| !s.owns_cell(c)) {
                    continue;
                }
                let nd = D * mesh.cells.nodes(c).len();
                if let Some(law) = &block.nonlinear {
                    let kernel = kernel_of::<D>(mesh.cells.kind(c))
                        .map_err(|e| format!("cell {c}: {}", e.message))?;
                    let x = mesh.cell_points(c);
                    let zero = vec![Point::<D>::zeros(); x.len()];
                    let mut trial = vec![virgin(block.kinematics); kernel.point_count()];
                    let history: Vec<History> = trial.iter().map(|p| p.history).collect();
                    kernel
                        .nonlinear(
                            &NonlinearInput {
                                x: &x,
                                u: &zero,
                                section: &self.section,
                                formulation: block.formulation,
                                kinematics: block.kinematics,
                                law,
                                history: &history,
                                dt: 1.0,
                                thermal_strain: 0.0,
                                with_tangent: true,
                            },
                            &mut scratch,
                            &mut trial,
                        )
                        .map_err(|e| format!("cell {c}: {}", e.message))?;
                    out[c] = (0..nd * nd)
                        .map(|e| scratch.entry(e % nd, e / nd))
                        .collect();
                } else {
                    out[c] = self.linear_k[self.linear_offset[c]..][..nd * nd].to_vec();
                }
            }
        }
        Ok(out)
    }

    /// Sets the thermal state used by the next evaluations: the thermal
    /// strain of each cell and, for temperature-dependent materials, the
    /// law of each cell at its temperature (`None`: the body's law).
    pub fn set_thermal_state(
        &mut self,
        mesh: &Mesh<D>,
        strain: Vec<f64>,
        laws: Vec<Option<crate::material::NonlinearLaw>>,
    ) -> Result<(), String> {
        if self.thermal_unit.is_empty() && strain.iter().any(|e| *e != 0.0) {
            let mut unit = vec![Vec::new(); mesh.cells.len()];
            for block in &self.blocks {
                for c in block.cells.clone() {
                    unit[c] = crate::thermal::expansion::unit_thermal_force(
                        mesh,
                        c,
                        &self.section,
                        block.formulation,
                        &block.law,
                    )
                    .map_err(|e| format!("cell {c}: {}", e.message))?;
                }
            }
            self.thermal_unit = unit;
        }
        let mut scale2 = 0.0;
        for (e, unit) in strain.iter().zip(&self.thermal_unit) {
            scale2 += unit
                .iter()
                .flat_map(|f| f.iter())
                .map(|f| (e * f) * (e * f))
                .sum::<f64>();
        }
        self.thermal_scale = scale2.sqrt();
        self.thermal_strain = strain;
        self.cell_law = laws;
        Ok(())
    }

    /// Isotropic thermal strain of each cell used by the evaluations (empty
    /// before the first thermal state).
    pub fn thermal_strains(&self) -> &[f64] {
        &self.thermal_strain
    }

    /// Norm of the element thermal forces (0 without thermal strains): a
    /// force scale for the relative residual (a freely expanding body has
    /// no load and no reaction).
    pub fn thermal_scale(&self) -> f64 {
        self.thermal_scale
    }

    /// Starts an attempt to reach time `t` from the committed state.
    pub fn begin_increment(&mut self, t: f64) {
        self.dt = t - self.t_committed;
    }

    /// Makes the points of the last evaluation the committed ones.
    pub fn commit(&mut self) {
        for (c, t) in self.committed.iter_mut().zip(&self.trial) {
            c.copy_from_slice(t);
        }
        self.t_committed += self.dt;
        self.dt = 0.0;
    }

    /// Forgets the points of the last evaluation.
    pub fn rollback(&mut self) {
        for (c, t) in self.committed.iter().zip(self.trial.iter_mut()) {
            t.copy_from_slice(c);
        }
    }

    /// Whether this rank holds the committed points of cell `c`
    /// ([`Assembler::points`]; every cell without a split share).
    pub fn holds(&self, c: usize) -> bool {
        holds(self.share.as_deref(), self.whole_points, c)
    }

    /// Distributed assembly ([`crate::solve::share`]): after a commit, the
    /// committed points of the other ranks' cells this rank holds (the
    /// exchanged cells, [`crate::solve::share::AssemblyShare::exchanged`],
    /// or every cell when they are held whole), which only their rank
    /// evaluated, received through `sum` (a sum over the ranks of a flat
    /// vector over the exchanged cells, the same bits on every rank): each
    /// rank puts its cells' values and `-0.0` elsewhere, and `x + (-0.0) =
    /// x` for every `x`, so every rank then holds those cells' points bit
    /// for bit as their owner computed them. Trial points of those cells
    /// are set alike (a rollback leaves them unchanged). Nothing to do
    /// without a split share or without nonlinear cells.
    pub fn exchange_points(&mut self, sum: impl FnOnce(&mut [f64])) {
        let Some(share) = self.share.clone().filter(|s| s.split()) else {
            return;
        };
        let whole = self.whole_points;
        let exchanged = |c: usize| whole || share.exchanged(c);
        let n: usize = (0..self.committed.len())
            .filter(|&c| exchanged(c))
            .map(|c| self.committed[c].len())
            .sum();
        if n == 0 {
            return;
        }
        let mut flat = vec![-0.0; n * POINT_VALUES];
        let mut at = 0;
        for (c, cell) in self.committed.iter().enumerate() {
            if !exchanged(c) {
                continue;
            }
            let len = cell.len() * POINT_VALUES;
            if share.owns_cell(c) {
                for (p, out) in cell.iter().zip(flat[at..at + len].chunks_mut(POINT_VALUES)) {
                    pack_point(p, out);
                }
            }
            at += len;
        }
        sum(&mut flat);
        let mut at = 0;
        for (c, (cell, trial)) in self.committed.iter_mut().zip(&mut self.trial).enumerate() {
            if !exchanged(c) {
                continue;
            }
            let len = cell.len() * POINT_VALUES;
            if !share.owns_cell(c) {
                for ((p, t), v) in cell
                    .iter_mut()
                    .zip(trial.iter_mut())
                    .zip(flat[at..at + len].chunks(POINT_VALUES))
                {
                    unpack_point(v, p);
                    *t = *p;
                }
            }
            at += len;
        }
    }

    /// The committed points of every cell, for a restart file: under a
    /// split share whose ranks hold only their part (and a model with
    /// integration points), each rank's own cells (`[cell, points,
    /// values..]` per cell) are gathered on the first rank by `gather`
    /// (the concatenation of the ranks' vectors on rank 0, `None`
    /// elsewhere, collective), which returns the whole layout; the other
    /// ranks get an empty list (they write no restart file). Otherwise a
    /// copy of [`Assembler::points`].
    pub fn gathered_points(
        &self,
        gather: impl FnOnce(&[f64]) -> Option<Vec<f64>>,
    ) -> Vec<Vec<MaterialPoint>> {
        let Some(share) = self
            .share
            .as_ref()
            .filter(|s| s.split() && !self.whole_points && self.has_points())
        else {
            return self.committed.clone();
        };
        let mut local = Vec::new();
        for (c, cell) in self.committed.iter().enumerate() {
            if share.owns_cell(c) && !cell.is_empty() {
                local.push(c as f64);
                local.push(cell.len() as f64);
                let at = local.len();
                local.resize(at + cell.len() * POINT_VALUES, 0.0);
                for (p, out) in cell.iter().zip(local[at..].chunks_mut(POINT_VALUES)) {
                    pack_point(p, out);
                }
            }
        }
        let Some(all) = gather(&local) else {
            return Vec::new();
        };
        drop(local);
        let mut out = vec![Vec::new(); self.committed.len()];
        let mut at = 0;
        while at + 2 <= all.len() {
            let (c, n) = (all[at] as usize, all[at + 1] as usize);
            at += 2;
            let Some(cell) = out.get_mut(c) else {
                break;
            };
            *cell = all[at..at + n * POINT_VALUES]
                .chunks(POINT_VALUES)
                .map(|v| {
                    // every field is overwritten
                    let mut p = virgin(crate::model::Kinematics::Small);
                    unpack_point(v, &mut p);
                    p
                })
                .collect();
            at += n * POINT_VALUES;
        }
        out
    }

    /// Committed integration points per global cell (empty for small-strain
    /// linear elastic cells, and for the cells this rank does not hold:
    /// [`Assembler::holds`]).
    pub fn points(&self) -> &[Vec<MaterialPoint>] {
        &self.committed
    }

    /// Time of the committed integration points.
    pub fn committed_time(&self) -> f64 {
        self.t_committed
    }

    /// Replaces the committed (and trial) points and their time by those of
    /// a restart point (the points of every cell; this rank keeps those of
    /// the cells it holds); the layout (cells, points per cell) must match.
    pub fn restore(&mut self, points: &[Vec<MaterialPoint>], t: f64) -> Result<(), String> {
        let same = points.len() == self.committed.len()
            && points
                .iter()
                .zip(&self.committed)
                .enumerate()
                .all(|(c, (a, b))| a.len() == b.len() || (b.is_empty() && !self.holds(c)));
        if !same {
            return Err("the restart point's integration points do not match the model".into());
        }
        for ((c, tr), p) in self.committed.iter_mut().zip(&mut self.trial).zip(points) {
            if !c.is_empty() {
                c.copy_from_slice(p);
                tr.copy_from_slice(p);
            }
        }
        self.t_committed = t;
        self.dt = 0.0;
        Ok(())
    }

    /// Whether the element tangent is symmetric (false with F-bar: finite
    /// strain with selective reduced integration).
    pub fn symmetric(&self) -> bool {
        !self.blocks.iter().any(|b| {
            b.nonlinear.is_some()
                && b.kinematics == crate::model::Kinematics::Finite
                && b.formulation == crate::model::Formulation::SelectiveReduced
        })
    }

    /// Whether any body has a nonlinear law (stored integration points).
    pub fn has_points(&self) -> bool {
        self.blocks.iter().any(|b| b.nonlinear.is_some())
    }

    /// Internal forces `f_int` (`D` per node, overwritten) at displacements
    /// `u`, and, if `values` is given, the tangent (the caller zeroes
    /// `values`; element entries are added).
    pub fn assemble(
        &mut self,
        mesh: &Mesh<D>,
        scatter: &Scatter,
        u: &[[f64; D]],
        f_int: &mut [f64],
        values: Option<&mut [f64]>,
    ) -> Result<(), String> {
        let threads = super::parallel::threads();
        self.assemble_with(
            mesh,
            scatter,
            u,
            f_int,
            values,
            (threads, PARALLEL_MIN_CELLS),
        )
    }

    /// [`Assembler::assemble`] on `threads` threads when the model has at
    /// least `min_cells` cells (and is not a rank's share of a distributed
    /// assembly): the same bits whatever `threads` ([`Plan`]). Without
    /// integration points (every cell small-strain linear elastic) the
    /// tangent and the forces come from the [`BulkTangent`]
    /// ([`Assembler::linear_tangent`]).
    pub fn assemble_with(
        &mut self,
        mesh: &Mesh<D>,
        scatter: &Scatter,
        u: &[[f64; D]],
        f_int: &mut [f64],
        values: Option<&mut [f64]>,
        par: (usize, usize),
    ) -> Result<(), String> {
        if !self.bulk_applies() {
            return self.element_loop(mesh, scatter, u, f_int, values, par);
        }
        if let Some(values) = values {
            let mut bulk = vec![0.0; values.len()];
            self.linear_tangent(mesh, scatter, u, f_int, &mut bulk, par)?;
            for (v, b) in values.iter_mut().zip(&bulk) {
                *v += b;
            }
            return Ok(());
        }
        self.linear_forces(mesh, u, f_int, par.0);
        Ok(())
    }

    /// Like [`Assembler::assemble`] with the tangent: `values` are
    /// overwritten by the element tangent (the caller needs not zero
    /// them). For a model without integration points, a copy of the
    /// [`BulkTangent`] (assembled by the element loop at the first call
    /// for a scatter map) and `f_int = K u`; otherwise the element loop.
    pub fn assemble_tangent(
        &mut self,
        mesh: &Mesh<D>,
        scatter: &Scatter,
        u: &[[f64; D]],
        f_int: &mut [f64],
        values: &mut [f64],
    ) -> Result<(), String> {
        let par = (super::parallel::threads(), PARALLEL_MIN_CELLS);
        if !self.bulk_applies() {
            values.fill(0.0);
            return self.element_loop(mesh, scatter, u, f_int, Some(values), par);
        }
        self.linear_tangent(mesh, scatter, u, f_int, values, par)
    }

    /// Whether the [`BulkTangent`] path applies: no integration points,
    /// the cache on, not a rank's share of a distributed assembly (whose
    /// partial forces stay the element loop's).
    pub fn bulk_applies(&self) -> bool {
        !self.has_points() && !self.bulk.disabled && self.share.is_none()
    }

    /// The element tangent of a linear model into `values` (overwritten):
    /// the bulk of `scatter`, assembled by the element loop into zeroed
    /// values when not held yet; and the forces
    /// ([`Assembler::linear_forces`]).
    fn linear_tangent(
        &mut self,
        mesh: &Mesh<D>,
        scatter: &Scatter,
        u: &[[f64; D]],
        f_int: &mut [f64],
        values: &mut [f64],
        par: (usize, usize),
    ) -> Result<(), String> {
        if !self.bulk.copy_to(scatter.id(), values) {
            values.fill(0.0);
            self.element_loop(mesh, scatter, u, f_int, Some(values), par)?;
            self.bulk.store(scatter.id(), values.to_vec());
        }
        self.linear_forces(mesh, u, f_int, par.0);
        Ok(())
    }

    /// `f_int = K u - eps_th f_unit` of a linear model: the stiffness over
    /// all dofs of the [`BulkTangent`] (assembled from the element matrices
    /// at the first call), then the thermal forces cell by cell.
    fn linear_forces(&mut self, mesh: &Mesh<D>, u: &[[f64; D]], f_int: &mut [f64], threads: usize) {
        let (blocks, linear_k, offset) = (&self.blocks, &self.linear_k, &self.linear_offset);
        self.bulk.forces(u.as_flattened(), f_int, threads, || {
            let cells: Vec<usize> = blocks.iter().flat_map(|b| b.cells.clone()).collect();
            DofMatrix::assemble(mesh, &cells, |c| {
                let nd = D * mesh.cells.nodes(c).len();
                &linear_k[offset[c]..][..nd * nd]
            })
            .expect("the dof count was checked by the dof map")
        });
        self.assembled = self.blocks.iter().map(|b| b.cells.len()).sum();
        for (c, &e) in self.thermal_strain.iter().enumerate() {
            if e == 0.0 {
                continue;
            }
            for (a, &n) in mesh.cells.nodes(c).iter().enumerate() {
                for i in 0..D {
                    f_int[D * n + i] -= e * self.thermal_unit[c][a][i];
                }
            }
        }
    }

    /// Tangents taken from the [`BulkTangent`] instead of the element
    /// loop, and bulk assemblies (one per scatter map).
    pub fn bulk_counts(&self) -> (usize, usize) {
        (self.bulk.reuses, self.bulk.builds)
    }

    /// Turns the [`BulkTangent`] off (`false`: the element loop assembles
    /// every tangent and force) or on (the default).
    pub fn set_bulk_tangent(&mut self, enabled: bool) {
        self.bulk.disabled = !enabled;
        self.bulk.clear();
    }

    /// The element loop of [`Assembler::assemble_with`]: forces, and the
    /// tangent when `values` is given.
    fn element_loop(
        &mut self,
        mesh: &Mesh<D>,
        scatter: &Scatter,
        u: &[[f64; D]],
        f_int: &mut [f64],
        values: Option<&mut [f64]>,
        (threads, min_cells): (usize, usize),
    ) -> Result<(), String> {
        if threads > 1 && self.share.is_none() && mesh.cells.len() >= min_cells.max(2) {
            let key = (threads, scatter.id());
            if self.plan.as_ref().is_none_or(|p| p.key != key) {
                self.plan = Plan::new(key, mesh, &self.blocks, scatter).map(Arc::new);
            }
            if let Some(plan) = self.plan.clone() {
                return self.assemble_parallel(&plan, mesh, scatter, u, f_int, values);
            }
        }
        self.assemble_serial(mesh, scatter, u, f_int, values)
    }

    /// The element loop on one thread, in cell order.
    fn assemble_serial(
        &mut self,
        mesh: &Mesh<D>,
        scatter: &Scatter,
        u: &[[f64; D]],
        f_int: &mut [f64],
        values: Option<&mut [f64]>,
    ) -> Result<(), String> {
        f_int.fill(0.0);
        let mut trial = std::mem::take(&mut self.trial);
        let r = self.serial_loop(mesh, scatter, u, f_int, values, &mut trial);
        self.trial = trial;
        self.assembled = r?;
        Ok(())
    }

    /// The cells of [`Assembler::assemble_serial`], in order; the number
    /// of cells evaluated.
    fn serial_loop(
        &self,
        mesh: &Mesh<D>,
        scatter: &Scatter,
        u: &[[f64; D]],
        f_int: &mut [f64],
        mut values: Option<&mut [f64]>,
        trial: &mut [Vec<MaterialPoint>],
    ) -> Result<usize, String> {
        let cx = self.context(mesh, u, values.is_some());
        let mut cell = CellWork::default();
        let mut assembled = 0;
        for (b, block) in self.blocks.iter().enumerate() {
            for c in block.cells.clone() {
                if self.share.as_ref().is_some_and(|s| !s.owns_cell(c)) {
                    continue;
                }
                assembled += 1;
                let nd = cx.element(b, c, &mut cell, &mut trial[c])?;
                let k = cx.stiffness(c, nd, &cell);
                let nodes = mesh.cells.nodes(c);
                for (i, f) in cell.fe[..nd].iter().enumerate() {
                    f_int[D * nodes[i / D] + i % D] += f;
                }
                if let Some(values) = values.as_deref_mut() {
                    for (&slot, kij) in scatter.cell_slots(c).iter().zip(k) {
                        if slot != NO_SLOT {
                            values[slot as usize] += kij;
                        }
                    }
                }
            }
        }
        Ok(assembled)
    }

    /// The shared, read-only inputs of the element loop.
    fn context<'a>(
        &'a self,
        mesh: &'a Mesh<D>,
        u: &'a [[f64; D]],
        with_tangent: bool,
    ) -> Cx<'a, D> {
        Cx {
            mesh,
            u,
            with_tangent,
            blocks: &self.blocks,
            section: &self.section,
            committed: &self.committed,
            dt: self.dt,
            linear_k: &self.linear_k,
            linear_offset: &self.linear_offset,
            thermal_strain: &self.thermal_strain,
            thermal_unit: &self.thermal_unit,
            cell_law: &self.cell_law,
        }
    }

    /// The element loop on the threads of `plan` (see [`Plan`]): the same
    /// bits as [`Assembler::assemble_serial`].
    fn assemble_parallel(
        &mut self,
        plan: &Plan,
        mesh: &Mesh<D>,
        scatter: &Scatter,
        u: &[[f64; D]],
        f_int: &mut [f64],
        values: Option<&mut [f64]>,
    ) -> Result<(), String> {
        f_int.fill(0.0);
        let mut trial = std::mem::take(&mut self.trial);
        let r = self.parallel_loop(plan, mesh, scatter, u, f_int, values, &mut trial);
        self.trial = trial;
        self.assembled = plan.seq.len();
        r
    }

    /// The threads of [`Assembler::assemble_parallel`].
    #[allow(clippy::too_many_arguments)]
    fn parallel_loop(
        &self,
        plan: &Plan,
        mesh: &Mesh<D>,
        scatter: &Scatter,
        u: &[[f64; D]],
        f_int: &mut [f64],
        mut values: Option<&mut [f64]>,
        all_trial: &mut [Vec<MaterialPoint>],
    ) -> Result<(), String> {
        use super::parallel::Disjoint;
        let with_tangent = values.is_some();
        // each chunk's trial points: its cells are a range of global cells
        let mut trial: Vec<&mut [Vec<MaterialPoint>]> = Vec::with_capacity(plan.chunks.len());
        let mut rest = all_trial;
        let mut offset = 0;
        let mut first_cell = Vec::with_capacity(plan.chunks.len());
        for (k, chunk) in plan.chunks.iter().enumerate() {
            let lo = plan.seq[chunk.start].1;
            let hi = plan
                .chunks
                .get(k + 1)
                .map_or(rest.len() + offset, |n| plan.seq[n.start].1);
            let (head, tail) = std::mem::take(&mut rest).split_at_mut(hi - offset);
            trial.push(&mut head[lo - offset..]);
            first_cell.push(lo);
            rest = tail;
            offset = hi;
        }
        let cx = self.context(mesh, u, with_tangent);
        let force_out = Disjoint::new(f_int);
        let value_out = values.as_deref_mut().map(Disjoint::new);
        let run_chunk = |k: usize, trial: &mut [Vec<MaterialPoint>]| -> Result<Vec<f64>, String> {
            let mut kept = Vec::new();
            let mut cell = CellWork::default();
            let owner = k as u32;
            for q in plan.chunks[k].clone() {
                let (b, c) = plan.seq[q];
                let nd = cx.element(b, c, &mut cell, &mut trial[c - first_cell[k]])?;
                let k_e = cx.stiffness(c, nd, &cell);
                let nodes = mesh.cells.nodes(c);
                for (i, &f) in cell.fe[..nd].iter().enumerate() {
                    let g = D * nodes[i / D] + i % D;
                    if plan.force_owner[g] == owner {
                        // SAFETY: force entry `g` is owned by this chunk only
                        unsafe { force_out.add(g, f) };
                    }
                }
                if let Some(out) = &value_out {
                    for (&slot, &kij) in scatter.cell_slots(c).iter().zip(k_e) {
                        if slot != NO_SLOT && plan.slot_owner[slot as usize] == owner {
                            // SAFETY: value slot `slot` is owned by this chunk only
                            unsafe { out.add(slot as usize, kij) };
                        }
                    }
                }
                if plan.interface[q] {
                    kept.extend_from_slice(&cell.fe[..nd]);
                    if with_tangent {
                        kept.extend_from_slice(k_e);
                    }
                }
            }
            Ok(kept)
        };
        let results: Vec<Result<Vec<f64>, String>> = std::thread::scope(|scope| {
            let mut handles = Vec::new();
            let mut chunks = trial.into_iter().enumerate();
            let own = chunks.next();
            for (k, t) in chunks {
                let run = &run_chunk;
                handles.push(scope.spawn(move || run(k, t)));
            }
            let mut out = vec![own.map_or(Ok(Vec::new()), |(k, t)| run_chunk(k, t))];
            for h in handles {
                out.push(
                    h.join()
                        .unwrap_or_else(|_| Err("an assembly thread panicked".into())),
                );
            }
            out
        });
        // the shared entries: interface cells in the serial order
        for (k, kept) in results.into_iter().enumerate() {
            let kept = kept?;
            let mut at = 0;
            for q in plan.chunks[k].clone().filter(|&q| plan.interface[q]) {
                let c = plan.seq[q].1;
                let nodes = mesh.cells.nodes(c);
                let nd = D * nodes.len();
                for (i, f) in kept[at..at + nd].iter().enumerate() {
                    let g = D * nodes[i / D] + i % D;
                    if plan.force_owner[g] == SHARED {
                        f_int[g] += f;
                    }
                }
                at += nd;
                if let Some(values) = values.as_deref_mut() {
                    for (&slot, kij) in scatter.cell_slots(c).iter().zip(&kept[at..at + nd * nd]) {
                        if slot != NO_SLOT && plan.slot_owner[slot as usize] == SHARED {
                            values[slot as usize] += kij;
                        }
                    }
                    at += nd * nd;
                }
            }
        }
        Ok(())
    }
}

/// The read-only inputs of the element loop ([`Assembler::context`]).
struct Cx<'a, const D: usize> {
    mesh: &'a Mesh<D>,
    u: &'a [[f64; D]],
    with_tangent: bool,
    blocks: &'a [CellBlock],
    section: &'a Section,
    committed: &'a [Vec<MaterialPoint>],
    dt: f64,
    linear_k: &'a [f64],
    linear_offset: &'a [usize],
    thermal_strain: &'a [f64],
    thermal_unit: &'a [Vec<Point<D>>],
    cell_law: &'a [Option<crate::material::NonlinearLaw>],
}

/// One thread's element results: the force of the last cell (`a D + c`),
/// the stiffness of the last nonlinear cell (column-major) and the
/// kernel's scratch.
struct CellWork<const D: usize> {
    fe: [f64; MAX_DOFS],
    k: Vec<f64>,
    scratch: ElementMatrix<D>,
}

impl<const D: usize> Default for CellWork<D> {
    fn default() -> Self {
        CellWork {
            fe: [0.0; MAX_DOFS],
            k: Vec::new(),
            scratch: ElementMatrix::default(),
        }
    }
}

impl<const D: usize> Cx<'_, D>
where
    Const<D>: Dimension<D>,
{
    /// Evaluates cell `c` of block `b`: its force into `out.fe`, and for a
    /// nonlinear law its tangent into `out.k` (if asked) and its trial
    /// points into `trial`; returns the cell's dof count.
    fn element(
        &self,
        b: usize,
        c: usize,
        out: &mut CellWork<D>,
        trial: &mut [MaterialPoint],
    ) -> Result<usize, String> {
        let mesh = self.mesh;
        let block = &self.blocks[b];
        let nodes = mesh.cells.nodes(c);
        let nd = D * nodes.len();
        assert!(nd <= MAX_DOFS, "a cell has more than {MAX_DOFS} dofs");
        let thermal_strain = self.thermal_strain.get(c).copied().unwrap_or(0.0);
        if let Some(law) = &block.nonlinear {
            let law = self.cell_law.get(c).and_then(|l| l.as_ref()).unwrap_or(law);
            let history: Vec<History> = self.committed[c].iter().map(|p| p.history).collect();
            let kernel = kernel_of::<D>(mesh.cells.kind(c))
                .map_err(|e| format!("cell {c}: {}", e.message))?;
            let (x, ue) = cell_input(mesh, c, self.u);
            kernel
                .nonlinear(
                    &NonlinearInput {
                        x: &x,
                        u: &ue,
                        section: self.section,
                        formulation: block.formulation,
                        kinematics: block.kinematics,
                        law,
                        history: &history,
                        dt: self.dt,
                        thermal_strain,
                        with_tangent: self.with_tangent,
                    },
                    &mut out.scratch,
                    trial,
                )
                .map_err(|e| {
                    format!(
                        "body `{}` cell {} (global {c}): {}",
                        block.body,
                        c - block.cells.start,
                        e.message
                    )
                })?;
            let r = &out.scratch;
            for (a, f) in r.force.iter().enumerate() {
                out.fe[D * a..D * (a + 1)].copy_from_slice(f.as_slice());
            }
            out.k.clear();
            if self.with_tangent {
                out.k.extend((0..nd * nd).map(|e| r.entry(e % nd, e / nd)));
            }
            return Ok(nd);
        }
        let k = &self.linear_k[self.linear_offset[c]..][..nd * nd];
        let mut ue = [0.0; MAX_DOFS];
        for (a, &n) in nodes.iter().enumerate() {
            ue[D * a..D * (a + 1)].copy_from_slice(&self.u[n]);
        }
        // f_e = K_e u_e (column-major K_e)
        let fe = &mut out.fe;
        fe[..nd].fill(0.0);
        for (j, &uj) in ue[..nd].iter().enumerate() {
            for (f, kij) in fe[..nd].iter_mut().zip(&k[j * nd..(j + 1) * nd]) {
                *f += kij * uj;
            }
        }
        if thermal_strain != 0.0 {
            // sigma = D (B u - eps_th): f_int = K u - eps_th f_unit
            for (i, f) in fe[..nd].iter_mut().enumerate() {
                *f -= thermal_strain * self.thermal_unit[c][i / D][i % D];
            }
        }
        Ok(nd)
    }

    /// The stiffness of cell `c` (`nd` dofs) just evaluated into `cell`
    /// (column-major; empty without the tangent for a nonlinear cell).
    fn stiffness<'b>(&'b self, c: usize, nd: usize, cell: &'b CellWork<D>) -> &'b [f64] {
        match self.linear_offset[c] {
            NO_MATRIX => &cell.k,
            o => &self.linear_k[o..][..nd * nd],
        }
    }
}

impl Plan {
    /// The partition of `blocks`' cells among `key.0` threads for
    /// `scatter`; `None` when the cells are not in increasing order (the
    /// chunks' trial points would not be contiguous) or fewer than two
    /// chunks result.
    fn new<const D: usize>(
        key: (usize, u64),
        mesh: &Mesh<D>,
        blocks: &[CellBlock],
        scatter: &Scatter,
    ) -> Option<Plan> {
        let seq: Vec<(usize, usize)> = blocks
            .iter()
            .enumerate()
            .flat_map(|(b, block)| block.cells.clone().map(move |c| (b, c)))
            .collect();
        if seq.windows(2).any(|w| w[1].1 <= w[0].1) {
            return None;
        }
        let chunks = super::parallel::split(seq.len(), key.0);
        if chunks.len() < 2 {
            return None;
        }
        const FREE: u32 = u32::MAX - 1;
        let mut slot_owner = vec![FREE; scatter.n_values()];
        let mut force_owner = vec![FREE; D * mesh.nodes.len()];
        let claim = |owner: &mut u32, k: u32| {
            *owner = match *owner {
                FREE => k,
                o if o == k => k,
                _ => SHARED,
            }
        };
        for (k, chunk) in chunks.iter().enumerate() {
            for &(_, c) in &seq[chunk.clone()] {
                for &n in mesh.cells.nodes(c) {
                    for owner in &mut force_owner[D * n..D * (n + 1)] {
                        claim(owner, k as u32);
                    }
                }
                for &slot in scatter.cell_slots(c) {
                    if slot != NO_SLOT {
                        claim(&mut slot_owner[slot as usize], k as u32);
                    }
                }
            }
        }
        let interface = seq
            .iter()
            .map(|&(_, c)| {
                mesh.cells
                    .nodes(c)
                    .iter()
                    .any(|&n| force_owner[D * n] == SHARED)
                    || scatter
                        .cell_slots(c)
                        .iter()
                        .any(|&s| s != NO_SLOT && slot_owner[s as usize] == SHARED)
            })
            .collect();
        Some(Plan {
            key,
            seq,
            chunks,
            interface,
            slot_owner,
            force_owner,
        })
    }
}

/// Element stiffness matrices of the small-strain linear elastic cells
/// (column-major, concatenated) and each cell's offset (`NO_MATRIX` for the
/// others).
fn linear_matrices<const D: usize>(
    mesh: &Mesh<D>,
    blocks: &[CellBlock],
    section: &Section,
    share: Option<&AssemblyShare>,
    (threads, min_cells): (usize, usize),
) -> Result<(Vec<f64>, Vec<usize>), String>
where
    Const<D>: Dimension<D>,
{
    let cells: Vec<(&CellBlock, usize)> = blocks
        .iter()
        .filter(|b| b.nonlinear.is_none())
        .flat_map(|b| b.cells.clone().map(move |c| (b, c)))
        .filter(|&(_, c)| share.is_none_or(|s| s.owns_cell(c)))
        .collect();
    // each cell's matrix alone: chunks of cells on the threads, their
    // matrices concatenated in cell order (the same array on any count)
    let matrices = |part: &[(&CellBlock, usize)]| -> Result<Vec<f64>, String> {
        let entries = part
            .iter()
            .map(|&(_, c)| (D * mesh.cells.nodes(c).len()).pow(2))
            .sum();
        let mut k = Vec::with_capacity(entries);
        let mut out = ElementMatrix::<D>::default();
        // the nodes of a cell without an allocation per cell
        let mut points = [Point::<D>::zeros(); MAX_DOFS];
        let zero = [Point::<D>::zeros(); MAX_DOFS];
        for &(block, c) in part {
            let err = |e: crate::element::ElementError| format!("cell {c}: {}", e.message);
            let kernel = kernel_of::<D>(mesh.cells.kind(c)).map_err(err)?;
            let nodes = mesh.cells.nodes(c);
            let x = &mut points[..nodes.len()];
            for (p, &n) in x.iter_mut().zip(nodes) {
                *p = Point::<D>::from(mesh.nodes[n]);
            }
            let x: &[Point<D>] = x;
            kernel
                .linear(
                    x,
                    &zero[..x.len()],
                    section,
                    block.formulation,
                    &block.law,
                    true,
                    &mut out,
                )
                .map_err(err)?;
            let nd = D * x.len();
            for j in 0..nd {
                for i in 0..nd {
                    k.push(out.entry(i, j));
                }
            }
        }
        Ok(k)
    };
    let threads = if cells.len() >= min_cells { threads } else { 1 };
    let parts = super::parallel::split(cells.len(), threads);
    let results: Vec<Result<Vec<f64>, String>> = if parts.len() > 1 {
        std::thread::scope(|scope| {
            let matrices = &matrices;
            let handles: Vec<_> = parts[1..]
                .iter()
                .map(|r| {
                    let part = &cells[r.clone()];
                    scope.spawn(move || matrices(part))
                })
                .collect();
            let mut out = vec![matrices(&cells[parts[0].clone()])];
            for h in handles {
                out.push(
                    h.join()
                        .unwrap_or_else(|_| Err("an element thread panicked".into())),
                );
            }
            out
        })
    } else {
        vec![matrices(&cells)]
    };
    let mut results = results.into_iter();
    // one part (one thread): its array as it is, not a copy
    let mut k = results.next().transpose()?.unwrap_or_default();
    for r in results {
        k.extend_from_slice(&r?);
    }
    let mut offset = vec![NO_MATRIX; mesh.cells.len()];
    let mut at = 0;
    for &(_, c) in &cells {
        offset[c] = at;
        let nd = D * mesh.cells.nodes(c).len();
        at += nd * nd;
    }
    Ok((k, offset))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::Cell;
    use crate::model::{Hardening, Kinematics, MaterialLaw};
    use crate::solve::dofs::DofMap;

    fn plastic_square() -> Model {
        crate::testkit::ModelBuilder::plane_strain()
            .material(
                "m",
                MaterialLaw::ElastoPlastic {
                    young: 200e3,
                    poisson: 0.3,
                    hardening: Hardening::Linear {
                        yield_stress: 250.0,
                        modulus: 1000.0,
                    },
                    viscosity: None,
                },
            )
            .body(
                "sq",
                Mesh::new(
                    vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]],
                    vec![Cell::quad(0, 1, 2, 3)],
                ),
                "m",
            )
            .kinematics(Kinematics::Finite)
            .build()
    }

    /// Two elastic quads side by side (0-1-2 bottom, 3-4-5 top), node 0
    /// fixed.
    fn two_quads() -> Model {
        crate::testkit::ModelBuilder::plane_strain()
            .material(
                "m",
                MaterialLaw::LinearElastic {
                    young: 100.0,
                    poisson: 0.3,
                },
            )
            .body(
                "b",
                Mesh::new(
                    vec![
                        [0.0, 0.0],
                        [1.0, 0.0],
                        [2.0, 0.0],
                        [0.0, 1.0],
                        [1.0, 1.0],
                        [2.0, 1.0],
                    ],
                    vec![Cell::quad(0, 1, 4, 3), Cell::quad(1, 2, 5, 4)],
                ),
                "m",
            )
            .fix([0], 0)
            .fix([0], 1)
            .build()
    }

    /// A grid of `nx x ny` unit quads with its lower-left corner at `x0`.
    fn grid(nx: usize, ny: usize, x0: f64) -> Mesh {
        let nodes = (0..=ny)
            .flat_map(|j| (0..=nx).map(move |i| [x0 + i as f64, j as f64]))
            .collect();
        let cells = (0..ny)
            .flat_map(|j| {
                (0..nx).map(move |i| {
                    let a = j * (nx + 1) + i;
                    Cell::quad(a, a + 1, a + nx + 2, a + nx + 1)
                })
            })
            .collect();
        Mesh::new(nodes, cells)
    }

    #[test]
    fn one_two_and_three_threads_assemble_the_same_bits() {
        // an elastic body (cached element matrices) and a finite-strain
        // plastic one (integration points), fixed at node 0
        let model = crate::testkit::ModelBuilder::plane_strain()
            .elastic("e", 100.0, 0.3)
            .material(
                "p",
                MaterialLaw::ElastoPlastic {
                    young: 200e3,
                    poisson: 0.3,
                    hardening: Hardening::Linear {
                        yield_stress: 250.0,
                        modulus: 1000.0,
                    },
                    viscosity: None,
                },
            )
            .body("a", grid(6, 4, 0.0), "e")
            .body("b", grid(3, 2, 7.0), "p")
            .kinematics(Kinematics::Finite)
            .fix([0], 0)
            .fix([0], 1)
            .build();
        let dofs = DofMap::new(&model);
        let scatter = Scatter::new(&model.mesh, &dofs).unwrap();
        let nn = model.mesh.nodes.len();
        // yielding displacements, irregular enough to round differently
        // if the summation order changed
        let u: Vec<[f64; 2]> = (0..nn)
            .map(|n| {
                let t = n as f64;
                [
                    0.013 * (0.7 * t).sin() / 3.0,
                    -0.011 * (1.3 * t).cos() / 7.0,
                ]
            })
            .collect();
        let run = |threads: usize, tangent: bool| {
            let mut asm = Assembler::new(&model).unwrap();
            let mut f = vec![0.0; 2 * nn];
            let mut k = vec![0.0; scatter.n_values()];
            // values already hold something (the contact blocks)
            for (i, v) in k.iter_mut().enumerate() {
                *v = 1.0 / (3.0 + i as f64);
            }
            asm.assemble_with(
                &model.mesh,
                &scatter,
                &u,
                &mut f,
                tangent.then_some(&mut k[..]),
                (threads, 0),
            )
            .unwrap();
            assert_eq!(asm.assembled_cells(), model.mesh.cells.len());
            let used_plan = asm.plan.is_some();
            asm.commit();
            let points = format!("{:?}", asm.points());
            let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
            (bits(&f), bits(&k), points, used_plan)
        };
        for tangent in [true, false] {
            let serial = run(1, tangent);
            assert!(!serial.3);
            for threads in [2, 3, 7] {
                let par = run(threads, tangent);
                assert!(par.3, "{threads} threads: the parallel path ran");
                assert!(par.0 == serial.0, "{threads} threads: forces differ");
                assert!(par.1 == serial.1, "{threads} threads: tangent differs");
                assert!(par.2 == serial.2, "{threads} threads: points differ");
            }
        }
        // the cached element matrices: the same array on 1 and 3 threads
        let blocks = blocks_of(&model).unwrap();
        let section = Section::new(&model.analysis);
        let one = linear_matrices(&model.mesh, &blocks, &section, None, (1, 0)).unwrap();
        let three = linear_matrices(&model.mesh, &blocks, &section, None, (3, 0)).unwrap();
        assert_eq!(one.1, three.1);
        assert!(one
            .0
            .iter()
            .zip(&three.0)
            .all(|(a, b)| a.to_bits() == b.to_bits()));
        assert_eq!(one.0.len(), 24 * 64);
        // the partition has shared entries (the test covers both paths)
        let plan = Plan::new(
            (2, scatter.id()),
            &model.mesh,
            &blocks_of(&model).unwrap(),
            &scatter,
        )
        .unwrap();
        assert!(plan.slot_owner.contains(&SHARED) && plan.slot_owner.contains(&0));
        assert!(plan.interface.iter().any(|&i| i) && !plan.interface.iter().all(|&i| i));
    }

    #[test]
    fn two_ranks_shares_assemble_their_own_cells_and_sum_to_the_whole() {
        // rank 0 owns cell 0 and nodes 0, 1, 3, 4; rank 1 cell 1 and 2, 5
        let model = two_quads();
        let dofs = DofMap::new(&model);
        let u: Vec<[f64; 2]> = (0..6)
            .map(|n| [0.01 * n as f64, -0.02 * (n % 3) as f64])
            .collect();
        let whole_scatter = Scatter::new(&model.mesh, &dofs).unwrap();
        let mut whole = Assembler::new(&model).unwrap();
        let mut f = vec![0.0; 12];
        let mut k = vec![0.0; whole_scatter.n_values()];
        whole
            .assemble(&model.mesh, &whole_scatter, &u, &mut f, Some(&mut k))
            .unwrap();
        assert_eq!(whole.assembled_cells(), 2);
        let mut f_sum = [0.0; 12];
        let mut k_sum = vec![0.0; whole_scatter.pattern.nnz()];
        for (cells, nodes) in [
            ([true, false], [true, true, false, true, true, false]),
            ([false, true], [false, false, true, false, false, true]),
        ] {
            let share = Arc::new(AssemblyShare {
                ranks: 2,
                cells: cells.to_vec(),
                nodes: nodes.to_vec(),
                exchanged: vec![true; cells.len()],
            });
            let scatter =
                Scatter::with_share(&model.mesh, &dofs, &[], Some(share.clone())).unwrap();
            // the couplings of its cell only: fewer entries, no slots for
            // the other cell, node blocks of its own nodes only
            assert!(scatter.pattern.nnz() < whole_scatter.pattern.nnz());
            let other = usize::from(cells[0]);
            assert!(scatter.cell_slots(other).is_empty());
            for (n, &own) in nodes.iter().enumerate() {
                let has_block = scatter.node_slots(n).iter().any(|&s| s != NO_SLOT);
                assert_eq!(has_block, own && n != 0, "node {n}");
            }
            let mut asm = Assembler::with_share(&model, Some(share)).unwrap();
            let mut fr = vec![0.0; 12];
            let mut kr = vec![0.0; scatter.n_values()];
            asm.assemble(&model.mesh, &scatter, &u, &mut fr, Some(&mut kr))
                .unwrap();
            assert_eq!(asm.assembled_cells(), 1);
            for (a, b) in f_sum.iter_mut().zip(&fr) {
                *a += b;
            }
            // each rank's entries added into the whole pattern (PETSc's
            // ADD_VALUES)
            let p = &scatter.pattern;
            for j in 0..p.n {
                let range = p.col_ptr[j]..p.col_ptr[j + 1];
                for (&i, v) in p.row_idx[range.clone()].iter().zip(&kr[range]) {
                    k_sum[whole_scatter.pattern.find(i, j).unwrap()] += v;
                }
            }
        }
        for (a, b) in f_sum.iter().zip(&f) {
            assert!((a - b).abs() <= 1e-12 * (1.0 + b.abs()), "{a} vs {b}");
        }
        for (a, b) in k_sum.iter().zip(&k) {
            assert!((a - b).abs() <= 1e-12 * (1.0 + b.abs()), "{a} vs {b}");
        }
    }

    /// The plastic two quads (`plastic_square`'s material) with the body's
    /// kinematics `kin`, its dofs, a displacement that yields them, and the
    /// whole assembler after one committed assembly at that displacement.
    fn plastic_two_quads_committed(kin: Kinematics) -> (Model, DofMap, Vec<[f64; 2]>, Assembler) {
        let mut model = two_quads();
        model.materials = plastic_square().materials.clone();
        model.bodies[0].kinematics = kin;
        let dofs = DofMap::new(&model);
        let u: Vec<[f64; 2]> = (0..6)
            .map(|n| [0.02 * (n % 3) as f64, -0.01 * (n / 3) as f64])
            .collect();
        let mut whole = Assembler::new(&model).unwrap();
        let scatter = Scatter::new(&model.mesh, &dofs).unwrap();
        let mut f = vec![0.0; 12];
        whole.begin_increment(1.0);
        whole
            .assemble(&model.mesh, &scatter, &u, &mut f, None)
            .unwrap();
        whole.commit();
        (model, dofs, u, whole)
    }

    /// A rank's assembler of `share` after one committed assembly at `u`.
    fn rank_assembler_committed(
        model: &Model,
        dofs: &DofMap,
        u: &[[f64; 2]],
        share: Arc<AssemblyShare>,
    ) -> Assembler {
        let scatter = Scatter::with_share(&model.mesh, dofs, &[], Some(share.clone())).unwrap();
        let mut asm = Assembler::with_share(model, Some(share)).unwrap();
        let mut f = vec![0.0; 12];
        asm.begin_increment(1.0);
        asm.assemble(&model.mesh, &scatter, u, &mut f, None)
            .unwrap();
        asm.commit();
        asm
    }

    #[test]
    fn two_ranks_exchange_their_committed_points_bit_for_bit() {
        // the plastic finite-strain law on the two quads: each rank
        // evaluates its cell; after commit and exchange both hold the
        // points the whole assembler computed, bit for bit
        let (model, dofs, u, whole) = plastic_two_quads_committed(Kinematics::Finite);
        assert!(whole.points()[1][0].history.ep > 0.0, "plastic");
        let mut ranks = Vec::new();
        for cells in [[true, false], [false, true]] {
            // the two quads share an edge: both cells are exchanged
            let exchanged = AssemblyShare::exchanged_cells(
                &[model.mesh.cells.nodes(0), model.mesh.cells.nodes(1)],
                &[0, 1],
                6,
            );
            assert_eq!(exchanged, [true, true]);
            let share = Arc::new(AssemblyShare {
                ranks: 2,
                cells: cells.to_vec(),
                nodes: vec![cells[0]; 6],
                exchanged,
            });
            let asm = rank_assembler_committed(&model, &dofs, &u, share);
            ranks.push(asm);
        }
        // before the exchange a rank holds virgin points of the other cell
        assert_eq!(ranks[0].points()[1][0].history.ep, 0.0);
        // the sum over ranks of the packed vectors (as MPI's reduction)
        let mut packed: Vec<Vec<f64>> = Vec::new();
        for r in &ranks {
            r.clone().exchange_points(|v| packed.push(v.to_vec()));
        }
        let total: Vec<f64> = packed[0]
            .iter()
            .zip(&packed[1])
            .map(|(a, b)| a + b)
            .collect();
        for r in &mut ranks {
            r.exchange_points(|v| v.copy_from_slice(&total));
            assert_eq!(format!("{:?}", r.points()), format!("{:?}", whole.points()));
            // a rollback keeps them
            r.rollback();
            assert_eq!(format!("{:?}", r.points()), format!("{:?}", whole.points()));
        }
        // one rank: nothing exchanged
        let mut one = whole.clone();
        one.exchange_points(|_| panic!("no exchange without a split share"));
    }

    #[test]
    fn a_rank_holds_its_own_points_and_the_restart_file_gathers_them_all() {
        // the plastic two quads, each cell on its rank, no cell exchanged
        // (as cells far from the border between the parts): a rank holds
        // the points of its cell only; gathered on the first rank they are
        // the whole assembler's, bit for bit, and a restart from them gives
        // each rank its own cell's points back
        // the small-strain kinematics of `two_quads`
        let small = two_quads().bodies[0].kinematics;
        let (model, dofs, u, whole) = plastic_two_quads_committed(small);
        assert!(whole.points().iter().all(|p| p.len() == 4));
        let mut ranks = Vec::new();
        for cells in [[true, false], [false, true]] {
            let share = Arc::new(AssemblyShare {
                ranks: 2,
                cells: cells.to_vec(),
                nodes: vec![cells[0]; 6],
                exchanged: vec![false; 2],
            });
            let mut asm = rank_assembler_committed(&model, &dofs, &u, share);
            // nothing to exchange
            asm.exchange_points(|v| assert!(v.is_empty()));
            ranks.push(asm);
        }
        for (r, asm) in ranks.iter().enumerate() {
            assert!(asm.holds(r) && !asm.holds(1 - r));
            assert_eq!(asm.points()[1 - r].len(), 0, "the other rank's cell");
            assert_eq!(
                format!("{:?}", asm.points()[r]),
                format!("{:?}", whole.points()[r])
            );
        }
        // the gather: each rank's vector, concatenated on the first
        let locals: Vec<Vec<f64>> = ranks
            .iter()
            .map(|a| {
                let mut mine = Vec::new();
                a.gathered_points(|v| {
                    mine = v.to_vec();
                    None
                });
                mine
            })
            .collect();
        let all: Vec<f64> = locals.concat();
        let gathered = ranks[0].gathered_points(|_| Some(all.clone()));
        assert_eq!(format!("{gathered:?}"), format!("{:?}", whole.points()));
        // another rank keeps no copy
        assert!(ranks[1].gathered_points(|_| None).is_empty());
        // restart: each rank keeps its own cell's points
        for (r, asm) in ranks.iter_mut().enumerate() {
            let mut fresh = asm.clone();
            fresh.rollback();
            fresh.restore(&gathered, 1.0).unwrap();
            assert_eq!(
                format!("{:?}", fresh.points()[r]),
                format!("{:?}", whole.points()[r])
            );
            assert!(fresh.points()[1 - r].is_empty());
            // a layout that does not match is refused
            let mut short = gathered.clone();
            short[r].pop();
            assert!(fresh.restore(&short, 1.0).is_err());
        }
        // an elastic model: nothing gathered, the empty layout of every cell
        let elastic = two_quads();
        let share = Arc::new(AssemblyShare {
            ranks: 2,
            cells: vec![true, false],
            nodes: vec![true; 6],
            exchanged: vec![false; 2],
        });
        let asm = Assembler::with_share(&elastic, Some(share)).unwrap();
        assert_eq!(asm.gathered_points(|_| panic!("no gather")).len(), 2);
        // serial: the points are the committed ones
        assert_eq!(
            format!("{:?}", whole.gathered_points(|_| panic!("no gather"))),
            format!("{:?}", whole.points())
        );
    }

    #[test]
    fn integration_point_state_is_committed_only_on_commit_and_rolled_back() {
        let model = plastic_square();
        let dofs = DofMap::new(&model);
        let scatter = Scatter::new(&model.mesh, &dofs).unwrap();
        let mut asm = Assembler::new(&model).unwrap();
        let mut f = vec![0.0; 8];
        // stretch 5 % in x: plastic
        let u = [[0.0, 0.0], [0.05, 0.0], [0.05, 0.0], [0.0, 0.0]];
        asm.begin_increment(1.0);
        asm.assemble(&model.mesh, &scatter, &u, &mut f, None)
            .unwrap();
        assert!(asm.trial[0].iter().all(|p| p.history.ep > 0.01));
        assert!(asm.points()[0].iter().all(|p| p.history.ep == 0.0));
        // a failed attempt is forgotten
        asm.rollback();
        assert!(asm.trial[0].iter().all(|p| p.history.ep == 0.0));
        asm.begin_increment(1.0);
        asm.assemble(&model.mesh, &scatter, &u, &mut f, None)
            .unwrap();
        let ep = asm.trial[0][0].history.ep;
        asm.commit();
        assert_eq!(asm.points()[0][0].history.ep, ep);
        // small unloading (0.1 % < 2 sigma_y / E): elastic, ep unchanged
        asm.begin_increment(2.0);
        let back = [[0.0, 0.0], [0.049, 0.0], [0.049, 0.0], [0.0, 0.0]];
        asm.assemble(&model.mesh, &scatter, &back, &mut f, None)
            .unwrap();
        assert_eq!(asm.trial[0][0].history.ep, ep);
        assert!(!asm.symmetric() || asm.has_points());
    }
}
