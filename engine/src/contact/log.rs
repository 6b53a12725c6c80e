//! Debug logging of the contact search on stderr, enabled by the
//! environment variable `CTC_LOG=debug` (stdout stays clean).

use std::sync::OnceLock;

/// Whether `CTC_LOG=debug` is set (read once per process).
pub fn debug_enabled() -> bool {
    static ENABLED: OnceLock<bool> = OnceLock::new();
    *ENABLED.get_or_init(|| {
        std::env::var("CTC_LOG")
            .map(|v| v.eq_ignore_ascii_case("debug"))
            .unwrap_or(false)
    })
}
