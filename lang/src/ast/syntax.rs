//! The generic syntax of block contents and values, as the grammar sees it.
//!
//! Blocks are lists of entries (`key = value`, `key { .. }`, bare `key`);
//! values are a small expression language. The typed passes in `parse/`
//! turn these into the typed nodes of [`crate::ast`].

use crate::span::{Ident, Span};

/// `{ entry* }`.
#[derive(Debug, Clone, PartialEq)]
pub struct Block {
    /// Entries in the order written.
    pub entries: Vec<Entry>,
    /// From `{` to `}` inclusive.
    pub span: Span,
}

/// One entry of a block.
#[derive(Debug, Clone, PartialEq)]
pub struct Entry {
    /// The key (`E`, `mesh`, `elastic`, `ux`, ...).
    pub key: Ident,
    /// What follows the key.
    pub body: EntryBody,
    /// The whole entry.
    pub span: Span,
}

/// What follows a key in a block.
#[derive(Debug, Clone, PartialEq)]
pub enum EntryBody {
    /// `key = value`.
    Assign(Value),
    /// `key { .. }`.
    Block(Block),
    /// A bare `key` (component lists such as `fix b.s { ux uy }`).
    Flag,
}

/// A value with its span.
#[derive(Debug, Clone, PartialEq)]
pub struct Value {
    /// The value.
    pub kind: ValueKind,
    /// Where it was written.
    pub span: Span,
}

/// The shapes a value can take.
#[derive(Debug, Clone, PartialEq)]
pub enum ValueKind {
    /// `1`, `-2.5`, `3e-4`.
    Number(f64),
    /// `"part.msh"` (no escapes).
    Str(String),
    /// `steel`, `true`, `block.top`.
    Path(Vec<Ident>),
    /// `ramp(0, 1)`, `block.nodes(y = 0)`, `contact_force(a.b -> t)`.
    Call {
        /// The called name, possibly dotted (`block.nodes`).
        path: Vec<Ident>,
        /// The arguments.
        args: Vec<Arg>,
    },
    /// `rectangle { .. }`, `penalty { .. }`.
    Ctor {
        /// The constructor name.
        name: Ident,
        /// Its block.
        block: Block,
    },
    /// `file "part.msh"`.
    CtorStr {
        /// The constructor name.
        name: Ident,
        /// The string (without quotes).
        text: String,
        /// Span of the string including quotes.
        text_span: Span,
    },
    /// `(a, b, ..)`.
    Tuple(Vec<Value>),
    /// `[a, b, ..]`.
    List(Vec<Value>),
    /// `a .. b`.
    Range(Box<Value>, Box<Value>),
    /// `210 GPa`: a number with a unit.
    Quantity {
        /// The number.
        value: f64,
        /// The unit as written (`GPa`, `N/mm^2`, `/s`).
        unit: String,
        /// Where the unit is written.
        unit_span: Span,
    },
    /// `a + b`, `a - b`, `a * b`, `a / b`, `a ^ b` (also set unions and
    /// differences `a.top + a.side`).
    Binary {
        /// The operator.
        op: BinOp,
        /// Left operand.
        lhs: Box<Value>,
        /// Right operand.
        rhs: Box<Value>,
        /// Where the operator is written.
        op_span: Span,
    },
    /// `-a`.
    Neg(Box<Value>),
}

/// Binary operators.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BinOp {
    /// `+`.
    Add,
    /// `-`.
    Sub,
    /// `*`.
    Mul,
    /// `/`.
    Div,
    /// `^`.
    Pow,
}

impl BinOp {
    /// The operator as written.
    pub fn symbol(self) -> &'static str {
        match self {
            BinOp::Add => "+",
            BinOp::Sub => "-",
            BinOp::Mul => "*",
            BinOp::Div => "/",
            BinOp::Pow => "^",
        }
    }
}

impl ValueKind {
    /// A short description of the shape, for "expected X, found Y" messages.
    pub fn describe(&self) -> &'static str {
        match self {
            ValueKind::Number(_) => "a number",
            ValueKind::Str(_) => "a string",
            ValueKind::Path(p) if p.len() == 1 => "a name",
            ValueKind::Path(_) => "a dotted name",
            ValueKind::Call { .. } => "a call",
            ValueKind::Ctor { .. } => "a block",
            ValueKind::CtorStr { .. } => "a named string",
            ValueKind::Tuple(_) => "a tuple",
            ValueKind::List(_) => "a list",
            ValueKind::Range(..) => "a range",
            ValueKind::Quantity { .. } => "a number with a unit",
            ValueKind::Binary { .. } | ValueKind::Neg(_) => "an expression",
        }
    }
}

/// One argument of a call.
#[derive(Debug, Clone, PartialEq)]
pub struct Arg {
    /// The argument.
    pub kind: ArgKind,
    /// Where it was written.
    pub span: Span,
}

/// The shapes of call arguments.
#[derive(Debug, Clone, PartialEq)]
pub enum ArgKind {
    /// A plain value.
    Positional(Value),
    /// `name = value` (as in `block.nodes(x = 0)`).
    Named(Ident, Value),
    /// `value -> name` (as in `contact_force(block.top -> punch)`).
    Arrow(Value, Ident),
}

/// Joins a dotted path back into text (`block.top`; parts that are not
/// plain names are quoted: `lug."Hole Edge"`).
pub fn path_text(path: &[Ident]) -> String {
    path.iter()
        .map(|i| quoted_name(&i.name))
        .collect::<Vec<_>>()
        .join(".")
}

/// A name as a deck writes it: bare if it is a plain identifier, else in
/// quotes.
pub fn quoted_name(name: &str) -> String {
    let plain = name
        .chars()
        .next()
        .is_some_and(|c| c.is_ascii_alphabetic() || c == '_')
        && name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_');
    if plain {
        name.to_string()
    } else {
        format!("\"{name}\"")
    }
}
