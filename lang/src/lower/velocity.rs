//! `initial_velocity` items -> `model::InitialVelocity`.

use super::Lowerer;
use crate::validate::Need;
use ctc_engine::model::InitialVelocity;

impl Lowerer<'_> {
    pub(super) fn initial_velocities(&mut self) -> Vec<InitialVelocity> {
        let mut out = Vec::new();
        for v in &self.deck.initial_velocities {
            if self.has_error_in(v.span) || self.body_failed(&v.target) {
                continue;
            }
            let Some(r) = self.resolve(&v.target, Need::Nodes, "initial_velocity") else {
                continue;
            };
            for (c, x) in &v.values {
                out.push(InitialVelocity {
                    label: format!("initial_velocity {}", v.target),
                    nodes: r.nodes.clone(),
                    component: c.index(),
                    value: x.value,
                });
            }
        }
        out
    }
}
