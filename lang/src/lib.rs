//! ctc-lang (work in progress)
pub mod ast;
pub mod diagnostics;
pub mod parse;
pub mod source;
pub mod span;
pub mod suggest;
