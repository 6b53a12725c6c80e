//! Reading a block through a key table ([`crate::keys`]) into typed
//! [`Settings`]: every key is read by its declared type (points and tuples
//! with their number of components, choices with "did you mean", nested
//! meshes), required keys are reported when missing, unknown keys get a
//! suggestion.

use super::fields::Fields;
use super::values::{self, Diags};
use crate::ast::settings::{Setting, SettingValue, Settings};
use crate::ast::syntax::{Block, Value, ValueKind};
use crate::diagnostics::Diagnostic;
use crate::keys::{Components, Key, KeyType};
use crate::span::{Span, Spanned};

/// Reads `block` (called `what` in messages) through `keys`; `at` is where
/// a missing required key is reported.
pub fn read(
    block: &Block,
    what: String,
    keys: &'static [Key],
    at: Span,
    diags: &mut Diags,
) -> Settings {
    let mut f = Fields::keyed(block, what, keys);
    let mut out = Settings::default();
    for key in keys {
        let Some(v) = f.value(key.name, diags) else {
            continue;
        };
        if let Some(value) = setting(v, key, diags) {
            out.entries.push(Setting { key, value });
        }
    }
    for key in keys {
        if let Some(help) = key.required {
            let found = out.get(key.name).map(|_| ());
            f.require(&found, key.name, at, help, diags);
        }
    }
    f.finish(diags);
    out
}

/// The elements of a tuple with an accepted number of components.
fn tuple<'v>(
    v: &'v Value,
    c: Components,
    expected: &str,
    diags: &mut Diags,
) -> Option<&'v [Value]> {
    match &v.kind {
        ValueKind::Tuple(items) if c.accepts(items.len()) => Some(items),
        ValueKind::Tuple(items) => {
            diags.push(Diagnostic::error(
                format!("expected {expected}, found a tuple of {}", items.len()),
                v.span,
                format!("expected {expected}"),
            ));
            None
        }
        other => {
            diags.push(Diagnostic::error(
                format!("expected {expected}, found {}", other.describe()),
                v.span,
                format!("expected {expected}"),
            ));
            None
        }
    }
}

/// A number of `key`'s dimension.
fn number(v: &Value, key: &Key, diags: &mut Diags) -> Option<Spanned<f64>> {
    values::number_of(v, Some(key.dim), &format!("`{}`", key.name), diags)
}

/// Reads one value by its key's type.
pub fn setting(v: &Value, key: &Key, diags: &mut Diags) -> Option<Spanned<SettingValue>> {
    let expected = key.ty.describe();
    let value = match key.ty {
        KeyType::Number => SettingValue::Number(number(v, key, diags)?.value),
        KeyType::Integer => SettingValue::Integer(values::integer(v, diags)?.value),
        KeyType::Bool => SettingValue::Bool(values::boolean(v, diags)?.value),
        KeyType::Choice(names) => {
            let options: Vec<(&str, &'static str)> = names.iter().map(|n| (*n, *n)).collect();
            SettingValue::Choice(values::choice(v, key.name, &options, diags)?.value)
        }
        KeyType::Point(c) => {
            // a point stops at its first bad coordinate
            let items = tuple(v, c, &expected, diags)?;
            let mut xs = Vec::new();
            for x in items {
                xs.push(number(x, key, diags)?);
            }
            SettingValue::Numbers(xs)
        }
        KeyType::Numbers(c) => {
            let items = tuple(v, c, &expected, diags)?;
            let xs: Vec<_> = items.iter().map(|x| number(x, key, diags)).collect();
            SettingValue::Numbers(xs.into_iter().collect::<Option<Vec<_>>>()?)
        }
        KeyType::Integers(c) => {
            let items = tuple(v, c, &expected, diags)?;
            let xs: Vec<_> = items.iter().map(|x| values::integer(x, diags)).collect();
            SettingValue::Integers(xs.into_iter().collect::<Option<Vec<_>>>()?)
        }
        KeyType::Grading => SettingValue::Grading(values::grading(v, diags)?.value),
        KeyType::Gradings(c) => {
            let items = tuple(v, c, &expected, diags)?;
            let gs: Vec<_> = items.iter().map(|x| values::grading(x, diags)).collect();
            SettingValue::Gradings(gs.into_iter().collect::<Option<Vec<_>>>()?)
        }
        KeyType::Mesh => SettingValue::Mesh(Box::new(super::body::mesh(v, diags)?)),
        KeyType::File => SettingValue::Text(values::text(v, "a file path in quotes", diags)?.value),
    };
    Some(Spanned::new(value, v.span))
}
