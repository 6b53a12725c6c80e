//! Result writers: VTU per increment + PVD index, CSV histories, contact
//! pressure along each surface, JSON run summary.
//!
//! Files in the result directory:
//! - `inc_NNNN.vtu`: every `output.every` converged increments and always
//!   the last one of the analysis (and, on failure, the last converged one);
//! - `results.pvd`: the time series, rewritten after each VTU, so a killed
//!   run leaves a valid index;
//! - `history.csv`: one row per converged increment (flushed each time);
//! - `contact_<pair>_<NNNN>.csv`: the slave nodes of each pair at each
//!   written increment;
//! - `summary.json`: the run summary, written by [`ResultWriter::finish`];
//! - `restart.bin`: the restart point of the last written increment
//!   ([`crate::solve::restart`]); [`ResultWriter::resume`] continues a
//!   stopped run in the same directory.
//!
//! VTU, PVD, contact CSV, restart and summary files are replaced atomically
//! (temporary file + rename); the restart file is written after the
//! increment's other files, so it never points past what is on disk.

pub mod atomic;
pub mod contact_csv;
pub mod history;
pub mod pvd;
pub mod vtu;

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
    contact: Vec<Vec<NodeContact>>,
    /// Converged integration points of nonlinear bodies (may be empty).
    points: Vec<Vec<crate::element::MaterialPoint>>,
    /// Nodal temperatures (thermal scenes only).
    temperature: Option<Vec<f64>>,
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
}

/// Name of the restart file in the result directory.
pub const RESTART_FILE: &str = "restart.bin";

impl<const D: usize> ResultWriter<D>
where
    Const<D>: Dimension<D>,
{
    /// Creates `dir` (and parents) and prepares the writers for `model`.
    pub fn create(dir: &Path, model: &Model<D>) -> std::io::Result<Self> {
        std::fs::create_dir_all(dir)?;
        let history = HistoryWriter::create(&dir.join("history.csv"), model)?;
        Ok(ResultWriter {
            dir: dir.to_path_buf(),
            model: model.clone(),
            history,
            pvd: Vec::new(),
            pending: None,
            written_last: false,
        })
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
        let writer = ResultWriter {
            dir: dir.to_path_buf(),
            model: model.clone(),
            history,
            pvd: file.pvd,
            pending: None,
            written_last: true,
        };
        Ok((writer, file.checkpoint))
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
        let text = serde_json::to_string_pretty(summary).map_err(std::io::Error::other)?;
        write_atomic(&self.dir.join("summary.json"), text.as_bytes())
    }

    fn write_increment(&mut self, snap: &Snapshot<D>) -> Result<(), String> {
        let model = &self.model;
        let fields = &model.output.fields;
        let needs_recovery = fields
            .iter()
            .any(|f| matches!(f, Field::Stress | Field::Strain | Field::VonMises));
        let nodal = if needs_recovery {
            Some(nodal_fields_of_model_with_points(
                model,
                &snap.displacement,
                &snap.points,
            )?)
        } else {
            None
        };
        let name = format!("inc_{:04}.vtu", snap.increment);
        let text = vtu::vtu(&vtu::VtuData {
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
        });
        let io = |e: std::io::Error| format!("cannot write results in {}: {e}", self.dir.display());
        write_atomic(&self.dir.join(&name), text.as_bytes()).map_err(io)?;
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
        if let Some(t) = view.thermal {
            row.extend([t.max_temperature, t.min_temperature]);
        }
        self.history
            .append(&row)
            .map_err(|e| format!("cannot write history.csv in {}: {e}", self.dir.display()))?;
        let snap = Snapshot {
            step: view.step,
            increment: view.increment,
            time: view.time,
            displacement: view.displacement.to_vec(),
            reaction: view.reaction.to_vec(),
            contact: view.contact.to_vec(),
            points: view.points.to_vec(),
            temperature: view.temperature.map(<[f64]>::to_vec),
        };
        let every = self.model.output.every.max(1);
        let last = view.step + 1 == self.model.steps.len()
            && self
                .model
                .steps
                .last()
                .is_some_and(|s| view.time >= s.t_end);
        if view.increment.is_multiple_of(every) || last {
            self.pending = None;
            self.written_last = true;
            self.write_increment(&snap)
        } else {
            self.pending = Some(snap);
            self.written_last = false;
            Ok(())
        }
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
