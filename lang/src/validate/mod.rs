//! Semantic checks of a parsed deck, all at once: unknown and duplicate
//! names (with "did you mean"), set references (does the set exist, does it
//! have edges where edges are needed), out-of-range values, time ranges,
//! and features that are reserved but not supported yet.
//!
//! One module per construct, mirroring [`crate::parse`]; each check is a
//! function named after the rule it enforces (`materials::poisson_in_range`,
//! `steps::times_are_contiguous`, ...), called in deck order by the
//! module's `check`. Ranges declared by key tables are checked by
//! [`ranges`].
//!
//! Shape errors (wrong value types, unknown keys, missing required keys) are
//! reported while parsing (see [`crate::parse`]); this pass only looks at
//! values that parsed, so nothing is reported twice.

pub mod analysis;
pub mod bodies;
pub mod boundaries;
pub mod contacts;
pub mod discrete;
pub mod loads;
pub mod materials;
pub mod output;
pub mod ranges;
pub mod sets;
pub mod steps;
pub mod thermal;
pub mod time_fns;
pub mod tools;
pub mod velocity;

use crate::ast::{Deck, Ident, Span, Spanned, Step};
use crate::diagnostics::{Diagnostic, LineIndex};
pub use crate::generators::SetKind;
use std::collections::BTreeMap;

/// Maximum number of cells a generator may be asked for (the default of
/// [`cell_limit`]).
pub const MAX_CELLS: i64 = 4_000_000;

/// The cell limit per generated mesh in force ([`set_cell_limit`]).
static CELL_LIMIT: std::sync::atomic::AtomicI64 = std::sync::atomic::AtomicI64::new(MAX_CELLS);

/// The most cells a generated mesh may have: [`MAX_CELLS`] unless an
/// embedding program lowered it with [`set_cell_limit`].
pub fn cell_limit() -> i64 {
    CELL_LIMIT.load(std::sync::atomic::Ordering::Relaxed)
}

/// Lowers (or restores) the per-mesh cell limit for the whole process,
/// clamped to `1..=MAX_CELLS`: decks above it get the "too many cells"
/// diagnostic instead of a mesh. For programs that compile many untrusted
/// decks quickly (the cargo-fuzz `deck` target uses 20 000, see
/// `fuzz/README.md`); `ctc` itself never calls it.
pub fn set_cell_limit(cells: i64) {
    CELL_LIMIT.store(
        cells.clamp(1, MAX_CELLS),
        std::sync::atomic::Ordering::Relaxed,
    );
}

/// What a reference is used for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Need {
    /// Any set (its nodes are used).
    Nodes,
    /// Boundary edges (pressure, contact).
    Edges,
}

/// What validation knows about a body's sets.
pub struct BodyInfo {
    /// Known sets; `None` when they are only known after reading a mesh file
    /// (or the mesh is broken): then any name is accepted here and checked
    /// when the mesh is built.
    pub sets: Option<BTreeMap<String, SetKind>>,
    /// Sets defined by `set` items so far (plus the built-in sets when
    /// `sets` is `None`).
    pub deck_sets: BTreeMap<String, SetKind>,
}

/// The state shared by all checks: the deck, the diagnostics found so far,
/// and what the checks of earlier items learned (bodies and their sets).
pub struct Ctx<'a> {
    /// The deck being checked.
    pub deck: &'a Deck,
    lines: LineIndex<'a>,
    diags: Vec<Diagnostic>,
    /// Bodies by name (filled by [`bodies::check`]).
    pub bodies: BTreeMap<String, BodyInfo>,
    /// Names of `set` items whose body is unknown (already reported):
    /// references to them are not reported again.
    pub orphan_sets: Vec<String>,
}

/// Checks `deck` (parsed from `text`) and returns every problem found.
pub fn validate(deck: &Deck, text: &str) -> Vec<Diagnostic> {
    let mut ctx = Ctx {
        deck,
        lines: LineIndex::new(text),
        diags: Vec::new(),
        bodies: BTreeMap::new(),
        orphan_sets: Vec::new(),
    };
    analysis::check(&mut ctx);
    materials::check(&mut ctx);
    bodies::check(&mut ctx);
    sets::check(&mut ctx);
    tools::check(&mut ctx);
    contacts::check(&mut ctx);
    boundaries::check(&mut ctx);
    loads::check(&mut ctx);
    velocity::check(&mut ctx);
    discrete::check(&mut ctx);
    steps::check(&mut ctx);
    output::check(&mut ctx);
    thermal::check(&mut ctx);
    ctx.diags
}

