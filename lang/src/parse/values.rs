//! Generic values -> typed values: numbers, whole numbers, booleans,
//! points, lists, enum choices, time functions, gradings, set references.
//!
//! Every function returns `None` after pushing a diagnostic when the value
//! has the wrong shape, so that callers simply skip the field.

use crate::ast::syntax::{path_text, Arg, ArgKind, BinOp, Value, ValueKind};
use crate::ast::{Coords, Grading, Point, Point3, Selection, SetRef, SetRefKind, TimeFn};
use crate::diagnostics::Diagnostic;
use crate::expr::Env;
use crate::keys::Dim;
use crate::span::{Ident, Span, Spanned};
use crate::suggest::{did_you_mean, one_of};

/// The diagnostics sink of all conversions, with the environment of
/// expressions (`let` parameters, the unit system) they evaluate in.
/// Dereferences to the list of diagnostics.
#[derive(Debug, Clone, Default)]
pub struct Diags {
    list: Vec<Diagnostic>,
    /// Parameters and unit system (see [`crate::expr`]).
    pub env: Env,
}

impl Diags {
    /// No diagnostics, an empty environment.
    pub fn new() -> Self {
        Self::default()
    }

    /// The diagnostics.
    pub fn into_vec(self) -> Vec<Diagnostic> {
        self.list
    }

    /// The environment and the diagnostics, borrowed separately.
    pub fn split(&mut self) -> (&mut Env, &mut Vec<Diagnostic>) {
        (&mut self.env, &mut self.list)
    }
}

impl std::ops::Deref for Diags {
    type Target = Vec<Diagnostic>;
    fn deref(&self) -> &Vec<Diagnostic> {
        &self.list
    }
}

impl std::ops::DerefMut for Diags {
    fn deref_mut(&mut self) -> &mut Vec<Diagnostic> {
        &mut self.list
    }
}

fn wrong(v: &Value, expected: &str, diags: &mut Diags) {
    diags.push(Diagnostic::error(
        format!("expected {expected}, found {}", v.kind.describe()),
        v.span,
        format!("expected {expected}"),
    ));
}

/// A finite number (an expression, possibly with units), of a key whose
/// dimension is not declared.
pub fn number(v: &Value, diags: &mut Diags) -> Option<Spanned<f64>> {
    number_of(v, None, "this value", diags)
}

/// A finite number of dimension `dim` (for a key called `what` in
/// messages), converted into the deck's unit system.
pub fn number_of(
    v: &Value,
    dim: Option<Dim>,
    what: &str,
    diags: &mut Diags,
) -> Option<Spanned<f64>> {
    match v.kind {
        ValueKind::Number(x) if x.is_finite() => Some(Spanned::new(x, v.span)),
        ValueKind::Number(_) => {
            diags.push(Diagnostic::error(
                "number out of range",
                v.span,
                "not a finite double-precision number",
            ));
            None
        }
        ValueKind::Quantity { .. }
        | ValueKind::Binary { .. }
        | ValueKind::Neg(_)
        | ValueKind::Call { .. } => evaluate(v, dim, what, diags),
        ValueKind::Path(ref p) if p.len() == 1 => evaluate(v, dim, what, diags),
        ValueKind::Tuple(ref items) if items.len() == 1 => evaluate(v, dim, what, diags),
        _ => {
            wrong(v, "a number", diags);
            None
        }
    }
}

fn evaluate(v: &Value, dim: Option<Dim>, what: &str, diags: &mut Diags) -> Option<Spanned<f64>> {
    let (env, out) = diags.split();
    let q = crate::expr::eval(v, env, out)?;
    let expected = dim.and_then(Dim::exponents);
    let degrees = dim == Some(Dim::AngleDegrees);
    crate::expr::in_system(q, expected, degrees, what, v.span, env, out)
}

/// A whole number (written without fraction, e.g. `20`, `1e3`).
pub fn integer(v: &Value, diags: &mut Diags) -> Option<Spanned<i64>> {
    let x = number_of(v, Some(Dim::None), "a count", diags)?;
    if x.value.fract() != 0.0 || x.value.abs() > 9.0e15 {
        diags.push(Diagnostic::error(
            format!("expected a whole number, found `{}`", x.value),
            v.span,
            "expected a whole number",
        ));
        return None;
    }
    Some(Spanned::new(x.value as i64, v.span))
}

