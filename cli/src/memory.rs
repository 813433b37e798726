//! This process's memory, from /proc (Linux); None elsewhere.

/// A `kB` field of a /proc status-like file, in bytes.
fn proc_field(file: &str, key: &str) -> Option<u64> {
    let text = std::fs::read_to_string(file).ok()?;
    let line = text.lines().find(|l| l.starts_with(key))?;
    let kb: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kb * 1024)
}

/// The peak resident memory of this process.
pub fn peak_bytes() -> Option<u64> {
    proc_field("/proc/self/status", "VmHWM:")
}

/// Memory the system can give without swapping.
pub fn available_bytes() -> Option<u64> {
    proc_field("/proc/meminfo", "MemAvailable:")
}
