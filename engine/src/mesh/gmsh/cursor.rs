//! Whitespace-separated tokens of a `.msh` text with their 1-based line
//! numbers, and typed reads that turn every surprise into a
//! [`MeshError::at_line`].

use crate::mesh::MeshError;

/// A forward-only reader of tokens.
#[derive(Clone)]
pub struct Cursor<'a> {
    lines: std::iter::Enumerate<std::str::Lines<'a>>,
    rest: &'a str,
    line: usize,
    /// Section being read, for error messages (e.g. `$Nodes`).
    pub section: &'static str,
}

impl<'a> Cursor<'a> {
    /// A cursor at the start of `text`.
    pub fn new(text: &'a str) -> Self {
        Cursor {
            lines: text.lines().enumerate(),
            rest: "",
            line: 0,
            section: "the file header",
        }
    }

    /// Line of the last token read (0 before the first).
    pub fn line(&self) -> usize {
        self.line.max(1)
    }

    /// The next token and its line, `None` at the end of the text.
    pub fn next_token(&mut self) -> Option<(&'a str, usize)> {
        loop {
            let t = self.rest.trim_start();
            if !t.is_empty() {
                let end = t.find(char::is_whitespace).unwrap_or(t.len());
                self.rest = &t[end..];
                return Some((&t[..end], self.line));
            }
            let (i, l) = self.lines.next()?;
            self.line = i + 1;
            self.rest = l;
        }
    }

    /// The unread rest of the current line (consumed), trimmed.
    pub fn rest_of_line(&mut self) -> &'a str {
        let r = self.rest.trim();
        self.rest = "";
        r
    }

    /// Error at the line of the last token.
    pub fn error(&self, message: impl Into<String>) -> MeshError {
        MeshError::at_line(self.line(), message)
    }

    /// The next token, or an end-of-file error naming `what` was expected.
    pub fn token(&mut self, what: &str) -> Result<(&'a str, usize), MeshError> {
        match self.next_token() {
            Some(t) => Ok(t),
            None => Err(self.error(format!(
                "unexpected end of file in {}: expected {what} (is the file truncated?)",
                self.section
            ))),
        }
    }

    /// Error for token `tok` at `line` when `what` was expected.
    fn unexpected(&self, tok: &str, line: usize, what: &str) -> MeshError {
        let hint = if tok.starts_with('$') {
            " (the section ends before the count announced in its header)"
        } else {
            ""
        };
        MeshError::at_line(
            line,
            format!(
                "in {}: expected {what}, found '{}'{hint}",
                self.section,
                shorten(tok)
            ),
        )
    }

    /// A non-negative integer.
    pub fn usize(&mut self, what: &str) -> Result<usize, MeshError> {
        let (tok, line) = self.token(what)?;
        tok.parse::<usize>()
            .map_err(|_| self.unexpected(tok, line, &format!("{what} (a non-negative integer)")))
    }

    /// A signed integer.
    pub fn i64(&mut self, what: &str) -> Result<i64, MeshError> {
        let (tok, line) = self.token(what)?;
        tok.parse::<i64>()
            .map_err(|_| self.unexpected(tok, line, &format!("{what} (an integer)")))
    }

    /// A positive integer tag (node or element number).
    pub fn tag(&mut self, what: &str) -> Result<u64, MeshError> {
        let (tok, line) = self.token(what)?;
        match tok.parse::<u64>() {
            Ok(t) if t > 0 => Ok(t),
            _ => Err(self.unexpected(tok, line, &format!("{what} (a positive integer)"))),
        }
    }

    /// A finite real number.
    pub fn f64(&mut self, what: &str) -> Result<f64, MeshError> {
        let (tok, line) = self.token(what)?;
        match tok.parse::<f64>() {
            Ok(v) if v.is_finite() => Ok(v),
            _ => Err(self.unexpected(tok, line, &format!("{what} (a finite number)"))),
        }
    }

    /// The `$End<name>` token closing section `$<name>`.
    pub fn end(&mut self, name: &str) -> Result<(), MeshError> {
        let want = format!("$End{name}");
        let (tok, line) = self.token(&want)?;
        if tok == want {
            Ok(())
        } else {
            Err(MeshError::at_line(
                line,
                format!(
                    "in ${name}: expected {want}, found '{}' (more entries than the count in the section header?)",
                    shorten(tok)
                ),
            ))
        }
    }
}

/// At most 40 characters of `tok` for messages (binary junk can be long).
fn shorten(tok: &str) -> String {
    if tok.chars().count() <= 40 {
        tok.to_string()
    } else {
        let s: String = tok.chars().take(40).collect();
        format!("{s}...")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tokens_carry_their_line_numbers() {
        let mut c = Cursor::new("a b\n\n  c\r\nd");
        let toks: Vec<_> = std::iter::from_fn(|| c.next_token()).collect();
        assert_eq!(toks, vec![("a", 1), ("b", 1), ("c", 3), ("d", 4)]);
    }

    #[test]
    fn typed_reads_report_line_and_expectation() {
        let mut c = Cursor::new("1\n-2\nx\n");
        c.section = "$Nodes";
        assert_eq!(c.usize("count").unwrap(), 1);
        let e = c.usize("node tag").unwrap_err();
        assert_eq!(e.line, Some(2));
        assert!(e.message.contains("node tag"), "{}", e.message);
        let e = c.f64("x").unwrap_err();
        assert_eq!(e.line, Some(3));
        let e = c.f64("y").unwrap_err();
        assert!(e.message.contains("end of file"), "{}", e.message);
        assert_eq!(e.line, Some(3));
    }

    #[test]
    fn nan_and_infinite_coordinates_rejected() {
        let mut c = Cursor::new("nan inf 1e400");
        assert!(c.f64("x").is_err());
        assert!(c.f64("y").is_err());
        assert!(c.f64("z").is_err());
    }
}
