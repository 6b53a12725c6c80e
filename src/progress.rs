//! Progress reporting of `ctc run`: a progress bar over the analysis time on
//! a terminal, plain lines otherwise, nothing with `-q`. Wraps the result
//! writer so both see every converged increment.

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
                "{spinner} [{elapsed_precise}] {bar:40} {percent:>3}% {msg}",
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
        }
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
