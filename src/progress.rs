//! Progress reporting of `ctc run`: a progress bar over the analysis time on
//! a terminal (with the estimated time left), plain lines otherwise,
//! nothing with `-q`. Wraps the result writer so both see every converged
//! increment, and keeps the key figures of the run for the end summary
//! ([`Progress::figures`]).

use ctc_engine::model::Model;
use ctc_engine::solve::{IncrementView, IterationInfo, Observer};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::io::IsTerminal;

/// Resolution of the progress bar (positions over the analysis time).
const TICKS: u64 = 1000;

/// An observer that reports progress and forwards to an inner observer.
pub struct Progress<'a, const D: usize = 2> {
    inner: &'a mut dyn Observer<D>,
    bar: Option<ProgressBar>,
    quiet: bool,
    verbose: bool,
    t0: f64,
    t1: f64,
    figures: Figures,
}

/// Key figures of a run, for the end summary.
#[derive(Debug, Clone, Default)]
pub struct Figures {
    /// Largest contact pressure over the run and its time.
    pub peak_pressure: Option<(f64, f64)>,
    /// Largest penetration over the run and its time.
    pub max_penetration: Option<(f64, f64)>,
    /// History columns (`history.csv` names) and their last values.
    pub last_history: Vec<(String, f64)>,
    /// Warnings of converged increments.
    pub warnings: usize,
}

impl Figures {
    /// The summary lines (`ctc run` prints them after `done:`).
    pub fn lines(&self) -> Vec<String> {
        let mut out = Vec::new();
        if let Some((p, t)) = self.peak_pressure {
            out.push(format!("  peak contact pressure {p:.6e} at t = {t}"));
        }
        if let Some((g, t)) = self.max_penetration {
            out.push(format!("  max penetration       {g:.6e} at t = {t}"));
        }
        for (name, v) in &self.last_history {
            out.push(format!("  {name} = {v:.6e} (end)"));
        }
        if self.warnings > 0 {
            out.push(format!(
                "  {} warning(s): see above and summary.json",
                self.warnings
            ));
        }
        out
    }
}

impl<'a, const D: usize> Progress<'a, D> {
    /// Progress over the time span of `model`'s steps.
    pub fn new(
        model: &Model<D>,
        inner: &'a mut dyn Observer<D>,
        quiet: bool,
        verbose: bool,
    ) -> Self {
        let t0 = model.steps.first().map_or(0.0, |s| s.t_start);
        let t1 = model.steps.last().map_or(1.0, |s| s.t_end);
        let bar = if !quiet && !verbose && std::io::stderr().is_terminal() {
            let bar = ProgressBar::with_draw_target(Some(TICKS), ProgressDrawTarget::stderr());
            if let Ok(style) = ProgressStyle::with_template(
                "{spinner} [{elapsed_precise}] {bar:40} {percent:>3}% eta {eta} {msg}",
            ) {
                bar.set_style(style);
            }
            Some(bar)
        } else {
            None
        };
        Progress {
            inner,
            bar,
            quiet,
            verbose,
            t0,
            t1,
            figures: Figures::default(),
        }
    }

    /// The key figures seen so far.
    pub fn figures(&self) -> &Figures {
        &self.figures
    }

    /// Clears the progress bar.
    pub fn finish(&mut self) {
        if let Some(bar) = self.bar.take() {
            bar.finish_and_clear();
        }
    }

    fn say(&self, line: String) {
        match &self.bar {
            Some(bar) => bar.println(line),
            None if !self.quiet => println!("{line}"),
            None => {}
        }
    }
}

impl<const D: usize> Progress<'_, D> {
    fn record(&mut self, view: &IncrementView<'_, D>) {
        let f = &mut self.figures;
        for c in view.contact.iter().flatten() {
            if c.pressure > f.peak_pressure.map_or(0.0, |p| p.0) {
                f.peak_pressure = Some((c.pressure, view.time));
            }
            if -c.gap > f.max_penetration.map_or(0.0, |p| p.0) {
                f.max_penetration = Some((-c.gap, view.time));
            }
        }
        let names = ctc_engine::output::history::columns(view.model);
        let row = ctc_engine::output::history::row(
            view.model,
            view.time,
            view.displacement,
            view.reaction,
            view.contact,
        );
        f.last_history = names
            .iter()
            .zip(row)
            .skip(1)
            .filter(|(n, _)| !n.starts_with("friction_work"))
            .map(|(n, v)| (n.clone(), v))
            .collect();
    }
}

impl<const D: usize> Observer<D> for Progress<'_, D> {
    fn iteration(&mut self, info: &IterationInfo) {
        if self.verbose {
            self.say(format!(
                "    iter {:>2}  residual {:.3e}  du {:.3e}  step {:.3}  contacts {}",
                info.iteration,
                info.residual,
                info.displacement,
                info.step_length,
                info.active_contacts
            ));
        }
        self.inner.iteration(info);
    }

    fn converged(&mut self, view: &IncrementView<'_, D>) -> Result<(), String> {
        self.record(view);
        let step = &view.model.steps[view.step].name;
        let line = format!(
            "step {step}  increment {:>3}  t = {:<10.4e} iterations {:>2}  residual {:.2e}",
            view.increment,
            view.time,
            view.residuals.len(),
            view.residuals.last().copied().unwrap_or(0.0)
        );
        if let Some(bar) = &self.bar {
            let span = (self.t1 - self.t0).max(f64::MIN_POSITIVE);
            let frac = ((view.time - self.t0) / span).clamp(0.0, 1.0);
            bar.set_position((frac * TICKS as f64).round() as u64);
            bar.set_message(format!("step {step} t = {:.4e}", view.time));
        } else {
            self.say(line);
        }
        self.inner.converged(view)
    }

    fn cutback(&mut self, reason: &str, new_dt: f64) {
        // one line: the reason already holds what failed and the residual
        // range (the whole sequence is in summary.json `cutback_log`)
        self.say(format!(
            "  cutback: {reason}; retrying with dt = {new_dt:.2e}"
        ));
        self.inner.cutback(reason, new_dt);
    }

    fn warning(&mut self, message: &str) {
        self.figures.warnings += 1;
        self.say(format!("  warning: {message}"));
        self.inner.warning(message);
    }

    fn wants_checkpoint(&self) -> bool {
        self.inner.wants_checkpoint()
    }

    fn checkpoint(
        &mut self,
        checkpoint: &ctc_engine::solve::restart::Checkpoint<D>,
    ) -> Result<(), String> {
        self.inner.checkpoint(checkpoint)
    }
}
