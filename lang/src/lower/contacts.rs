//! `contact` items -> `model::ContactPair` (tool or deformable master, method, strategy, friction).

use super::{mesh, Lowerer};
use crate::ast::{self, Method};
use crate::validate::Need;
use ctc_engine::model::{
    self as m, ContactMaster, ContactMethod, ContactPair, ContactStrategy, PenaltyKind,
};

impl Lowerer<'_> {
    /// The pairs; `tools` are the names of the lowered tools (curves in
    /// planar analyses, surfaces in `3d`), in `Model` order.
    pub(super) fn contacts(&mut self, bodies: &[m::Body], tools: &[&str]) -> Vec<ContactPair> {
        let mut out = Vec::new();
        for c in &self.deck.contacts {
            if self.has_error_in(c.span) || self.body_failed(&c.target) {
                continue;
            }
            let Some(r) = self.resolve(&c.target, Need::Edges, "contact") else {
                continue;
            };
            let Some(body) = bodies.iter().position(|b| b.name == c.target.body.name) else {
                continue;
            };
            let master = match &c.master {
                Some(m) => {
                    if self.body_failed(m) {
                        continue;
                    }
                    let Some(mr) = self.resolve(m, Need::Edges, "contact master") else {
                        continue;
                    };
                    let Some(mbody) = bodies.iter().position(|b| b.name == m.body.name) else {
                        continue;
                    };
                    let medges = mr.edges.unwrap_or_default();
                    ContactMaster::Surface {
                        body: mbody,
                        nodes: mesh::edge_nodes(&medges),
                        edges: medges,
                    }
                }
                None => {
                    let Some(tool) = tools.iter().position(|t| *t == c.tool.name) else {
                        self.missing("the tool", c.tool.span);
                        continue;
                    };
                    ContactMaster::Tool(tool)
                }
            };
            let method = match c.method.as_ref().map(|m| &m.value) {
                Some(Method::Penalty {
                    kind,
                    stiffness: Some(s),
                }) => ContactMethod::Penalty {
                    kind: match kind.as_ref().map(|k| k.value) {
                        Some(ast::PenaltyKind::Nodal) => PenaltyKind::Nodal,
                        _ => PenaltyKind::Area,
                    },
                    stiffness: s.value,
                },
                Some(Method::Lagrange { formulation }) => ContactMethod::Lagrange {
                    formulation: match formulation.as_ref().map(|f| f.value) {
                        Some(ast::LagrangeFormulation::Doubled) => m::LagrangeFormulation::Doubled,
                        _ => m::LagrangeFormulation::Single,
                    },
                },
                Some(Method::AugmentedLagrange {
                    kind,
                    penalty: Some(p),
                    tolerance: Some(tol),
                    update,
                }) => ContactMethod::AugmentedLagrange {
                    kind: match kind.as_ref().map(|k| k.value) {
                        Some(ast::PenaltyKind::Nodal) => PenaltyKind::Nodal,
                        _ => PenaltyKind::Area,
                    },
                    penalty: p.value,
                    tolerance: tol.value,
                    update: match update.as_ref().map(|u| u.value) {
                        Some(ast::MultiplierUpdate::Newton) => m::MultiplierUpdate::Newton,
                        _ => m::MultiplierUpdate::Converged,
                    },
                },
                _ => {
                    self.missing("a supported contact method", c.tool.span);
                    continue;
                }
            };
            let edges = r.edges.unwrap_or_default();
            let faces = r.faces.unwrap_or_default();
            let nodes = if faces.is_empty() {
                mesh::edge_nodes(&edges)
            } else {
                let mut n: Vec<usize> = faces.iter().flat_map(|f| f.nodes().to_vec()).collect();
                n.sort_unstable();
                n.dedup();
                n
            };
            out.push(ContactPair {
                name: format!("{} -> {}", c.target, c.tool.name),
                body,
                nodes,
                edges,
                faces,
                master,
                strategy: match c.strategy.as_ref().map(|s| s.value) {
                    Some(ast::Strategy::DoublePass) => ContactStrategy::DoublePass,
                    Some(ast::Strategy::ModifiedDoublePass) => ContactStrategy::ModifiedDoublePass,
                    _ => ContactStrategy::SinglePass,
                },
                formulation: match c.formulation.as_ref().map(|s| s.value) {
                    Some(ast::ContactFormulation::Mortar) => m::ContactFormulation::Mortar,
                    _ => m::ContactFormulation::NodeToSegment,
                },
                smoothing: match c.smoothing.as_ref().map(|s| s.value) {
                    Some(ast::Smoothing::Nodal) => m::NormalSmoothing::Nodal,
                    _ => m::NormalSmoothing::None,
                },
                search: match c.search.as_ref().map(|s| s.value) {
                    Some(ast::Search::Circle) => m::LocalSearch::Circle,
                    _ => m::LocalSearch::Memory,
                },
                method,
                prof: c.prof.as_ref().map(|p| p.value),
                friction: c.friction.as_ref().and_then(|f| {
                    Some(m::Friction {
                        mu: f.value.mu.as_ref()?.value,
                        stiffness: f.value.stiffness.as_ref().map(|s| s.value),
                        first_impact: match f.value.first_impact.as_ref().map(|v| v.value) {
                            Some(ast::FirstImpact::Frictionless) => m::FirstImpact::Frictionless,
                            _ => m::FirstImpact::Intersect,
                        },
                        cut_at_impact: f.value.cut_at_impact.as_ref().is_some_and(|v| v.value),
                    })
                }),
            });
        }
        out
    }
}
