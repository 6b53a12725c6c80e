//! Diagnostics: errors and warnings about a deck, accumulated and rendered
//! like rustc (plain text, no colours, deterministic).
//!
//! ```text
//! error: unknown material `steeel`
//!   --> examples/foo.ctc:12:14
//!    |
//! 12 |   material = steeel
//!    |              ^^^^^^ no material with this name
//!    = help: did you mean `steel`?
//! ```

use crate::source::Source;
use crate::span::Span;
use std::fmt::Write as _;

/// How serious a diagnostic is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum Severity {
    /// The deck cannot be run.
    Error,
    /// The deck runs, but probably not as intended.
    Warning,
}

/// One message about the deck, pointing at a span of its text.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Diagnostic {
    /// Error or warning.
    pub severity: Severity,
    /// The headline, e.g. "unknown material `steeel`".
    pub message: String,
    /// The text the message is about.
    pub span: Span,
    /// Short text printed after the carets, e.g. "no material with this name".
    pub label: String,
    /// An optional suggestion, e.g. "did you mean `steel`?".
    pub help: Option<String>,
    /// Secondary labels and notes, in the order added.
    pub extra: Vec<Extra>,
}

/// What a diagnostic may add to its primary label.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Extra {
    /// Another span the message is about, with its label (the operands of
    /// a bad expression), underlined with `-`.
    Label(Span, String),
    /// A line `= note: ..`, e.g. an include chain.
    Note(String),
}

impl Diagnostic {
    /// An error at `span`.
    pub fn error(message: impl Into<String>, span: Span, label: impl Into<String>) -> Self {
        Diagnostic {
            severity: Severity::Error,
            message: message.into(),
            span,
            label: label.into(),
            help: None,
            extra: Vec::new(),
        }
    }

    /// A warning at `span`.
    pub fn warning(message: impl Into<String>, span: Span, label: impl Into<String>) -> Self {
        Diagnostic {
            severity: Severity::Warning,
            message: message.into(),
            span,
            label: label.into(),
            help: None,
            extra: Vec::new(),
        }
    }

    /// Adds a help line.
    pub fn with_help(mut self, help: impl Into<String>) -> Self {
        self.help = Some(help.into());
        self
    }

    /// Adds a secondary span with its label.
    pub fn with_secondary(mut self, span: Span, label: impl Into<String>) -> Self {
        self.extra.push(Extra::Label(span, label.into()));
        self
    }

    /// Adds a note line.
    pub fn with_note(mut self, note: impl Into<String>) -> Self {
        self.extra.push(Extra::Note(note.into()));
        self
    }

    /// Adds a help line if `help` is `Some`.
    pub fn with_help_opt(mut self, help: Option<String>) -> Self {
        if help.is_some() {
            self.help = help;
        }
        self
    }

    /// Whether this is an error.
    pub fn is_error(&self) -> bool {
        self.severity == Severity::Error
    }

    /// Renders this diagnostic against the deck it is about.
    pub fn render(&self, src: &Source) -> String {
        let index = LineIndex::new(&src.text);
        let mut out = String::new();
        render_one(self, src, &index, &mut out);
        out
    }
}

/// All diagnostics of a deck (errors and warnings), in deck order.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct Diagnostics(pub Vec<Diagnostic>);

impl Diagnostics {
    /// No diagnostics.
    pub fn new() -> Self {
        Diagnostics(Vec::new())
    }

    /// Adds one diagnostic.
    pub fn push(&mut self, d: Diagnostic) {
        self.0.push(d);
    }

    /// Adds several diagnostics.
    pub fn extend(&mut self, ds: impl IntoIterator<Item = Diagnostic>) {
        self.0.extend(ds);
    }

    /// Number of errors.
    pub fn error_count(&self) -> usize {
        self.0.iter().filter(|d| d.is_error()).count()
    }

    /// Number of warnings.
    pub fn warning_count(&self) -> usize {
        self.0.len() - self.error_count()
    }

    /// Whether there is at least one error.
    pub fn has_errors(&self) -> bool {
        self.0.iter().any(Diagnostic::is_error)
    }

    /// Whether there are no diagnostics at all.
    pub fn is_empty(&self) -> bool {
        self.0.is_empty()
    }

    /// Sorts by position in the deck (stable: diagnostics at the same place
    /// keep the order in which they were found).
    pub fn sort(&mut self) {
        self.0.sort_by_key(|d| (d.span.start, d.span.end));
    }

