//! Peak resident memory of the process, for `summary.json` and `wrinkle bench`.
//!
//! On Linux the kernel keeps the high-water mark of the resident set (`VmHWM` in
//! `/proc/self/status`) and resets it to the current resident set when `5` is written to
//! `/proc/self/clear_refs` (Linux ≥ 4.0). A run resets it when it starts and reads it when its
//! numbers are done, so each run of a benchmark reports its own peak, not the largest so far.
//! Elsewhere, or where `/proc` cannot be written or read (some sandboxes), the run reports no
//! peak (`null` in the summary) rather than one that may belong to earlier work.
//!
//! The mark is the whole process's: work running beside the run in the same process (other
//! tests of one test binary) counts too.

/// Resets the peak resident set to the current one; `false` when the platform cannot.
pub fn reset_peak() -> bool {
    #[cfg(target_os = "linux")]
    {
        std::fs::write("/proc/self/clear_refs", "5").is_ok()
    }
    #[cfg(not(target_os = "linux"))]
    {
        false
    }
}

/// Peak resident set of the process since it started or since the last [`reset_peak`], in
/// bytes; `None` where the platform does not say.
pub fn peak_resident_bytes() -> Option<u64> {
    #[cfg(target_os = "linux")]
    {
        let status = std::fs::read_to_string("/proc/self/status").ok()?;
        parse_high_water_mark(&status)
    }
    #[cfg(not(target_os = "linux"))]
    {
        None
    }
}

/// `VmHWM:   218372 kB` → bytes.
#[cfg_attr(not(target_os = "linux"), allow(dead_code))]
fn parse_high_water_mark(status: &str) -> Option<u64> {
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let mut words = line["VmHWM:".len()..].split_whitespace();
    let value: u64 = words.next()?.parse().ok()?;
    match words.next() {
        Some("kB") => value.checked_mul(1024),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn high_water_mark_line_in_kilobytes() {
        let status =
            "Name:\twrinkle\nVmPeak:\t  300000 kB\nVmHWM:\t  218372 kB\nVmRSS:\t 13568 kB\n";
        assert_eq!(parse_high_water_mark(status), Some(218_372 * 1024));
        assert_eq!(parse_high_water_mark("VmHWM:\t12 MB\n"), None);
        assert_eq!(parse_high_water_mark("VmRSS:\t12 kB\n"), None);
    }

    #[cfg(target_os = "linux")]
    #[test]
    fn peak_follows_an_allocation_and_resets() {
        // 64 MiB touched page by page must show in the peak (the test binary's other threads
        // can only raise it).
        reset_peak();
        let before = peak_resident_bytes().expect("Linux reports VmHWM");
        let mut block = vec![0u8; 64 << 20];
        for i in (0..block.len()).step_by(4096) {
            block[i] = 1;
        }
        std::hint::black_box(&block);
        let during = peak_resident_bytes().unwrap();
        assert!(during >= before + (60 << 20), "{before} -> {during}");
        drop(block);
    }
}