/// `true` or `false`.
pub fn boolean(v: &Value, diags: &mut Diags) -> Option<Spanned<bool>> {
    match &v.kind {
        ValueKind::Path(p) if p.len() == 1 && p[0].name == "true" => {
            Some(Spanned::new(true, v.span))
        }
        ValueKind::Path(p) if p.len() == 1 && p[0].name == "false" => {
            Some(Spanned::new(false, v.span))
        }
        ValueKind::Path(p) if p.len() == 1 => {
            diags.push(Diagnostic::error(
                format!("expected `true` or `false`, found `{}`", p[0].name),
                v.span,
                "expected `true` or `false`",
            ));
            None
        }
        _ => {
            wrong(v, "`true` or `false`", diags);
            None
        }
    }
}

/// One of a fixed set of names, with a "did you mean" for a misspelling.
/// `what` names the setting in messages (e.g. "dimension").
pub fn choice<T: Copy>(
    v: &Value,
    what: &str,
    options: &[(&str, T)],
    diags: &mut Diags,
) -> Option<Spanned<T>> {
    let names: Vec<&str> = options.iter().map(|(n, _)| *n).collect();
    let word = match &v.kind {
        ValueKind::Path(p) if p.len() == 1 => &p[0].name,
        _ => {
            wrong(v, &one_of(&names), diags);
            return None;
        }
    };
    if let Some((_, t)) = options.iter().find(|(n, _)| n == word) {
        return Some(Spanned::new(*t, v.span));
    }
    diags.push(
        Diagnostic::error(
            format!("unknown {what} `{word}`"),
            v.span,
            format!("expected {}", one_of(&names)),
        )
        .with_help_opt(did_you_mean(word, &names)),
    );
    None
}

/// A point or vector `(x, y)`.
pub fn point(v: &Value, diags: &mut Diags) -> Option<Point> {
    let [a, b] = pair_of(v, "a point `(x, y)`", diags)?;
    let x = number(a, diags)?;
    let y = number(b, diags)?;
    Some(Spanned::new([x.value, y.value], v.span))
}

/// A point of space `(x, y, z)`.
pub fn point3(v: &Value, diags: &mut Diags) -> Option<Point3> {
    match &v.kind {
        ValueKind::Tuple(items) if items.len() == 3 => {
            let x = number(&items[0], diags);
            let y = number(&items[1], diags);
            let z = number(&items[2], diags);
            Some(Spanned::new([x?.value, y?.value, z?.value], v.span))
        }
        ValueKind::Tuple(items) => {
            diags.push(
                Diagnostic::error(
                    format!(
                        "expected a point `(x, y, z)`, found a tuple of {}",
                        items.len()
                    ),
                    v.span,
                    "expected a point `(x, y, z)`",
                )
                .with_help("a `3d` analysis takes three coordinates"),
            );
            None
        }
        _ => {
            wrong(v, "a point `(x, y, z)`", diags);
            None
        }
    }
}

/// A string in quotes.
pub fn text(v: &Value, expected: &str, diags: &mut Diags) -> Option<Spanned<String>> {
    match &v.kind {
        ValueKind::Str(s) => Some(Spanned::new(s.clone(), v.span)),
        _ => {
            wrong(v, expected, diags);
            None
        }
    }
}

/// The number of elements of a tuple value (`None` for other values).
pub fn tuple_len(v: &Value) -> Option<usize> {
    match &v.kind {
        ValueKind::Tuple(items) => Some(items.len()),
        _ => None,
    }
}

/// A pair of numbers `(a, b)`, keeping each number's span.
pub fn pair(v: &Value, diags: &mut Diags) -> Option<Spanned<[Spanned<f64>; 2]>> {
    let [a, b] = pair_of(v, "a pair `(a, b)`", diags)?;
    let x = number(a, diags);
    let y = number(b, diags);
    Some(Spanned::new([x?, y?], v.span))
}

/// A pair of whole numbers `(a, b)`.
pub fn int_pair(v: &Value, diags: &mut Diags) -> Option<Spanned<[Spanned<i64>; 2]>> {
    let [a, b] = pair_of(v, "a pair of whole numbers `(nx, ny)`", diags)?;
    let x = integer(a, diags);
    let y = integer(b, diags);
    Some(Spanned::new([x?, y?], v.span))
}

