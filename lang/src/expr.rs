//! Arithmetic wherever a number goes: `let` parameters, `+ - * / ^`,
//! parentheses, `sqrt sin cos tan abs exp min max`, `pi`, and numbers with
//! units (`210 GPa`), checked for dimensional consistency.
//!
//! Evaluation works on [`Quantity`]: a number without a unit is *untyped*
//! (taken in the deck's unit system, its dimension given by the key it is
//! written for); a number with a unit is *typed* and held in SI. Sums of a
//! typed and an untyped operand take the typed one's dimension; products
//! treat an untyped operand as a pure number. At the key, a typed value
//! must have the key's dimension and is converted into the deck's system.
//! Every error points at the operand it is about, with the other operands
//! labelled.

use crate::ast::syntax::{BinOp, Value, ValueKind};
use crate::diagnostics::Diagnostic;
use crate::span::{Ident, Span, Spanned};
use crate::suggest::did_you_mean;
use crate::units::{self, Exponents, System};

/// A value during evaluation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Quantity {
    /// The value: in SI when `dim` is `Some`, else in the deck's system.
    pub value: f64,
    /// The dimension, when a unit made it known.
    pub dim: Option<Exponents>,
}

impl Quantity {
    /// An untyped number.
    pub fn plain(value: f64) -> Self {
        Quantity { value, dim: None }
    }
}

/// Names a parameter cannot take (constants and functions).
pub const RESERVED: [&str; 10] = [
    "pi", "sqrt", "sin", "cos", "tan", "abs", "exp", "ln", "min", "max",
];

/// Whether `name` is a function of expressions.
pub fn is_function(name: &str) -> bool {
    UNARY.contains(&name) || NARY.contains(&name)
}

/// Functions of one argument.
const UNARY: [&str; 7] = ["sqrt", "sin", "cos", "tan", "abs", "exp", "ln"];
/// Functions of two or more arguments.
const NARY: [&str; 2] = ["min", "max"];

/// What expressions can refer to: `let` parameters (in deck order) and the
/// unit system.
#[derive(Debug, Clone, Default)]
pub struct Env {
    /// Parameters defined so far.
    pub params: Vec<(Ident, Quantity)>,
    /// `analysis { units = .. }`.
    pub system: Option<&'static System>,
    /// Whether "units need a unit system" was already reported.
    pub reported_no_system: bool,
}

impl Env {
    fn param(&self, name: &str) -> Option<Quantity> {
        self.params
            .iter()
            .rev()
            .find(|(n, _)| n.name == name)
            .map(|(_, q)| *q)
    }

    /// The SI value of an untyped number of dimension `dim`.
    fn to_si(&self, x: f64, dim: Exponents) -> f64 {
        match self.system {
            Some(s) => x * s.scale(dim),
            None => x,
        }
    }
}

/// Sink for evaluation diagnostics.
pub type Out = Vec<Diagnostic>;

/// Evaluates `v` to a quantity; `None` after reporting why not.
pub fn eval(v: &Value, env: &mut Env, out: &mut Out) -> Option<Quantity> {
    match &v.kind {
        ValueKind::Number(x) => Some(Quantity::plain(*x)),
        ValueKind::Quantity {
            value,
            unit,
            unit_span,
        } => typed(*value, unit, *unit_span, env, out),
        ValueKind::Path(p) if p.len() == 1 => name(&p[0], env, out),
        ValueKind::Tuple(items) if items.len() == 1 => eval(&items[0], env, out),
        ValueKind::Neg(x) => {
            let q = eval(x, env, out)?;
            Some(Quantity {
                value: -q.value,
                dim: q.dim,
            })
        }
        ValueKind::Binary {
            op,
            lhs,
            rhs,
            op_span,
        } => binary(*op, lhs, rhs, *op_span, v.span, env, out),
        ValueKind::Call { path, args } if path.len() == 1 => call(&path[0], args, v.span, env, out),
        other => {
            out.push(Diagnostic::error(
                format!("expected a number, found {}", other.describe()),
                v.span,
                "expected a number",
            ));
            None
        }
    }
}

