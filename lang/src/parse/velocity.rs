//! `initial_velocity body.nodes { vx = ..  vy = ..  vz = .. }`.

use super::values::{self, Diags};
use super::ItemParts;
use crate::ast::syntax::EntryBody;
use crate::ast::{Component, InitialVelocity};
use crate::diagnostics::Diagnostic;
use crate::suggest::{did_you_mean, one_of};

/// The item keyword (carried by the generic item rule, like `traction`).
pub const KEYWORD: &str = "initial_velocity";

/// Converts an `initial_velocity` item.
pub fn parse(item: ItemParts, diags: &mut Diags) -> Option<InitialVelocity> {
    let target = values::set_ref(item.target.as_ref()?, diags)?;
    let block = item.block?;
    let keys = [
        ("vx", Component::X),
        ("vy", Component::Y),
        ("vz", Component::Z),
    ];
    let names: Vec<&str> = keys.iter().map(|(n, _)| *n).collect();
    let mut out = Vec::new();
    for e in &block.entries {
        let Some((key, comp)) = keys.iter().find(|(n, _)| *n == e.key.name) else {
            diags.push(
                Diagnostic::error(
                    format!("unknown key `{}` in `{KEYWORD}`", e.key.name),
                    e.key.span,
                    format!("expected {}", one_of(&names)),
                )
                .with_help_opt(did_you_mean(&e.key.name, &names)),
            );
            continue;
        };
        if out.iter().any(|(c, _)| c == comp) {
            diags.push(
                Diagnostic::error(
                    format!("`{key}` is given twice in `{KEYWORD}`"),
                    e.key.span,
                    "duplicate key",
                )
                .with_help("remove one of them"),
            );
            continue;
        }
        match &e.body {
            EntryBody::Assign(v) => {
                if let Some(x) = values::number_of(
                    v,
                    Some(crate::keys::Dim::Velocity),
                    &format!("`{key}`"),
                    diags,
                ) {
                    out.push((*comp, x));
                }
            }
            _ => diags.push(Diagnostic::error(
                format!("`{key}` needs a value"),
                e.span,
                format!("expected `{key} = <velocity>`"),
            )),
        }
    }
    if block.entries.is_empty() {
        diags.push(
            Diagnostic::error(
                format!("`{KEYWORD}` gives no value"),
                block.span,
                "empty block",
            )
            .with_help(format!("write e.g. `{KEYWORD} {target} {{ vx = -5 }}`")),
        );
    }
    Some(InitialVelocity {
        keyword: item.keyword,
        target,
        values: out,
        span: item.span,
    })
}

#[cfg(test)]
mod tests {
    use crate::ast::Component;
    use crate::parse::test_support::{parse_messages, parse_ok};

    #[test]
    fn initial_velocity_components() {
        let deck = parse_ok("initial_velocity bar.all { vx = -2  vy = 0.5 }");
        let v = &deck.initial_velocities[0];
        assert_eq!(v.values[0].0, Component::X);
        assert_eq!(v.values[0].1.value, -2.0);
        assert_eq!(v.values[1].0, Component::Y);
        assert_eq!(
            parse_messages("initial_velocity bar.all { ux = 1 }"),
            ["unknown key `ux` in `initial_velocity`"]
        );
        assert_eq!(
            parse_messages("initial_velocity bar.all { }"),
            ["`initial_velocity` gives no value"]
        );
    }
}
