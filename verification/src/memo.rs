//! Runs shared within one process. A program's run asked for twice — by its
//! catalogue case and by a test that prints the run's table or history, as
//! `cargo test` does in one process — is made once: the key is the generated
//! deck's text (with whatever else decides the result), the value the run's
//! outcome. [`crate::registry::run_default`] does the same for whole cases.
//!
//! Only deterministic functions of their key go through here (a run is bit
//! for bit the same whatever the thread count), so sharing changes no figure:
//! it only saves the second run's time (the CI time budget of
//! `docs/ARCHITECTURE.md`).

use std::any::Any;
use std::collections::BTreeMap;
use std::sync::{Arc, Mutex, OnceLock};

/// One shared value of any type.
type Shared = Arc<OnceLock<Box<dyn Any + Send + Sync>>>;

/// The values made so far, by key.
static VALUES: Mutex<BTreeMap<String, Shared>> = Mutex::new(BTreeMap::new());

/// The value of `key`: made by `make` the first time it is asked for in this
/// process, a clone of that value afterwards. Two threads asking at once
/// make it once (the second waits). A key names one type: asking for it as
/// another type is a programming error and panics.
pub fn once<T: Clone + Send + Sync + 'static>(key: String, make: impl FnOnce() -> T) -> T {
    let cell = VALUES
        .lock()
        .unwrap_or_else(|e| e.into_inner())
        .entry(key)
        .or_default()
        .clone();
    cell.get_or_init(|| Box::new(make()))
        .downcast_ref::<T>()
        .expect("one key, one type")
        .clone()
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::atomic::{AtomicUsize, Ordering};

    #[test]
    fn a_value_is_made_once_per_key_even_when_two_threads_ask_at_once() {
        static MADE: AtomicUsize = AtomicUsize::new(0);
        let make = || {
            MADE.fetch_add(1, Ordering::SeqCst);
            std::thread::sleep(std::time::Duration::from_millis(20));
            vec![1.5, 2.5]
        };
        let (a, b) = std::thread::scope(|s| {
            let a = s.spawn(|| once("memo test a".into(), make));
            let b = s.spawn(|| once("memo test a".into(), make));
            (a.join().unwrap(), b.join().unwrap())
        });
        assert_eq!(a, vec![1.5, 2.5]);
        assert_eq!(a, b);
        assert_eq!(MADE.load(Ordering::SeqCst), 1);
        let c = once("memo test b".to_string(), || vec![0.5]);
        assert_eq!(c, vec![0.5]);
        assert_eq!(MADE.load(Ordering::SeqCst), 1);
    }
}
