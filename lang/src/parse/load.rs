//! `pressure body.edges { p = .. }`, `traction body.faces { tx = .. ty = ..
//! tz = .. }` and `force body.nodes { fx = .. fy = .. }`.

use super::fields::Fields;
use super::values::{self, Diags};
use super::ItemParts;
use crate::ast::syntax::{EntryBody, Value, ValueKind};
use crate::ast::{Component, Gravity, LoadDef, LoadKind, RateControlDef};
use crate::diagnostics::Diagnostic;
use crate::span::Spanned;
use crate::suggest::{did_you_mean, one_of};

/// Converts a `pressure`, `traction` or `force` item.
pub fn parse(item: ItemParts, kind: LoadKind, diags: &mut Diags) -> Option<LoadDef> {
    let target = values::set_ref(item.target.as_ref()?, diags)?;
    let block = item.block?;
    let (word, keys): (&str, &[(&str, Option<Component>)]) = match kind {
        LoadKind::Pressure => ("pressure", &[("p", None)]),
        LoadKind::Traction => (
            "traction",
            &[
                ("tx", Some(Component::X)),
                ("ty", Some(Component::Y)),
                ("tz", Some(Component::Z)),
            ],
        ),
        LoadKind::Force => (
            "force",
            &[
                ("fx", Some(Component::X)),
                ("fy", Some(Component::Y)),
                ("fz", Some(Component::Z)),
            ],
        ),
    };
    let mut names: Vec<&str> = keys.iter().map(|(n, _)| *n).collect();
    if kind == LoadKind::Pressure {
        names.push("follower");
        names.push("control");
    }
    let mut follower = None;
    let mut control = None;
    let values_out = time_components(&block, word, keys, &names, diags, |e, diags| {
        if kind == LoadKind::Pressure && e.key.name == "control" {
            match &e.body {
                EntryBody::Assign(v) if control.is_none() => control = rate_control(v, diags),
                EntryBody::Assign(_) => diags.push(
                    Diagnostic::error(
                        "`control` is given twice in `pressure`",
                        e.key.span,
                        "duplicate key",
                    )
                    .with_help("remove one of them"),
                ),
                _ => diags.push(Diagnostic::error(
                    "`control` needs a value",
                    e.span,
                    "expected `control = strain_rate { target = .. }`",
                )),
            }
            return true;
        }
        if kind != LoadKind::Pressure || e.key.name != "follower" {
            return false;
        }
        match &e.body {
            EntryBody::Assign(v) if follower.is_none() => {
                follower = values::boolean(v, diags);
            }
            EntryBody::Assign(_) => diags.push(
                Diagnostic::error(
                    "`follower` is given twice in `pressure`",
                    e.key.span,
                    "duplicate key",
                )
                .with_help("remove one of them"),
            ),
            _ => diags.push(Diagnostic::error(
                "`follower` needs a value",
                e.span,
                "expected `follower = true` or `follower = false`",
            )),
        }
        true
    });
    if block.entries.is_empty() {
        let example = match kind {
            LoadKind::Pressure => "p = ramp(0, 10)",
            LoadKind::Traction => "tx = ramp(0, 5)",
            LoadKind::Force => "fy = -1",
        };
        diags.push(
            Diagnostic::error(
                format!("`{word}` gives no value"),
                block.span,
                "empty block",
            )
            .with_help(format!("write e.g. `{word} {target} {{ {example} }}`")),
        );
    }
    Some(LoadDef {
        kind,
        keyword: item.keyword,
        target,
        values: values_out,
        follower,
        control,
        span: item.span,
    })
}

