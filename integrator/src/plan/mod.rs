//! What a render will do, decided before it traces: its settings resolved into
//! estimators ([`estimators`]).

pub(crate) mod adaptive_pilot;
pub mod estimators;
pub(crate) mod modes;
pub(crate) mod setup;