fn typed(value: f64, unit: &str, at: Span, env: &mut Env, out: &mut Out) -> Option<Quantity> {
    let u = match units::parse(unit) {
        Ok(u) => u,
        Err(bad) => {
            let names: Vec<&str> = units::ATOMS.iter().map(|a| a.name).collect();
            out.push(
                Diagnostic::error(format!("unknown unit `{bad}`"), at, "not a unit").with_help(
                    did_you_mean(&bad, &names).unwrap_or_else(|| {
                        "units are products of m, mm, kg, t, s, N, Pa, MPa, GPa, J, W, K, deg, \
                         rad, .. with powers, e.g. `N/mm^2`"
                            .to_string()
                    }),
                ),
            );
            return None;
        }
    };
    if env.system.is_none() {
        if !env.reported_no_system {
            env.reported_no_system = true;
            out.push(
                Diagnostic::error(
                    "a number with a unit needs the deck's unit system",
                    at,
                    "unit without a unit system",
                )
                .with_help(
                    "add `units = SI` (or `mm_N_s`, `mm_kg_ms`) to the `analysis` block; numbers \
                     without a unit are taken in that system",
                ),
            );
        }
        return None;
    }
    Some(Quantity {
        value: value * u.scale,
        dim: Some(u.dim),
    })
}

fn name(n: &Ident, env: &mut Env, out: &mut Out) -> Option<Quantity> {
    if n.name == "pi" {
        return Some(Quantity::plain(std::f64::consts::PI));
    }
    if let Some(q) = env.param(&n.name) {
        return Some(q);
    }
    let mut names: Vec<&str> = env.params.iter().map(|(n, _)| n.name.as_str()).collect();
    names.push("pi");
    let help = did_you_mean(&n.name, &names).unwrap_or_else(|| {
        if env.params.is_empty() {
            format!("define it before its use: `let {} = ..`", n.name)
        } else {
            format!(
                "the parameters defined so far are {}",
                crate::suggest::one_of(&names[..names.len() - 1])
            )
        }
    });
    out.push(
        Diagnostic::error(
            format!("unknown parameter `{}`", n.name),
            n.span,
            "not a parameter",
        )
        .with_help(help),
    );
    None
}

/// Brings two operands of a sum or comparison to a common dimension; the
/// error names both dimensions and points at both operands.
#[allow(clippy::too_many_arguments)]
fn common(
    what: &str,
    a: Quantity,
    b: Quantity,
    sa: Span,
    sb: Span,
    at: Span,
    env: &Env,
    out: &mut Out,
) -> Option<(f64, f64, Option<Exponents>)> {
    match (a.dim, b.dim) {
        (Some(da), Some(db)) if da != db => {
            out.push(
                Diagnostic::error(
                    format!("cannot {what} {} and {}", da.describe(), db.describe()),
                    at,
                    "mixed dimensions",
                )
                .with_secondary(sa, da.describe())
                .with_secondary(sb, db.describe())
                .with_help("check the units of the operands"),
            );
            None
        }
        (Some(d), None) => Some((a.value, env.to_si(b.value, d), Some(d))),
        (None, Some(d)) => Some((env.to_si(a.value, d), b.value, Some(d))),
        (d, _) => Some((a.value, b.value, d)),
    }
}

