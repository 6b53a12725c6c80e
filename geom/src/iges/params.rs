//! Free-format parameters (Global and Parameter sections): fields separated
//! by the parameter delimiter, ended by the record delimiter; integers,
//! reals (`E` or `D` exponents), Hollerith strings `nH...` (which may hold
//! delimiters), and empty fields (defaults).

use super::error::{IgesError, IgesErrorKind};

/// One parameter and the file line where it starts.
#[derive(Debug, Clone, PartialEq)]
pub struct Param {
    /// The field's text (trimmed); a Hollerith string's content.
    pub text: String,
    /// Whether the field was a Hollerith string.
    pub string: bool,
    /// 1-based file line.
    pub line: usize,
}

/// Text with the file line of each character.
pub struct Located {
    /// The characters.
    pub chars: Vec<u8>,
    /// Line of each character.
    pub lines: Vec<usize>,
}

impl Located {
    /// Concatenates `(text, line)` pieces.
    pub fn new<'a>(pieces: impl Iterator<Item = (&'a str, usize)>) -> Self {
        let mut chars = Vec::new();
        let mut lines = Vec::new();
        for (t, l) in pieces {
            chars.extend_from_slice(t.as_bytes());
            lines.extend(std::iter::repeat_n(l, t.len()));
        }
        Located { chars, lines }
    }

    fn line(&self, i: usize) -> usize {
        self.lines
            .get(i)
            .or(self.lines.last())
            .copied()
            .unwrap_or(1)
    }
}

/// Splits into parameters up to the record delimiter, starting at byte
/// `from`; returns the parameters and the index after the record delimiter
/// (or the end).
pub fn split(
    text: &Located,
    from: usize,
    pd: u8,
    rd: u8,
) -> Result<(Vec<Param>, usize), IgesError> {
    let c = &text.chars;
    let mut out = Vec::new();
    let mut i = from;
    loop {
        // Skip leading blanks of the field.
        let start = i;
        while i < c.len() && c[i] == b' ' {
            i += 1;
        }
        // Hollerith: digits then H.
        let mut j = i;
        while j < c.len() && c[j].is_ascii_digit() {
            j += 1;
        }
        if j > i && j < c.len() && (c[j] == b'H' || c[j] == b'h') {
            let n: usize = std::str::from_utf8(&c[i..j])
                .ok()
                .and_then(|s| s.parse().ok())
                .ok_or_else(|| {
                    IgesError::new(
                        text.line(i),
                        IgesErrorKind::Parameter,
                        "bad Hollerith string length",
                    )
                })?;
            let s0 = j + 1;
            let s1 = s0.checked_add(n).filter(|&e| e <= c.len()).ok_or_else(|| {
                IgesError::new(
                    text.line(i),
                    IgesErrorKind::Parameter,
                    format!("the Hollerith string {n}H... runs past the end of its section"),
                )
            })?;
            out.push(Param {
                text: String::from_utf8_lossy(&c[s0..s1]).into_owned(),
                string: true,
                line: text.line(i),
            });
            i = s1;
            while i < c.len() && c[i] == b' ' {
                i += 1;
            }
            if i >= c.len() {
                return Ok((out, i));
            }
            if c[i] == rd {
                return Ok((out, i + 1));
            }
            if c[i] != pd {
                return Err(IgesError::new(
                    text.line(i),
                    IgesErrorKind::Parameter,
                    format!(
                        "expected a delimiter after a Hollerith string, found `{}`",
                        c[i] as char
                    ),
                ));
            }
            i += 1;
            continue;
        }
        let mut k = i;
        while k < c.len() && c[k] != pd && c[k] != rd {
            k += 1;
        }
        let field = String::from_utf8_lossy(&c[i..k]).trim().to_string();
        out.push(Param {
            text: field,
            string: false,
            line: text.line(start.min(c.len().saturating_sub(1))),
        });
        if k >= c.len() {
            return Ok((out, k));
        }
        if c[k] == rd {
            return Ok((out, k + 1));
        }
        i = k + 1;
    }
}

