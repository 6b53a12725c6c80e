//! Result writers: VTU per increment + PVD index, CSV histories, contact
//! pressure along each surface, JSON run summary.
//!
//! Files in the result directory:
//! - `inc_NNNN.vtu`: every `output.every` converged increments and always
//!   the last one of the analysis (and, on failure, the last converged one);
//!   under `mpirun -n N ctc run --solver petsc` instead `inc_NNNN.pvtu`
//!   (written by rank 0) listing the pieces `inc_NNNN_p<rank>.vtu`, each
//!   rank's cells written by that rank ([`Pieces`], [`PieceWriter`]);
//! - `tool_<k>_NNNN.vtu`: the current geometry of rigid tool `k` at each
//!   written increment ([`tool_vtu`]);
//! - `results.pvd`: the time series, rewritten after each VTU, so a killed
//!   run leaves a valid index; the bodies are part 0, tool `k` part `k + 1`;
//! - `history.csv`: one row per converged increment (flushed each time);
//! - `contact_<pair>_<NNNN>.csv`: the slave nodes of each pair at each
//!   written increment;
//! - `summary.json`: the run summary, written by [`ResultWriter::finish`];
//! - `thickness.csv`: with `output { thickness = (a, b) }`, the thickness
//!   along the first face set at the last written increment
//!   ([`thickness`]);
//! - `progress.sta`: one line per converged increment (step, increment,
//!   attempts, Newton iterations, total and step time, increment size,
//!   closed contact nodes, largest penetration, last residual), flushed
//!   each time, like Abaqus' `.sta` file; the last line says how the run
//!   ended ([`sta`]);
//! - `restart.bin`: the restart point of the last written increment
//!   ([`crate::solve::restart`]); [`ResultWriter::resume`] continues a
//!   stopped run in the same directory.
//!
//! A run into an existing directory first removes the files a previous
//! run left there under these names ([`is_result_file`]: a stale
//! `inc_0042.vtu` of a longer run would otherwise sit beside the new ones);
//! other files are left alone.
//!
//! VTU, PVD, contact CSV, restart and summary files are replaced atomically
//! (temporary file + rename); the restart file is written after the
//! increment's other files, so it never points past what is on disk.

pub mod atomic;
pub mod contact_csv;
pub mod encode;
pub mod history;
pub mod pvd;
pub mod roughness;
pub mod sta;
pub mod thickness;
pub mod tool_vtu;
pub mod vtu;
pub mod vtu_read;

use crate::contact::NodeContact;
use crate::element::recovery::nodal_fields_of_model_with_points;
use crate::geom::Dimension;
use crate::model::{Field, Model};
use crate::solve::restart::{Checkpoint, RestartFile};
use crate::solve::scene::ContactScene;
use crate::solve::{IncrementView, Observer, RunSummary};
use atomic::write_atomic;
use history::HistoryWriter;
use nalgebra::Const;
use std::path::{Path, PathBuf};

/// A converged increment kept until it is written.
#[derive(Debug, Clone)]
struct Snapshot<const D: usize> {
    step: usize,
    increment: usize,
    time: f64,
    displacement: Vec<[f64; D]>,
    reaction: Vec<[f64; D]>,
    contact: Vec<Vec<NodeContact<D>>>,
    /// Converged integration points of nonlinear bodies (may be empty).
    points: Vec<Vec<crate::element::MaterialPoint>>,
    /// Thermal strain per cell the increment was solved with (may be empty).
    thermal_strain: Vec<f64>,
    /// Nodal temperatures (thermal scenes only).
    temperature: Option<Vec<f64>>,
    /// Velocity and acceleration per dof (dynamic models, when requested).
    velocity: Option<Vec<f64>>,
    acceleration: Option<Vec<f64>>,
}

