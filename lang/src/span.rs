//! Byte ranges into a deck's text, and values that carry one.

use std::cell::Cell;

thread_local! {
    /// Where the text the parser is reading starts in the deck (0 but while
    /// [`at_offset`] runs).
    static OFFSET: Cell<usize> = const { Cell::new(0) };
}

/// Runs `f` with every [`Span::of`] moved `offset` bytes to the right: the
/// error recovery parses a chunk of the deck on its own (pest reads a
/// slice; padding the chunk to its place in the deck made each chunk cost
/// the whole deck before it) and converts it with spans in the deck.
pub(crate) fn at_offset<T>(offset: usize, f: impl FnOnce() -> T) -> T {
    struct Restore(usize);
    impl Drop for Restore {
        fn drop(&mut self) {
            OFFSET.with(|o| o.set(self.0));
        }
    }
    let _restore = Restore(OFFSET.with(|o| o.replace(offset)));
    f()
}

/// A byte range `start..end` into the deck text. Every AST node has one, so
/// every diagnostic can point at the exact text it is about.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Default)]
pub struct Span {
    /// First byte.
    pub start: usize,
    /// One past the last byte (`start == end` for an empty span, e.g. end of file).
    pub end: usize,
}

impl Span {
    /// The range `start..end`.
    pub fn new(start: usize, end: usize) -> Self {
        Span { start, end }
    }

    /// The span of a pest pair or span, in the whole deck (a chunk parsed
    /// on its own during error recovery is placed by [`at_offset`]).
    pub fn of(span: pest::Span<'_>) -> Self {
        let o = OFFSET.with(Cell::get);
        Span::new(span.start() + o, span.end() + o)
    }

    /// The smallest span covering `self` and `other`.
    pub fn to(self, other: Span) -> Span {
        Span::new(self.start.min(other.start), self.end.max(other.end))
    }

    /// This span moved `offset` bytes to the right (used when a chunk of the
    /// deck is parsed on its own during error recovery).
    pub fn shifted(self, offset: usize) -> Span {
        Span::new(self.start + offset, self.end + offset)
    }

    /// The text under the span (empty if it is out of range).
    pub fn text(self, source: &str) -> &str {
        source.get(self.start..self.end).unwrap_or("")
    }
}

/// A value together with the span of the deck text it came from.
#[derive(Debug, Clone, PartialEq)]
pub struct Spanned<T> {
    /// The value.
    pub value: T,
    /// Where it was written.
    pub span: Span,
}

impl<T> Spanned<T> {
    /// Wraps `value` with `span`.
    pub fn new(value: T, span: Span) -> Self {
        Spanned { value, span }
    }
}

/// A name written in the deck (key, item name, body, set or tool name).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Ident {
    /// The name as written.
    pub name: String,
    /// Where it was written.
    pub span: Span,
}

impl Ident {
    /// A name at `span`.
    pub fn new(name: impl Into<String>, span: Span) -> Self {
        Ident {
            name: name.into(),
            span,
        }
    }
}

impl std::fmt::Display for Ident {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.name)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn span_union_and_shift() {
        let a = Span::new(3, 5);
        let b = Span::new(8, 10);
        assert_eq!(a.to(b), Span::new(3, 10));
        assert_eq!(b.to(a), Span::new(3, 10));
        assert_eq!(a.shifted(100), Span::new(103, 105));
        assert_eq!(Span::new(2, 5).text("abcdefg"), "cde");
        assert_eq!(Span::new(2, 50).text("abc"), "");
    }
}
