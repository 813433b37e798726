//! Nothing to see here: the programs are in `tests/`, each written against the public API
//! of prism's library crates the way a crate that depends on them would write it.
