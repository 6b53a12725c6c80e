//! The fixed 80-column record structure: sections S (Start), G (Global),
//! D (Directory), P (Parameter), T (Terminate), in that order; columns 1-72
//! hold data, column 73 the section letter, columns 74-80 the sequence
//! number within the section.

use super::error::{IgesError, IgesErrorKind};

/// One record (line) of a section.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Record<'a> {
    /// 1-based line of the file.
    pub line: usize,
    /// Columns 1-72 (padded with blanks).
    pub data: String,
    /// Sequence number (columns 74-80).
    pub seq: usize,
    /// The raw line (for the Parameter section's columns 65-72).
    pub raw: &'a str,
}

/// The records of each section.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct Sections<'a> {
    /// Start section.
    pub start: Vec<Record<'a>>,
    /// Global section.
    pub global: Vec<Record<'a>>,
    /// Directory entry section.
    pub directory: Vec<Record<'a>>,
    /// Parameter data section.
    pub parameter: Vec<Record<'a>>,
    /// Terminate section.
    pub terminate: Vec<Record<'a>>,
}

/// Splits a file into its sections, checking the record layout.
pub fn split(text: &str) -> Result<Sections<'_>, IgesError> {
    let mut s = Sections::default();
    let order = ['S', 'G', 'D', 'P', 'T'];
    let mut current = 0usize;
    for (i, raw) in text.split('\n').enumerate() {
        let line = i + 1;
        let raw = raw.strip_suffix('\r').unwrap_or(raw);
        if raw.trim().is_empty() {
            continue;
        }
        if !raw.is_ascii() {
            return Err(IgesError::new(
                line,
                IgesErrorKind::Record,
                "the line holds non-ASCII characters",
            ));
        }
        if raw.len() < 73 || raw.len() > 80 {
            return Err(IgesError::new(
                line,
                IgesErrorKind::Record,
                format!("a record has 80 columns with the section letter in column 73; this line has {}", raw.len()),
            ));
        }
        let letter = raw.as_bytes()[72] as char;
        let Some(sec) = order.iter().position(|&c| c == letter) else {
            let msg = if letter == 'C' || letter == 'B' {
                format!("the compressed or binary IGES form (section letter `{letter}`) is not supported")
            } else {
                format!("unknown section letter `{letter}` in column 73 (expected S, G, D, P or T)")
            };
            return Err(IgesError::new(line, IgesErrorKind::Record, msg));
        };
        if sec < current {
            return Err(IgesError::new(
                line,
                IgesErrorKind::Record,
                format!("section {letter} after section {}: sections must come in the order S, G, D, P, T", order[current]),
            ));
        }
        current = sec;
        let seq_txt = raw[73..].trim();
        let seq: usize = seq_txt.parse().map_err(|_| {
            IgesError::new(
                line,
                IgesErrorKind::Record,
                format!("bad sequence number `{seq_txt}` in columns 74-80"),
            )
        })?;
        let list = match sec {
            0 => &mut s.start,
            1 => &mut s.global,
            2 => &mut s.directory,
            3 => &mut s.parameter,
            _ => &mut s.terminate,
        };
        if seq != list.len() + 1 {
            return Err(IgesError::new(
                line,
                IgesErrorKind::Record,
                format!(
                    "sequence number {seq} in section {letter}, expected {}",
                    list.len() + 1
                ),
            ));
        }
        let mut data = raw[..72].to_string();
        while data.len() < 72 {
            data.push(' ');
        }
        list.push(Record {
            line,
            data,
            seq,
            raw,
        });
    }
    if s.terminate.is_empty() {
        let last = text.lines().count().max(1);
        return Err(IgesError::new(
            last,
            IgesErrorKind::Record,
            "the file has no Terminate (T) section",
        ));
    }
    if s.global.is_empty() {
        return Err(IgesError::new(
            1,
            IgesErrorKind::Record,
            "the file has no Global (G) section",
        ));
    }
    if s.directory.len() % 2 != 0 {
        let l = s.directory.last().map_or(1, |r| r.line);
        return Err(IgesError::new(
            l,
            IgesErrorKind::Directory,
            "the Directory section has an odd number of lines (two per entity)",
        ));
    }
    Ok(s)
}