impl<const D: usize> Snapshot<D>
where
    Const<D>: Dimension<D>,
{
    /// The increment of `view` (velocity and acceleration when `model`
    /// asks for them).
    fn of(model: &Model<D>, view: &IncrementView<'_, D>) -> Snapshot<D> {
        Snapshot {
            step: view.step,
            increment: view.increment,
            time: view.time,
            displacement: view.displacement.to_vec(),
            reaction: view.reaction.to_vec(),
            contact: view.contact.to_vec(),
            points: view.points.to_vec(),
            thermal_strain: view.thermal_strain.to_vec(),
            temperature: view.temperature.map(<[f64]>::to_vec),
            velocity: view
                .velocity
                .filter(|_| model.output.fields.contains(&Field::Velocity))
                .map(<[f64]>::to_vec),
            acceleration: view
                .acceleration
                .filter(|_| model.output.fields.contains(&Field::Acceleration))
                .map(<[f64]>::to_vec),
        }
    }

    /// The recovered nodal and cell stresses and strains, when a field
    /// asks for them (those of `piece`'s cells and nodes only, when given).
    fn nodal_fields(
        &self,
        model: &Model<D>,
        piece: Option<&[usize]>,
    ) -> Result<Option<crate::element::recovery::NodalFields>, String> {
        let needs_recovery = model
            .output
            .fields
            .iter()
            .any(|f| matches!(f, Field::Stress | Field::Strain | Field::VonMises));
        if !needs_recovery {
            return Ok(None);
        }
        nodal_fields_of_model_with_points(
            model,
            &self.displacement,
            &self.points,
            &self.thermal_strain,
            piece,
        )
        .map(Some)
    }
}

/// Whether the increment of `view` is written: every `output.every`
/// increments and the last one of the analysis.
fn written_now<const D: usize>(model: &Model<D>, view: &IncrementView<'_, D>) -> bool {
    let every = model.output.every.max(1);
    let last = view.step + 1 == model.steps.len()
        && model.steps.last().is_some_and(|s| view.time >= s.t_end);
    view.increment.is_multiple_of(every) || last
}

/// The pieces of a parallel output (`mpirun -n N ctc run --solver petsc`):
/// each rank writes the cells of its partition as `inc_NNNN_p<rank>.vtu`
/// ([`vtu::VtuData::piece`]: with the global `node` and `cell` numbers),
/// rank 0 also `inc_NNNN.pvtu`, which lists them and is what
/// `results.pvd` names.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Pieces {
    /// This rank.
    pub rank: usize,
    /// Ranks of the run (pieces of each increment).
    pub ranks: usize,
    /// This rank's cells (global numbers, increasing).
    pub cells: Vec<usize>,
}

impl Pieces {
    /// The file of rank `rank`'s piece of increment `increment`.
    pub fn file_name(increment: usize, rank: usize) -> String {
        format!("inc_{increment:04}_p{rank}.vtu")
    }

    /// Writes this rank's piece of `data` into `dir`; returns its bytes.
    fn write<const D: usize>(
        &self,
        dir: &Path,
        data: &vtu::VtuData<'_, D>,
    ) -> Result<Vec<u8>, String> {
        let bytes = vtu::vtu(&vtu::VtuData {
            piece: Some(&self.cells),
            ..*data
        });
        let name = Self::file_name(data.increment, self.rank);
        write_atomic(&dir.join(&name), &bytes)
            .map_err(|e| format!("cannot write results in {}: {e}", dir.display()))?;
        Ok(bytes)
    }
}

/// The [`Observer`] of the ranks other than 0 under `mpirun`: writes this
/// rank's piece of each written increment ([`Pieces`]) into the result
/// directory rank 0's [`ResultWriter`] made, nothing else.
#[derive(Debug)]
pub struct PieceWriter<'m, const D: usize = 2> {
    dir: PathBuf,
    model: &'m Model<D>,
    pieces: Pieces,
    pending: Option<Snapshot<D>>,
    /// Whether the last converged increment was written: rank 0's
    /// [`ResultWriter`] then writes a restart point, whose integration
    /// points every rank helps gather ([`Observer::wants_checkpoint`]).
    written_last: bool,
}

