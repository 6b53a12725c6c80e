//! `pressure`, `traction`, `force` and `gravity` -> `model::Load`.

use super::Lowerer;
use crate::ast;
use crate::validate::Need;
use ctc_engine::mesh::select::{select_nodes, Selection};
use ctc_engine::mesh::Facet;
use ctc_engine::model::Load;

impl Lowerer<'_> {
    pub(super) fn loads(&mut self) -> Vec<Load> {
        let mut out = Vec::new();
        for l in &self.deck.loads {
            if self.has_error_in(l.span) || self.body_failed(&l.target) {
                continue;
            }
            match l.kind {
                ast::LoadKind::Pressure => {
                    let Some(r) = self.resolve(&l.target, Need::Edges, "pressure") else {
                        continue;
                    };
                    let label = format!("pressure {}", l.target);
                    if l.follower.as_ref().is_some_and(|f| f.value) {
                        // on the deformed surface: faces, or planar edges
                        // with their midside nodes when quadratic
                        let facets: Vec<Facet> = match (&r.faces, &r.edges) {
                            (Some(f), _) if self.solid => f.clone(),
                            (_, Some(e)) => {
                                let midsides = self.mesh.edge_midsides();
                                e.iter()
                                    .map(|&e| ctc_engine::mesh::Mesh::edge_facet(&midsides, e))
                                    .collect()
                            }
                            _ => Vec::new(),
                        };
                        // the controlled body: the one holding the surface
                        let control = l.control.as_ref().and_then(|c| {
                            let first = *r.nodes.first()?;
                            let body = self.deck.bodies.iter().position(|b| {
                                self.body_nodes
                                    .get(&b.name.name)
                                    .is_some_and(|n| n.contains(&first))
                            })?;
                            let v = |x: &Option<crate::span::Spanned<f64>>, d: f64| {
                                x.as_ref().map_or(d, |x| x.value)
                            };
                            let range = self.body_nodes.get(&self.deck.bodies[body].name.name)?;
                            let candidates: Vec<usize> = range.clone().collect();
                            let at = c.value.at.as_ref().map_or_else(Vec::new, |p| {
                                let x = p.values();
                                if self.solid && x.len() == 3 {
                                    let sel = Selection::Nearest([x[0], x[1], x[2]]);
                                    select_nodes(&self.mesh3, &candidates, &sel)
                                } else if !self.solid && x.len() == 2 {
                                    let sel = Selection::Nearest([x[0], x[1]]);
                                    select_nodes(&self.mesh, &candidates, &sel)
                                } else {
                                    Vec::new()
                                }
                            });
                            Some(ctc_engine::model::RateControl {
                                body,
                                at,
                                target: c.value.target.as_ref()?.value,
                                exponent: v(&c.value.exponent, 0.5),
                                max_factor: v(&c.value.max_change, 2.0),
                                max_pressure: v(&c.value.max_pressure, f64::INFINITY),
                            })
                        });
                        for (_, f) in &l.values {
                            out.push(Load::FollowerPressure {
                                label: label.clone(),
                                facets: facets.clone(),
                                value: self.tf(f),
                                control: control.clone(),
                            });
                        }
                        continue;
                    }
                    if self.solid {
                        for (_, f) in &l.values {
                            out.push(Load::FacetPressure {
                                label: label.clone(),
                                facets: r.faces.clone().unwrap_or_default(),
                                value: self.tf(f),
                            });
                        }
                        continue;
                    }
                    // edges of quadratic cells take the consistent load on
                    // their 3-node edges [a, b, m]; linear ones the 2-node
                    // closed form
                    let midsides = self.mesh.edge_midsides();
                    let (quadratic, linear): (Vec<Facet>, Vec<Facet>) = r
                        .edges
                        .clone()
                        .unwrap_or_default()
                        .into_iter()
                        .map(|e| ctc_engine::mesh::Mesh::edge_facet(&midsides, e))
                        .partition(|f| f.nodes().len() == 3);
                    for (_, f) in &l.values {
                        if !linear.is_empty() || quadratic.is_empty() {
                            out.push(Load::Pressure {
                                label: label.clone(),
                                edges: linear.iter().map(Facet::edge).collect(),
                                value: self.tf(f),
                            });
                        }
                        if !quadratic.is_empty() {
                            out.push(Load::FacetPressure {
                                label: label.clone(),
                                facets: quadratic.clone(),
                                value: self.tf(f),
                            });
                        }
                    }
                }
                ast::LoadKind::Traction => {
                    let Some(r) = self.resolve(&l.target, Need::Edges, "traction") else {
                        continue;
                    };
                    let label = format!("traction {}", l.target);
                    let facets: Vec<Facet> = match (&r.faces, &r.edges) {
                        (Some(f), _) => f.clone(),
                        (None, Some(e)) => {
                            let midsides = self.mesh.edge_midsides();
                            e.iter()
                                .map(|&e| ctc_engine::mesh::Mesh::edge_facet(&midsides, e))
                                .collect()
                        }
                        (None, None) => Vec::new(),
                    };
                    for (c, f) in &l.values {
                        out.push(Load::FacetTraction {
                            label: label.clone(),
                            facets: facets.clone(),
                            component: c.map_or(0, |c| c.index()),
                            value: self.tf(f),
                        });
                    }
                }
                ast::LoadKind::Force => {
                    let Some(r) = self.resolve(&l.target, Need::Nodes, "force") else {
                        continue;
                    };
                    let label = format!("force {}", l.target);
                    for (c, f) in &l.values {
                        out.push(Load::NodalForce {
                            label: label.clone(),
                            nodes: r.nodes.clone(),
                            component: c.map_or(0, |c| c.index()),
                            value: self.tf(f),
                        });
                    }
                }
            }
        }
        for g in &self.deck.gravity {
            if self.has_error_in(g.span) {
                continue;
            }
            for (c, f) in &g.values {
                let c = c.map_or(0, |c| c.index());
                out.push(Load::Gravity {
                    label: format!("gravity g{}", ["x", "y", "z"][c.min(2)]),
                    component: c,
                    value: self.tf(f),
                });
            }
        }
        out
    }
}