impl Ctx<'_> {
    /// Records a diagnostic.
    pub fn err(&mut self, d: Diagnostic) {
        self.diags.push(d);
    }

    /// 1-based line of a span's start.
    pub fn line(&self, span: Span) -> usize {
        self.lines.line_col(span.start).0
    }

    /// Error if `x <= 0`.
    pub fn must_be_positive(&mut self, x: &Option<Spanned<f64>>, what: &str) {
        if let Some(v) = x.as_ref().filter(|v| v.value <= 0.0) {
            self.err(Diagnostic::error(
                format!("{what} must be positive"),
                v.span,
                "must be > 0",
            ));
        }
    }

    /// Error if a whole number is below `min`.
    pub fn at_least(&mut self, x: &Option<Spanned<i64>>, min: i64, what: &str) {
        if let Some(v) = x.as_ref().filter(|v| v.value < min) {
            self.err(Diagnostic::error(
                format!("{what} must be at least {min}"),
                v.span,
                format!("must be >= {min}"),
            ));
        }
    }

    /// Error for every name defined twice (`what`: "material", "body", ..).
    pub fn names_are_unique<'n>(&mut self, names: impl IntoIterator<Item = &'n Ident>, what: &str) {
        let mut seen: BTreeMap<&str, Span> = BTreeMap::new();
        for n in names {
            match seen.get(n.name.as_str()) {
                Some(first) => {
                    let line = self.line(*first);
                    self.err(
                        Diagnostic::error(
                            format!("{what} `{}` is defined twice", n.name),
                            n.span,
                            format!("second definition of `{}`", n.name),
                        )
                        .with_help(format!(
                            "the first definition is on line {line}; rename one of them"
                        )),
                    );
                }
                None => {
                    seen.insert(&n.name, n.span);
                }
            }
        }
    }
}

/// "step `name`" or "step 2" for unnamed steps.
pub fn step_label(s: &Step, index: usize) -> String {
    match &s.name {
        Some(n) => format!("step `{}`", n.name),
        None => format!("step {}", index + 1),
    }
}

#[cfg(test)]
pub(crate) mod test_support {
    //! Decks for the rule tests.
    use super::validate;
    use crate::parse::parse;

    /// A valid base deck (body `block` of material `steel`).
    pub const BASE: &str = "analysis { dimension = plane_strain }\n\
        material steel { elastic { E = 210e3  nu = 0.3 } }\n\
        body block { mesh = rectangle { origin = (0, 0) size = (2, 1) divisions = (4, 2) } material = steel }\n\
        fix block.bottom { ux uy }\n\
        step load { time = 0 .. 1  increments = 2 }\n";

    /// Validation messages of `text` (which must parse cleanly).
    pub fn messages_of(text: &str) -> Vec<String> {
        let (deck, d) = parse(text);
        assert!(d.is_empty(), "{d:?}");
        validate(&deck, text)
            .into_iter()
            .map(|d| d.message)
            .collect()
    }

    /// Validation messages of [`BASE`] followed by `extra`.
    pub fn messages(extra: &str) -> Vec<String> {
        messages_of(&format!("{BASE}{extra}"))
    }

    /// Messages of a deck with one body `b` of material `m` (given in full).
    pub fn material_messages(dim: &str, material: &str, body_extra: &str) -> Vec<String> {
        messages_of(&format!(
            "analysis {{ dimension = {dim} }}\nmaterial m {{ {material} }}\n\
             body b {{ mesh = rectangle {{ origin = (0, 0) size = (2, 1) divisions = (4, 2) }} \
             material = m {body_extra} }}\nfix b.bottom {{ ux uy }}\n\
             step load {{ time = 0 .. 1  increments = 2 }}\n"
        ))
    }

    #[test]
    fn base_deck_is_clean() {
        assert!(messages("").is_empty());
    }
}
