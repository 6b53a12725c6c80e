//! A deck's text and where it came from, with its `include`d files.
//!
//! `include "part.ctc"` (a line of its own, outside any block) inserts the
//! text of `part.ctc` (relative to the including file) right after the
//! statement. The parser reads the combined [`Source::text`]; spans are
//! offsets into it, and [`Source::locate`] maps an offset back to the file
//! and offset it came from, so diagnostics name the included file, its
//! line and column, and the chain of includes. Missing files and include
//! cycles are diagnosed at the statement, with the chain.

use crate::diagnostics::Diagnostic;
use crate::span::Span;
use std::path::{Path, PathBuf};

/// Deepest include nesting accepted.
pub const MAX_INCLUDE_DEPTH: usize = 16;

/// One file of a deck: the deck itself or an included file.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SourceFile {
    /// Path as shown in diagnostics (the deck's, or the including file's
    /// directory joined with the include path).
    pub path: PathBuf,
    /// Its text.
    pub text: String,
    /// The file and byte offset (in that file) of the `include` statement
    /// that brought it in; `None` for the deck itself.
    pub included_from: Option<(usize, usize)>,
}

/// A run of [`Source::text`] copied from one file.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Piece {
    /// Start in the combined text.
    pub start: usize,
    /// End in the combined text.
    pub end: usize,
    /// Index in [`Source::files`].
    pub file: usize,
    /// Offset of `start` in that file.
    pub offset: usize,
}

/// The text of a `.ctc` deck and its path (used in diagnostics and to
/// resolve `mesh = file "..."` relative to the deck's directory).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Source {
    /// Path of the deck, as given by the user (shown in diagnostics).
    pub path: PathBuf,
    /// Full text of the deck, included files inserted.
    pub text: String,
    /// The deck (first) and every included file.
    pub files: Vec<SourceFile>,
    /// Where each part of `text` comes from, in order.
    pub pieces: Vec<Piece>,
    /// Problems with `include` statements (missing files, cycles).
    pub include_errors: Vec<Diagnostic>,
}

impl Source {
    /// Reads a deck from disk (and the files it includes).
    pub fn read(path: impl AsRef<Path>) -> std::io::Result<Source> {
        let path = path.as_ref();
        let text = std::fs::read_to_string(path)?;
        Ok(Source::new(path, text))
    }

    /// A deck held in memory; `path` is used for display, to resolve
    /// relative mesh file paths and the files it includes.
    pub fn new(path: impl Into<PathBuf>, text: impl Into<String>) -> Source {
        let path = path.into();
        let mut src = Source {
            path: path.clone(),
            text: String::new(),
            files: vec![SourceFile {
                path,
                text: text.into(),
                included_from: None,
            }],
            pieces: Vec::new(),
            include_errors: Vec::new(),
        };
        let mut chain = vec![canonical(&src.files[0].path)];
        src.expand(0, &mut chain);
        src
    }

    /// The directory mesh files are resolved against (the deck's directory,
    /// or `.` for a bare file name).
    pub fn directory(&self) -> PathBuf {
        directory_of(&self.path)
    }

    /// The directory of the file the text at `offset` comes from (mesh
    /// files of an included file are relative to it).
    pub fn directory_at(&self, offset: usize) -> PathBuf {
        let (file, _) = self.locate(offset);
        directory_of(&self.files[file].path)
    }

    /// The file and offset in it of byte `offset` of [`Source::text`].
    pub fn locate(&self, offset: usize) -> (usize, usize) {
        let i = self
            .pieces
            .partition_point(|p| p.end <= offset)
            .min(self.pieces.len().saturating_sub(1));
        match self.pieces.get(i) {
            Some(p) if offset >= p.start => (p.file, p.offset + (offset - p.start)),
            Some(p) => (p.file, p.offset),
            None => (0, offset),
        }
    }

    /// The chain of includes of `file`, innermost first: (including file,
    /// offset of the statement in it).
    pub fn include_chain(&self, file: usize) -> Vec<(usize, usize)> {
        let mut out = Vec::new();
        let mut f = file;
        while let Some((parent, at)) = self.files[f].included_from {
            out.push((parent, at));
            f = parent;
        }
        out
    }

    fn copy(&mut self, file: usize, from: usize, to: usize) {
        if to <= from {
            return;
        }
        let start = self.text.len();
        let piece_text = &self.files[file].text[from..to];
        self.text.push_str(piece_text);
        self.pieces.push(Piece {
            start,
            end: self.text.len(),
            file,
            offset: from,
        });
    }

