//! Reading a verification deck, rendering a refinement level and compiling
//! it into an engine [`Model`] with `ctc-lang`.

use crate::refine::RefinableDeck;
use ctc_engine::model::Model;
use ctc_lang::{compile, Source};
use std::path::{Path, PathBuf};

/// A deck file with its refinement markers.
#[derive(Debug, Clone)]
pub struct DeckFile {
    /// Path of the deck (diagnostics, relative mesh files).
    pub path: PathBuf,
    /// Parsed markers and text.
    pub deck: RefinableDeck,
}

impl DeckFile {
    /// Reads and parses the refinement markers of the deck at `path`.
    pub fn read(path: &Path) -> Result<Self, String> {
        let text = std::fs::read_to_string(path)
            .map_err(|e| format!("cannot read deck {}: {e}", path.display()))?;
        let deck = RefinableDeck::parse(&text).map_err(|e| format!("{}: {e}", path.display()))?;
        Ok(DeckFile {
            path: path.to_path_buf(),
            deck,
        })
    }

    /// Number of refinement levels the deck defines.
    pub fn levels(&self) -> usize {
        self.deck.levels()
    }

    /// The deck text at level `level` (errors name the deck).
    pub fn render(&self, level: usize) -> Result<String, String> {
        self.deck
            .render(level)
            .map_err(|e| format!("{}: {e}", self.path.display()))
    }

    /// Renders and compiles level `level`. Errors carry the rendered
    /// diagnostics (file, line, caret) of `ctc-lang`.
    pub fn compile(&self, level: usize) -> Result<Model, String> {
        let text = self
            .deck
            .render(level)
            .map_err(|e| format!("{}: {e}", self.path.display()))?;
        compile_text(&self.path, &text)
    }
}

/// Compiles deck text; `path` is shown in diagnostics and resolves relative
/// mesh files.
pub fn compile_text(path: &Path, text: &str) -> Result<Model, String> {
    let src = Source::new(path, text);
    compile(&src).map_err(|d| d.render(&src))
}
