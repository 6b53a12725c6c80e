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
}
