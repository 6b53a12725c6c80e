//! The process's peak resident memory, reported in `summary.json`
//! (`peak_memory_bytes`) and by `ctc bench --solid`.

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
