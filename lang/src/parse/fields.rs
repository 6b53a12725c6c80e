//! Reading the entries of a generic block by key.
//!
//! Each construct declares the keys its block accepts; [`Fields`] hands out
//! the typed value of each key, and [`Fields::finish`] reports every entry
//! that was not asked for as an unknown key with a "did you mean", and
//! every key given twice.

use super::values::{self, Diags};
use crate::ast::syntax::{Block, Entry, EntryBody, Value};
use crate::ast::{Grading, Pair, Point, TimeFn};
use crate::diagnostics::Diagnostic;
use crate::keys::{Dim, Key};
use crate::span::{Span, Spanned};
use crate::suggest::{closest, one_of};

/// The entries of one block, consumed key by key.
pub struct Fields<'b> {
    /// How the block is called in messages, e.g. "`elastic` block".
    what: String,
    entries: &'b [Entry],
    known: Vec<&'static str>,
    /// Dimensions of the keys of a key table (empty: not declared).
    dims: Vec<(&'static str, Dim)>,
    used: Vec<bool>,
}

impl<'b> Fields<'b> {
    /// Starts reading `block`, whose accepted keys are `known`.
    pub fn new(block: &'b Block, what: impl Into<String>, known: &[&'static str]) -> Self {
        Fields {
            what: what.into(),
            entries: &block.entries,
            known: known.to_vec(),
            dims: Vec::new(),
            used: vec![false; block.entries.len()],
        }
    }

    /// Starts reading `block` through a key table (numbers are checked
    /// against the keys' dimensions).
    pub fn keyed(block: &'b Block, what: impl Into<String>, keys: &[Key]) -> Self {
        let mut f = Self::new(block, what, &crate::keys::names(keys));
        f.dims = keys.iter().map(|k| (k.name, k.dim)).collect();
        f
    }

    /// The declared dimension of `key`.
    pub fn dim(&self, key: &str) -> Option<Dim> {
        self.dims.iter().find(|(k, _)| *k == key).map(|(_, d)| *d)
    }

    /// How the block is called in messages.
    pub fn what(&self) -> &str {
        &self.what
    }

    /// The first entry with `key`; later entries with the same key are
    /// reported as duplicates.
    pub fn entry(&mut self, key: &str, diags: &mut Diags) -> Option<&'b Entry> {
        let mut first: Option<&'b Entry> = None;
        for (i, e) in self.entries.iter().enumerate() {
            if e.key.name != key {
                continue;
            }
            self.used[i] = true;
            match first {
                None => first = Some(e),
                Some(_) => diags.push(
                    Diagnostic::error(
                        format!("`{key}` is given twice in the {}", self.what),
                        e.key.span,
                        "duplicate key",
                    )
                    .with_help("remove one of them"),
                ),
            }
        }
        first
    }

    /// The value of `key = value`.
    pub fn value(&mut self, key: &str, diags: &mut Diags) -> Option<&'b Value> {
        let e = self.entry(key, diags)?;
        match &e.body {
            EntryBody::Assign(v) => Some(v),
            EntryBody::Block(b) => {
                diags.push(Diagnostic::error(
                    format!("`{key}` needs a value"),
                    b.span,
                    format!("expected `{key} = <value>`, found a block"),
                ));
                None
            }
            EntryBody::Flag => {
                diags.push(Diagnostic::error(
                    format!("`{key}` needs a value"),
                    e.span,
                    format!("expected `{key} = <value>`"),
                ));
                None
            }
        }
    }

    /// The block of `key { .. }`.
    pub fn block(&mut self, key: &str, diags: &mut Diags) -> Option<&'b Block> {
        let e = self.entry(key, diags)?;
        match &e.body {
            EntryBody::Block(b) => Some(b),
            EntryBody::Assign(v) => {
                diags.push(Diagnostic::error(
                    format!("`{key}` is a block"),
                    Span::new(e.key.span.start, v.span.end),
                    format!("expected `{key} {{ .. }}`"),
                ));
                None
            }
            EntryBody::Flag => {
                diags.push(Diagnostic::error(
                    format!("`{key}` is a block"),
                    e.span,
                    format!("expected `{key} {{ .. }}`"),
                ));
                None
            }
        }
    }

    /// `key = <number>`.
    pub fn number(&mut self, key: &str, diags: &mut Diags) -> Option<Spanned<f64>> {
        let v = self.value(key, diags)?;
        values::number_of(v, self.dim(key), &format!("`{key}`"), diags)
    }

    /// `key = <whole number>`.
    pub fn integer(&mut self, key: &str, diags: &mut Diags) -> Option<Spanned<i64>> {
        let v = self.value(key, diags)?;
        values::integer(v, diags)
    }

    /// `key = true | false`.
    pub fn boolean(&mut self, key: &str, diags: &mut Diags) -> Option<Spanned<bool>> {
        let v = self.value(key, diags)?;
        values::boolean(v, diags)
    }

    /// `key = (x, y)`.
    pub fn point(&mut self, key: &str, diags: &mut Diags) -> Option<Point> {
        let v = self.value(key, diags)?;
        values::point(v, diags)
    }

    /// `key = (a, b)` keeping each number's span.
    pub fn pair(&mut self, key: &str, diags: &mut Diags) -> Option<Pair> {
        let v = self.value(key, diags)?;
        values::pair(v, diags)
    }

    /// `key = <time function>`.
    pub fn time_fn(&mut self, key: &str, diags: &mut Diags) -> Option<Spanned<TimeFn>> {
        let v = self.value(key, diags)?;
        values::time_fn_of(v, self.dim(key), diags)
    }

    /// `key = <grading>`.
    pub fn grading(&mut self, key: &str, diags: &mut Diags) -> Option<Spanned<Grading>> {
        let v = self.value(key, diags)?;
        values::grading(v, diags)
    }

    /// `key = name` among `options`.
    pub fn choice<T: Copy>(
        &mut self,
        key: &str,
        what: &str,
        options: &[(&str, T)],
        diags: &mut Diags,
    ) -> Option<Spanned<T>> {
        let v = self.value(key, diags)?;
        values::choice(v, what, options, diags)
    }

    /// Entries whose key is one of `keys` (marked as used), e.g. reserved
    /// blocks that validation reports as not supported yet.
    pub fn take_all(&mut self, keys: &[&str]) -> Vec<&'b Entry> {
        let mut out = Vec::new();
        for (i, e) in self.entries.iter().enumerate() {
            if keys.contains(&e.key.name.as_str()) {
                self.used[i] = true;
                out.push(e);
            }
        }
        out
    }

    /// Whether `key` was written, or an unknown key looks like a misspelling
    /// of it (then "missing `key`" would only repeat that error).
    pub fn mentions(&self, key: &str) -> bool {
        self.entries.iter().any(|e| {
            e.key.name == key
                || (!self.known.contains(&e.key.name.as_str())
                    && closest(&e.key.name, &self.known).as_deref() == Some(key))
        })
    }

    /// Reports a missing required key at `at` unless [`Fields::mentions`] it.
    pub fn require<T>(
        &self,
        found: &Option<T>,
        key: &str,
        at: Span,
        help: &str,
        diags: &mut Diags,
    ) {
        if found.is_none() && !self.mentions(key) {
            diags.push(
                Diagnostic::error(
                    format!("missing `{key}` in the {}", self.what),
                    at,
                    format!("`{key}` is required"),
                )
                .with_help(help),
            );
        }
    }

    /// Reports every entry no one asked for as an unknown key (a bare word
    /// right after a number on its line is an unknown unit: `E = 210 GPaa`).
    pub fn finish(self, diags: &mut Diags) {
        for (i, (e, used)) in self.entries.iter().zip(&self.used).enumerate() {
            if *used {
                continue;
            }
            if let Some(d) = unknown_unit(self.entries, i) {
                diags.push(d);
                continue;
            }
            let help = match closest(&e.key.name, &self.known) {
                Some(c) => format!("did you mean `{c}`?"),
                None if self.known.is_empty() => format!("the {} takes no keys", self.what),
                None => format!("expected {}", one_of(&self.known)),
            };
            diags.push(
                Diagnostic::error(
                    format!("unknown key `{}` in the {}", e.key.name, self.what),
                    e.key.span,
                    "unknown key",
                )
                .with_help(help),
            );
        }
    }
}

