//! `ctc fmt`: the canonical layout of a deck, comments kept.
//!
//! - one item per line group, a blank line kept where the source had one
//!   (never two);
//! - a block is written on one line (`elastic { E = 210e3  nu = 0.3 }`,
//!   two spaces between entries) when it holds only short entries without
//!   nested blocks or comments and fits in [`WIDTH`] columns; otherwise one
//!   entry per line, indented by two spaces;
//! - `key = value`, `a .. b`, `(a, b)`, `[a, b]`, `f(a, b)`, binary
//!   operators spaced (`10 * E / h`, `x^2`), numbers and names as written.
//!
//! The formatter works on the grammar's pairs, so what it prints parses to
//! the same deck (tested on every deck of the repository and on mutated
//! decks), and formatting is idempotent. A deck with a syntax error is not
//! formatted (its diagnostics are returned).

use crate::parse::{CtcParser, Rule};
use pest::iterators::Pair;
use pest::Parser as _;

/// Widest one-line block.
pub const WIDTH: usize = 88;

/// A comment of the source: where it starts, its text, and whether code
/// precedes it on its line.
#[derive(Debug, Clone)]
struct Comment {
    at: usize,
    text: String,
    trailing: bool,
}

/// Comments of `text`, in order (outside strings).
fn comments(text: &str) -> Vec<Comment> {
    let mut out = Vec::new();
    let mut offset = 0;
    for line in text.split_inclusive('\n') {
        let mut in_string = false;
        for (i, c) in line.char_indices() {
            match c {
                '"' => in_string = !in_string,
                '#' if !in_string => {
                    let body = line[i..].trim_end_matches(['\n', '\r']).trim_end();
                    out.push(Comment {
                        at: offset + i,
                        text: body.to_string(),
                        trailing: !line[..i].trim().is_empty(),
                    });
                    break;
                }
                _ => {}
            }
        }
        offset += line.len();
    }
    out
}

struct Printer<'t> {
    src: &'t str,
    comments: Vec<Comment>,
    next: usize,
    out: String,
}

/// Where the last token of `pair` ends. A pair that ends in a repetition
/// (`let a = 4  # note` ends in the expression's `(infix primary)*`) has a
/// span that runs on over the whitespace and comments pest skipped while
/// trying one more round; those belong to what follows.
fn content_end(src: &str, pair: &Pair<'_, Rule>) -> usize {
    let end = pair.as_span().end();
    match pair.clone().into_inner().last() {
        Some(last) => {
            let e = content_end(src, &last);
            if only_trivia(&src[e..end]) {
                e
            } else {
                end
            }
        }
        None => end,
    }
}

/// Whether `text` is only whitespace and `#` comments.
fn only_trivia(text: &str) -> bool {
    let mut rest = text.trim_start();
    while let Some(comment) = rest.strip_prefix('#') {
        rest = comment
            .find('\n')
            .map_or("", |i| &comment[i..])
            .trim_start();
    }
    rest.is_empty()
}

/// Formats `text`; `Err` with the rendered syntax error when it does not
/// parse.
pub fn format(text: &str) -> Result<String, String> {
    let pairs = CtcParser::parse(Rule::deck, text)
        .map_err(|e| crate::parse::errors::syntax_error(&e, text).message)?;
    let mut p = Printer {
        src: text,
        comments: comments(text),
        next: 0,
        out: String::new(),
    };
    let deck = pairs.into_iter().next().ok_or("empty parse")?;
    let mut last_end: Option<usize> = None;
    for item in deck.into_inner().filter(|p| p.as_rule() != Rule::EOI) {
        let start = item.as_span().start();
        // comments before the item, then a blank line where there was one
        let prev = p.flush_comments(start, 0, last_end);
        if prev.is_some_and(|e| p.src[e..start].matches('\n').count() >= 2) {
            p.blank_line();
        }
        p.item(item.clone());
        let end = content_end(text, &item);
        last_end = Some(end);
        p.trailing_comment(end);
        p.newline();
    }
    p.flush_comments(text.len(), 0, last_end);
    let mut out = p.out.trim_end().to_string();
    out.push('\n');
    if out.trim().is_empty() {
        out.clear();
    }
    Ok(out)
}