/// The two elements of a 2-tuple.
pub fn pair_of<'v>(v: &'v Value, expected: &str, diags: &mut Diags) -> Option<[&'v Value; 2]> {
    match &v.kind {
        ValueKind::Tuple(items) if items.len() == 2 => Some([&items[0], &items[1]]),
        ValueKind::Tuple(items) => {
            diags.push(Diagnostic::error(
                format!("expected {expected}, found a tuple of {}", items.len()),
                v.span,
                format!("expected {expected}"),
            ));
            None
        }
        _ => {
            wrong(v, expected, diags);
            None
        }
    }
}

/// The elements of a list `[..]`.
pub fn list<'v>(v: &'v Value, expected: &str, diags: &mut Diags) -> Option<&'v [Value]> {
    match &v.kind {
        ValueKind::List(items) => Some(items),
        _ => {
            wrong(v, expected, diags);
            None
        }
    }
}

/// A list of points `[(x, y), ..]`.
pub fn point_list(v: &Value, diags: &mut Diags) -> Option<Spanned<Vec<Point>>> {
    let items = list(v, "a list of points `[(x, y), ..]`", diags)?;
    let n = diags.len();
    let pts: Vec<Point> = items.iter().filter_map(|p| point(p, diags)).collect();
    (diags.len() == n).then(|| Spanned::new(pts, v.span))
}

/// A list of numbers `[a, b, ..]`.
pub fn number_list(v: &Value, diags: &mut Diags) -> Option<Spanned<Vec<Spanned<f64>>>> {
    let items = list(v, "a list of numbers `[a, b, ..]`", diags)?;
    let n = diags.len();
    let xs: Vec<Spanned<f64>> = items.iter().filter_map(|x| number(x, diags)).collect();
    (diags.len() == n).then(|| Spanned::new(xs, v.span))
}

/// A single-name call such as `ramp(..)`: its name and arguments.
fn simple_call(v: &Value) -> Option<(&Ident, &[Arg])> {
    match &v.kind {
        ValueKind::Call { path, args } if path.len() == 1 => Some((&path[0], args)),
        _ => None,
    }
}

/// The values of positional arguments; errors for named or arrow arguments.
fn positional<'v>(args: &'v [Arg], diags: &mut Diags) -> Option<Vec<&'v Value>> {
    let mut out = Vec::new();
    for a in args {
        match &a.kind {
            ArgKind::Positional(v) => out.push(v),
            _ => {
                diags.push(Diagnostic::error(
                    "unexpected argument",
                    a.span,
                    "expected a plain value here",
                ));
                return None;
            }
        }
    }
    Some(out)
}

fn arity(name: &Ident, call: Span, got: usize, expected: &str, diags: &mut Diags) {
    diags.push(Diagnostic::error(
        format!("`{}` takes {expected}, found {got}", name.name),
        call,
        format!("expected {expected}"),
    ));
}

const TIME_FUNCTIONS: [&str; 3] = ["constant", "ramp", "table"];
const TIME_FN_HELP: &str = "a time function is a number, `constant(v)`, `ramp(v0, v1)`, \
`ramp(v0, v1, t0, t1)` or `table((t, v), ..)`";

/// A time function: a number, `constant(v)`, `ramp(v0, v1)`,
/// `ramp(v0, v1, t0, t1)` or `table((t, v), ..)`.
pub fn time_fn(v: &Value, diags: &mut Diags) -> Option<Spanned<TimeFn>> {
    time_fn_of(v, None, diags)
}

