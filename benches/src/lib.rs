//! prism-benches: criterion benchmarks of the prism crates. Run them with
//! `cargo bench -p prism-benches`; `benches/README.md` says what each one measures. The
//! library part is empty: the benches live in `benches/`.