#[allow(clippy::too_many_arguments)]
fn binary(
    op: BinOp,
    lhs: &Value,
    rhs: &Value,
    op_span: Span,
    whole: Span,
    env: &mut Env,
    out: &mut Out,
) -> Option<Quantity> {
    let a = eval(lhs, env, out);
    let b = eval(rhs, env, out);
    let (a, b) = (a?, b?);
    let q = match op {
        BinOp::Add | BinOp::Sub => {
            let what = if op == BinOp::Add { "add" } else { "subtract" };
            let (x, y, d) = common(what, a, b, lhs.span, rhs.span, op_span, env, out)?;
            Quantity {
                value: if op == BinOp::Add { x + y } else { x - y },
                dim: d,
            }
        }
        BinOp::Mul => Quantity {
            value: a.value * b.value,
            dim: match (a.dim, b.dim) {
                (Some(x), Some(y)) => Some(x.times(y)),
                (x, y) => x.or(y),
            },
        },
        BinOp::Div => {
            if b.value == 0.0 {
                out.push(
                    Diagnostic::error("division by zero", rhs.span, "this is zero")
                        .with_secondary(lhs.span, "divided"),
                );
                return None;
            }
            Quantity {
                value: a.value / b.value,
                dim: match (a.dim, b.dim) {
                    (Some(x), Some(y)) => Some(x.per(y)),
                    (Some(x), None) => Some(x),
                    (None, Some(y)) => Some(Exponents::NONE.per(y)),
                    (None, None) => None,
                },
            }
        }
        BinOp::Pow => {
            if b.dim.is_some_and(|d| d != Exponents::NONE) {
                out.push(Diagnostic::error(
                    format!(
                        "an exponent must be a pure number, not {}",
                        b.dim.map_or(String::new(), |d| d.describe())
                    ),
                    rhs.span,
                    "has a unit",
                ));
                return None;
            }
            let dim = match a.dim {
                Some(d) if d != Exponents::NONE => {
                    let n = b.value;
                    if n.fract() != 0.0 || n.abs() > 8.0 {
                        out.push(
                            Diagnostic::error(
                                format!("{} can only be raised to a whole power", d.describe()),
                                rhs.span,
                                format!("power {}", crate::ast::num(n)),
                            )
                            .with_secondary(lhs.span, d.describe()),
                        );
                        return None;
                    }
                    Some(d.pow(n as i8))
                }
                d => d,
            };
            Quantity {
                value: a.value.powf(b.value),
                dim,
            }
        }
    };
    finite(q, whole, out)
}

fn finite(q: Quantity, at: Span, out: &mut Out) -> Option<Quantity> {
    if q.value.is_finite() {
        Some(q)
    } else {
        out.push(Diagnostic::error(
            "the expression has no finite value",
            at,
            "overflow or undefined",
        ));
        None
    }
}

