//! One module per subcommand.

pub mod color;
pub mod compare;
pub mod denoise;
pub mod info;
pub mod lens;
pub mod merge;
pub mod render;
pub mod table;
pub mod trade;
pub mod upsample;