    /// Renders every diagnostic followed by a one-line summary, e.g.
    /// `error: 3 errors and 1 warning in deck.ctc`. Empty string if there is
    /// nothing to report.
    pub fn render(&self, src: &Source) -> String {
        if self.0.is_empty() {
            return String::new();
        }
        let index = LineIndex::new(&src.text);
        let mut out = String::new();
        for d in &self.0 {
            render_one(d, src, &index, &mut out);
            out.push('\n');
        }
        let (e, w) = (self.error_count(), self.warning_count());
        let plural = |n: usize, what: &str| {
            if n == 1 {
                format!("1 {what}")
            } else {
                format!("{n} {what}s")
            }
        };
        let path = src.path.display();
        match (e, w) {
            (0, w) => {
                let _ = writeln!(out, "warning: {} in {path}", plural(w, "warning"));
            }
            (e, 0) => {
                let _ = writeln!(out, "error: {} in {path}", plural(e, "error"));
            }
            (e, w) => {
                let _ = writeln!(
                    out,
                    "error: {} and {} in {path}",
                    plural(e, "error"),
                    plural(w, "warning")
                );
            }
        }
        out
    }
}

impl From<Vec<Diagnostic>> for Diagnostics {
    fn from(v: Vec<Diagnostic>) -> Self {
        Diagnostics(v)
    }
}

/// Byte offsets of line starts, to turn spans into line/column positions.
#[derive(Debug, Clone)]
pub struct LineIndex<'a> {
    text: &'a str,
    starts: Vec<usize>,
}

impl<'a> LineIndex<'a> {
    /// Indexes `text`.
    pub fn new(text: &'a str) -> Self {
        let mut starts = vec![0];
        for (i, b) in text.bytes().enumerate() {
            if b == b'\n' {
                starts.push(i + 1);
            }
        }
        LineIndex { text, starts }
    }

    /// Clamps a byte offset into the text, on a character boundary.
    fn clamp(&self, mut offset: usize) -> usize {
        offset = offset.min(self.text.len());
        while !self.text.is_char_boundary(offset) {
            offset -= 1;
        }
        offset
    }

    /// 0-based line number containing byte `offset`.
    pub fn line_of(&self, offset: usize) -> usize {
        let offset = self.clamp(offset);
        match self.starts.binary_search(&offset) {
            Ok(l) => l,
            Err(l) => l - 1,
        }
    }

    /// Text of 0-based line `line`, without the line break.
    pub fn line_text(&self, line: usize) -> &'a str {
        let start = self.starts[line];
        let end = self
            .starts
            .get(line + 1)
            .map(|&s| s - 1)
            .unwrap_or(self.text.len());
        self.text[start..end].trim_end_matches('\r')
    }

    /// 1-based (line, column) of byte `offset`; the column counts characters.
    pub fn line_col(&self, offset: usize) -> (usize, usize) {
        let offset = self.clamp(offset);
        let line = self.line_of(offset);
        let col = self.text[self.starts[line]..offset].chars().count();
        (line + 1, col + 1)
    }
}

/// Width of a character on screen: tabs are expanded to 4 columns.
fn display_width(s: &str) -> usize {
    s.chars().map(|c| if c == '\t' { 4 } else { 1 }).sum()
}

fn render_one(d: &Diagnostic, src: &Source, _index: &LineIndex<'_>, out: &mut String) {
    let kind = match d.severity {
        Severity::Error => "error",
        Severity::Warning => "warning",
    };
    let _ = writeln!(out, "{kind}: {}", d.message);
    let (file, start) = src.locate(d.span.start.min(src.text.len()));
    let f = &src.files[file];
    let index = LineIndex::new(&f.text);
    let start = index.clamp(start);
    // the end in the same file (a span never crosses files in practice)
    let end = index.clamp(start + d.span.end.saturating_sub(d.span.start));
    let (line, col) = index.line_col(start);
    let gutter = line.to_string().len();
    let pad = " ".repeat(gutter);
    let path = if file == 0 { &src.path } else { &f.path };
    let _ = writeln!(out, "{pad}--> {}:{line}:{col}", path.display());
    let _ = writeln!(out, "{pad} |");
    underline(&index, start, end, '^', &d.label, &pad, true, out);
    for (span, label) in d.extra.iter().filter_map(|e| match e {
        Extra::Label(s, l) => Some((s, l)),
        Extra::Note(_) => None,
    }) {
        let (sf, s) = src.locate(span.start.min(src.text.len()));
        if sf != file {
            continue;
        }
        let s = index.clamp(s);
        let e = index.clamp(s + span.end.saturating_sub(span.start));
        let same_line = index.line_of(s) == index.line_of(start);
        underline(&index, s, e, '-', label, &pad, !same_line, out);
    }
    if let Some(help) = &d.help {
        let _ = writeln!(out, "{pad} = help: {help}");
    }
    for (parent, at) in src.include_chain(file) {
        let pi = LineIndex::new(&src.files[parent].text);
        let (l, c) = pi.line_col(at);
        let ppath = if parent == 0 {
            &src.path
        } else {
            &src.files[parent].path
        };
        let _ = writeln!(
            out,
            "{pad} = note: `{}` is included from {}:{l}:{c}",
            f.path.display(),
            ppath.display()
        );
    }
    for n in d.extra.iter().filter_map(|e| match e {
        Extra::Note(n) => Some(n),
        Extra::Label(..) => None,
    }) {
        let _ = writeln!(out, "{pad} = note: {n}");
    }
}

