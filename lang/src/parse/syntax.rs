//! pest pairs -> the generic syntax tree ([`crate::ast::syntax`]).
//!
//! The grammar guarantees the shape of every pair, so the only thing that
//! can go wrong here is a bug in the grammar; such a mismatch turns into an
//! empty node rather than a panic.

use super::Rule;
use crate::ast::syntax::{Arg, ArgKind, BinOp, Block, Entry, EntryBody, Value, ValueKind};
use crate::span::{Ident, Span};
use pest::iterators::Pair;
use pest::pratt_parser::{Assoc, Op, PrattParser};
use std::sync::LazyLock;

/// Operator precedence of `expr` (later lines bind tighter): `+ -`, then
/// `* /`, then unary `-`, then `^` (right associative: `2^3^2 = 2^9`,
/// `-2^2 = -4`).
static PRATT: LazyLock<PrattParser<Rule>> = LazyLock::new(|| {
    PrattParser::new()
        .op(Op::infix(Rule::add, Assoc::Left) | Op::infix(Rule::sub, Assoc::Left))
        .op(Op::infix(Rule::mul, Assoc::Left) | Op::infix(Rule::div, Assoc::Left))
        .op(Op::prefix(Rule::neg))
        .op(Op::infix(Rule::pow, Assoc::Right))
});

fn bin_op(rule: Rule) -> BinOp {
    match rule {
        Rule::add => BinOp::Add,
        Rule::sub => BinOp::Sub,
        Rule::mul => BinOp::Mul,
        Rule::div => BinOp::Div,
        _ => BinOp::Pow,
    }
}

fn binary(op: BinOp, op_span: Span, lhs: Value, rhs: Value) -> Value {
    Value {
        span: lhs.span.to(rhs.span),
        kind: ValueKind::Binary {
            op,
            lhs: Box::new(lhs),
            rhs: Box::new(rhs),
            op_span,
        },
    }
}

/// `expr` pair -> a value (a single operand stays that operand).
fn expr(pair: Pair<'_, Rule>) -> Value {
    PRATT
        .map_primary(value)
        .map_prefix(|op, rhs| Value {
            span: Span::of(op.as_span()).to(rhs.span),
            kind: ValueKind::Neg(Box::new(rhs)),
        })
        .map_infix(|lhs, op, rhs| binary(bin_op(op.as_rule()), Span::of(op.as_span()), lhs, rhs))
        .parse(pair.into_inner())
}

/// `set_expr` pair -> a value: terms joined left to right by `+` / `-`.
fn set_expr(pair: Pair<'_, Rule>) -> Value {
    let mut inner = pair.into_inner();
    let Some(first) = inner.next() else {
        return empty(Span::default());
    };
    let mut acc = value(first);
    while let (Some(op), Some(term)) = (inner.next(), inner.next()) {
        let o = if op.as_str().starts_with('+') {
            BinOp::Add
        } else {
            BinOp::Sub
        };
        acc = binary(o, Span::of(op.as_span()), acc, value(term));
    }
    acc
}

/// `name` pair -> [`Ident`].
pub fn ident(pair: Pair<'_, Rule>) -> Ident {
    Ident::new(pair.as_str(), Span::of(pair.as_span()))
}

/// A part of a dotted path: a name, or a quoted name (`"Hole Edge"`, the
/// span covering the quotes).
fn path_part(pair: Pair<'_, Rule>) -> Ident {
    match pair.as_rule() {
        Rule::string => {
            let span = Span::of(pair.as_span());
            Ident::new(string_text(pair), span)
        }
        _ => ident(pair),
    }
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
                    // from the operands: the pair's span may hold the
                    // whitespace skipped after the last one
                    Value {
                        span: a.span.to(b.span),
                        kind: ValueKind::Range(Box::new(a), Box::new(b)),
                    }
                }
                _ => empty(span),
            }
        }
        Rule::expr => expr(pair),
        Rule::set_expr => set_expr(pair),
        Rule::number => {
            let v = pair.as_str().parse::<f64>().unwrap_or(f64::NAN);
            Value {
                kind: ValueKind::Number(v),
                span,
            }
        }
        Rule::quantity => {
            let mut inner = pair.into_inner();
            let (Some(n), Some(u)) = (inner.next(), inner.next()) else {
                return empty(span);
            };
            Value {
                kind: ValueKind::Quantity {
                    value: n.as_str().parse::<f64>().unwrap_or(f64::NAN),
                    unit: u.as_str().to_string(),
                    unit_span: Span::of(u.as_span()),
                },
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
            kind: ValueKind::Path(pair.into_inner().map(path_part).collect()),
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
                Some(p) => p.into_inner().map(path_part).collect(),
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
