//! Coefficient tables that ship with the crate, so that upsampling in the colour space
//! nearly every asset uses costs no fitting at all.
//!
//! `data/srgb-32.bin` is the 32^3 table of linear sRGB under the CIE D65 spectrum, exactly
//! what [`CoefficientTable::fit`] writes for `FitContext::new(RgbSpaceId::Srgb.space(),
//! &RgbSpaceId::Srgb.illuminant())` at resolution 32 (regenerate with `prism table fit
//! --space srgb --res 32 -o upsample/data/srgb-32.bin`; `tests/shipped_table.rs` checks
//! that a fresh fit agrees). Size against accuracy, measured over 2000 random sRGB
//! colours against exact fits (docs/upsample-accuracy.md has 20 134): 16^3 is 0.15 MB
//! with mean 0.14 / max 0.64 dE2000, 32^3 is 1.18 MB with mean 0.03 / max 0.18, 64^3 is
//! 9.4 MB with mean 0.008 / max 0.04. 32^3 keeps every lookup far below a visible
//! difference (dE2000 1) at an eighth of the size of 64^3, which would make the crate
//! too large to publish; callers who want 64^3 fit it once ([`CoefficientTable::fit`],
//! seconds on a few cores) and keep the bytes ([`CoefficientTable::to_bytes`]).

use std::sync::{Arc, LazyLock};

use prism_spectrum::color::RgbSpaceId;

use crate::table::CoefficientTable;

/// The resolution of the shipped tables.
pub const SHIPPED_RESOLUTION: usize = 32;

#[cfg(feature = "srgb-table")]
static SRGB: LazyLock<Option<Arc<CoefficientTable>>> = LazyLock::new(|| {
    CoefficientTable::from_bytes(include_bytes!("../data/srgb-32.bin"))
        .ok()
        .map(Arc::new)
});

#[cfg(not(feature = "srgb-table"))]
static SRGB: LazyLock<Option<Arc<CoefficientTable>>> = LazyLock::new(|| None);

impl CoefficientTable {
    /// The table that ships with the crate for `space`, if there is one: the 32^3 sRGB
    /// table (feature `srgb-table`, on by default), which serves Rec.709 too (same
    /// primaries and white; tables work on linear RGB, so the transfer function does not
    /// matter). Decoded on first use (a few milliseconds) and shared afterwards.
    ///
    /// ```
    /// use prism_spectrum::color::RgbSpaceId;
    /// use prism_spectrum::Spectrum;
    /// use prism_upsample::{CoefficientTable, FitContext};
    ///
    /// let table = CoefficientTable::shipped(RgbSpaceId::Srgb).expect("feature srgb-table");
    /// let srgb = RgbSpaceId::Srgb;
    /// assert!(table.space().matches(&FitContext::new(srgb.space(), &srgb.illuminant())?));
    /// // A saturated red reflects long wavelengths and absorbs short ones.
    /// let red = table.lookup([0.9, 0.05, 0.05]);
    /// assert!(red.evaluate(650.0) > 0.7 && red.evaluate(450.0) < 0.1);
    /// // No table ships for Rec.2020: fit one with `CoefficientTable::fit`.
    /// assert!(CoefficientTable::shipped(RgbSpaceId::Rec2020).is_none());
    /// # Ok::<(), prism_upsample::UpsampleError>(())
    /// ```
    pub fn shipped(space: RgbSpaceId) -> Option<Arc<CoefficientTable>> {
        match space {
            RgbSpaceId::Srgb | RgbSpaceId::Rec709 => SRGB.clone(),
            _ => None,
        }
    }
}
