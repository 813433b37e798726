//! The instruction set this binary was compiled for, checked against the CPU it runs on.
//!
//! The workspace builds for x86-64-v2 (`.cargo/config.toml`); on an older CPU the first
//! SSE4.1 instruction would kill the process with SIGILL, mid-render and without a word.
//! `main` asks first, so such a CPU gets one line saying what to rebuild with.

/// The features the build assumes that this CPU lacks, by name (empty: all present, or a
/// build that assumes none of them).
pub fn missing_features() -> Vec<&'static str> {
    #[allow(unused_mut)]
    let mut missing = Vec::new();
    #[cfg(target_arch = "x86_64")]
    {
        macro_rules! require {
            ($($feature:tt),*) => {$(
                if cfg!(target_feature = $feature) && !std::arch::is_x86_feature_detected!($feature) {
                    missing.push($feature);
                }
            )*};
        }
        require!(
            "sse3", "ssse3", "sse4.1", "sse4.2", "popcnt", "avx", "avx2", "fma", "bmi1", "bmi2"
        );
    }
    missing
}

/// The one-line error for a CPU without `missing`.
pub fn unsupported(missing: &[&str]) -> String {
    format!(
        "this build of prism needs CPU instructions this machine lacks ({}); rebuild it with \
         RUSTFLAGS=\"-C target-cpu=native\" cargo build --release",
        missing.join(", ")
    )
}

#[cfg(test)]
mod tests {
    use super::{missing_features, unsupported};

    /// The machine that runs the tests built them, so it has what the build assumes.
    #[test]
    fn the_building_machine_has_every_feature_the_build_assumes() {
        assert_eq!(missing_features(), Vec::<&str>::new());
    }

    #[test]
    fn the_error_names_what_is_missing_and_the_remedy() {
        let line = unsupported(&["sse4.1", "popcnt"]);
        assert!(line.contains("sse4.1, popcnt"), "{line}");
        assert!(line.contains("target-cpu=native"), "{line}");
        assert!(!line.contains('\n'));
    }
}
