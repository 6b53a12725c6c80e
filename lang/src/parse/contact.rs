//! `contact body.set -> tool { method = penalty { .. } prof = .. }`.

use super::fields::Fields;
use super::values::{self, Diags};
use super::ItemParts;
use crate::ast::syntax::{Value, ValueKind};
use crate::ast::{Contact, Method, PenaltyKindAst};
use crate::diagnostics::Diagnostic;
use crate::span::Spanned;
use crate::suggest::did_you_mean;

/// Contact methods the language knows; only `penalty` is supported yet.
pub const METHODS: [&str; 3] = ["penalty", "lagrange", "augmented_lagrange"];

const KINDS: [(&str, PenaltyKindAst); 2] = [
    ("nodal", PenaltyKindAst::Nodal),
    ("area", PenaltyKindAst::Area),
];

/// Converts a `contact` item.
pub fn parse(item: ItemParts, diags: &mut Diags) -> Option<Contact> {
    let target = values::set_ref(item.target.as_ref()?, diags)?;
    let tool = item.names.into_iter().next()?;
    let block = item.block?;
    let mut f = Fields::new(&block, "`contact` block", &["method", "prof", "friction"]);
    let method = f.value("method", diags).and_then(|v| method(v, diags));
    let prof = f.number("prof", diags);
    let reserved = f
        .take_all(&["friction"])
        .into_iter()
        .map(|e| e.key.clone())
        .collect();
    f.require(
        &method,
        "method",
        target.span.to(tool.span),
        "add `method = penalty { stiffness = .. }`",
        diags,
    );
    f.finish(diags);
    Some(Contact {
        target,
        tool,
        method,
        prof,
        reserved,
        span: item.span,
    })
}

fn method(v: &Value, diags: &mut Diags) -> Option<Spanned<Method>> {
    let (name, block) = match &v.kind {
        ValueKind::Ctor { name, block } => (name, Some(block)),
        ValueKind::Path(p) if p.len() == 1 => (&p[0], None),
        other => {
            diags.push(Diagnostic::error(
                format!("expected a contact method, found {}", other.describe()),
                v.span,
                "expected `penalty { stiffness = .. }`",
            ));
            return None;
        }
    };
    match name.name.as_str() {
        "penalty" => {
            let Some(block) = block else {
                diags.push(Diagnostic::error(
                    "`penalty` needs its stiffness",
                    v.span,
                    "expected `penalty { stiffness = .. }`",
                ));
                return None;
            };
            let mut f = Fields::new(block, "`penalty` block", &["kind", "stiffness"]);
            let kind = f.choice("kind", "penalty kind", &KINDS, diags);
            let stiffness = f.number("stiffness", diags);
            f.require(
                &stiffness,
                "stiffness",
                name.span,
                "add `stiffness = <penalty coefficient>`",
                diags,
            );
            f.finish(diags);
            Some(Spanned::new(Method::Penalty { kind, stiffness }, v.span))
        }
        "lagrange" | "augmented_lagrange" => {
            Some(Spanned::new(Method::Reserved(name.clone()), v.span))
        }
        other => {
            diags.push(
                Diagnostic::error(
                    format!("unknown contact method `{other}`"),
                    name.span,
                    "not a contact method",
                )
                .with_help(
                    did_you_mean(other, METHODS)
                        .unwrap_or_else(|| "expected `penalty { .. }`".into()),
                ),
            );
            None
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::ast::{Method, PenaltyKindAst, SetRefKind};
    use crate::parse::test_support::{parse_messages, parse_ok};

    #[test]
    fn penalty_contact_pair() {
        let deck = parse_ok(
            "contact block.top -> punch {\n  method = penalty { kind = nodal  stiffness = 1e4 }\n  prof = 0.5\n}",
        );
        let c = &deck.contacts[0];
        assert_eq!(c.tool.name, "punch");
        assert!(matches!(&c.target.kind, SetRefKind::Named(n) if n.name == "top"));
        assert_eq!(c.prof.as_ref().unwrap().value, 0.5);
        match &c.method.as_ref().unwrap().value {
            Method::Penalty { kind, stiffness } => {
                assert_eq!(kind.as_ref().unwrap().value, PenaltyKindAst::Nodal);
                assert_eq!(stiffness.as_ref().unwrap().value, 1e4);
            }
            m => panic!("{m:?}"),
        }
    }

    #[test]
    fn reserved_and_unknown_methods() {
        let deck =
            parse_ok("contact a.b -> t { method = lagrange  friction = coulomb { mu = 0.2 } }");
        assert!(
            matches!(&deck.contacts[0].method.as_ref().unwrap().value, Method::Reserved(n) if n.name == "lagrange")
        );
        assert_eq!(deck.contacts[0].reserved[0].name, "friction");
        assert_eq!(
            parse_messages("contact a.b -> t { method = penalti { stiffness = 1 } }"),
            ["unknown contact method `penalti`"]
        );
        assert_eq!(
            parse_messages("contact a.b -> t { method = penalty { kind = area } }"),
            ["missing `stiffness` in the `penalty` block"]
        );
    }
}
