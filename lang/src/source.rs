//! A deck's text and where it came from.

use std::path::{Path, PathBuf};

/// The text of a `.ctc` deck and its path (used in diagnostics and to
/// resolve `mesh = file "..."` relative to the deck's directory).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Source {
    /// Path of the deck, as given by the user (shown in diagnostics).
    pub path: PathBuf,
    /// Full text of the deck.
    pub text: String,
}

impl Source {
    /// Reads a deck from disk.
    pub fn read(path: impl AsRef<Path>) -> std::io::Result<Source> {
        let path = path.as_ref();
        let text = std::fs::read_to_string(path)?;
        Ok(Source {
            path: path.to_path_buf(),
            text,
        })
    }

    /// A deck held in memory; `path` is only used for display and to resolve
    /// relative mesh file paths.
    pub fn new(path: impl Into<PathBuf>, text: impl Into<String>) -> Source {
        Source {
            path: path.into(),
            text: text.into(),
        }
    }

    /// The directory mesh files are resolved against (the deck's directory,
    /// or `.` for a bare file name).
    pub fn directory(&self) -> PathBuf {
        match self.path.parent() {
            Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
            _ => PathBuf::from("."),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn directory_of_bare_and_nested_paths() {
        assert_eq!(Source::new("deck.ctc", "").directory(), PathBuf::from("."));
        assert_eq!(
            Source::new("examples/hertz/deck.ctc", "").directory(),
            PathBuf::from("examples/hertz")
        );
    }

    #[test]
    fn read_missing_file_is_an_error() {
        assert!(Source::read("/definitely/not/here.ctc").is_err());
    }
}
