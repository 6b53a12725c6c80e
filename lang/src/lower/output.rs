//! The `output` block -> `model::OutputRequest`.

use super::Lowerer;
use crate::ast;
use crate::diagnostics::Diagnostic;
use crate::validate::Need;
use ctc_engine::model::{
    ContactPair, Field, HistoryRequest, OutputRequest, ThicknessRequest, VtuFormat,
};

impl Lowerer<'_> {
    pub(super) fn output(&mut self, contacts: &[ContactPair]) -> OutputRequest {
        let units = self
            .deck
            .analysis
            .iter()
            .find_map(|a| a.units.as_ref())
            .and_then(|u| crate::units::system(u.value))
            .map(|s| s.names());
        let Some(o) = self.deck.outputs.first() else {
            return OutputRequest {
                units,
                ..OutputRequest::default()
            };
        };
        let mut out = OutputRequest {
            units,
            ..OutputRequest::default()
        };
        if let Some(e) = &o.every {
            out.every = e.value.max(1) as usize;
        }
        if let Some(f) = &o.format {
            out.format = match f.value {
                ast::OutputFormat::Binary => VtuFormat::Binary,
                ast::OutputFormat::Ascii => VtuFormat::Ascii,
            };
        }
        if let Some(fields) = &o.fields {
            let mut list: Vec<Field> = Vec::new();
            for f in &fields.value {
                let field = match f.value {
                    ast::FieldName::Displacement => Field::Displacement,
                    ast::FieldName::Stress => Field::Stress,
                    ast::FieldName::Strain => Field::Strain,
                    ast::FieldName::VonMises => Field::VonMises,
                    ast::FieldName::Reaction => Field::Reaction,
                    ast::FieldName::Contact => Field::Contact,
                    ast::FieldName::Velocity => Field::Velocity,
                    ast::FieldName::Acceleration => Field::Acceleration,
                };
                if !list.contains(&field) {
                    list.push(field);
                }
            }
            out.fields = list;
        }
        if let Some(t) = o.thickness.as_ref().filter(|t| !self.has_error_in(t.span)) {
            out.thickness = self.thickness(t);
        }
        for h in o.history.iter().flatten() {
            if self.has_error_in(h.span) {
                continue;
            }
            match &h.value {
                ast::History::Reaction(r) | ast::History::Displacement(r) => {
                    if self.body_failed(r) {
                        continue;
                    }
                    let is_reaction = matches!(h.value, ast::History::Reaction(_));
                    let word = if is_reaction {
                        "reaction"
                    } else {
                        "displacement"
                    };
                    let Some(res) = self.resolve(r, Need::Nodes, word) else {
                        continue;
                    };
                    let label = format!("{word}({r})");
                    out.history.push(if is_reaction {
                        HistoryRequest::Reaction {
                            label,
                            nodes: res.nodes,
                        }
                    } else {
                        HistoryRequest::Displacement {
                            label,
                            nodes: res.nodes,
                        }
                    });
                }
                ast::History::Roughness(r) => {
                    if self.body_failed(r) {
                        continue;
                    }
                    let Some(res) = self.resolve(r, Need::Nodes, "roughness") else {
                        continue;
                    };
                    if res.nodes.len() < 3 {
                        self.diags.push(Diagnostic::error(
                            format!(
                                "`roughness({r})` needs at least 3 nodes, the set has {}",
                                res.nodes.len()
                            ),
                            h.span,
                            "a profile of fewer than 3 points has no roughness",
                        ));
                        continue;
                    }
                    let axis = if self.solid {
                        height_axis(&self.mesh3.nodes, &res.nodes)
                    } else {
                        height_axis(&self.mesh.nodes, &res.nodes)
                    };
                    out.history.push(HistoryRequest::Roughness {
                        label: format!("roughness({r})"),
                        axis,
                        nodes: res.nodes,
                    });
                }
                ast::History::ContactForce(r, tool) => {
                    let name = format!("{r} -> {}", tool.name);
                    match contacts.iter().position(|c| c.name == name) {
                        Some(pair) => out.history.push(HistoryRequest::ContactForce {
                            label: format!("contact_force({name})"),
                            pair,
                        }),
                        None if self.body_failed(r) => {}
                        None => self.missing("the contact pair", h.span),
                    }
                }
            }
        }
        out
    }

    /// `thickness = (a, b)`: both face sets and the body's nodes.
    fn thickness(
        &mut self,
        t: &crate::span::Spanned<[ast::SetRef; 2]>,
    ) -> Option<ThicknessRequest> {
        let [a, b] = &t.value;
        if !self.solid || self.body_failed(a) || self.body_failed(b) {
            return None;
        }
        let fa = self.resolve(a, Need::Edges, "thickness")?.faces;
        let fb = self.resolve(b, Need::Edges, "thickness")?.faces;
        let (Some(fa), Some(fb)) = (fa, fb) else {
            self.missing("the thickness faces", t.span);
            return None;
        };
        let nodes: Vec<usize> = self.body_nodes.get(&a.body.name)?.clone().collect();
        Some(ThicknessRequest {
            label: format!("{a}, {b}"),
            faces: [fa, fb],
            nodes,
        })
    }
}

/// The height axis of the surface through the reference positions of
/// `nodes` ([`ctc_engine::output::roughness::height_axis`]).
fn height_axis<const D: usize>(all: &[[f64; D]], nodes: &[usize]) -> usize {
    let reference: Vec<[f64; D]> = nodes.iter().filter_map(|&n| all.get(n).copied()).collect();
    ctc_engine::output::roughness::height_axis(&reference)
}
