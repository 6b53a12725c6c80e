//! `progress.sta`: the run's progress, one line per converged increment,
//! flushed each time (`tail -f` it during a long run), like Abaqus' `.sta`
//! file. Columns:
//!
//! | column | meaning |
//! | --- | --- |
//! | `step` | step number (1-based; a `#` line names each step as it starts) |
//! | `inc` | converged increment number in the run |
//! | `att` | attempts of the increment (1 + its cutbacks) |
//! | `iter` | Newton iterations of the converged attempt |
//! | `total_time` | analysis time at the end of the increment |
//! | `step_time` | time since the start of the step |
//! | `dt` | increment size |
//! | `contacts` | closed contact nodes (all pairs) |
//! | `max_penetration` | largest penetration `max(0, -gap)` (length) |
//! | `residual` | relative residual of the last iteration |
//!
//! The last line (`# completed ..` or `# stopped ..`) is written by
//! [`StaWriter::finish`].

use super::encode::fmt_f64;
use crate::contact::ContactStatus;
use crate::solve::{IncrementView, RunSummary};
use std::io::Write;

/// The column header.
pub const HEADER: &str = "# step   inc  att iter       total_time        step_time         dt contacts max_penetration   residual";

/// Writes `progress.sta`.
#[derive(Debug)]
pub struct StaWriter {
    file: std::io::BufWriter<std::fs::File>,
    /// Failed attempts since the last converged increment.
    cutbacks: usize,
    /// Time of the last converged increment (`None`: none yet).
    last_time: Option<f64>,
    /// Step of the last line.
    last_step: Option<usize>,
}

impl StaWriter {
    /// Creates the file with its header.
    pub fn create(path: &std::path::Path) -> std::io::Result<Self> {
        let mut file = std::io::BufWriter::new(std::fs::File::create(path)?);
        writeln!(file, "# ctc progress log: one line per converged increment")?;
        writeln!(file, "{HEADER}")?;
        file.flush()?;
        Ok(StaWriter {
            file,
            cutbacks: 0,
            last_time: None,
            last_step: None,
        })
    }

    /// Reopens the file of a stopped run to continue it after increment
    /// `increments` at time `time`: the lines of later increments and the
    /// old end line are dropped (the file is replaced atomically).
    pub fn resume(path: &std::path::Path, increments: usize, time: f64) -> std::io::Result<Self> {
        if !path.exists() {
            let mut w = StaWriter::create(path)?;
            w.last_time = Some(time);
            return Ok(w);
        }
        let text = std::fs::read_to_string(path)?;
        let mut kept = String::new();
        let mut rows = 0;
        let mut last_step = None;
        for line in text.lines() {
            if line.starts_with("# completed") || line.starts_with("# stopped") {
                continue;
            }
            if !line.starts_with('#') {
                if rows == increments {
                    break;
                }
                rows += 1;
                last_step = line
                    .split_whitespace()
                    .next()
                    .and_then(|s| s.parse::<usize>().ok())
                    .map(|s| s - 1);
            }
            kept.push_str(line);
            kept.push('\n');
        }
        kept.push_str(&format!("# restarted after increment {increments}\n"));
        super::atomic::write_atomic(path, kept.as_bytes())?;
        let file = std::fs::OpenOptions::new().append(true).open(path)?;
        Ok(StaWriter {
            file: std::io::BufWriter::new(file),
            cutbacks: 0,
            last_time: Some(time),
            last_step,
        })
    }

    /// Counts a failed attempt of the current increment.
    pub fn cutback(&mut self) {
        self.cutbacks += 1;
    }

    /// Writes the line of a converged increment.
    pub fn increment<const D: usize>(
        &mut self,
        view: &IncrementView<'_, D>,
    ) -> std::io::Result<()> {
        let step = &view.model.steps[view.step];
        if self.last_step != Some(view.step) {
            writeln!(self.file, "# step {} `{}`", view.step + 1, step.name)?;
            self.last_step = Some(view.step);
        }
        let start = self.last_time.unwrap_or(step.t_start);
        let closed = view
            .contact
            .iter()
            .flatten()
            .filter(|c| c.status == ContactStatus::Closed)
            .count();
        let penetration = view
            .contact
            .iter()
            .flatten()
            .map(|c| (-c.gap).max(0.0))
            .fold(0.0, f64::max);
        writeln!(
            self.file,
            "{:>6} {:>5} {:>4} {:>4} {:>16} {:>16} {:>10.4e} {:>8} {:>15.4e} {:>10.3e}",
            view.step + 1,
            view.increment,
            self.cutbacks + 1,
            view.residuals.len(),
            fmt_f64(view.time),
            fmt_f64(crate::solve::stepping::step_time(step, view.time)),
            view.time - start,
            closed,
            penetration,
            view.residuals.last().copied().unwrap_or(0.0)
        )?;
        self.cutbacks = 0;
        self.last_time = Some(view.time);
        self.file.flush()
    }

    /// Writes the end line.
    pub fn finish(&mut self, summary: &RunSummary) -> std::io::Result<()> {
        let what = if summary.completed {
            "completed"
        } else {
            "stopped"
        };
        writeln!(
            self.file,
            "# {what}: {} increments, {} Newton iterations, {} cutbacks, {:.3} s{}",
            summary.increments.len(),
            summary.newton_iterations,
            summary.cutbacks,
            summary.timings.total,
            summary
                .failure
                .as_deref()
                .map(|f| format!(": {}", f.lines().next().unwrap_or("")))
                .unwrap_or_default()
        )?;
        self.file.flush()
    }
}
