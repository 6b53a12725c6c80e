//! pest pairs -> the generic syntax tree ([`crate::ast::syntax`]).
//!
//! The grammar guarantees the shape of every pair, so the only thing that
//! can go wrong here is a bug in the grammar; such a mismatch turns into an
//! empty node rather than a panic.

use super::Rule;
use crate::ast::syntax::{Arg, ArgKind, Block, Entry, EntryBody, Value, ValueKind};
use crate::span::{Ident, Span};
use pest::iterators::Pair;

/// `name` pair -> [`Ident`].
pub fn ident(pair: Pair<'_, Rule>) -> Ident {
    Ident::new(pair.as_str(), Span::of(pair.as_span()))
}

/// `block` pair -> [`Block`].
pub fn block(pair: Pair<'_, Rule>) -> Block {
    let span = Span::of(pair.as_span());
    let entries = pair
        .into_inner()
        .filter(|p| p.as_rule() == Rule::entry)
        .map(entry)
        .collect();
    Block { entries, span }
}

/// `entry` pair -> [`Entry`].
fn entry(pair: Pair<'_, Rule>) -> Entry {
    let span = Span::of(pair.as_span());
    let mut inner = pair.into_inner();
    let key = inner
        .next()
        .map(ident)
        .unwrap_or_else(|| Ident::new("", span));
    let body = match inner.next() {
        None => EntryBody::Flag,
        Some(p) if p.as_rule() == Rule::block => EntryBody::Block(block(p)),
        Some(p) => EntryBody::Assign(value(p)),
    };
    Entry { key, body, span }
}

/// `value` pair (or any atom pair) -> [`Value`].
pub fn value(pair: Pair<'_, Rule>) -> Value {
    let span = Span::of(pair.as_span());
    match pair.as_rule() {
        Rule::value => {
            let mut atoms: Vec<Value> = pair.into_inner().map(value).collect();
            match atoms.len() {
                1 => atoms.remove(0),
                2 => {
                    let b = atoms.remove(1);
                    let a = atoms.remove(0);
                    Value {
                        kind: ValueKind::Range(Box::new(a), Box::new(b)),
                        span,
                    }
                }
                _ => empty(span),
            }
        }
        Rule::number => {
            let v = pair.as_str().parse::<f64>().unwrap_or(f64::NAN);
            Value {
                kind: ValueKind::Number(v),
                span,
            }
        }
        Rule::string => Value {
            kind: ValueKind::Str(string_text(pair)),
            span,
        },
        Rule::tuple => Value {
            kind: ValueKind::Tuple(pair.into_inner().map(value).collect()),
            span,
        },
        Rule::list => Value {
            kind: ValueKind::List(pair.into_inner().map(value).collect()),
            span,
        },
        Rule::path => Value {
            kind: ValueKind::Path(pair.into_inner().map(ident).collect()),
            span,
        },
        Rule::ctor => {
            let mut inner = pair.into_inner();
            let (Some(n), Some(rest)) = (inner.next(), inner.next()) else {
                return empty(span);
            };
            let name = ident(n);
            if rest.as_rule() == Rule::block {
                Value {
                    kind: ValueKind::Ctor {
                        name,
                        block: block(rest),
                    },
                    span,
                }
            } else {
                let text_span = Span::of(rest.as_span());
                Value {
                    kind: ValueKind::CtorStr {
                        name,
                        text: string_text(rest),
                        text_span,
                    },
                    span,
                }
            }
        }
        Rule::call => {
            let mut inner = pair.into_inner();
            let path = match inner.next() {
                Some(p) => p.into_inner().map(ident).collect(),
                None => Vec::new(),
            };
            let args = inner.map(arg).collect();
            Value {
                kind: ValueKind::Call { path, args },
                span,
            }
        }
        _ => empty(span),
    }
}

/// `arg` pair -> [`Arg`].
fn arg(pair: Pair<'_, Rule>) -> Arg {
    let span = Span::of(pair.as_span());
    let mut inner = pair.into_inner();
    let Some(first) = inner.next() else {
        return Arg {
            kind: ArgKind::Positional(empty(span)),
            span,
        };
    };
    let kind = if first.as_rule() == Rule::named_arg {
        let mut parts = first.into_inner();
        match (parts.next(), parts.next()) {
            (Some(n), Some(v)) => ArgKind::Named(ident(n), value(v)),
            _ => ArgKind::Positional(empty(span)),
        }
    } else {
        let v = value(first);
        match inner.next() {
            Some(n) => ArgKind::Arrow(v, ident(n)),
            None => ArgKind::Positional(v),
        }
    };
    Arg { kind, span }
}

/// The text between the quotes of a `string` pair.
fn string_text(pair: Pair<'_, Rule>) -> String {
    pair.into_inner()
        .next()
        .map(|p| p.as_str().to_string())
        .unwrap_or_default()
}

/// A placeholder for a node the grammar should never produce.
fn empty(span: Span) -> Value {
    Value {
        kind: ValueKind::Tuple(Vec::new()),
        span,
    }
}
