//! prism-integrator: not built yet; see ARCHITECTURE.md and the issue tracker.