    /// Copies file `file` into the text, inserting its includes.
    fn expand(&mut self, file: usize, chain: &mut Vec<PathBuf>) {
        let statements = includes(&self.files[file].text);
        let mut pos = 0;
        for st in statements {
            self.copy(file, pos, st.end);
            pos = st.end;
            // span of the quoted path in the combined text
            let base = self.text.len() - (st.end - st.path_start);
            let at = Span::new(base, base + (st.path_end - st.path_start));
            let dir = directory_of(&self.files[file].path);
            let path = dir.join(&st.path);
            let canon = canonical(&path);
            let names: Vec<String> = chain.iter().map(|p| short(p)).collect();
            if chain.contains(&canon) {
                self.include_errors.push(
                    Diagnostic::error(
                        format!("include cycle: {} -> {}", names.join(" -> "), short(&canon)),
                        at,
                        "includes a file that is already being read",
                    )
                    .with_help("remove this include (a file can be included once per chain)"),
                );
                continue;
            }
            if chain.len() >= MAX_INCLUDE_DEPTH {
                self.include_errors.push(Diagnostic::error(
                    format!("includes nested more than {MAX_INCLUDE_DEPTH} deep"),
                    at,
                    "too deep",
                ));
                continue;
            }
            let text = match std::fs::read_to_string(&path) {
                Ok(t) => t,
                Err(e) => {
                    let label = match e.kind() {
                        std::io::ErrorKind::NotFound => "file not found",
                        _ => "cannot read this file",
                    };
                    let mut d = Diagnostic::error(
                        format!("cannot read included file `{}`: {e}", st.path),
                        at,
                        label,
                    )
                    .with_help(format!(
                        "looked for `{}`; include paths are relative to the including file",
                        path.display()
                    ));
                    if chain.len() > 1 {
                        d = d.with_note(format!("include chain: {}", names.join(" -> ")));
                    }
                    self.include_errors.push(d);
                    continue;
                }
            };
            self.files.push(SourceFile {
                path,
                text,
                included_from: Some((file, st.start)),
            });
            let child = self.files.len() - 1;
            if !self.text.ends_with('\n') {
                self.text.push('\n');
            }
            chain.push(canon);
            self.expand(child, chain);
            chain.pop();
            if !self.text.ends_with('\n') {
                self.text.push('\n');
            }
        }
        let len = self.files[file].text.len();
        self.copy(file, pos, len);
    }
}

/// `include "path"` statements of a text: at the start of a line, outside
/// any bracket, strings and comments.
struct Statement {
    start: usize,
    end: usize,
    path: String,
    path_start: usize,
    path_end: usize,
}

fn includes(text: &str) -> Vec<Statement> {
    let mut out = Vec::new();
    let mut depth: i64 = 0;
    let mut offset = 0;
    for line in text.split_inclusive('\n') {
        let trimmed = line.trim_start();
        let indent = line.len() - trimmed.len();
        if depth == 0 {
            if let Some(rest) = trimmed.strip_prefix("include") {
                let after = rest.trim_start();
                if rest.len() > after.len() && after.starts_with('"') {
                    if let Some(close) = after[1..].find('"') {
                        let q = offset + indent + "include".len() + (rest.len() - after.len());
                        out.push(Statement {
                            start: offset + indent,
                            end: q + close + 2,
                            path: after[1..1 + close].to_string(),
                            path_start: q,
                            path_end: q + close + 2,
                        });
                    }
                }
            }
        }
        // bracket depth at the end of the line (comments and strings skipped)
        let mut in_string = false;
        for c in line.chars() {
            match c {
                '"' => in_string = !in_string,
                '#' if !in_string => break,
                '{' | '(' | '[' if !in_string => depth += 1,
                '}' | ')' | ']' if !in_string => depth -= 1,
                _ => {}
            }
        }
        offset += line.len();
    }
    out
}

fn directory_of(path: &Path) -> PathBuf {
    match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    }
}

/// The canonical path when the file exists (cycles through `..` or links
/// are caught), else the path as joined.
fn canonical(path: &Path) -> PathBuf {
    std::fs::canonicalize(path).unwrap_or_else(|_| path.to_path_buf())
}

/// The file name, for include chains.
fn short(path: &Path) -> String {
    path.file_name().map_or_else(
        || path.display().to_string(),
        |n| n.to_string_lossy().into_owned(),
    )
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

    #[test]
    fn includes_are_inserted_and_located() {
        let dir = std::env::temp_dir().join(format!("ctc-include-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        std::fs::write(dir.join("part.ctc"), "let b = 2\n").unwrap();
        let main = "let a = 1\ninclude \"part.ctc\"\nlet c = 3\n";
        let src = Source::new(dir.join("main.ctc"), main);
        assert!(src.include_errors.is_empty(), "{:?}", src.include_errors);
        assert_eq!(
            src.text,
            "let a = 1\ninclude \"part.ctc\"\nlet b = 2\n\nlet c = 3\n"
        );
        let b = src.text.find('b').unwrap();
        assert_eq!(src.locate(b), (1, 4));
        let c = src.text.find('c').unwrap();
        assert_eq!(src.locate(c), (0, main.find('c').unwrap()));
        assert_eq!(src.include_chain(1), vec![(0, 10)]);
        // a cycle and a missing file are reported at the path
        std::fs::write(dir.join("loop.ctc"), "include \"loop.ctc\"\n").unwrap();
        let src = Source::new(
            dir.join("main.ctc"),
            "include \"loop.ctc\"\ninclude \"nope.ctc\"\n",
        );
        let msgs: Vec<&str> = src
            .include_errors
            .iter()
            .map(|d| d.message.as_str())
            .collect();
        assert_eq!(msgs.len(), 2, "{msgs:?}");
        assert!(msgs[0].starts_with("include cycle: main.ctc -> loop.ctc -> loop.ctc"));
        assert!(msgs[1].starts_with("cannot read included file `nope.ctc`"));
        // inside a block, `include` is not a statement
        assert!(includes("material m {\n  include \"x\"\n}\n").is_empty());
        std::fs::remove_dir_all(&dir).ok();
    }
}
