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

/// CPU time (user + system, all threads) of this process so far
/// (`utime + stime` of `/proc/self/stat` in clock ticks of 1/100 s, the
/// Linux `USER_HZ`), seconds; 0 where the system does not say.
pub fn process_cpu_seconds() -> f64 {
    std::fs::read_to_string("/proc/self/stat")
        .ok()
        .and_then(|s| {
            // fields after the command name (in parentheses, may hold spaces)
            let rest = &s[s.rfind(')')? + 1..];
            let f: Vec<&str> = rest.split_whitespace().collect();
            // rest[0] is field 3 (state): utime is field 14, stime 15
            let utime: u64 = f.get(11)?.parse().ok()?;
            let stime: u64 = f.get(12)?.parse().ok()?;
            Some((utime + stime) as f64 / 100.0)
        })
        .unwrap_or(0.0)
}

#[cfg(test)]
mod tests {
    #[test]
    fn cpu_time_grows_with_work_on_linux() {
        if cfg!(target_os = "linux") {
            let before = super::process_cpu_seconds();
            let start = std::time::Instant::now();
            let mut x = 0u64;
            while start.elapsed().as_secs_f64() < 0.1 {
                x = x.wrapping_mul(6364136223846793005).wrapping_add(1);
            }
            std::hint::black_box(x);
            let after = super::process_cpu_seconds();
            assert!(after >= before, "{before} -> {after}");
            assert!(before > 0.0 || after > 0.0);
        }
    }

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
}
