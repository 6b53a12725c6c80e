//! `spring` and `point_mass` items -> `model::Discrete` (`Ground`,
//! `Link`, `Mass`).

use super::Lowerer;
use crate::ast::DiscreteKind;
use crate::diagnostics::Diagnostic;
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
            if let Some(o) = &d.other {
                if self.body_failed(o) {
                    continue;
                }
                let Some(b) = self.resolve(o, Need::Nodes, what) else {
                    continue;
                };
                // one node at the far end takes every link; otherwise the
                // sets pair in node order
                let pairs: Vec<(usize, usize)> = match (r.nodes.len(), b.nodes.len()) {
                    (_, 1) => r.nodes.iter().map(|&a| (a, b.nodes[0])).collect(),
                    (n, m) if n == m => r
                        .nodes
                        .iter()
                        .copied()
                        .zip(b.nodes.iter().copied())
                        .collect(),
                    (n, m) => {
                        self.diags.push(
                            Diagnostic::error(
                                format!(
                                    "a spring between {n} and {m} nodes: the sets must have as \
                                     many nodes, or the far end one"
                                ),
                                o.span,
                                format!("{m} nodes"),
                            )
                            .with_secondary(d.target.span, format!("{n} nodes"))
                            .with_help(
                                "the i-th node of the first set (in node order) is linked to \
                                 the i-th of the second; select single nodes with \
                                 `body.node(near(x, y))`",
                            ),
                        );
                        continue;
                    }
                };
                if let Some(&(a, _)) = pairs.iter().find(|(a, b)| a == b) {
                    self.diags.push(
                        Diagnostic::error(
                            format!("a spring from node {a} to itself"),
                            o.span,
                            "the same node as the first end",
                        )
                        .with_help("link two different nodes"),
                    );
                    continue;
                }
                out.push(Discrete::Link {
                    label: format!("spring {} -> {}", d.target, o),
                    pairs,
                    stiffness: v(&d.stiffness),
                    damping: v(&d.damping),
                });
                continue;
            }
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