/// `strain_rate { target = ..  exponent = ..  max_change = ..  max_pressure = ..  at = .. }`.
fn rate_control(v: &Value, diags: &mut Diags) -> Option<Spanned<RateControlDef>> {
    let ValueKind::Ctor { name, block } = &v.kind else {
        diags.push(Diagnostic::error(
            format!("expected a controller, found {}", v.kind.describe()),
            v.span,
            "expected `strain_rate { target = .. }`",
        ));
        return None;
    };
    if name.name != "strain_rate" {
        diags.push(
            Diagnostic::error(
                format!("unknown controller `{}`", name.name),
                name.span,
                "not a controller",
            )
            .with_help("expected `strain_rate { target = .. }`"),
        );
        return None;
    }
    let mut f = Fields::keyed(
        block,
        "`strain_rate` controller",
        &crate::tables::RATE_CONTROL,
    );
    let target = f.number("target", diags);
    let exponent = f.number("exponent", diags);
    let max_change = f.number("max_change", diags);
    let max_pressure = f.number("max_pressure", diags);
    let at = f
        .value("at", diags)
        .and_then(|v| super::values::coords(v, diags));
    f.require(
        &target,
        "target",
        name.span,
        "add the target strain rate `target = ..` (1 / time)",
        diags,
    );
    f.finish(diags);
    Some(Spanned::new(
        RateControlDef {
            target,
            exponent,
            max_change,
            max_pressure,
            at,
        },
        v.span,
    ))
}

/// The keyword of `gravity { gx  gy  gz }` (carried by the generic item
/// rule, like `traction`).
pub const GRAVITY: &str = "gravity";

/// Converts a `gravity` item: no set (it acts on every mass), components
/// `gx gy gz` (accelerations, functions of time).
pub fn gravity(item: ItemParts, diags: &mut Diags) -> Option<Gravity> {
    if let Some(t) = &item.target {
        diags.push(
            Diagnostic::error(
                "`gravity` takes no set",
                t.span,
                "gravity acts on every body with a density and every point mass",
            )
            .with_help("write `gravity { gy = -9.81 }`"),
        );
        return None;
    }
    let Some(block) = item.block else {
        diags.push(
            Diagnostic::error("`gravity` needs a block", item.keyword, "no block")
                .with_help("write `gravity { gy = -9.81 }`"),
        );
        return None;
    };
    let keys = [
        ("gx", Some(Component::X)),
        ("gy", Some(Component::Y)),
        ("gz", Some(Component::Z)),
    ];
    let names: Vec<&str> = keys.iter().map(|(n, _)| *n).collect();
    let values = time_components(&block, GRAVITY, &keys, &names, diags, |_, _| false);
    if block.entries.is_empty() {
        diags.push(
            Diagnostic::error("`gravity` gives no value", block.span, "empty block")
                .with_help("write e.g. `gravity { gy = -9.81 }`"),
        );
    }
    Some(Gravity {
        keyword: item.keyword,
        values,
        span: item.span,
    })
}

/// The `key = F(t)` entries of an item's block whose keys are `keys`
/// (component of each), in block order: unknown keys (all `names` are
/// known) and duplicates are reported; `other` takes an entry first and
/// returns whether it handled it.
pub(super) fn time_components(
    block: &crate::ast::syntax::Block,
    word: &str,
    keys: &[(&str, Option<Component>)],
    names: &[&str],
    diags: &mut Diags,
    mut other: impl FnMut(&crate::ast::syntax::Entry, &mut Diags) -> bool,
) -> Vec<(Option<Component>, crate::span::Spanned<crate::ast::TimeFn>)> {
    let mut values_out = Vec::new();
    let mut seen: Vec<&str> = Vec::new();
    for e in &block.entries {
        if other(e, diags) {
            continue;
        }
        let Some((key, comp)) = keys.iter().find(|(n, _)| *n == e.key.name) else {
            diags.push(
                Diagnostic::error(
                    format!("unknown key `{}` in `{word}`", e.key.name),
                    e.key.span,
                    format!("expected {}", one_of(names)),
                )
                .with_help_opt(did_you_mean(&e.key.name, names)),
            );
            continue;
        };
        if seen.contains(key) {
            diags.push(
                Diagnostic::error(
                    format!("`{key}` is given twice in `{word}`"),
                    e.key.span,
                    "duplicate key",
                )
                .with_help("remove one of them"),
            );
            continue;
        }
        seen.push(key);
        match &e.body {
            EntryBody::Assign(v) => {
                if let Some(t) = values::time_fn(v, diags) {
                    values_out.push((*comp, t));
                }
            }
            _ => diags.push(Diagnostic::error(
                format!("`{key}` needs a value"),
                e.span,
                format!("expected `{key} = <value or time function>`"),
            )),
        }
    }
    values_out
}

