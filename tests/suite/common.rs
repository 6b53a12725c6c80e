//! Helpers shared by the integration tests.

use std::path::Path;
use std::process::Command;

/// `ctc run DECK -o OUT -q` with the binary under test; panics (naming the
/// deck) unless it exits with success.
pub fn run_quiet(deck: &Path, out: &Path) {
    let status = Command::new(env!("CARGO_BIN_EXE_ctc"))
        .arg("run")
        .arg(deck)
        .arg("-o")
        .arg(out)
        .arg("-q")
        .status()
        .expect("ctc starts");
    assert!(status.success(), "{}", deck.display());
}
