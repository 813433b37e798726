use crate::Spectrum;
use crate::colorimetry::{Observer, emission_xyz};
use crate::constants::{ELEMENTARY_CHARGE, LUMINOUS_EFFICACY_MAX, PLANCK, SPEED_OF_LIGHT};
use crate::error::{SpectrumError, require_positive};

/// Energy of one photon of vacuum wavelength `lambda_nm`, E = h c / lambda, in joules.
/// Errors unless `lambda_nm` is finite and > 0 (and large enough, > ~1e-290 nm, for the
/// energy to be finite); beyond ~1e290 nm the energy underflows to 0.
pub fn photon_energy_joules(lambda_nm: f64) -> Result<f64, SpectrumError> {
    finite_energy(lambda_nm, PLANCK * SPEED_OF_LIGHT * 1e9)
}

/// Energy of one photon of vacuum wavelength `lambda_nm`, in electronvolts
/// (1239.84... / lambda_nm).
pub fn photon_energy_ev(lambda_nm: f64) -> Result<f64, SpectrumError> {
    finite_energy(lambda_nm, PLANCK * SPEED_OF_LIGHT * 1e9 / ELEMENTARY_CHARGE)
}

/// `hc_in_unit_nm / lambda_nm`, or an error where that is not a finite number.
fn finite_energy(lambda_nm: f64, hc_in_unit_nm: f64) -> Result<f64, SpectrumError> {
    let lambda = require_positive("photon wavelength (nm)", lambda_nm)?;
    let energy = hc_in_unit_nm / lambda;
    if energy.is_finite() {
        Ok(energy)
    } else {
        Err(SpectrumError::InvalidValue {
            what: "photon wavelength (nm)",
            value: lambda_nm,
            expected: "large enough for a finite photon energy (> ~1e-290 nm)",
        })
    }
}

/// Photometric quantity of a radiometric spectrum: K_m * integral S(l) y-bar(l) dl with
/// K_m = 683 lm/W (CIE 1931 observer). Radiance in W m^-2 sr^-1 nm^-1 gives luminance in
/// cd m^-2; spectral power in W nm^-1 gives luminous flux in lm.
pub fn luminous_flux<S: Spectrum + ?Sized>(spectrum: &S) -> f64 {
    LUMINOUS_EFFICACY_MAX * emission_xyz(spectrum, Observer::Cie1931).y
}

/// The factor by which `spectrum` must be multiplied so that its photometric quantity is
/// `target` (lm, or cd m^-2): how a light given in photometric units (glTF
/// `KHR_lights_punctual`) becomes radiometric. Errors if the spectrum has no luminance or
/// `target` is negative or not finite.
pub fn radiant_scale_for_luminance<S: Spectrum + ?Sized>(
    spectrum: &S,
    target: f64,
) -> Result<f64, SpectrumError> {
    if !(target.is_finite() && target >= 0.0) {
        return Err(SpectrumError::InvalidValue {
            what: "photometric target",
            value: target,
            expected: "a finite number >= 0",
        });
    }
    let current = luminous_flux(spectrum);
    if !(current > 0.0 && current.is_finite()) {
        return Err(SpectrumError::Degenerate(format!(
            "the spectrum has luminous value {current}: it cannot be scaled to {target}"
        )));
    }
    Ok(target / current)
}