#[cfg(test)]
mod tests {
    use crate::ast::{Component, LoadKind, TimeFn};
    use crate::parse::test_support::{parse_messages, parse_ok};

    #[test]
    fn gravity_components_and_errors() {
        let deck = parse_ok("gravity { gy = -9.81  gx = ramp(0, 1) }");
        let g = &deck.gravity[0];
        assert_eq!(g.values.len(), 2);
        assert_eq!(g.values[0].0, Some(Component::Y));
        assert_eq!(g.values[0].1.value, TimeFn::Number(-9.81));
        assert_eq!(
            parse_messages("gravity { gg = 1 }"),
            ["unknown key `gg` in `gravity`"]
        );
        assert_eq!(
            parse_messages("gravity block.all { gy = 1 }"),
            ["`gravity` takes no set"]
        );
        assert_eq!(parse_messages("gravity { }"), ["`gravity` gives no value"]);
    }

    #[test]
    fn pressure_and_force() {
        let deck = parse_ok("pressure block.right { p = ramp(0, 10) }\nforce block.node(near(0, 0)) { fy = -1  fx = table((0, 0), (1, 2)) }");
        assert_eq!(deck.loads.len(), 2);
        assert_eq!(deck.loads[0].kind, LoadKind::Pressure);
        assert_eq!(deck.loads[0].values[0].0, None);
        let f = &deck.loads[1];
        assert_eq!(f.values[0].0, Some(Component::Y));
        assert_eq!(f.values[0].1.value, TimeFn::Number(-1.0));
        assert_eq!(f.values[1].0, Some(Component::X));
    }

    #[test]
    fn follower_pressure() {
        let deck = parse_ok("pressure sheet.bottom { p = ramp(0, 2)  follower = true }");
        assert_eq!(deck.loads[0].follower.as_ref().map(|f| f.value), Some(true));
        assert_eq!(deck.loads[0].values.len(), 1);
        let deck = parse_ok("pressure sheet.bottom { p = 1 }");
        assert!(deck.loads[0].follower.is_none());
        assert_eq!(
            parse_messages("pressure a.b { p = 1  follower = 3 }").len(),
            1,
            "a number is not a boolean"
        );
        assert_eq!(
            parse_messages("force a.b { fx = 1  follower = true }"),
            ["unknown key `follower` in `force`"]
        );
    }

    #[test]
    fn traction_components() {
        let deck = parse_ok("traction block.faces(z = 1) { tx = ramp(0, 5)  tz = -1 }");
        let t = &deck.loads[0];
        assert_eq!(t.kind, LoadKind::Traction);
        assert_eq!(t.values[0].0, Some(Component::X));
        assert_eq!(t.values[1].0, Some(Component::Z));
        assert_eq!(t.values[1].1.value, TimeFn::Number(-1.0));
        assert_eq!(
            parse_messages("traction a.b { px = 1 }"),
            ["unknown key `px` in `traction`"]
        );
        assert_eq!(
            parse_messages("traction a.b { }"),
            ["`traction` gives no value"]
        );
    }

    #[test]
    fn load_mistakes() {
        assert_eq!(
            parse_messages("force a.b { fw = 1 }"),
            ["unknown key `fw` in `force`"]
        );
        assert_eq!(
            parse_messages("pressure a.b { }"),
            ["`pressure` gives no value"]
        );
    }
}
