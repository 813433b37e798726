//! One module per subcommand.

pub mod color;
