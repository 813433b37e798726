//! One module per subcommand.

pub mod color;
pub mod table;
pub mod upsample;
