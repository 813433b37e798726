//! Colorimetry: from spectra to CIE XYZ, chromaticity, CIELAB, colour differences and
//! correlated colour temperature.
//!
//! References: CIE 015:2018 *Colorimetry*, 4th ed. (§7 tristimulus values, §8.2 CIELAB,
//! §9.4 CCT); Sharma, Wu and Dalal, Color Res. Appl. 30(1), 2005 (CIEDE2000);
//! Ohno, LEUKOS 10(1), 2014 (CCT and Duv).

mod cct;
mod ciede2000;
mod integrate;
mod lab;
mod observer;
mod xyz;

pub use cct::{CCT_MAX_KELVIN, CCT_MIN_KELVIN, CctResult, cct_ohno2013, planckian_uv};
pub use ciede2000::ciede2000;
pub use integrate::{emission_xyz, luminous_xyz_normalized, reflectance_xyz};
pub use lab::{Lab, WhitePoint};
pub use observer::Observer;
pub use xyz::{Chromaticity, Uv, Xyz};