/// A time function whose values have dimension `dim` (a number, an
/// expression, or `constant`/`ramp`/`table` of them).
pub fn time_fn_of(v: &Value, dim: Option<Dim>, diags: &mut Diags) -> Option<Spanned<TimeFn>> {
    let num = |x: &Value, diags: &mut Diags| number_of(x, dim, "this value", diags);
    let is_number = match &v.kind {
        ValueKind::Number(_)
        | ValueKind::Quantity { .. }
        | ValueKind::Binary { .. }
        | ValueKind::Neg(_) => true,
        ValueKind::Path(p) => p.len() == 1,
        ValueKind::Tuple(items) => items.len() == 1,
        ValueKind::Call { path, .. } => path.len() == 1 && crate::expr::is_function(&path[0].name),
        _ => false,
    };
    if is_number {
        return num(v, diags).map(|x| Spanned::new(TimeFn::Number(x.value), v.span));
    }
    let Some((name, args)) = simple_call(v) else {
        diags.push(
            Diagnostic::error(
                format!("expected a time function, found {}", v.kind.describe()),
                v.span,
                "expected a number or a time function",
            )
            .with_help(TIME_FN_HELP),
        );
        return None;
    };
    let args = positional(args, diags)?;
    let f = match name.name.as_str() {
        "constant" => {
            if args.len() != 1 {
                arity(name, v.span, args.len(), "1 argument", diags);
                return None;
            }
            TimeFn::Constant(num(args[0], diags)?.value)
        }
        "ramp" => {
            if args.len() != 2 && args.len() != 4 {
                arity(name, v.span, args.len(), "2 or 4 arguments", diags);
                return None;
            }
            let nums: Vec<Option<Spanned<f64>>> = args
                .iter()
                .enumerate()
                .map(|(i, a)| {
                    // the window (t0, t1) is a time
                    if i >= 2 {
                        number_of(a, Some(Dim::Time), "a time", diags)
                    } else {
                        num(a, diags)
                    }
                })
                .collect();
            let nums: Option<Vec<Spanned<f64>>> = nums.into_iter().collect();
            let nums = nums?;
            TimeFn::Ramp {
                v0: nums[0].value,
                v1: nums[1].value,
                window: (nums.len() == 4).then(|| [nums[2].clone(), nums[3].clone()]),
            }
        }
        "table" => {
            if args.is_empty() {
                arity(name, v.span, 0, "at least 1 point `(t, v)`", diags);
                return None;
            }
            let mut pts = Vec::new();
            for a in args {
                let [t, x] = pair_of(a, "a point `(t, v)`", diags)?;
                let t = number_of(t, Some(Dim::Time), "a time", diags)?;
                let x = num(x, diags)?;
                pts.push(Spanned::new((t.value, x.value), a.span));
            }
            TimeFn::Table(pts)
        }
        other => {
            diags.push(
                Diagnostic::error(
                    format!("unknown time function `{other}`"),
                    name.span,
                    format!("expected {}", one_of(&TIME_FUNCTIONS)),
                )
                .with_help(did_you_mean(other, TIME_FUNCTIONS).unwrap_or(TIME_FN_HELP.into())),
            );
            return None;
        }
    };
    Some(Spanned::new(f, v.span))
}

const GRADINGS: [&str; 3] = ["uniform", "geometric", "center"];

/// A grading: `uniform`, `geometric(ratio)` or `center(ratio)`.
pub fn grading(v: &Value, diags: &mut Diags) -> Option<Spanned<Grading>> {
    let unknown = |word: &Ident, diags: &mut Diags| {
        diags.push(
            Diagnostic::error(
                format!("unknown grading `{}`", word.name),
                word.span,
                "expected `uniform`, `geometric(ratio)` or `center(ratio)`",
            )
            .with_help_opt(did_you_mean(&word.name, GRADINGS)),
        );
    };
    match &v.kind {
        ValueKind::Path(p) if p.len() == 1 => {
            if p[0].name == "uniform" {
                Some(Spanned::new(Grading::Uniform, v.span))
            } else {
                unknown(&p[0], diags);
                None
            }
        }
        ValueKind::Call { path, args } if path.len() == 1 => {
            let name = &path[0];
            let make: fn(Spanned<f64>) -> Grading = match name.name.as_str() {
                "geometric" => Grading::Geometric,
                "center" => Grading::Center,
                _ => {
                    unknown(name, diags);
                    return None;
                }
            };
            let args = positional(args, diags)?;
            if args.len() != 1 {
                arity(name, v.span, args.len(), "1 argument (the ratio)", diags);
                return None;
            }
            let r = number(args[0], diags)?;
            Some(Spanned::new(make(r), v.span))
        }
        _ => {
            wrong(
                v,
                "a grading (`uniform`, `geometric(ratio)` or `center(ratio)`)",
                diags,
            );
            None
        }
    }
}

const SELECTORS: [&str; 4] = ["nodes", "node", "edges", "faces"];
const SETREF_HELP: &str = "a set reference is `body.set`, `body.nodes(x = ..)` (or `y`, \
`z`), `body.nodes(box((x0, y0), (x1, y1)))`, `body.node(near(x, y))` (3d: `(x, y, z)`), \
`body.edges(..)` (planar) or `body.faces(..)` (3d)";