impl<'m, const D: usize> PieceWriter<'m, D>
where
    Const<D>: Dimension<D>,
{
    /// The writer of `pieces` of `model`'s results in `dir`.
    pub fn new(dir: &Path, model: &'m Model<D>, pieces: Pieces) -> Self {
        PieceWriter {
            dir: dir.to_path_buf(),
            model,
            pieces,
            pending: None,
            written_last: false,
        }
    }

    fn write(&self, snap: &Snapshot<D>) -> Result<(), String> {
        let model = self.model;
        let nodal = snap.nodal_fields(model, Some(&self.pieces.cells))?;
        crate::solve::memory::trace("output: stress recovery");
        let thickness = model
            .output
            .thickness
            .as_ref()
            .filter(|_| D == 3)
            .map(|t| thickness::nodal(&model.mesh, t, &snap.displacement));
        self.pieces
            .write(
                &self.dir,
                &vtu::VtuData {
                    model,
                    step: model.steps.get(snap.step).map_or("", |s| s.name.as_str()),
                    increment: snap.increment,
                    time: snap.time,
                    fields: &model.output.fields,
                    displacement: &snap.displacement,
                    reaction: &snap.reaction,
                    contact: &snap.contact,
                    nodal: nodal.as_ref(),
                    temperature: snap.temperature.as_deref(),
                    thickness: thickness.as_deref(),
                    velocity: snap.velocity.as_deref(),
                    acceleration: snap.acceleration.as_deref(),
                    encoding: model.output.format,
                    piece: None,
                },
            )
            .map(|_| ())
    }

    /// Writes the last converged increment if it was not written (as
    /// [`ResultWriter::finish`] does).
    pub fn finish(&mut self) -> Result<(), String> {
        match self.pending.take() {
            Some(snap) => self.write(&snap),
            None => Ok(()),
        }
    }
}

impl<const D: usize> Observer<D> for PieceWriter<'_, D>
where
    Const<D>: Dimension<D>,
{
    fn converged(&mut self, view: &IncrementView<'_, D>) -> Result<(), String> {
        let snap = Snapshot::of(self.model, view);
        crate::solve::memory::trace("output: snapshot");
        self.written_last = written_now(self.model, view);
        if self.written_last {
            self.pending = None;
            let r = self.write(&snap);
            crate::solve::memory::trace("output: vtu piece written");
            r
        } else {
            self.pending = Some(snap);
            Ok(())
        }
    }

    /// When rank 0 writes a restart point: building the checkpoint gathers
    /// the integration points on rank 0 (collective); this rank's copy is
    /// not kept.
    fn wants_checkpoint(&self) -> bool {
        self.written_last
    }
}

/// Writes a run's results into a directory (an [`Observer`]) for a model
/// of dimension `D`.
#[derive(Debug)]
pub struct ResultWriter<const D: usize = 2> {
    dir: PathBuf,
    model: Model<D>,
    history: HistoryWriter,
    pvd: Vec<(f64, String)>,
    pending: Option<Snapshot<D>>,
    /// Whether the last converged increment was written (a restart point
    /// is written only then).
    written_last: bool,
    /// Files of a previous run removed by [`ResultWriter::create`].
    removed: usize,
    /// `progress.sta`.
    sta: sta::StaWriter,
    /// Under `mpirun`: rank 0's piece; the VTU of an increment is then a
    /// `.pvtu` of the ranks' pieces ([`Pieces`]).
    pieces: Option<Pieces>,
}

/// Whether `name` is a file that a run writes into its result directory
/// (or the temporary of one): `inc_<n>.vtu`, `inc_<n>.pvtu`,
/// `inc_<n>_p<rank>.vtu`, `tool_<k>_<n>.vtu`,
/// `contact_<pair>_<n>.csv`,
/// `results.pvd`, `history.csv`, `summary.json`, `restart.bin`,
/// `progress.sta`.
pub fn is_result_file(name: &str) -> bool {
    let name = match name.strip_prefix('.').and_then(|n| n.strip_suffix(".tmp")) {
        Some(inner) => inner,
        None => name,
    };
    let digits = |s: &str| !s.is_empty() && s.bytes().all(|b| b.is_ascii_digit());
    if let Some(n) = name
        .strip_prefix("inc_")
        .and_then(|n| n.strip_suffix(".vtu"))
    {
        // a piece of a parallel run: inc_<n>_p<rank>.vtu
        return match n.split_once("_p") {
            Some((n, rank)) => digits(n) && digits(rank),
            None => digits(n),
        };
    }
    if let Some(n) = name
        .strip_prefix("inc_")
        .and_then(|n| n.strip_suffix(".pvtu"))
    {
        return digits(n);
    }
    for (prefix, suffix) in [("contact_", ".csv"), ("tool_", ".vtu")] {
        if let Some(rest) = name
            .strip_prefix(prefix)
            .and_then(|n| n.strip_suffix(suffix))
        {
            return rest
                .split_once('_')
                .is_some_and(|(p, n)| digits(p) && digits(n));
        }
    }
    [
        "results.pvd",
        "history.csv",
        "summary.json",
        "thickness.csv",
        RESTART_FILE,
        STA_FILE,
    ]
    .contains(&name)
}

