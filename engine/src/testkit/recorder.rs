//! [`Recorder`]: an observer that keeps everything a test may look at.

use crate::contact::{ContactStatus, NodeContact};
use crate::element::MaterialPoint;
use crate::model::Model;
use crate::solve::{run, IncrementView, IterationInfo, Observer, RunSummary};

/// One converged increment as the observer saw it.
#[derive(Debug, Clone)]
pub struct Increment {
    /// Step index (0-based).
    pub step: usize,
    /// Converged increment number in the run (1-based).
    pub increment: usize,
    /// Time at the end of the increment.
    pub time: f64,
    /// Nodal displacements.
    pub displacement: Vec<[f64; 2]>,
    /// Nodal reactions (non-zero only at prescribed dofs).
    pub reaction: Vec<[f64; 2]>,
    /// Contact evaluation of each pair.
    pub contact: Vec<Vec<NodeContact>>,
    /// Relative residual after each Newton iteration.
    pub residuals: Vec<f64>,
    /// Converged integration points per cell (nonlinear laws only).
    pub points: Vec<Vec<MaterialPoint>>,
    /// Nodal temperatures (thermal scenes only).
    pub temperature: Option<Vec<f64>>,
}

impl Increment {
    /// Sum of the reactions of every node.
    pub fn total_reaction(&self) -> [f64; 2] {
        sum(self.reaction.iter().copied())
    }

    /// Sum of the reactions of `nodes`.
    pub fn reaction_of(&self, nodes: &[usize]) -> [f64; 2] {
        sum(nodes.iter().map(|&n| self.reaction[n]))
    }

    /// Total force on the slave nodes of pair `pair` (the tool's force on
    /// the body for a rigid master).
    pub fn contact_force(&self, pair: usize) -> [f64; 2] {
        sum(self.contact[pair].iter().map(|c| c.force))
    }

    /// Sum of every contact force of pair `pair`, slave and master ends
    /// (zero by the contact element's equilibrium).
    pub fn net_contact_force(&self, pair: usize) -> [f64; 2] {
        let mut f = self.contact_force(pair);
        for c in &self.contact[pair] {
            if let Some(m) = &c.master {
                for g in m.forces {
                    f[0] += g[0];
                    f[1] += g[1];
                }
            }
        }
        f
    }

    /// Closed contact entries of pair `pair`.
    pub fn closed(&self, pair: usize) -> Vec<&NodeContact> {
        self.contact[pair]
            .iter()
            .filter(|c| c.status == ContactStatus::Closed)
            .collect()
    }

    /// Largest penetration `max(0, -g)` of pair `pair`.
    pub fn max_penetration(&self, pair: usize) -> f64 {
        self.contact[pair]
            .iter()
            .map(|c| -c.gap)
            .fold(0.0, f64::max)
    }

    /// Newton iterations of the increment.
    pub fn iterations(&self) -> usize {
        self.residuals.len()
    }
}

fn sum(v: impl Iterator<Item = [f64; 2]>) -> [f64; 2] {
    v.fold([0.0; 2], |a, f| [a[0] + f[0], a[1] + f[1]])
}

/// Records every callback of a run.
#[derive(Debug, Default, Clone)]
pub struct Recorder {
    /// Converged increments, in order.
    pub increments: Vec<Increment>,
    /// Every Newton iteration (converged and failed attempts).
    pub iterations: Vec<IterationInfo>,
    /// Cutbacks: reason and new increment size.
    pub cutbacks: Vec<(String, f64)>,
    /// Warnings.
    pub warnings: Vec<String>,
}

impl Recorder {
    /// The last converged increment.
    pub fn last(&self) -> &Increment {
        self.increments
            .last()
            .expect("test kit: the run converged no increment")
    }
}

impl Observer for Recorder {
    fn iteration(&mut self, info: &IterationInfo) {
        self.iterations.push(info.clone());
    }

    fn converged(&mut self, v: &IncrementView<'_>) -> Result<(), String> {
        self.increments.push(Increment {
            step: v.step,
            increment: v.increment,
            time: v.time,
            displacement: v.displacement.to_vec(),
            reaction: v.reaction.to_vec(),
            contact: v.contact.to_vec(),
            residuals: v.residuals.to_vec(),
            points: v.points.to_vec(),
            temperature: v.temperature.map(<[f64]>::to_vec),
        });
        Ok(())
    }

    fn cutback(&mut self, reason: &str, new_dt: f64) {
        self.cutbacks.push((reason.to_string(), new_dt));
    }

    fn warning(&mut self, message: &str) {
        self.warnings.push(message.to_string());
    }
}

/// Runs `model` with a [`Recorder`]; the solver's message on failure.
pub fn solve(model: &Model) -> Result<(RunSummary, Recorder), String> {
    let mut rec = Recorder::default();
    let summary = run(model, &mut rec).map_err(|e| e.message)?;
    Ok((summary, rec))
}