/// A set reference: `body.set`, `body.nodes(..)`, `body.node(near(..))`,
/// `body.edges(..)`, `body.faces(..)`, or a union / difference of references to one body
/// (`a.top + a.side - a.corner_tl`).
pub fn set_ref(v: &Value, diags: &mut Diags) -> Option<SetRef> {
    if let ValueKind::Binary { op, .. } = &v.kind {
        if matches!(op, BinOp::Add | BinOp::Sub) {
            return set_combination(v, diags);
        }
    }
    if let ValueKind::Tuple(items) = &v.kind {
        if items.len() == 1 {
            return set_ref(&items[0], diags);
        }
    }
    single_set_ref(v, diags)
}

/// Flattens `a + b - c` into signed terms.
fn set_terms<'v>(v: &'v Value, add: bool, out: &mut Vec<(bool, &'v Value)>) {
    match &v.kind {
        ValueKind::Binary {
            op: op @ (BinOp::Add | BinOp::Sub),
            lhs,
            rhs,
            ..
        } => {
            set_terms(lhs, add, out);
            set_terms(rhs, if *op == BinOp::Add { add } else { !add }, out);
        }
        ValueKind::Tuple(items) if items.len() == 1 => set_terms(&items[0], add, out),
        _ => out.push((add, v)),
    }
}

fn set_combination(v: &Value, diags: &mut Diags) -> Option<SetRef> {
    let mut terms = Vec::new();
    set_terms(v, true, &mut terms);
    let refs: Vec<Option<(bool, SetRef)>> = terms
        .iter()
        .map(|(add, t)| single_set_ref(t, diags).map(|r| (*add, r)))
        .collect();
    let refs: Vec<(bool, SetRef)> = refs.into_iter().collect::<Option<_>>()?;
    let body = refs[0].1.body.clone();
    if let Some((_, other)) = refs.iter().find(|(_, r)| r.body.name != body.name) {
        diags.push(
            Diagnostic::error(
                "a set combines sets of one body",
                other.body.span,
                format!("body `{}`, not `{}`", other.body.name, body.name),
            )
            .with_secondary(refs[0].1.body.span, format!("body `{}`", body.name))
            .with_help("combine sets of the same body; each body needs its own item"),
        );
        return None;
    }
    if !refs[0].0 {
        diags.push(Diagnostic::error(
            "a set combination starts with the set to remove from",
            v.span,
            "starts with `-`",
        ));
        return None;
    }
    Some(SetRef {
        body,
        kind: SetRefKind::Combination(refs),
        span: v.span,
    })
}

/// A set reference that is not a combination.
fn single_set_ref(v: &Value, diags: &mut Diags) -> Option<SetRef> {
    let bad = |diags: &mut Diags, found: &str| {
        diags.push(
            Diagnostic::error(
                format!("expected a set reference, found {found}"),
                v.span,
                "expected `body.set`",
            )
            .with_help(SETREF_HELP),
        );
    };
    match &v.kind {
        ValueKind::Path(p) if p.len() == 2 => Some(SetRef {
            body: p[0].clone(),
            kind: SetRefKind::Named(p[1].clone()),
            span: v.span,
        }),
        ValueKind::Path(p) if p.len() == 1 => {
            bad(diags, &format!("the bare name `{}`", p[0].name));
            None
        }
        ValueKind::Call { path, args } if path.len() == 2 => {
            let body = path[0].clone();
            let sel_name = &path[1];
            if !SELECTORS.contains(&sel_name.name.as_str()) {
                diags.push(
                    Diagnostic::error(
                        format!("unknown selection `{}`", sel_name.name),
                        sel_name.span,
                        "expected `nodes`, `node`, `edges` or `faces`",
                    )
                    .with_help(
                        did_you_mean(&sel_name.name, SELECTORS).unwrap_or(SETREF_HELP.into()),
                    ),
                );
                return None;
            }
            let call_span = Span::new(sel_name.span.start, v.span.end);
            if args.len() != 1 {
                arity(sel_name, call_span, args.len(), "1 argument", diags);
                return None;
            }
            let sel = selection(&args[0], diags)?;
            let kind = match sel_name.name.as_str() {
                "node" => {
                    if !matches!(sel.value, Selection::Near(_)) {
                        diags.push(
                            Diagnostic::error(
                                "`node(..)` selects a single node",
                                sel.span,
                                "expected `near(x, y)` or `near(x, y, z)`",
                            )
                            .with_help(format!(
                                "to select several nodes write `{}.nodes({})`",
                                body.name, sel.value
                            )),
                        );
                        return None;
                    }
                    SetRefKind::Node(sel)
                }
                _ if matches!(sel.value, Selection::Near(_)) => {
                    diags.push(
                        Diagnostic::error(
                            format!("`near(..)` selects a single node, not {}", sel_name.name),
                            sel.span,
                            "not allowed here",
                        )
                        .with_help(format!("write `{}.node({})`", body.name, sel.value)),
                    );
                    return None;
                }
                "nodes" => SetRefKind::Nodes(sel),
                "faces" => SetRefKind::Faces(sel),
                _ => SetRefKind::Edges(sel),
            };
            Some(SetRef {
                body,
                kind,
                span: v.span,
            })
        }
        ValueKind::Path(p) => {
            bad(diags, &format!("`{}`", path_text(p)));
            None
        }
        other => {
            bad(diags, other.describe());
            None
        }
    }
}

