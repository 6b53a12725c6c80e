//! Threads of the deterministic parallel kernels (issue 20): the element
//! assembly ([`super::assembly`]) and the low-rank solves
//! ([`super::linalg::low_rank`]).
//!
//! Every parallel kernel gives the same bits whatever the thread count:
//! work is split so that each output value is computed by one thread with
//! the same operations in the same order as the serial code (the assembly
//! adds each value slot's element contributions in cell order, the
//! low-rank update's `Z y` updates each row in column order, the columns of
//! `K0^{-1}` are solved in batches fixed by their number, not by the
//! threads). The thread count is only a speed setting: `ctc run --threads
//! N`, `ctc bench --threads N`, else the environment variable
//! `CTC_THREADS`, else the cores.

use std::sync::atomic::{AtomicUsize, Ordering};

/// The thread count set by [`set_threads`] (0: not set).
static THREADS: AtomicUsize = AtomicUsize::new(0);

/// Sets the thread count of the parallel kernels (at least 1).
pub fn set_threads(n: usize) {
    THREADS.store(n.max(1), Ordering::Relaxed);
}

/// `CTC_THREADS` as a thread count: `None` when unset, an error when it is
/// not a positive integer.
pub fn threads_from_env() -> Result<Option<usize>, String> {
    match std::env::var("CTC_THREADS") {
        Err(_) => Ok(None),
        Ok(v) => match v.trim().parse::<usize>() {
            Ok(n) if n >= 1 => Ok(Some(n)),
            _ => Err(format!(
                "CTC_THREADS = `{v}`: expected a positive number of threads"
            )),
        },
    }
}

/// The thread count of the parallel kernels: [`set_threads`], else
/// `CTC_THREADS` (ignored when invalid: the program reports it), else the
/// cores.
pub fn threads() -> usize {
    match THREADS.load(Ordering::Relaxed) {
        0 => threads_from_env().ok().flatten().unwrap_or_else(|| {
            std::thread::available_parallelism().map_or(1, std::num::NonZeroUsize::get)
        }),
        n => n,
    }
}

/// `0..n` cut into `parts` contiguous ranges of nearly equal length (the
/// first ones one longer), empty ranges dropped.
pub fn split(n: usize, parts: usize) -> Vec<std::ops::Range<usize>> {
    let parts = parts.clamp(1, n.max(1));
    let (q, r) = (n / parts, n % parts);
    let mut out = Vec::with_capacity(parts);
    let mut start = 0;
    for p in 0..parts {
        let len = q + usize::from(p < r);
        if len > 0 {
            out.push(start..start + len);
        }
        start += len;
    }
    out
}

/// A raw view of a mutable slice shared by threads that write disjoint
/// entries (each index by at most one thread, by construction of the
/// caller's partition).
#[derive(Clone, Copy)]
pub(crate) struct Disjoint<T> {
    ptr: *mut T,
    len: usize,
}

// SAFETY: the threads holding copies write disjoint indices (the caller's
// contract, see `Disjoint::add`), and the slice outlives the scoped threads.
unsafe impl<T: Send> Send for Disjoint<T> {}
unsafe impl<T: Send> Sync for Disjoint<T> {}

impl<T: Copy + std::ops::AddAssign> Disjoint<T> {
    pub(crate) fn new(s: &mut [T]) -> Self {
        Disjoint {
            ptr: s.as_mut_ptr(),
            len: s.len(),
        }
    }

    /// `s[i] += v`.
    ///
    /// # Safety
    /// No other thread reads or writes index `i` while the view is used,
    /// and the slice outlives the view.
    #[inline]
    pub(crate) unsafe fn add(&self, i: usize, v: T) {
        assert!(i < self.len, "index {i} out of {}", self.len);
        // SAFETY: in bounds (asserted); exclusive by the caller's contract
        unsafe { *self.ptr.add(i) += v };
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn split_covers_the_range_in_order() {
        assert_eq!(split(10, 3), vec![0..4, 4..7, 7..10]);
        assert_eq!(split(2, 4), vec![0..1, 1..2]);
        assert_eq!(split(0, 2), Vec::<std::ops::Range<usize>>::new());
        assert_eq!(split(5, 1), vec![0..5]);
    }
}