/// Removes the result files ([`is_result_file`]) in `dir`; returns how
/// many.
fn remove_stale(dir: &Path) -> std::io::Result<usize> {
    let mut names: Vec<PathBuf> = Vec::new();
    for e in std::fs::read_dir(dir)? {
        let e = e?;
        if e.file_type()?.is_file() && e.file_name().to_str().is_some_and(is_result_file) {
            names.push(e.path());
        }
    }
    for p in &names {
        std::fs::remove_file(p)?;
    }
    Ok(names.len())
}

/// Name of the restart file in the result directory.
pub const RESTART_FILE: &str = "restart.bin";

/// Name of the one-line-per-increment progress log.
pub const STA_FILE: &str = "progress.sta";

impl<const D: usize> ResultWriter<D>
where
    Const<D>: Dimension<D>,
{
    /// Creates `dir` (and parents), removes the result files of a previous
    /// run in it, and prepares the writers for `model`.
    pub fn create(dir: &Path, model: &Model<D>) -> std::io::Result<Self> {
        std::fs::create_dir_all(dir)?;
        let removed = remove_stale(dir)?;
        let history = HistoryWriter::create(&dir.join("history.csv"), model)?;
        let sta = sta::StaWriter::create(&dir.join(STA_FILE))?;
        Ok(ResultWriter {
            dir: dir.to_path_buf(),
            model: model.clone(),
            history,
            pvd: Vec::new(),
            pending: None,
            written_last: false,
            removed,
            sta,
            pieces: None,
        })
    }

    /// How many result files of a previous run [`ResultWriter::create`]
    /// removed.
    pub fn removed(&self) -> usize {
        self.removed
    }

    /// Reopens `dir`, where a run of `model` stopped, to continue it from
    /// its restart point: returns the writer (history truncated to the
    /// restart point, PVD index as of the restart point) and the checkpoint
    /// to pass to [`crate::solve::run_from`].
    pub fn resume(dir: &Path, model: &Model<D>) -> Result<(Self, Checkpoint<D>), String> {
        let file = RestartFile::<D>::read(&dir.join(RESTART_FILE))?;
        if file.checkpoint.fingerprint != crate::solve::restart::fingerprint(model) {
            return Err(format!(
                "cannot restart from {}: it was written by a different model (the deck or a \
                 mesh file changed since); run from the start",
                dir.display()
            ));
        }
        let history =
            HistoryWriter::resume(&dir.join("history.csv"), model, file.checkpoint.increment)
                .map_err(|e| format!("cannot restart from {}: {e}", dir.display()))?;
        write_atomic(&dir.join("results.pvd"), pvd::pvd(&file.pvd).as_bytes())
            .map_err(|e| format!("cannot rewrite results.pvd in {}: {e}", dir.display()))?;
        let sta = sta::StaWriter::resume(
            &dir.join(STA_FILE),
            file.checkpoint.increment,
            file.checkpoint.resume.time,
        )
        .map_err(|e| format!("cannot reopen {STA_FILE} in {}: {e}", dir.display()))?;
        let writer = ResultWriter {
            dir: dir.to_path_buf(),
            model: model.clone(),
            history,
            pvd: file.pvd,
            pending: None,
            written_last: true,
            removed: 0,
            sta,
            pieces: None,
        };
        Ok((writer, file.checkpoint))
    }

    /// Writes the VTU of each increment as pieces, this one rank 0's
    /// ([`Pieces`]; the other ranks' [`PieceWriter`]s write theirs).
    pub fn set_pieces(&mut self, pieces: Pieces) {
        self.pieces = Some(pieces);
    }

    /// The result directory.
    pub fn dir(&self) -> &Path {
        &self.dir
    }

    /// Writes `summary.json` (call at the end, also after a failed run);
    /// writes the last converged increment first if it was not written.
    pub fn finish(&mut self, summary: &RunSummary) -> std::io::Result<()> {
        if let Some(snap) = self.pending.take() {
            self.write_increment(&snap).map_err(std::io::Error::other)?;
        }
        self.sta.finish(summary)?;
        let text = serde_json::to_string_pretty(summary).map_err(std::io::Error::other)?;
        write_atomic(&self.dir.join("summary.json"), text.as_bytes())
    }

    fn write_increment(&mut self, snap: &Snapshot<D>) -> Result<(), String> {
        let model = &self.model;
        let fields = &model.output.fields;
        let nodal = snap.nodal_fields(model, self.pieces.as_ref().map(|p| &p.cells[..]))?;
        crate::solve::memory::trace("output: stress recovery");
        let io = |e: std::io::Error| format!("cannot write results in {}: {e}", self.dir.display());
        let thickness = model
            .output
            .thickness
            .as_ref()
            .filter(|_| D == 3)
            .map(|t| (t, thickness::nodal(&model.mesh, t, &snap.displacement)));
        if let Some((request, values)) = &thickness {
            let csv = thickness::csv(&model.mesh, request, values, &snap.displacement);
            write_atomic(&self.dir.join("thickness.csv"), csv.as_bytes()).map_err(io)?;
        }
        let data = vtu::VtuData {
            model,
            step: model.steps.get(snap.step).map_or("", |s| s.name.as_str()),
            increment: snap.increment,
            time: snap.time,
            fields,
            displacement: &snap.displacement,
            reaction: &snap.reaction,
            contact: &snap.contact,
            nodal: nodal.as_ref(),
            temperature: snap.temperature.as_deref(),
            thickness: thickness.as_ref().map(|(_, v)| v.as_slice()),
            velocity: snap.velocity.as_deref(),
            acceleration: snap.acceleration.as_deref(),
            encoding: model.output.format,
            piece: None,
        };
        let name = match &self.pieces {
            None => {
                let name = format!("inc_{:04}.vtu", snap.increment);
                write_atomic(&self.dir.join(&name), &vtu::vtu(&data)).map_err(io)?;
                name
            }
            Some(pieces) => {
                // this rank's piece, and the parallel file of all of them
                let bytes = pieces.write(&self.dir, &data)?;
                let name = format!("inc_{:04}.pvtu", snap.increment);
                let sources: Vec<String> = (0..pieces.ranks)
                    .map(|r| Pieces::file_name(snap.increment, r))
                    .collect();
                write_atomic(
                    &self.dir.join(&name),
                    vtu::pvtu(&bytes, &sources).as_bytes(),
                )
                .map_err(io)?;
                name
            }
        };
        for (p, list) in snap.contact.iter().enumerate() {
            let csv = <Const<D> as Dimension<D>>::Contact::contact_csv(
                model,
                p,
                &snap.displacement,
                list,
            );
            let file = format!("contact_{p}_{:04}.csv", snap.increment);
            write_atomic(&self.dir.join(file), csv.as_bytes()).map_err(io)?;
        }
        self.pvd.push((snap.time, name));
        if !model.tools.is_empty() {
            let extent = tool_vtu::extent(&model.mesh.nodes, &snap.displacement);
            for (k, tool) in model.tools.iter().enumerate() {
                let file = tool_vtu::file_name(k, snap.increment);
                // a free tool is drawn at its angle (its pilot node's x)
                let turned = tool.free_rotation.as_ref().map(|f| {
                    let mut t = tool.clone();
                    t.motion.rotation = crate::model::TimeFunction::Constant(
                        snap.displacement.get(f.node).map_or(0.0, |u| u[0]),
                    );
                    t
                });
                let bytes = tool_vtu::tool_vtu(
                    turned.as_ref().unwrap_or(tool),
                    k,
                    snap.time,
                    snap.increment,
                    extent,
                    model.output.format,
                );
                write_atomic(&self.dir.join(&file), &bytes).map_err(io)?;
                self.pvd.push((snap.time, file));
            }
        }
        write_atomic(
            &self.dir.join("results.pvd"),
            pvd::pvd(&self.pvd).as_bytes(),
        )
        .map_err(io)?;
        Ok(())
    }
}

