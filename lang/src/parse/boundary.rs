//! `fix body.set { ux uy }` and `displace body.set { uy = ramp(0, -0.05) }`.

use super::values::{self, Diags};
use super::ItemParts;
use crate::ast::syntax::{EntryBody, ValueKind};
use crate::ast::{Boundary, BoundaryKind, Component, TimeFn};
use crate::diagnostics::Diagnostic;
use crate::span::Spanned;
use crate::suggest::did_you_mean;

/// Displacement component keys.
pub const COMPONENTS: [(&str, Component); 3] = [
    ("ux", Component::X),
    ("uy", Component::Y),
    ("uz", Component::Z),
];

/// The component named `key`, or a diagnostic with a suggestion.
pub fn component(key: &crate::span::Ident, context: &str, diags: &mut Diags) -> Option<Component> {
    if let Some((_, c)) = COMPONENTS.iter().find(|(n, _)| *n == key.name) {
        return Some(*c);
    }
    diags.push(
        Diagnostic::error(
            format!("unknown component `{}` in `{context}`", key.name),
            key.span,
            "expected `ux`, `uy` or `uz`",
        )
        .with_help_opt(did_you_mean(&key.name, ["ux", "uy", "uz"])),
    );
    None
}

/// Converts a `fix` or `displace` item.
pub fn parse(item: ItemParts, kind: BoundaryKind, diags: &mut Diags) -> Option<Boundary> {
    let target = values::set_ref(item.target.as_ref()?, diags)?;
    let block = item.block?;
    let word = match kind {
        BoundaryKind::Fix => "fix",
        BoundaryKind::Displace => "displace",
    };
    let mut components: Vec<(Spanned<Component>, Spanned<TimeFn>)> = Vec::new();
    for e in &block.entries {
        let Some(c) = component(&e.key, word, diags) else {
            continue;
        };
        if components.iter().any(|(k, _)| k.value == c) {
            diags.push(
                Diagnostic::error(
                    format!("`{}` is given twice in `{word}`", e.key.name),
                    e.key.span,
                    "duplicate component",
                )
                .with_help("remove one of them"),
            );
            continue;
        }
        let value = match (&e.body, kind) {
            (EntryBody::Flag, BoundaryKind::Fix) => Spanned::new(TimeFn::Number(0.0), e.key.span),
            (EntryBody::Assign(v), BoundaryKind::Fix) => match v.kind {
                ValueKind::Number(0.0) => Spanned::new(TimeFn::Number(0.0), v.span),
                _ => {
                    diags.push(
                        Diagnostic::error(
                            "`fix` holds components at zero",
                            v.span,
                            "only `0` is allowed here",
                        )
                        .with_help(format!(
                            "write `fix {target} {{ {} }}`, or use `displace {target} {{ {} = .. }}` for a nonzero value",
                            e.key.name, e.key.name
                        )),
                    );
                    continue;
                }
            },
            (EntryBody::Assign(v), BoundaryKind::Displace) => match values::time_fn(v, diags) {
                Some(t) => t,
                None => continue,
            },
            (EntryBody::Flag, BoundaryKind::Displace) => {
                diags.push(
                    Diagnostic::error(
                        format!("`{}` needs a prescribed value", e.key.name),
                        e.key.span,
                        format!("expected `{} = <value or time function>`", e.key.name),
                    )
                    .with_help(format!(
                        "to hold it at zero write `fix {target} {{ {} }}`",
                        e.key.name
                    )),
                );
                continue;
            }
            (EntryBody::Block(b), _) => {
                diags.push(Diagnostic::error(
                    format!("unexpected block after `{}`", e.key.name),
                    b.span,
                    "not a block",
                ));
                continue;
            }
        };
        components.push((Spanned::new(c, e.key.span), value));
    }
    if block.entries.is_empty() {
        let example = match kind {
            BoundaryKind::Fix => format!("fix {target} {{ ux uy }}"),
            BoundaryKind::Displace => format!("displace {target} {{ uy = ramp(0, -0.1) }}"),
        };
        diags.push(
            Diagnostic::error(
                format!("`{word}` lists no components"),
                block.span,
                "empty block",
            )
            .with_help(format!("write e.g. `{example}`")),
        );
    }
    Some(Boundary {
        kind,
        keyword: item.keyword,
        target,
        components,
        span: item.span,
    })
}

#[cfg(test)]
mod tests {
    use crate::ast::{BoundaryKind, Component, TimeFn};
    use crate::parse::test_support::{parse_messages, parse_ok};

    #[test]
    fn fix_and_displace() {
        let deck = parse_ok("fix block.bottom { ux uy }\ndisplace block.top { uy = ramp(0, -0.05) }\nfix b.left { ux = 0 }");
        assert_eq!(deck.boundaries.len(), 3);
        let f = &deck.boundaries[0];
        assert_eq!(f.kind, BoundaryKind::Fix);
        let comps: Vec<Component> = f.components.iter().map(|(c, _)| c.value).collect();
        assert_eq!(comps, [Component::X, Component::Y]);
        assert_eq!(f.components[0].1.value, TimeFn::Number(0.0));
        let d = &deck.boundaries[1];
        assert_eq!(d.kind, BoundaryKind::Displace);
        assert_eq!(d.components.len(), 1);
        assert!(matches!(d.components[0].1.value, TimeFn::Ramp { v1, .. } if v1 == -0.05));
    }

    #[test]
    fn boundary_mistakes() {
        assert_eq!(
            parse_messages("fix a.b { uw }"),
            ["unknown component `uw` in `fix`"]
        );
        assert_eq!(
            parse_messages("fix a.b { ux = 1 }"),
            ["`fix` holds components at zero"]
        );
        assert_eq!(
            parse_messages("displace a.b { ux }"),
            ["`ux` needs a prescribed value"]
        );
        assert_eq!(parse_messages("fix a.b { }"), ["`fix` lists no components"]);
        assert_eq!(
            parse_messages("fix a.b { ux ux }"),
            ["`ux` is given twice in `fix`"]
        );
    }
}
