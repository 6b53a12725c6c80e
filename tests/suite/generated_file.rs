//! Repository files written by a generator in the tests (the IGES dies and
//! punch of `examples/`): the committed copy must be what the generator
//! writes, byte for byte, so a change of the generator or of the IGES
//! writer cannot leave a stale file behind.

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
