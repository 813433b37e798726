//! Tristimulus values of spectra: the CIE integrals over the 1 nm grid (CIE 015:2018 §7).

use super::Observer;
use super::xyz::Xyz;
use crate::Spectrum;
use crate::constants::{LAMBDA_MAX, LAMBDA_MIN};
use crate::error::SpectrumError;

/// Wavelengths of the 1 nm integration grid, 360..=830.
fn grid() -> impl Iterator<Item = f64> {
    (LAMBDA_MIN as i32..=LAMBDA_MAX as i32).map(f64::from)
}

/// Tristimulus values of an emission spectrum: X = sum S(l) x-bar(l) dl over 360-830 nm at
/// dl = 1 nm (CIE 015:2018 §7.1 with k = 1). For radiance in W m^-2 sr^-1 nm^-1, multiply
/// Y by [`crate::constants::LUMINOUS_EFFICACY_MAX`] for luminance in cd m^-2.
pub fn emission_xyz<S: Spectrum + ?Sized>(spectrum: &S, observer: Observer) -> Xyz {
    let mut xyz = [0.0f64; 3];
    for l in grid() {
        let s = spectrum.evaluate(l);
        if s != 0.0 {
            for (acc, c) in xyz.iter_mut().zip(observer.cmf(l)) {
                *acc += s * c;
            }
        }
    }
    Xyz::new(xyz[0], xyz[1], xyz[2])
}

/// Emission XYZ scaled to Y = 1: the colour of a light independent of its power. Errors
/// for a spectrum with no luminance (for example a 1 K blackbody, or pure UV).
pub fn luminous_xyz_normalized<S: Spectrum + ?Sized>(
    spectrum: &S,
    observer: Observer,
) -> Result<Xyz, SpectrumError> {
    emission_xyz(spectrum, observer).normalized_to_unit_y()
}

/// Tristimulus values of a reflectance (or transmittance) under an illuminant, normalized
/// so that a perfect reflecting diffuser has Y = 1 (CIE 015:2018 §7.2 with
/// k = 1 / sum S y-bar). Errors for an illuminant with no luminance.
pub fn reflectance_xyz<R: Spectrum + ?Sized, I: Spectrum + ?Sized>(
    reflectance: &R,
    illuminant: &I,
    observer: Observer,
) -> Result<Xyz, SpectrumError> {
    let mut xyz = [0.0f64; 3];
    let mut white_y = 0.0;
    for l in grid() {
        let s = illuminant.evaluate(l);
        let cmf = observer.cmf(l);
        white_y += s * cmf[1];
        let sr = s * reflectance.evaluate(l);
        for (acc, c) in xyz.iter_mut().zip(cmf) {
            *acc += sr * c;
        }
    }
    if white_y == 0.0 || !white_y.is_finite() {
        return Err(SpectrumError::Degenerate(format!(
            "the illuminant has luminance {white_y}: reflectance colour is undefined"
        )));
    }
    Ok(Xyz::new(
        xyz[0] / white_y,
        xyz[1] / white_y,
        xyz[2] / white_y,
    ))
}
