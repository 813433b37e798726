//! The code of the `prism` command line as a library: the binary (`main.rs`) parses
//! arguments and calls these commands, and the Python package (`python/`) renders through
//! the same code, so that an image from Python is the command line's to the bit. This
//! layer owns files, the terminal and the environment; the library crates below it never
//! touch them.
//!
//! It is not a stable API: the commands' arguments are their `--help` text.

// The argument structs' doc comments are clap's --help text, documented there.
#![allow(missing_docs)]
// The doc comments of the argument structs are clap's --help text, where `reinhard[:WHITE]`
// means an optional argument, not a link; escaping it would print the backslash.
#![allow(rustdoc::broken_intra_doc_links)]

// First: the modules below print with its `outln!`.
#[macro_use]
pub mod stdout;

pub mod commands;
pub mod cpu;
pub mod denoise;
pub mod image_args;
mod memory;
pub mod output;
mod progress;
pub mod scene_file;
pub mod session;
mod space_arg;
mod spectrum_spec;
mod svg_plot;
mod table_cache;
pub mod tev;