/// Coordinates `(x, y)` or `(x, y, z)` of a selection (which count is right
/// depends on the analysis: validation checks it).
pub fn coords(v: &Value, diags: &mut Diags) -> Option<Coords> {
    let expected = "a point `(x, y)` or `(x, y, z)`";
    match &v.kind {
        ValueKind::Tuple(items) if items.len() == 2 => point(v, diags).map(Coords::Plane),
        ValueKind::Tuple(items) if items.len() == 3 => point3(v, diags).map(Coords::Space),
        ValueKind::Tuple(items) => {
            diags.push(Diagnostic::error(
                format!("expected {expected}, found a tuple of {}", items.len()),
                v.span,
                format!("expected {expected}"),
            ));
            None
        }
        _ => {
            wrong(v, expected, diags);
            None
        }
    }
}

/// The argument of `nodes(..)`, `node(..)`, `edges(..)`, `faces(..)`.
fn selection(a: &Arg, diags: &mut Diags) -> Option<Spanned<Selection>> {
    let help = "expected `x = ..`, `y = ..`, `z = ..`, `box((x0, y0[, z0]), (x1, y1[, z1]))` \
                or `near(x, y[, z])`";
    match &a.kind {
        ArgKind::Named(n, v) if matches!(n.name.as_str(), "x" | "y" | "z") => {
            let x = number(v, diags)?;
            let s = match n.name.as_str() {
                "x" => Selection::X(x.value),
                "y" => Selection::Y(x.value),
                _ => Selection::Z(x.value),
            };
            Some(Spanned::new(s, a.span))
        }
        ArgKind::Named(n, _) => {
            diags.push(
                Diagnostic::error(
                    format!("unknown coordinate `{}`", n.name),
                    n.span,
                    "expected `x`, `y` or `z`",
                )
                .with_help_opt(did_you_mean(&n.name, ["x", "y", "z"])),
            );
            None
        }
        ArgKind::Positional(v) => {
            let Some((name, args)) = simple_call(v) else {
                diags.push(Diagnostic::error(
                    format!("expected a selection, found {}", v.kind.describe()),
                    v.span,
                    help,
                ));
                return None;
            };
            let args = positional(args, diags)?;
            match name.name.as_str() {
                "box" => {
                    if args.len() != 2 {
                        arity(name, v.span, args.len(), "2 corners", diags);
                        return None;
                    }
                    let a0 = coords(args[0], diags);
                    let a1 = coords(args[1], diags);
                    let (a0, a1) = (a0?, a1?);
                    if a0.len() != a1.len() {
                        diags.push(
                            Diagnostic::error(
                                format!(
                                    "the corners of a box have {} and {} coordinates",
                                    a0.len(),
                                    a1.len()
                                ),
                                a1.span(),
                                format!("{} coordinates", a1.len()),
                            )
                            .with_secondary(a0.span(), format!("{} coordinates", a0.len()))
                            .with_help(
                                "give both corners as `(x, y)` (planar) or `(x, y, z)` (3d)",
                            ),
                        );
                        return None;
                    }
                    Some(Spanned::new(Selection::Box { min: a0, max: a1 }, v.span))
                }
                "near" => {
                    if args.len() != 2 && args.len() != 3 {
                        arity(
                            name,
                            v.span,
                            args.len(),
                            "2 or 3 coordinates `near(x, y[, z])`",
                            diags,
                        );
                        return None;
                    }
                    let n = diags.len();
                    let xs: Vec<f64> = args
                        .iter()
                        .filter_map(|x| number(x, diags).map(|x| x.value))
                        .collect();
                    let p = match xs[..] {
                        _ if diags.len() != n => return None,
                        [x, y] => Coords::Plane(Spanned::new([x, y], v.span)),
                        [x, y, z] => Coords::Space(Spanned::new([x, y, z], v.span)),
                        _ => unreachable!("2 or 3 arguments checked above"),
                    };
                    Some(Spanned::new(Selection::Near(p), v.span))
                }
                other => {
                    diags.push(
                        Diagnostic::error(
                            format!("unknown selection function `{other}`"),
                            name.span,
                            help,
                        )
                        .with_help_opt(did_you_mean(other, ["box", "near"])),
                    );
                    None
                }
            }
        }
        ArgKind::Arrow(..) => {
            diags.push(Diagnostic::error(
                "unexpected `->` in a selection",
                a.span,
                help,
            ));
            None
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::parse::test_support::value_of;

    #[test]
    fn numbers_and_integers() {
        let mut d = Diags::new();
        assert_eq!(number(&value_of("-2.5e3"), &mut d).unwrap().value, -2500.0);
        assert_eq!(number(&value_of(".5"), &mut d).unwrap().value, 0.5);
        assert_eq!(number(&value_of("1.2E+3"), &mut d).unwrap().value, 1200.0);
        assert_eq!(integer(&value_of("1e3"), &mut d).unwrap().value, 1000);
        assert!(d.is_empty());
        assert!(integer(&value_of("2.5"), &mut d).is_none());
        assert!(number(&value_of("1e999"), &mut d).is_none());
        assert!(number(&value_of("(1, 2)"), &mut d).is_none());
        assert_eq!(d.len(), 3);
        assert_eq!(d[2].message, "expected a number, found a tuple");
    }

    #[test]
    fn points_and_lists() {
        let mut d = Diags::new();
        assert_eq!(
            point(&value_of("(0, -1.5)"), &mut d).unwrap().value,
            [0.0, -1.5]
        );
        let pts = point_list(&value_of("[(0, 0), (1, 0), (2, 1)]"), &mut d).unwrap();
        assert_eq!(pts.value.len(), 3);
        assert_eq!(pts.value[2].value, [2.0, 1.0]);
        assert!(d.is_empty());
        assert!(point(&value_of("(1, 2, 3)"), &mut d).is_none());
        assert_eq!(
            d[0].message,
            "expected a point `(x, y)`, found a tuple of 3"
        );
    }

    #[test]
    fn choices_suggest_the_closest_name() {
        let mut d = Diags::new();
        let opts = [("plane_strain", 1), ("plane_stress", 2)];
        assert_eq!(
            choice(&value_of("plane_stress"), "dimension", &opts, &mut d)
                .unwrap()
                .value,
            2
        );
        assert!(choice(&value_of("plane_stran"), "dimension", &opts, &mut d).is_none());
        assert_eq!(d[0].message, "unknown dimension `plane_stran`");
        assert_eq!(d[0].help.as_deref(), Some("did you mean `plane_strain`?"));
    }

    #[test]
    fn time_functions() {
        let mut d = Diags::new();
        let t = |s: &str, d: &mut Diags| time_fn(&value_of(s), d).map(|t| t.value);
        assert_eq!(t("-1", &mut d), Some(TimeFn::Number(-1.0)));
        assert_eq!(t("constant(2)", &mut d), Some(TimeFn::Constant(2.0)));
        assert_eq!(
            t("ramp(0, -0.05)", &mut d),
            Some(TimeFn::Ramp {
                v0: 0.0,
                v1: -0.05,
                window: None
            })
        );
        match t("ramp(0, 1, 0.5, 2)", &mut d) {
            Some(TimeFn::Ramp {
                window: Some([a, b]),
                ..
            }) => assert_eq!((a.value, b.value), (0.5, 2.0)),
            other => panic!("{other:?}"),
        }
        match t("table((0, 0), (0.5, 1), (1, 0))", &mut d) {
            Some(TimeFn::Table(p)) => {
                let v: Vec<(f64, f64)> = p.iter().map(|s| s.value).collect();
                assert_eq!(v, vec![(0.0, 0.0), (0.5, 1.0), (1.0, 0.0)]);
            }
            other => panic!("{other:?}"),
        }
        assert!(d.is_empty());
        assert!(t("ramp(0)", &mut d).is_none());
        assert!(t("rmap(0, 1)", &mut d).is_none());
        assert_eq!(d[1].help.as_deref(), Some("did you mean `ramp`?"));
    }

    #[test]
    fn gradings() {
        let mut d = Diags::new();
        assert_eq!(
            grading(&value_of("uniform"), &mut d).unwrap().value,
            Grading::Uniform
        );
        match grading(&value_of("geometric(0.2)"), &mut d).unwrap().value {
            Grading::Geometric(r) => assert_eq!(r.value, 0.2),
            g => panic!("{g:?}"),
        }
        match grading(&value_of("center(4)"), &mut d).unwrap().value {
            Grading::Center(r) => assert_eq!(r.value, 4.0),
            g => panic!("{g:?}"),
        }
        assert!(d.is_empty());
        assert!(grading(&value_of("geometrik(2)"), &mut d).is_none());
        assert_eq!(d[0].help.as_deref(), Some("did you mean `geometric`?"));
    }

    #[test]
    fn set_references() {
        let mut d = Diags::new();
        let r = set_ref(&value_of("block.top"), &mut d).unwrap();
        assert_eq!(r.to_string(), "block.top");
        let r = set_ref(&value_of("block.nodes(y = -4)"), &mut d).unwrap();
        assert_eq!(
            r.kind,
            SetRefKind::Nodes(Spanned::new(Selection::Y(-4.0), r_span(&r)))
        );
        let r = set_ref(
            &value_of("block.edges(box((-1, -0.01), (1, 0.01)))"),
            &mut d,
        )
        .unwrap();
        assert_eq!(r.to_string(), "block.edges(box((-1, -0.01), (1, 0.01)))");
        let r = set_ref(&value_of("block.node(near(0, 0))"), &mut d).unwrap();
        assert!(matches!(r.kind, SetRefKind::Node(_)));
        assert!(d.is_empty());
        assert!(set_ref(&value_of("block.node(x = 0)"), &mut d).is_none());
        assert!(set_ref(&value_of("block.nodez(x = 0)"), &mut d).is_none());
        assert_eq!(d[1].help.as_deref(), Some("did you mean `nodes`?"));
        assert!(set_ref(&value_of("top"), &mut d).is_none());
    }

    #[test]
    fn set_references_3d_selections() {
        let mut d = Diags::new();
        for text in [
            "block.nodes(z = 2.5)",
            "block.nodes(box((0, 0, 0), (1, 1, 1)))",
            "block.node(near(1, 2, 3))",
            "block.faces(z = 0)",
            "block.faces(box((0, 0, 1), (2, 1, 1)))",
        ] {
            let r = set_ref(&value_of(text), &mut d).unwrap();
            assert_eq!(r.to_string(), text);
        }
        let r = set_ref(&value_of("block.faces(z = 0)"), &mut d).unwrap();
        assert!(matches!(&r.kind, SetRefKind::Faces(s) if s.value == Selection::Z(0.0)));
        assert!(d.is_empty());
        assert!(set_ref(&value_of("block.nodes(box((0, 0), (1, 1, 1)))"), &mut d).is_none());
        assert_eq!(
            d[0].message,
            "the corners of a box have 2 and 3 coordinates"
        );
        assert!(set_ref(&value_of("block.node(near(1, 2, 3, 4))"), &mut d).is_none());
        assert_eq!(
            d[1].message,
            "`near` takes 2 or 3 coordinates `near(x, y[, z])`, found 4"
        );
        assert!(set_ref(
            &value_of("block.nodes(box((0, 0, 0, 0), (1, 1, 1, 1)))"),
            &mut d
        )
        .is_none());
        assert_eq!(
            d[2].message,
            "expected a point `(x, y)` or `(x, y, z)`, found a tuple of 4"
        );
        assert!(set_ref(&value_of("block.nodes(w = 0)"), &mut d).is_none());
        assert_eq!(d[4].message, "unknown coordinate `w`");
    }

    fn r_span(r: &SetRef) -> Span {
        match &r.kind {
            SetRefKind::Nodes(s) => s.span,
            _ => Span::default(),
        }
    }
}
