//! prism-benches: not built yet; see ARCHITECTURE.md and the issue tracker.
