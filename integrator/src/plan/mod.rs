//! What a render will do, decided before it traces: its settings resolved into
//! estimators ([`estimators`]).

pub mod estimators;
pub(crate) mod modes;
