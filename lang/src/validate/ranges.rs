//! Ranges declared by key tables ([`crate::keys::Range`]), checked on the
//! settings that parsed. Messages name the value (or each component of a
//! tuple) by the key's labels: "width must be positive", "radial divisions
//! must be at least 1".

use super::Ctx;
use crate::ast::settings::{SettingValue, Settings};
use crate::ast::{num, Grading, Spanned};
use crate::diagnostics::Diagnostic;
use crate::keys::{Key, Range};

/// Checks every given setting against its key's range, in table order.
pub fn settings_in_range(settings: &Settings, keys: &[Key], ctx: &mut Ctx<'_>) {
    for key in keys {
        let Some(s) = settings.get(key.name) else {
            continue;
        };
        let span = s.value.span;
        match &s.value.value {
            SettingValue::Number(x) => number_in_range(key, 0, &Spanned::new(*x, span), ctx),
            SettingValue::Numbers(xs) => {
                for (i, x) in xs.iter().enumerate() {
                    number_in_range(key, i, x, ctx);
                }
            }
            SettingValue::Integer(n) => integer_in_range(key, 0, &Spanned::new(*n, span), ctx),
            SettingValue::Integers(ns) => {
                for (i, n) in ns.iter().enumerate() {
                    integer_in_range(key, i, n, ctx);
                }
            }
            SettingValue::Grading(g) => grading_in_range(key, 0, g, ctx),
            SettingValue::Gradings(gs) => {
                for (i, g) in gs.iter().enumerate() {
                    grading_in_range(key, i, &g.value, ctx);
                }
            }
            SettingValue::Bool(_)
            | SettingValue::Choice(_)
            | SettingValue::Mesh(_)
            | SettingValue::Text(_) => {}
        }
    }
}

/// A number against `key.range`.
pub fn number_in_range(key: &Key, i: usize, x: &Spanned<f64>, ctx: &mut Ctx<'_>) {
    let what = key.label(i);
    match key.range {
        Range::Any | Range::AtLeast(_) => {}
        Range::Positive => ctx.must_be_positive(&Some(x.clone()), what),
        Range::NonNegative => {
            if x.value < 0.0 || x.value.is_nan() {
                ctx.err(Diagnostic::error(
                    format!("{what} must not be negative"),
                    x.span,
                    "must be >= 0",
                ));
            }
        }
        Range::Closed(lo, hi) => {
            if !(lo..=hi).contains(&x.value) {
                ctx.err(Diagnostic::error(
                    format!("{what} must lie in [{}, {}]", num(lo), num(hi)),
                    x.span,
                    format!("{what} = {}", num(x.value)),
                ));
            }
        }
    }
}

/// A whole number against `key.range`.
pub fn integer_in_range(key: &Key, i: usize, n: &Spanned<i64>, ctx: &mut Ctx<'_>) {
    match key.range {
        Range::AtLeast(min) => ctx.at_least(&Some(n.clone()), min, key.label(i)),
        Range::Positive => ctx.at_least(&Some(n.clone()), 1, key.label(i)),
        Range::NonNegative => ctx.at_least(&Some(n.clone()), 0, key.label(i)),
        _ => number_in_range(key, i, &Spanned::new(n.value as f64, n.span), ctx),
    }
}

/// The ratio of a grading against `key.range`.
pub fn grading_in_range(key: &Key, i: usize, g: &Grading, ctx: &mut Ctx<'_>) {
    if let Grading::Geometric(r) | Grading::Center(r) = g {
        number_in_range(key, i, r, ctx);
    }
}
