//! An [`Observer`] that keeps a copy of the last converged increment: the
//! state from which every verification quantity is extracted.

use ctc_engine::contact::NodeContact;
use ctc_engine::solve::{IncrementView, IterationInfo, Observer};

/// Copy of the data of a converged increment.
#[derive(Debug, Clone, Default)]
pub struct FinalState {
    /// Step index (0-based).
    pub step: usize,
    /// Converged increment number in the run (1-based).
    pub increment: usize,
    /// Time at the end of the increment.
    pub time: f64,
    /// Nodal displacements.
    pub displacement: Vec<[f64; 2]>,
    /// Nodal reactions (non-zero only at constrained dofs).
    pub reaction: Vec<[f64; 2]>,
    /// Contact evaluation of each pair, as the engine reported it.
    pub contact: Vec<Vec<NodeContact>>,
    /// Relative residual after each Newton iteration of the increment.
    pub residuals: Vec<f64>,
}

/// Observer keeping the last converged state and counting iterations.
#[derive(Debug, Clone, Default)]
pub struct Capture {
    /// The last converged increment, if any converged.
    pub last: Option<FinalState>,
    /// Newton iterations seen (all attempts, including cut-back ones).
    pub iterations: usize,
    /// Reasons of the cutbacks, in order.
    pub cutbacks: Vec<String>,
}

impl Observer for Capture {
    fn iteration(&mut self, _info: &IterationInfo) {
        self.iterations += 1;
    }

    fn converged(&mut self, view: &IncrementView<'_>) -> Result<(), String> {
        let state = self.last.get_or_insert_with(FinalState::default);
        state.step = view.step;
        state.increment = view.increment;
        state.time = view.time;
        state.displacement.clear();
        state.displacement.extend_from_slice(view.displacement);
        state.reaction.clear();
        state.reaction.extend_from_slice(view.reaction);
        state.contact.clear();
        state.contact.extend(view.contact.iter().cloned());
        state.residuals.clear();
        state.residuals.extend_from_slice(view.residuals);
        Ok(())
    }

    fn cutback(&mut self, reason: &str, new_dt: f64) {
        self.cutbacks
            .push(format!("{reason} (new increment {new_dt:e})"));
    }
}