impl<const D: usize> Observer<D> for ResultWriter<D>
where
    Const<D>: Dimension<D>,
{
    fn converged(&mut self, view: &IncrementView<'_, D>) -> Result<(), String> {
        let mut row = history::row(
            view.model,
            view.time,
            view.displacement,
            view.reaction,
            view.contact,
        );
        if let Some(e) = view.energy {
            row.extend([
                e.kinetic,
                e.internal,
                e.external,
                e.contact,
                e.damping,
                e.balance,
                e.gain,
                e.numerical,
                e.error,
            ]);
        }
        for c in view.controls {
            row.extend([c.pressure, c.rate]);
        }
        for t in view.tools {
            row.extend([t.angle, t.angular_velocity, t.moment, t.applied]);
        }
        if let Some(t) = view.thermal {
            row.extend([t.max_temperature, t.min_temperature]);
        }
        if let Some(t) = self.model.output.thickness.as_ref().filter(|_| D == 3) {
            let values = thickness::nodal(&self.model.mesh, t, view.displacement);
            let (min, at) = thickness::minimum(&self.model.mesh, t, &values);
            row.push(min);
            row.extend(at);
        }
        self.history
            .append(&row)
            .map_err(|e| format!("cannot write history.csv in {}: {e}", self.dir.display()))?;
        self.sta
            .increment(view)
            .map_err(|e| format!("cannot write {STA_FILE} in {}: {e}", self.dir.display()))?;
        let snap = Snapshot::of(&self.model, view);
        crate::solve::memory::trace("output: snapshot");
        if written_now(&self.model, view) {
            self.pending = None;
            self.written_last = true;
            let r = self.write_increment(&snap);
            crate::solve::memory::trace("output: vtu written (rank 0)");
            r
        } else {
            self.pending = Some(snap);
            self.written_last = false;
            Ok(())
        }
    }

    fn cutback(&mut self, _reason: &str, _new_dt: f64) {
        self.sta.cutback();
    }

    fn wants_checkpoint(&self) -> bool {
        self.written_last
    }

    fn checkpoint(&mut self, checkpoint: &Checkpoint<D>) -> Result<(), String> {
        let file = RestartFile {
            checkpoint: checkpoint.clone(),
            pvd: self.pvd.clone(),
        };
        write_atomic(&self.dir.join(RESTART_FILE), &file.encode()).map_err(|e| {
            format!(
                "cannot write the restart file in {}: {e}",
                self.dir.display()
            )
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn result_files_are_recognised_by_name() {
        for ours in [
            "inc_0001.vtu",
            "inc_0001.pvtu",
            "inc_0001_p1.vtu",
            ".inc_0003_p0.vtu.tmp",
            "inc_12345.vtu",
            "contact_0_0003.csv",
            "contact_12_0003.csv",
            "tool_0_0003.vtu",
            ".tool_1_0012.vtu.tmp",
            "results.pvd",
            "history.csv",
            "summary.json",
            "restart.bin",
            "progress.sta",
            ".inc_0002.vtu.tmp",
            ".summary.json.tmp",
        ] {
            assert!(is_result_file(ours), "{ours}");
        }
        for theirs in [
            "inc_.vtu",
            "inc_0001_p.vtu",
            "inc_0001_q1.vtu",
            "inc_x.pvtu",
            "inc_final.vtu",
            "inc_0001.vtu.bak",
            "contact_a_0001.csv",
            "contact_0001.csv",
            "tool_0001.vtu",
            "tool_a_0001.vtu",
            "notes.txt",
            "deck.ctc",
            "history.csv.old",
            "plot.svg",
            ".notes.tmp",
        ] {
            assert!(!is_result_file(theirs), "{theirs}");
        }
    }

    #[test]
    fn a_new_run_removes_the_files_of_the_previous_one_only() {
        let dir = tempfile::tempdir().unwrap();
        for f in [
            "inc_0007.vtu",
            "contact_0_0007.csv",
            "restart.bin",
            "notes.txt",
            "inc_final.vtu",
        ] {
            std::fs::write(dir.path().join(f), "old").unwrap();
        }
        std::fs::create_dir(dir.path().join("inc_0001.vtu")).unwrap();
        let model = crate::output::contact_csv::tests::model_with_pair();
        let w = ResultWriter::create(dir.path(), &model).unwrap();
        assert_eq!(w.removed(), 3);
        let mut left: Vec<String> = std::fs::read_dir(dir.path())
            .unwrap()
            .map(|e| e.unwrap().file_name().into_string().unwrap())
            .collect();
        left.sort();
        // a directory is never removed; history.csv and progress.sta are
        // the new run's
        assert_eq!(
            left,
            [
                "history.csv",
                "inc_0001.vtu",
                "inc_final.vtu",
                "notes.txt",
                "progress.sta"
            ]
        );
    }
}
