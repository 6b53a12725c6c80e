//! Typed errors of the IGES reader: every one names the file line.

/// What went wrong.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum IgesErrorKind {
    /// A record is not an 80-column line with a section letter and a
    /// sequence number, or the sections are out of order.
    Record,
    /// The Global section (delimiters, fields) is malformed.
    Global,
    /// A Directory entry is malformed.
    Directory,
    /// A parameter is missing or of the wrong type.
    Parameter,
    /// A pointer does not point at a directory entry of the right kind.
    Pointer,
    /// A supported entity needs an entity the reader does not support.
    Unsupported,
    /// The geometry is invalid (knots, weights, an open trimming loop).
    Geometry,
}

/// An error reading an IGES file.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct IgesError {
    /// 1-based line of the file.
    pub line: usize,
    /// The kind of error.
    pub kind: IgesErrorKind,
    /// What is wrong, in words.
    pub message: String,
}

impl IgesError {
    /// An error at `line`.
    pub fn new(line: usize, kind: IgesErrorKind, message: impl Into<String>) -> Self {
        IgesError {
            line,
            kind,
            message: message.into(),
        }
    }
}

impl std::fmt::Display for IgesError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "IGES line {}: {}", self.line, self.message)
    }
}

impl std::error::Error for IgesError {}
