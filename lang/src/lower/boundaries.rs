//! `fix` and `displace` -> `model::Dirichlet` (with a warning for conflicting prescriptions).

use super::Lowerer;
use crate::ast;
use crate::diagnostics::Diagnostic;
use crate::validate::Need;
use ctc_engine::model::{self as m, Dirichlet};
use std::collections::BTreeMap;

impl Lowerer<'_> {
    pub(super) fn constraints(&mut self) -> Vec<Dirichlet> {
        let mut out = Vec::new();
        // (node, component) -> (label, value) of the first prescription.
        let mut seen: BTreeMap<(usize, usize), (String, m::TimeFunction)> = BTreeMap::new();
        for b in &self.deck.boundaries {
            if self.has_error_in(b.span) || self.body_failed(&b.target) {
                continue;
            }
            let word = match b.kind {
                ast::BoundaryKind::Fix => "fix",
                ast::BoundaryKind::Displace => "displace",
            };
            let Some(r) = self.resolve(&b.target, Need::Nodes, word) else {
                continue;
            };
            let label = format!("{word} {}", b.target);
            for (c, f) in &b.components {
                let value = self.tf(f);
                let component = c.value.index();
                let mut clashes: BTreeMap<String, usize> = BTreeMap::new();
                for &n in &r.nodes {
                    match seen.get(&(n, component)) {
                        Some((other, v)) if *v != value => {
                            *clashes.entry(other.clone()).or_default() += 1
                        }
                        Some(_) => {}
                        None => {
                            seen.insert((n, component), (label.clone(), value.clone()));
                        }
                    }
                }
                let comp = ["ux", "uy", "uz"][component.min(2)];
                for (other, count) in clashes {
                    self.diags.push(
                        Diagnostic::warning(
                            format!("`{label}` and `{other}` prescribe different values of {comp} on {count} node(s)"),
                            c.span,
                            "conflicting prescription",
                        )
                        .with_help("make them agree, or use sets that do not share nodes"),
                    );
                }
                out.push(Dirichlet {
                    label: label.clone(),
                    nodes: r.nodes.clone(),
                    component,
                    value,
                });
            }
        }
        out
    }
}
