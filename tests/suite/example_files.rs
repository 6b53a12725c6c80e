//! Repository files the example tests share: files written by a generator
//! in the tests (the IGES dies and punch of `examples/`), whose committed
//! copy must be what the generator writes, byte for byte, so a change of the
//! generator or of the IGES writer cannot leave a stale file behind; and the
//! 3D example decks compiled with some of their `let` lines replaced (the
//! coarse deck a test runs made into its full run).

use ctc_engine::model::{AnyModel, Model};
use std::path::Path;

/// Asserts that the repository file `relative` (e.g. `examples/x.igs`)
/// holds exactly `text`; with `CTC_REGENERATE` set it first writes `text`
/// there. `module` is the suite module whose tests regenerate it (named in
/// the failure message).
pub fn assert_committed(relative: &str, text: &str, module: &str) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(relative);
    if std::env::var_os("CTC_REGENERATE").is_some() {
        std::fs::write(&path, text).unwrap_or_else(|e| panic!("{relative}: {e}"));
    }
    let file = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{relative}: {e}"));
    assert!(
        file == text,
        "{relative} differs from the generator: CTC_REGENERATE=1 cargo test --test suite {module}::"
    );
}

/// The 3D example deck `relative` compiled with each `(from, to)` of
/// `replace` substituted in its text (each `from` must occur: a renamed
/// `let` line fails here, not silently).
pub fn compile_3d(relative: &str, replace: &[(&str, &str)]) -> Model<3> {
    let deck = Path::new(env!("CARGO_MANIFEST_DIR")).join(relative);
    let mut text = std::fs::read_to_string(&deck).expect("readable deck");
    for (from, to) in replace {
        assert!(text.contains(from), "the deck has no `{from}`");
        text = text.replace(from, to);
    }
    let src = ctc_lang::Source::new(deck, text);
    let AnyModel::D3(model) = ctc_lang::compile_any(&src)
        .map_err(|d| d.render(&src))
        .unwrap()
    else {
        panic!("{relative} is not a 3D deck");
    };
    model
}