/// `key = <number> word`: `word` was meant as a unit.
fn unknown_unit(entries: &[Entry], i: usize) -> Option<Diagnostic> {
    let e = &entries[i];
    if !matches!(e.body, EntryBody::Flag) || i == 0 {
        return None;
    }
    let EntryBody::Assign(v) = &entries[i - 1].body else {
        return None;
    };
    let numeric = matches!(
        v.kind,
        crate::ast::syntax::ValueKind::Number(_) | crate::ast::syntax::ValueKind::Quantity { .. }
    );
    // on the same line, separated by blanks only
    let gap = e.key.span.start.checked_sub(v.span.end)?;
    if !numeric || gap == 0 || gap > 4 {
        return None;
    }
    let names: Vec<&str> = crate::units::ATOMS.iter().map(|a| a.name).collect();
    let suggestion = closest(&e.key.name, &names)?;
    Some(
        Diagnostic::error(
            format!("unknown unit `{}`", e.key.name),
            e.key.span,
            "not a unit",
        )
        .with_help(format!("did you mean `{suggestion}`?")),
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::parse::test_support::block_of;

    #[test]
    fn unknown_keys_get_a_suggestion_and_do_not_count_as_missing() {
        let b = block_of("{ E = 210e3  un = 0.3 }");
        let mut d = Diags::new();
        let mut f = Fields::new(&b, "`elastic` block", &["E", "nu"]);
        assert_eq!(f.number("E", &mut d).unwrap().value, 210e3);
        let nu = f.number("nu", &mut d);
        assert!(nu.is_none());
        f.require(&nu, "nu", b.span, "add `nu = ..`", &mut d);
        f.finish(&mut d);
        assert_eq!(d.len(), 1, "{d:?}");
        assert_eq!(d[0].message, "unknown key `un` in the `elastic` block");
        assert_eq!(d[0].help.as_deref(), Some("did you mean `nu`?"));
    }

    #[test]
    fn duplicates_and_missing_keys_are_reported() {
        let b = block_of("{ E = 1  E = 2 }");
        let mut d = Diags::new();
        let mut f = Fields::new(&b, "`elastic` block", &["E", "nu"]);
        assert_eq!(f.number("E", &mut d).unwrap().value, 1.0);
        let nu = f.number("nu", &mut d);
        f.require(&nu, "nu", b.span, "add `nu = ..`", &mut d);
        f.finish(&mut d);
        let msgs: Vec<&str> = d.iter().map(|x| x.message.as_str()).collect();
        assert_eq!(
            msgs,
            [
                "`E` is given twice in the `elastic` block",
                "missing `nu` in the `elastic` block"
            ]
        );
    }

    #[test]
    fn wrong_entry_shapes() {
        let b = block_of("{ E { } motion = 1 nu }");
        let mut d = Diags::new();
        let mut f = Fields::new(&b, "block", &["E", "motion", "nu"]);
        assert!(f.number("E", &mut d).is_none());
        assert!(f.block("motion", &mut d).is_none());
        assert!(f.number("nu", &mut d).is_none());
        f.finish(&mut d);
        assert_eq!(d.len(), 3);
    }
}
