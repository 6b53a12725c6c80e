//! `spring` and `point_mass` items -> `model::Discrete` (`Ground`,
//! `Link`, `Mass`); `rigid_body` items -> `rigid_body::RigidSpec` (applied
//! to the planar or 3d model by `rigid_body::make_rigid`).

use super::Lowerer;
use crate::ast::DiscreteKind;
use crate::diagnostics::Diagnostic;
use crate::validate::Need;
use ctc_engine::model::{self as m, Discrete};
use ctc_engine::solve::rigid_body::RigidSpec;

impl Lowerer<'_> {
    pub(super) fn discrete(&mut self) -> Vec<Discrete> {
        let mut out = Vec::new();
        for d in &self.deck.discrete {
            if self.has_error_in(d.span)
                || self.body_failed(&d.target)
                || d.kind == DiscreteKind::RigidBody
            {
                continue;
            }
            let what = match d.kind {
                DiscreteKind::Spring => "spring",
                DiscreteKind::PointMass => "point_mass",
                DiscreteKind::RigidBody => "rigid_body",
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
                    release_at: d.release_at.as_ref().map(|x| x.value),
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
                DiscreteKind::PointMass | DiscreteKind::RigidBody => Discrete::Mass {
                    label: format!("point_mass {}", d.target),
                    nodes: r.nodes.clone(),
                    mass: v(&d.mass),
                },
            });
        }
        out
    }

    /// The rigid bodies of the deck, with the span of each item.
    pub(super) fn rigid_bodies(&mut self) -> Vec<(RigidSpec, crate::ast::Span)> {
        let mut out = Vec::new();
        for d in &self.deck.discrete {
            let Some(keys) = &d.rigid else { continue };
            if self.has_error_in(d.span) || self.body_failed(&d.target) {
                continue;
            }
            let Some(r) = self.resolve(&d.target, Need::Nodes, "rigid_body") else {
                continue;
            };
            let v = |x: &Option<crate::span::Spanned<f64>>| x.as_ref().map_or(0.0, |x| x.value);
            let rotation = match (&keys.rotation, &keys.angular_velocity) {
                (Some(r), _) => Some(self.tf(r)),
                (None, Some(w)) => Some(ctc_engine::solve::rigid_body::angle_of(
                    &self.tf(w),
                    self.window,
                )),
                (None, None) => None,
            };
            let mut centre = [0.0; 3];
            if let Some(c) = &keys.center {
                for (x, y) in centre.iter_mut().zip(c.values()) {
                    *x = *y;
                }
            }
            // planar: the inertia about the normal; 3d: `inertia` the same
            // about every axis, or the tensor's diagonal and products
            let diagonal = match (&keys.inertia, &keys.inertia_diagonal) {
                (Some(i), _) => [i.value; 3],
                (None, Some(t)) => t.value,
                (None, None) => [0.0; 3],
            };
            let p = keys.inertia_products.as_ref().map_or([0.0; 3], |p| p.value);
            let inertia = [
                [diagonal[0], p[0], p[2]],
                [p[0], diagonal[1], p[1]],
                [p[2], p[1], diagonal[2]],
            ];
            out.push((
                RigidSpec {
                    label: format!("rigid_body {}", d.target),
                    nodes: r.nodes.clone(),
                    centre,
                    mass: v(&d.mass),
                    inertia,
                    axis: keys.axis.as_ref().map_or([0.0, 0.0, 1.0], |a| a.value),
                    rotation,
                    moment: keys
                        .moment
                        .as_ref()
                        .map_or(m::TimeFunction::Constant(0.0), |f| self.tf(f)),
                    bearing_stiffness: v(&d.stiffness),
                    bearing_damping: v(&d.damping),
                    stiffness: v(&keys.tie_stiffness),
                },
                d.span,
            ));
        }
        out
    }
}