impl Printer<'_> {
    fn newline(&mut self) {
        while self.out.ends_with(' ') {
            self.out.pop();
        }
        if !self.out.is_empty() && !self.out.ends_with('\n') {
            self.out.push('\n');
        }
    }

    fn blank_line(&mut self) {
        self.newline();
        if !self.out.is_empty() && !self.out.ends_with("\n\n") {
            self.out.push('\n');
        }
    }

    fn indent(&mut self, depth: usize) {
        for _ in 0..depth {
            self.out.push_str("  ");
        }
    }

    /// Writes every comment before `before` on its own line(s), keeping a
    /// blank line where the source had one before it; returns where the
    /// last thing written ends in the source (`last` if nothing).
    fn flush_comments(
        &mut self,
        before: usize,
        depth: usize,
        mut last: Option<usize>,
    ) -> Option<usize> {
        while self.next < self.comments.len() && self.comments[self.next].at < before {
            let c = self.comments[self.next].clone();
            if let Some(l) = last {
                if l <= c.at && self.src[l..c.at].matches('\n').count() >= 2 {
                    self.blank_line();
                }
            }
            self.newline();
            self.indent(depth);
            self.out.push_str(&c.text);
            self.out.push('\n');
            last = Some(c.at + c.text.len());
            self.next += 1;
        }
        last
    }

    /// A comment on the same line after `after`, appended.
    fn trailing_comment(&mut self, after: usize) {
        if let Some(c) = self.comments.get(self.next) {
            let line_end = self.src[after..]
                .find('\n')
                .map_or(self.src.len(), |i| after + i);
            if c.at >= after && c.at < line_end && c.trailing {
                let c = c.clone();
                self.out.push_str("  ");
                self.out.push_str(&c.text);
                self.next += 1;
            }
        }
    }

    /// Whether a comment lies inside `start..end`.
    fn has_comment_in(&self, start: usize, end: usize) -> bool {
        self.comments[self.next..]
            .iter()
            .any(|c| c.at >= start && c.at < end)
    }

    fn item(&mut self, item: Pair<'_, Rule>) {
        let rule = item.as_rule();
        let parts: Vec<Pair<'_, Rule>> = item.into_inner().collect();
        for (i, part) in parts.iter().enumerate() {
            let sep = if i == 0 {
                ""
            } else {
                match (rule, part.as_rule()) {
                    (_, Rule::block) => " ",
                    (Rule::contact | Rule::unknown_item, Rule::master) => " -> ",
                    (Rule::unknown_item, Rule::name) => " -> ",
                    (Rule::tool, Rule::name) if i == 2 => " = ",
                    (Rule::set, Rule::set_expr)
                    | (Rule::let_item, Rule::value)
                    | (Rule::unknown_item, Rule::value) => " = ",
                    _ => " ",
                }
            };
            self.out.push_str(sep);
            if part.as_rule() == Rule::block {
                self.block(part.clone(), 0);
            } else {
                self.value(part.clone(), 0);
            }
        }
    }

    /// Whether a block can be written on one line.
    fn inline(&self, block: &Pair<'_, Rule>, depth: usize) -> Option<String> {
        let span = block.as_span();
        if self.has_comment_in(span.start(), span.end()) {
            return None;
        }
        if span.as_str().contains('\n') && self.src[span.start()..span.end()].lines().count() > 1 {
            // multi-line in the source: keep it multi-line when it has more
            // than one entry (a user choice worth keeping)
            let entries = block.clone().into_inner().count();
            if entries > 1 {
                return None;
            }
        }
        let mut parts = Vec::new();
        for e in block.clone().into_inner() {
            let mut inner = e.into_inner();
            let key = inner.next()?.as_str().to_string();
            match inner.next() {
                None => parts.push(key),
                Some(v) if v.as_rule() == Rule::block => return None,
                Some(v) => {
                    let t = self.flat(v);
                    if t.contains('\n') {
                        return None;
                    }
                    parts.push(format!("{key} = {t}"));
                }
            }
        }
        let line = if parts.is_empty() {
            "{ }".to_string()
        } else {
            format!("{{ {} }}", parts.join("  "))
        };
        let col = self.out.len() - self.out.rfind('\n').map_or(0, |i| i + 1);
        (col + line.len() + 2 * depth <= WIDTH).then_some(line)
    }

    fn block(&mut self, block: Pair<'_, Rule>, depth: usize) {
        if let Some(line) = self.inline(&block, depth) {
            self.out.push_str(&line);
            return;
        }
        let end = block.as_span().end();
        self.out.push('{');
        let mut last = Some(block.as_span().start() + 1);
        let open_line_end = self.src[block.as_span().start()..].find('\n');
        // a trailing comment right after `{`
        let first_entry = block
            .clone()
            .into_inner()
            .next()
            .map_or(end, |e| e.as_span().start());
        if let Some(le) = open_line_end {
            let le = block.as_span().start() + le;
            if let Some(c) = self.comments.get(self.next) {
                if c.at < le && c.at > block.as_span().start() && c.at < first_entry {
                    let c = c.clone();
                    self.out.push_str("  ");
                    self.out.push_str(&c.text);
                    self.next += 1;
                }
            }
        }
        self.newline();
        for e in block.into_inner() {
            let start = e.as_span().start();
            let prev = self.flush_comments(start, depth + 1, last);
            if let Some(l) = prev {
                if self.src[l..start].matches('\n').count() >= 2 && !self.out.ends_with("{\n") {
                    self.blank_line();
                }
            }
            self.indent(depth + 1);
            let e_end = e.as_span().end();
            self.entry(e, depth + 1);
            self.trailing_comment(e_end);
            self.newline();
            last = Some(e_end);
        }
        self.flush_comments(end, depth + 1, last);
        self.newline();
        self.indent(depth);
        self.out.push('}');
    }

    fn entry(&mut self, e: Pair<'_, Rule>, depth: usize) {
        let mut inner = e.into_inner();
        let Some(key) = inner.next() else { return };
        self.out.push_str(key.as_str());
        match inner.next() {
            None => {}
            Some(b) if b.as_rule() == Rule::block => {
                self.out.push(' ');
                self.block(b, depth);
            }
            Some(v) => {
                self.out.push_str(" = ");
                self.value(v, depth);
            }
        }
    }

    /// A value at `depth` (constructor blocks may span lines; a value
    /// holding a comment is kept verbatim, so no comment is lost).
    fn value(&mut self, v: Pair<'_, Rule>, depth: usize) {
        let span = v.as_span();
        match v.as_rule() {
            Rule::value | Rule::expr => {
                let inner: Vec<Pair<'_, Rule>> = v.clone().into_inner().collect();
                if v.as_rule() == Rule::value {
                    for (i, x) in inner.into_iter().enumerate() {
                        if i > 0 {
                            self.out.push_str(" .. ");
                        }
                        self.value(x, depth);
                    }
                } else if inner.len() == 1 && inner[0].as_rule() == Rule::ctor {
                    self.value(inner[0].clone(), depth);
                } else {
                    self.verbatim_or_flat(v);
                }
            }
            Rule::ctor => {
                let mut inner = v.into_inner();
                let Some(name) = inner.next() else { return };
                self.out.push_str(name.as_str());
                if let Some(rest) = inner.next() {
                    self.out.push(' ');
                    if rest.as_rule() == Rule::block {
                        self.block(rest, depth);
                    } else {
                        self.out.push_str(rest.as_str());
                    }
                }
            }
            _ if self.has_comment_in(span.start(), span.end()) => self.verbatim_or_flat(v),
            _ => {
                let t = self.flat(v);
                self.out.push_str(&t);
            }
        }
    }

    /// The canonical text, or the source text when a comment is inside.
    fn verbatim_or_flat(&mut self, v: Pair<'_, Rule>) {
        let (start, end) = (v.as_span().start(), content_end(self.src, &v));
        if self.has_comment_in(start, end) {
            self.out.push_str(&self.src[start..end]);
            while self.next < self.comments.len() && self.comments[self.next].at < end {
                self.next += 1;
            }
        } else {
            let t = self.flat(v);
            self.out.push_str(&t);
        }
    }

    /// The canonical one-line text of a value.
    fn flat(&self, v: Pair<'_, Rule>) -> String {
        match v.as_rule() {
            Rule::value => v
                .into_inner()
                .map(|x| self.flat(x))
                .collect::<Vec<_>>()
                .join(" .. "),
            Rule::expr | Rule::set_expr => {
                let mut s = String::new();
                for x in v.into_inner() {
                    match x.as_rule() {
                        Rule::add | Rule::sub | Rule::mul | Rule::div => {
                            s.push(' ');
                            s.push_str(x.as_str());
                            s.push(' ');
                        }
                        Rule::set_op => {
                            s.push(' ');
                            s.push_str(x.as_str().trim());
                            s.push(' ');
                        }
                        Rule::pow => s.push('^'),
                        Rule::neg => s.push('-'),
                        // a parenthesized set term
                        Rule::set_expr => {
                            s.push('(');
                            s.push_str(&self.flat(x));
                            s.push(')');
                        }
                        _ => s.push_str(&self.flat(x)),
                    }
                }
                s
            }
            Rule::quantity => {
                let mut inner = v.into_inner();
                let n = inner.next().map_or("", |p| p.as_str());
                let u = inner.next().map_or("", |p| p.as_str());
                format!("{n} {u}")
            }
            Rule::tuple => format!(
                "({})",
                v.into_inner()
                    .map(|x| self.flat(x))
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
            Rule::list => format!(
                "[{}]",
                v.into_inner()
                    .map(|x| self.flat(x))
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
            Rule::call => {
                let mut inner = v.into_inner();
                let head = inner.next().map_or(String::new(), |p| self.flat(p));
                let args: Vec<String> = inner.map(|a| self.flat(a)).collect();
                format!("{head}({})", args.join(", "))
            }
            Rule::arg => {
                let parts: Vec<Pair<'_, Rule>> = v.into_inner().collect();
                match parts.as_slice() {
                    [one] => self.flat(one.clone()),
                    [value, path] => format!("{} -> {}", self.flat(value.clone()), path.as_str()),
                    _ => String::new(),
                }
            }
            Rule::named_arg => {
                let mut inner = v.into_inner();
                let n = inner.next().map_or("", |p| p.as_str()).to_string();
                let x = inner.next().map_or(String::new(), |p| self.flat(p));
                format!("{n} = {x}")
            }
            Rule::ctor => {
                let mut inner = v.into_inner();
                let n = inner.next().map_or("", |p| p.as_str()).to_string();
                match inner.next() {
                    Some(b) if b.as_rule() == Rule::block => match self.inline(&b, 0) {
                        Some(line) => format!("{n} {line}"),
                        None => format!("{n} {}", b.as_str()),
                    },
                    Some(s) => format!("{n} {}", s.as_str()),
                    None => n,
                }
            }
            Rule::master => v.into_inner().map(|x| self.flat(x)).collect(),
            _ => v.as_str().to_string(),
        }
    }
}
