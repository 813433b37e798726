//! RGB colour spaces, chromatic adaptation, transfer functions and display tone mapping.
//!
//! Colour spaces are defined by their primaries and white point; the RGB <-> XYZ matrices
//! are derived from those in code (SMPTE RP 177-1993 §3.3) instead of being pasted, so a
//! user-defined space is exactly as trustworthy as a built-in one.

mod adaptation;
mod matrix;
mod space;
mod tonemap;
mod transfer;

pub use adaptation::{AdaptationMethod, adaptation_matrix};
pub use matrix::Mat3;
pub use space::{RgbColorSpace, RgbSpaceId};
pub use tonemap::{ToneMap, display_8bit};
pub use transfer::TransferFunction;
