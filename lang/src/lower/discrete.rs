//! `spring` and `point_mass` items -> `model::Discrete`.

use super::Lowerer;
use crate::ast::DiscreteKind;
use crate::validate::Need;
use ctc_engine::model::Discrete;

impl Lowerer<'_> {
    pub(super) fn discrete(&mut self) -> Vec<Discrete> {
        let mut out = Vec::new();
        for d in &self.deck.discrete {
            if self.has_error_in(d.span) || self.body_failed(&d.target) {
                continue;
            }
            let what = match d.kind {
                DiscreteKind::Spring => "spring",
                DiscreteKind::PointMass => "point_mass",
            };
            let Some(r) = self.resolve(&d.target, Need::Nodes, what) else {
                continue;
            };
            let v = |x: &Option<crate::span::Spanned<f64>>| x.as_ref().map_or(0.0, |x| x.value);
            out.push(match d.kind {
                DiscreteKind::Spring => Discrete::Ground {
                    label: format!("spring {}", d.target),
                    nodes: r.nodes.clone(),
                    stiffness: v(&d.stiffness),
                    damping: v(&d.damping),
                },
                DiscreteKind::PointMass => Discrete::Mass {
                    label: format!("point_mass {}", d.target),
                    nodes: r.nodes.clone(),
                    mass: v(&d.mass),
                },
            });
        }
        out
    }
}
