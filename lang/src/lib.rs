//! ctc-lang: the `.ctc` deck language.
//!
//! ```text
//! text --pest (ctc.pest)--> generic syntax --parse/<construct>.rs--> typed AST (spans)
//!      --validate/<construct>.rs--> all semantic errors at once
//!      --lower/<construct>.rs--> ctc_engine::model::Model
//! ```
//!
//! Key tables ([`keys`]) and the mesh generator registry ([`generators`])
//! describe what each block accepts, once, for the parser, validation,
//! lowering and the keyword reference.
//!
//! ```text
//! ```
//!
//! - [`compile`]: parse + validate + lower; the model, or every diagnostic;
//! - [`check`]: the same, but also returns the warnings of a valid deck;
//! - [`Diagnostics::render`]: rustc-style plain text;
//! - [`explain()`]: the plan of a lowered scene (`ctc check --explain`).

#![warn(missing_docs)]

pub mod ast;
pub mod diagnostics;
pub mod explain;
pub mod explain_surface;
pub mod expr;
pub mod format;
pub mod generators;
pub mod keys;
pub mod lower;
pub mod override_path;
pub mod parse;
pub mod reference;
pub mod source;
pub mod span;
pub mod suggest;
pub mod tables;
pub mod units;
pub mod validate;

pub use diagnostics::{Diagnostic, Diagnostics, Severity};
pub use explain::explain;
pub use source::Source;
pub use span::Span;

use ctc_engine::model::{AnyModel, Model};

/// The outcome of checking a deck: the model when there is no error, and
/// every diagnostic (errors and warnings) in deck order.
#[derive(Debug, Clone)]
pub struct Compilation {
    /// The lowered planar scene, `None` if there is at least one error or
    /// the analysis is `3d`.
    pub model: Option<Model>,
    /// The lowered solid scene of a `3d` analysis without error.
    pub solid: Option<Model<3>>,
    /// All errors and warnings, sorted by position in the deck.
    pub diagnostics: Diagnostics,
}

/// Parses, validates and lowers a deck, collecting every diagnostic.
pub fn check(src: &Source) -> Compilation {
    let (deck, mut diags) = parse::parse(&src.text);
    diags.extend(src.include_errors.iter().cloned());
    diags.extend(validate::validate(&deck, &src.text));
    let (model, lowered) = lower::lower(&deck, src, &diags);
    diags.extend(lowered);
    let mut diagnostics = Diagnostics(diags);
    diagnostics.sort();
    let model = if diagnostics.has_errors() {
        None
    } else {
        model
    };
    let (model, solid) = match model {
        Some(AnyModel::D2(m)) => (Some(m), None),
        Some(AnyModel::D3(m)) => (None, Some(m)),
        None => (None, None),
    };
    Compilation {
        model,
        solid,
        diagnostics,
    }
}

/// Parses, validates and lowers a deck of either dimension: the planar or
/// solid model, or every diagnostic.
pub fn compile_any(src: &Source) -> Result<AnyModel, Diagnostics> {
    let c = check(src);
    match (c.model, c.solid) {
        (Some(m), _) => Ok(AnyModel::D2(m)),
        (None, Some(m)) => Ok(AnyModel::D3(m)),
        (None, None) => Err(c.diagnostics),
    }
}

/// Parses, validates and lowers a deck into the engine's [`Model`].
/// On failure returns every diagnostic of the deck (errors and warnings);
/// warnings of a successful compilation are dropped (use [`check`] to see
/// them).
pub fn compile(src: &Source) -> Result<Model, Diagnostics> {
    let c = check(src);
    match (c.model, c.solid) {
        (Some(m), _) => Ok(m),
        (None, Some(_)) => {
            let mut d = c.diagnostics;
            d.0.push(Diagnostic::error(
                "the deck is a 3d analysis, and this command takes planar decks only",
                Span::new(0, 0),
                "3d deck",
            ));
            Err(d)
        }
        (None, None) => Err(c.diagnostics),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn empty_deck_reports_what_is_missing() {
        let e = compile(&Source::new("empty.ctc", "")).unwrap_err();
        let msgs: Vec<&str> = e.0.iter().map(|d| d.message.as_str()).collect();
        assert_eq!(
            msgs,
            [
                "the deck has no `analysis` block",
                "the deck has no `body`",
                "the deck has no `step`"
            ]
        );
    }
}