fn call(
    f: &Ident,
    args: &[crate::ast::syntax::Arg],
    whole: Span,
    env: &mut Env,
    out: &mut Out,
) -> Option<Quantity> {
    use crate::ast::syntax::ArgKind;
    let name = f.name.as_str();
    if !UNARY.contains(&name) && !NARY.contains(&name) {
        let all: Vec<&str> = UNARY.iter().chain(NARY.iter()).copied().collect();
        out.push(
            Diagnostic::error(
                format!("unknown function `{name}`"),
                f.span,
                "not a function",
            )
            .with_help(
                did_you_mean(name, &all).unwrap_or_else(|| {
                    format!("the functions are {}", crate::suggest::one_of(&all))
                }),
            ),
        );
        return None;
    }
    let mut values = Vec::new();
    for a in args {
        match &a.kind {
            ArgKind::Positional(v) => values.push(v),
            _ => {
                out.push(Diagnostic::error(
                    "unexpected argument",
                    a.span,
                    "expected a plain value here",
                ));
                return None;
            }
        }
    }
    let unary = UNARY.contains(&name);
    if (unary && values.len() != 1) || (!unary && values.len() < 2) {
        out.push(Diagnostic::error(
            format!(
                "`{name}` takes {}, found {}",
                if unary {
                    "1 argument"
                } else {
                    "2 or more arguments"
                },
                values.len()
            ),
            whole,
            "wrong number of arguments",
        ));
        return None;
    }
    let qs: Vec<Option<Quantity>> = values.iter().map(|v| eval(v, env, out)).collect();
    let qs: Vec<Quantity> = qs.into_iter().collect::<Option<_>>()?;
    if !unary {
        let mut acc = qs[0];
        let mut acc_span = values[0].span;
        for (q, v) in qs.iter().zip(&values).skip(1) {
            let (x, y, d) = common("compare", acc, *q, acc_span, v.span, whole, env, out)?;
            let pick = if name == "min" { x.min(y) } else { x.max(y) };
            acc = Quantity {
                value: pick,
                dim: d,
            };
            acc_span = acc_span.to(v.span);
        }
        return Some(acc);
    }
    let x = qs[0];
    let arg = values[0];
    let pure = |d: Option<Exponents>| d.is_none_or(|d| d == Exponents::NONE);
    let q = match name {
        "sqrt" => {
            if x.value < 0.0 {
                out.push(Diagnostic::error(
                    "square root of a negative number",
                    arg.span,
                    format!("= {}", crate::ast::num(x.value)),
                ));
                return None;
            }
            let dim = match x.dim {
                Some(d) => match d.root(2) {
                    Some(r) => Some(r),
                    None => {
                        out.push(Diagnostic::error(
                            format!("the square root of {} has no unit", d.describe()),
                            arg.span,
                            format!("dimension {d}"),
                        ));
                        return None;
                    }
                },
                None => None,
            };
            Quantity {
                value: x.value.sqrt(),
                dim,
            }
        }
        "abs" => Quantity {
            value: x.value.abs(),
            dim: x.dim,
        },
        "sin" | "cos" | "tan" => {
            let angle = x
                .dim
                .is_none_or(|d| d == Exponents::ANGLE || d == Exponents::NONE);
            if !angle {
                out.push(Diagnostic::error(
                    format!(
                        "`{name}` takes an angle, not {}",
                        x.dim.map_or(String::new(), |d| d.describe())
                    ),
                    arg.span,
                    "not an angle",
                ));
                return None;
            }
            let v = match name {
                "sin" => x.value.sin(),
                "cos" => x.value.cos(),
                _ => x.value.tan(),
            };
            Quantity::plain(v)
        }
        _ => {
            if !pure(x.dim) {
                out.push(Diagnostic::error(
                    format!(
                        "`{name}` takes a pure number, not {}",
                        x.dim.map_or(String::new(), |d| d.describe())
                    ),
                    arg.span,
                    "has a unit",
                ));
                return None;
            }
            if name == "ln" && x.value <= 0.0 {
                out.push(Diagnostic::error(
                    "logarithm of a number <= 0",
                    arg.span,
                    format!("= {}", crate::ast::num(x.value)),
                ));
                return None;
            }
            Quantity::plain(if name == "exp" {
                x.value.exp()
            } else {
                x.value.ln()
            })
        }
    };
    finite(q, whole, out)
}

/// A quantity as the value of a key of dimension `expected` (`None`: the
/// key's dimension is not declared; a typed value keeps its own), in the
/// deck's unit system. `degrees`: the key is an angle in degrees.
pub fn in_system(
    q: Quantity,
    expected: Option<Exponents>,
    degrees: bool,
    what: &str,
    at: Span,
    env: &Env,
    out: &mut Out,
) -> Option<Spanned<f64>> {
    let Some(dim) = q.dim else {
        return Some(Spanned::new(q.value, at));
    };
    if let Some(e) = expected {
        if e != dim {
            out.push(
                Diagnostic::error(
                    format!("{what} is {}, but this is {}", e.describe(), dim.describe()),
                    at,
                    format!("dimension {dim}, expected {e}"),
                )
                .with_help("check the unit"),
            );
            return None;
        }
    }
    let system = env.system?;
    let mut v = q.value / system.scale(dim);
    if degrees && dim == Exponents::ANGLE {
        v /= std::f64::consts::PI / 180.0;
    }
    Some(Spanned::new(v, at))
}
