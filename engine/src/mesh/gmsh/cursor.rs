//! Whitespace-separated tokens of a `.msh` text with their 1-based line
//! numbers, and typed reads that turn every surprise into a
//! [`MeshError::at_line`].

use crate::mesh::MeshError;

/// A forward-only reader of tokens.
///
/// Tokens are separated by `char::is_whitespace` and lines end at `\n`:
/// the tokens and line numbers of `str::lines` then `split_whitespace`,
/// read byte by byte (ASCII bytes classified directly, other characters
/// decoded; issue 20: the `.msh` of the 80,000-dof tutorial mesh is 4.4 MB
/// of text, and the reader was a third of the mesh reading).
#[derive(Clone)]
pub struct Cursor<'a> {
    text: &'a str,
    /// Byte offset of the next unread byte.
    at: usize,
    /// Line of the last token read (0 before the first).
    line: usize,
    /// Line of the byte at `at` (1-based; a `\n` ending the text starts
    /// no line).
    at_line: usize,
    /// Section being read, for error messages (e.g. `$Nodes`).
    pub section: &'static str,
}

/// Whether the character starting at byte `i` of `text` is whitespace,
/// and its length in bytes.
#[inline]
fn space_at(text: &str, i: usize) -> (bool, usize) {
    let b = text.as_bytes()[i];
    if b.is_ascii() {
        // `char::is_whitespace` of the ASCII characters
        (matches!(b, b'\t' | b'\n' | 0x0b | 0x0c | b'\r' | b' '), 1)
    } else {
        let c = text[i..].chars().next().unwrap_or(' ');
        (c.is_whitespace(), c.len_utf8().max(1))
    }
}

impl<'a> Cursor<'a> {
    /// A cursor at the start of `text`.
    pub fn new(text: &'a str) -> Self {
        Cursor {
            text,
            at: 0,
            line: 0,
            at_line: 1,
            section: "the file header",
        }
    }

    /// Line of the last token read (0 before the first).
    pub fn line(&self) -> usize {
        self.line.max(1)
    }

    /// The next token and its line, `None` at the end of the text (the
    /// line is then the text's last).
    pub fn next_token(&mut self) -> Option<(&'a str, usize)> {
        let bytes = self.text.as_bytes();
        let len = bytes.len();
        let mut i = self.at;
        loop {
            if i >= len {
                self.at = len;
                if len > 0 {
                    self.line = self.at_line;
                }
                return None;
            }
            let (space, n) = space_at(self.text, i);
            if !space {
                break;
            }
            if bytes[i] == b'\n' && i + 1 < len {
                self.at_line += 1;
            }
            i += n;
        }
        let start = i;
        while i < len {
            let (space, n) = space_at(self.text, i);
            if space {
                break;
            }
            i += n;
        }
        self.at = i;
        self.line = self.at_line;
        Some((&self.text[start..i], self.line))
    }

    /// Bytes of the text not read yet (a bound on what is left to read:
    /// every token takes at least two bytes with its separator).
    pub fn remaining_bytes(&self) -> usize {
        self.text.len() - self.at
    }

    /// The unread rest of the current line (consumed), trimmed.
    pub fn rest_of_line(&mut self) -> &'a str {
        if self.line == 0 {
            // no line taken yet
            return "";
        }
        let rest = &self.text[self.at..];
        let end = rest.find('\n').unwrap_or(rest.len());
        self.at += end;
        rest[..end].trim()
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

    /// The reader this one replaced: `str::lines`, then the tokens of
    /// each line split at `char::is_whitespace` (the reference of the
    /// tokens, their lines, the line at the end and `rest_of_line`).
    struct LinesReader<'a> {
        lines: std::iter::Enumerate<std::str::Lines<'a>>,
        rest: &'a str,
        line: usize,
    }

    impl<'a> LinesReader<'a> {
        fn new(text: &'a str) -> Self {
            LinesReader {
                lines: text.lines().enumerate(),
                rest: "",
                line: 0,
            }
        }

        fn next_token(&mut self) -> Option<(&'a str, usize)> {
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

        fn rest_of_line(&mut self) -> &'a str {
            let r = self.rest.trim();
            self.rest = "";
            r
        }
    }

    proptest::proptest! {
        /// Texts of ASCII and Unicode whitespace (NBSP, NEL, line and
        /// paragraph separators, vertical tab, form feed, CR LF), letters
        /// and a multi-byte letter: the same tokens with the same lines,
        /// the same line at the end of the text, the same rest of a line.
        #[test]
        fn tokens_and_lines_are_those_of_lines_then_whitespace(
            pieces in proptest::collection::vec(0usize..14, 0..60),
            rest_at in proptest::collection::vec(proptest::bool::ANY, 60),
        ) {
            const ALPHABET: [&str; 14] = [
                "a", "12", "-3.5e2", " ", "\t", "\n", "\r\n", "\r", "\u{a0}", "\u{85}",
                "\u{2028}", "\u{b}\u{c}", "\u{e9}", "\u{3000}",
            ];
            let text: String = pieces.iter().map(|&i| ALPHABET[i]).collect();
            let (mut new, mut old) = (Cursor::new(&text), LinesReader::new(&text));
            for &rest in &rest_at {
                if rest {
                    proptest::prop_assert_eq!(new.rest_of_line(), old.rest_of_line());
                }
                let (a, b) = (new.next_token(), old.next_token());
                proptest::prop_assert_eq!(a, b, "text {:?}", text);
                proptest::prop_assert_eq!(new.line(), old.line.max(1), "text {:?}", text);
                if a.is_none() {
                    break;
                }
            }
        }
    }

    #[test]
    fn nan_and_infinite_coordinates_rejected() {
        let mut c = Cursor::new("nan inf 1e400");
        assert!(c.f64("x").is_err());
        assert!(c.f64("y").is_err());
        assert!(c.f64("z").is_err());
    }
}