/// A cursor over one entity's parameters with typed accessors.
pub struct Cursor<'a> {
    /// The parameters.
    pub params: &'a [Param],
    /// Next index.
    pub at: usize,
    /// Line of the entity's first parameter (for missing parameters).
    pub line: usize,
    /// Entity description for messages, e.g. "entity 128 (DE 7)".
    pub what: String,
}

impl<'a> Cursor<'a> {
    fn next(&mut self, kind: &str) -> Result<&'a Param, IgesError> {
        let p = self.params.get(self.at).ok_or_else(|| {
            IgesError::new(
                self.params.last().map_or(self.line, |p| p.line),
                IgesErrorKind::Parameter,
                format!(
                    "{}: parameter {} ({kind}) is missing",
                    self.what,
                    self.at + 1
                ),
            )
        })?;
        self.at += 1;
        Ok(p)
    }

    /// Parameters left.
    pub fn remaining(&self) -> usize {
        self.params.len().saturating_sub(self.at)
    }

    /// An integer (blank: `default`).
    pub fn int_or(&mut self, kind: &str, default: i64) -> Result<i64, IgesError> {
        let at = self.at + 1;
        let p = self.next(kind)?;
        if p.text.is_empty() && !p.string {
            return Ok(default);
        }
        p.text.parse::<i64>().map_err(|_| {
            IgesError::new(
                p.line,
                IgesErrorKind::Parameter,
                format!(
                    "{}: parameter {at} ({kind}) must be an integer, found `{}`",
                    self.what, p.text
                ),
            )
        })
    }

    /// An integer.
    pub fn int(&mut self, kind: &str) -> Result<i64, IgesError> {
        self.int_or(kind, 0)
    }

    /// A count in `[0, max]`.
    pub fn count(&mut self, kind: &str, max: usize) -> Result<usize, IgesError> {
        let line = self.params.get(self.at).map_or(self.line, |p| p.line);
        let v = self.int(kind)?;
        if v < 0 || v as u64 > max as u64 {
            return Err(IgesError::new(
                line,
                IgesErrorKind::Parameter,
                format!("{}: {kind} = {v} is out of range (0..{max})", self.what),
            ));
        }
        Ok(v as usize)
    }

    /// A real (blank: `default`).
    pub fn real_or(&mut self, kind: &str, default: f64) -> Result<f64, IgesError> {
        let at = self.at + 1;
        let p = self.next(kind)?;
        if p.text.is_empty() && !p.string {
            return Ok(default);
        }
        parse_real(&p.text).ok_or_else(|| {
            IgesError::new(
                p.line,
                IgesErrorKind::Parameter,
                format!(
                    "{}: parameter {at} ({kind}) must be a real number, found `{}`",
                    self.what, p.text
                ),
            )
        })
    }

    /// A real.
    pub fn real(&mut self, kind: &str) -> Result<f64, IgesError> {
        self.real_or(kind, 0.0)
    }

    /// A directory-entry pointer (0: none).
    pub fn pointer(&mut self, kind: &str) -> Result<usize, IgesError> {
        let line = self.params.get(self.at).map_or(self.line, |p| p.line);
        let v = self.int(kind)?;
        if v < 0 {
            return Err(IgesError::new(
                line,
                IgesErrorKind::Pointer,
                format!("{}: {kind} pointer {v} is negative", self.what),
            ));
        }
        Ok(v as usize)
    }

    /// Line of the next parameter.
    pub fn line_here(&self) -> usize {
        self.params.get(self.at).map_or(self.line, |p| p.line)
    }
}

/// Parses an IGES real: `1.5`, `-2.`, `.5E3`, `1.0D-3`, `7`.
pub fn parse_real(s: &str) -> Option<f64> {
    let t: String = s
        .chars()
        .map(|c| if c == 'D' || c == 'd' { 'E' } else { c })
        .collect();
    let v: f64 = t.parse().ok()?;
    v.is_finite().then_some(v)
}
