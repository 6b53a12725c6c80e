//! The process's peak resident memory, reported in `summary.json`
//! (`peak_memory_bytes`) and by `ctc bench --solid`; CPU times; and the
//! memory trace of `CTC_MEMORY_TRACE` ([`trace`]).

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

/// Peak resident memory of this process so far (`VmHWM` of
/// `/proc/self/status`, Linux), bytes; 0 where the system does not say.
pub fn peak_memory_bytes() -> u64 {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("VmHWM:"))
                .and_then(|l| l.split_whitespace().nth(1))
                .and_then(|kb| kb.parse::<u64>().ok())
        })
        .map_or(0, |kb| kb * 1024)
}

/// CPU time this thread has run so far (`/proc/thread-self/schedstat`,
/// Linux, nanoseconds), seconds; 0 where the system does not say.
pub fn thread_cpu_seconds() -> f64 {
    std::fs::read_to_string("/proc/thread-self/schedstat")
        .ok()
        .and_then(|s| s.split_whitespace().next()?.parse::<u64>().ok())
        .map_or(0.0, |ns| ns as f64 * 1e-9)
}

/// CPU time of the whole process so far, user + system
/// (`/proc/self/stat`, clock ticks of 1/100 s), seconds; 0 where the
/// system does not say.
pub fn process_cpu_seconds() -> f64 {
    std::fs::read_to_string("/proc/self/stat")
        .ok()
        .and_then(|s| {
            // the fields after the command name `(..)`: utime, stime are
            // the 12th and 13th
            let rest = &s[s.rfind(')')? + 1..];
            let f: Vec<&str> = rest.split_whitespace().collect();
            Some(f.get(11)?.parse::<u64>().ok()? + f.get(12)?.parse::<u64>().ok()?)
        })
        .map_or(0.0, |ticks| ticks as f64 / 100.0)
}

/// Whether [`trace`] prints (`CTC_MEMORY_TRACE` set at start-up) and the
/// [`CountingAllocator`] counts.
static TRACE_ON: AtomicBool = AtomicBool::new(false);
/// Rust heap bytes allocated and not yet freed (while tracing).
static HEAP_LIVE: AtomicUsize = AtomicUsize::new(0);
/// Largest [`HEAP_LIVE`] since the last [`trace`].
static HEAP_PEAK: AtomicUsize = AtomicUsize::new(0);

/// The system allocator, counting the live Rust heap while
/// `CTC_MEMORY_TRACE` is set (one relaxed load per allocation otherwise);
/// the `ctc` binary installs it as its global allocator, so [`trace`]
/// tells what each phase of a run holds (issue 21: the memory every MPI
/// rank holds, `petsc/README.md`). PETSc's and MPI's C allocations are not
/// counted: `VmRSS` shows them.
pub struct CountingAllocator;

impl CountingAllocator {
    fn grew(by: usize) {
        let now = HEAP_LIVE.fetch_add(by, Ordering::Relaxed) + by;
        HEAP_PEAK.fetch_max(now, Ordering::Relaxed);
    }
}

// SAFETY: every call is forwarded to the system allocator unchanged; the
// counters only observe sizes.
unsafe impl GlobalAlloc for CountingAllocator {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        // SAFETY: the caller's contract, forwarded.
        let p = unsafe { System.alloc(layout) };
        if !p.is_null() && TRACE_ON.load(Ordering::Relaxed) {
            Self::grew(layout.size());
        }
        p
    }

    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        // SAFETY: the caller's contract, forwarded.
        let p = unsafe { System.alloc_zeroed(layout) };
        if !p.is_null() && TRACE_ON.load(Ordering::Relaxed) {
            Self::grew(layout.size());
        }
        p
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: the caller's contract, forwarded.
        unsafe { System.dealloc(ptr, layout) };
        if TRACE_ON.load(Ordering::Relaxed) {
            HEAP_LIVE.fetch_sub(layout.size(), Ordering::Relaxed);
        }
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        // SAFETY: the caller's contract, forwarded.
        let q = unsafe { System.realloc(ptr, layout, new_size) };
        if !q.is_null() && TRACE_ON.load(Ordering::Relaxed) {
            if new_size >= layout.size() {
                Self::grew(new_size - layout.size());
            } else {
                HEAP_LIVE.fetch_sub(layout.size() - new_size, Ordering::Relaxed);
            }
        }
        q
    }
}

/// Starts the memory trace if `CTC_MEMORY_TRACE` is set (call first in
/// `main`: the bytes allocated before are not counted).
pub fn trace_start() {
    if std::env::var_os("CTC_MEMORY_TRACE").is_some() {
        TRACE_ON.store(true, Ordering::Relaxed);
    }
}

/// A field of `/proc/self/status` in KiB (Linux); 0 where absent.
fn status_kib(key: &str) -> u64 {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with(key))
                .and_then(|l| l.split_whitespace().nth(1))
                .and_then(|kb| kb.parse::<u64>().ok())
        })
        .unwrap_or(0)
}

/// With `CTC_MEMORY_TRACE` set, prints to stderr at the end of the phase
/// `label`: the live Rust heap ([`CountingAllocator`]), its largest value
/// since the previous trace, `VmRSS` and `VmHWM`, in MiB, with the MPI
/// rank (`OMPI_COMM_WORLD_RANK`, `-` outside `mpirun`). Nothing otherwise.
pub fn trace(label: &str) {
    if !TRACE_ON.load(Ordering::Relaxed) {
        return;
    }
    let rank = std::env::var("OMPI_COMM_WORLD_RANK").unwrap_or_else(|_| "-".into());
    let live = HEAP_LIVE.load(Ordering::Relaxed);
    let peak = HEAP_PEAK.swap(live, Ordering::Relaxed);
    let mib = |bytes: f64| bytes / (1u64 << 20) as f64;
    eprintln!(
        "memory: rank {rank} {label:<32} heap {:8.1} peak {:8.1} VmRSS {:8.1} VmHWM {:8.1} MiB",
        mib(live as f64),
        mib(peak as f64),
        mib(status_kib("VmRSS:") as f64 * 1024.0),
        mib(status_kib("VmHWM:") as f64 * 1024.0),
    );
}

#[cfg(test)]
mod tests {
    #[test]
    fn a_running_process_has_a_peak_memory_on_linux() {
        let before = super::peak_memory_bytes();
        if cfg!(target_os = "linux") {
            // 64 MiB touched: the high-water mark cannot stay below it
            let v = vec![1u8; 64 << 20];
            assert!(v.iter().map(|&b| b as u64).sum::<u64>() == 64 << 20);
            let after = super::peak_memory_bytes();
            assert!(after >= 64 << 20, "{after}");
            assert!(after >= before);
        }
    }

    #[test]
    fn cpu_time_grows_with_work_on_linux() {
        if cfg!(target_os = "linux") {
            let (t0, p0) = (super::thread_cpu_seconds(), super::process_cpu_seconds());
            let mut x = 0.0f64;
            let start = std::time::Instant::now();
            while start.elapsed().as_millis() < 50 {
                for i in 0..10_000 {
                    x += (i as f64).sqrt();
                }
            }
            assert!(x > 0.0);
            let (t1, p1) = (super::thread_cpu_seconds(), super::process_cpu_seconds());
            assert!(t1 > t0, "{t0} -> {t1}");
            assert!(p1 >= p0, "{p0} -> {p1}");
        }
    }
}
