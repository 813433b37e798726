//! Shared by the binary's end-to-end tests.

#![allow(dead_code)]

use std::process::{Command, Output};

/// Runs the `prism` binary with `args`.
pub fn prism(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_prism"))
        .args(args)
        .output()
        .expect("the prism binary runs")
}

/// Asserts that a run succeeded, showing its stderr when it did not.
pub fn assert_success(out: &Output) {
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

/// Runs `prism` with the argument lists `parts` joined, and asserts that it succeeded.
pub fn prism_ok(parts: &[&[&str]]) -> Output {
    let out = prism(&parts.concat());
    assert_success(&out);
    out
}

/// Each case must fail with exactly one line on stderr that contains its needle, and
/// never panic.
pub fn assert_one_line_errors(cases: &[(&[&str], &str)]) {
    for (args, needle) in cases {
        let out = prism(args);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success(), "{args:?} succeeded");
        assert_eq!(stderr.trim_end().lines().count(), 1, "{args:?}: {stderr}");
        assert!(
            stderr.contains(needle),
            "{args:?}: '{stderr}' lacks '{needle}'"
        );
        assert!(!stderr.contains("panicked"), "{args:?}: {stderr}");
    }
}

/// A test's directory, removed with everything in it when dropped, whether the test
/// passed or failed (runs used to leave one per test and process in the temp directory).
pub struct TempDir(std::path::PathBuf);

impl std::ops::Deref for TempDir {
    type Target = std::path::Path;
    fn deref(&self) -> &std::path::Path {
        &self.0
    }
}

impl AsRef<std::path::Path> for TempDir {
    fn as_ref(&self) -> &std::path::Path {
        &self.0
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

/// A fresh directory for one test's files, named by `name` and this process.
pub fn temp_dir(name: &str) -> TempDir {
    let dir = std::env::temp_dir().join(format!("prism-test-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    TempDir(dir)
}