/// The source line of `start` (when `with_line`) and a line of `mark`
/// under `start..end` (clipped to that line), followed by `label`.
#[allow(clippy::too_many_arguments)]
fn underline(
    index: &LineIndex<'_>,
    start: usize,
    end: usize,
    mark: char,
    label: &str,
    pad: &str,
    with_line: bool,
    out: &mut String,
) {
    let line = index.line_of(start);
    let line_text = index.line_text(line);
    if with_line {
        let _ = writeln!(
            out,
            "{:>w$} | {}",
            line + 1,
            line_text.replace('\t', "    "),
            w = pad.len()
        );
    }
    let line_start = start - col_bytes(index, start);
    let before = &index.text[line_start..start];
    let line_end = line_start + line_text.len();
    let under_end = end.min(line_end).max(start);
    let under = &index.text[start..under_end];
    let n = display_width(under).max(1);
    let mut caret_line = format!(
        "{pad} | {}{}",
        " ".repeat(display_width(before)),
        mark.to_string().repeat(n)
    );
    if !label.is_empty() {
        caret_line.push(' ');
        caret_line.push_str(label);
    }
    let _ = writeln!(out, "{}", caret_line.trim_end());
}

/// Number of bytes between the start of the line and `offset`.
fn col_bytes(index: &LineIndex<'_>, offset: usize) -> usize {
    let line = index.line_of(offset);
    offset - index.starts[line]
}

#[cfg(test)]
mod tests {
    use super::*;

    fn src(text: &str) -> Source {
        Source::new("examples/foo.ctc", text)
    }

    #[test]
    fn renders_like_rustc_with_two_digit_gutter() {
        let mut text = String::new();
        for _ in 0..11 {
            text.push_str("#\n");
        }
        text.push_str("  material = steeel\n");
        let start = text.find("steeel").unwrap();
        let d = Diagnostic::error(
            "unknown material `steeel`",
            Span::new(start, start + 6),
            "no material with this name",
        )
        .with_help("did you mean `steel`?");
        let expected = "\
error: unknown material `steeel`
  --> examples/foo.ctc:12:14
   |
12 |   material = steeel
   |              ^^^^^^ no material with this name
   = help: did you mean `steel`?
";
        assert_eq!(d.render(&src(&text)), expected);
    }

    #[test]
    fn columns_count_characters_not_bytes() {
        let text = "# é\nbody é { }\n";
        let idx = LineIndex::new(text);
        let at = text.rfind('{').unwrap();
        assert_eq!(idx.line_col(at), (2, 8));
    }

    #[test]
    fn multi_line_span_underlines_first_line_only() {
        let text = "body b {\n  mesh = x\n}\n";
        let d = Diagnostic::error("m", Span::new(5, text.len()), "here");
        let r = d.render(&src(text));
        assert!(r.contains("1 | body b {\n  |      ^^^ here\n"), "{r}");
    }

    #[test]
    fn span_at_end_of_file_gets_one_caret() {
        let text = "analysis {";
        let d = Diagnostic::error("unclosed", Span::new(10, 10), "");
        let r = d.render(&src(text));
        assert!(r.contains("1 | analysis {\n  |           ^\n"), "{r}");
        let d = Diagnostic::error("past the end", Span::new(50, 60), "x");
        assert!(d.render(&src(text)).contains(":1:11"));
    }

    #[test]
    fn summary_counts_errors_and_warnings() {
        let mut ds = Diagnostics::new();
        ds.push(Diagnostic::error("a", Span::new(0, 1), ""));
        ds.push(Diagnostic::warning("b", Span::new(0, 1), ""));
        ds.push(Diagnostic::error("c", Span::new(0, 1), ""));
        assert_eq!(ds.error_count(), 2);
        assert_eq!(ds.warning_count(), 1);
        let r = ds.render(&src("x\n"));
        assert!(r.ends_with("error: 2 errors and 1 warning in examples/foo.ctc\n"));
    }

    #[test]
    fn tabs_are_expanded_consistently() {
        let text = "\tE = -1\n";
        let d = Diagnostic::error("bad", Span::new(5, 7), "");
        let r = d.render(&src(text));
        assert!(r.contains("1 |     E = -1\n  |         ^^\n"), "{r}");
    }
}
