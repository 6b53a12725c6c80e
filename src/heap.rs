//! The C heap of the `ctc` process (glibc): freed memory is kept for the
//! next allocation instead of being handed back to the system.
//!
//! By default glibc serves every allocation above 128 KiB (a dynamic
//! threshold: the size of the last large block freed) by a fresh `mmap`
//! and returns it with `munmap` when freed, so a Newton loop that
//! allocates and frees vectors of the model's size (solves, residuals,
//! output arrays) touches new pages, each a page fault, at every
//! iteration. Issue 20, tutorial Hertz deck (80,200 dofs): 79,000 page
//! faults against 53,000 with these settings, about 0.1 s of the 0.95 s
//! process CPU (`perf stat -e page-faults`), peak memory 209 -> 218 MiB.
//! Allocation sizes and contents are unchanged: the results are the same
//! bits.

/// Blocks at least this large are still mapped on their own (256 MiB).
#[cfg(all(target_os = "linux", target_env = "gnu"))]
const MMAP_THRESHOLD: libc::c_int = 1 << 28;

/// Free memory at the top of the heap kept before trimming (1 GiB).
#[cfg(all(target_os = "linux", target_env = "gnu"))]
const TRIM_THRESHOLD: libc::c_int = 1 << 30;

/// Extra memory requested with each growth of the heap (64 MiB).
#[cfg(all(target_os = "linux", target_env = "gnu"))]
const TOP_PAD: libc::c_int = 1 << 26;

/// Sets the heap's thresholds; call at start-up, before any thread. A
/// refused setting leaves glibc's default (only slower).
pub fn keep_freed_memory() {
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    // SAFETY: `mallopt` only changes the allocator's parameters; called
    // once from `main` before any other thread exists.
    unsafe {
        libc::mallopt(libc::M_MMAP_THRESHOLD, MMAP_THRESHOLD);
        libc::mallopt(libc::M_TRIM_THRESHOLD, TRIM_THRESHOLD);
        libc::mallopt(libc::M_TOP_PAD, TOP_PAD);
    }
}
