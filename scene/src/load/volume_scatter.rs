//! `KHR_materials_volume_scatter` (draft, glTF PR #2453; Khronos's ScatteringSkull sample):
//! scattering inside a `KHR_materials_volume`, as a participating medium.
//!
//! The draft keeps `KHR_materials_volume`'s attenuation, now the whole extinction:
//! sigma_t = -ln(attenuationColor) / attenuationDistance. `multiscatterColor` is the
//! multi-scatter albedo rho_ms (the colour after many bounces, Kulla and Conty 2017), and
//! the single-scatter albedo follows from it by the draft's fit,
//! rho_ss = 1 - (4.09712 + 4.20863 rho_ms - sqrt(9.59217 + 41.6808 rho_ms + 17.7126
//! rho_ms^2))^2; then sigma_s = rho_ss sigma_t, sigma_a = (1 - rho_ss) sigma_t, and
//! `scatterAnisotropy` is Henyey-Greenstein's g. Both colours are upsampled as
//! reflectances (bounded, so grey stays flat: no blue halo from an unbounded fit of a grey
//! coefficient) and the formulas applied per nanometre, so the medium is spectral through.

use std::sync::Arc;

use prism_spectrum::Spectrum;
use prism_spectrum::spectra::DenselySampled;
use prism_upsample::RgbKind;
use serde_json::Value;

use super::materials::Upsampler;
use crate::medium::{MAX_ABS_G, Medium, Phase};
use crate::textures::SceneSpectrum;

/// The single-scatter albedo for multi-scatter albedo `ms` (the draft's formula).
pub(crate) fn single_scatter_albedo(ms: f64) -> f64 {
    let ms = ms.clamp(0.0, 1.0);
    let root = (9.59217 + 41.6808 * ms + 17.7126 * ms * ms).sqrt();
    (1.0 - (4.09712 + 4.20863 * ms - root).powi(2)).clamp(0.0, 1.0)
}

/// The medium of a material with `KHR_materials_volume` (`color`, `distance`) and the
/// scatter extension's JSON `ext`; None where the volume attenuates nothing.
pub(crate) fn medium(
    ext: &Value,
    color: [f32; 3],
    distance: f32,
    upsampler: &Upsampler,
) -> Result<Option<Medium>, String> {
    let map = ext
        .as_object()
        .ok_or("KHR_materials_volume_scatter must be an object")?;
    let multiscatter = match map.get("multiscatterColor") {
        None => [0.0; 3],
        Some(v) => {
            let a = v
                .as_array()
                .filter(|a| a.len() == 3)
                .ok_or("KHR_materials_volume_scatter multiscatterColor must be three numbers")?;
            let mut c = [0.0f64; 3];
            for (k, x) in a.iter().enumerate() {
                c[k] = x
                    .as_f64()
                    .filter(|x| x.is_finite() && (0.0..=1.0).contains(x))
                    .ok_or("KHR_materials_volume_scatter multiscatterColor must be in [0, 1]")?;
            }
            c
        }
    };
    let g = match map.get("scatterAnisotropy") {
        None => 0.0,
        Some(v) => v
            .as_f64()
            .filter(|g| g.is_finite() && g.abs() < 1.0)
            .ok_or("KHR_materials_volume_scatter scatterAnisotropy must be in (-1, 1)")?
            .clamp(-MAX_ABS_G, MAX_ABS_G),
    };
    let Some(attenuation) = super::materials::attenuation(color, distance, upsampler)? else {
        return Ok(None);
    };
    let albedo = upsampler.fit(multiscatter, RgbKind::Albedo)?;
    let (mut sigma_a, mut sigma_s) = (Vec::new(), Vec::new());
    for nm in 300..=830 {
        let nm = f64::from(nm);
        let sigma_t = super::materials::extinction(&attenuation, distance, nm);
        let rho = single_scatter_albedo(albedo.evaluate(nm));
        sigma_s.push(rho * sigma_t);
        sigma_a.push((1.0 - rho) * sigma_t);
    }
    let dense = |values| {
        DenselySampled::from_values(300.0, values)
            .map(|d| SceneSpectrum::Dense(Arc::new(d)))
            .map_err(|e| e.to_string())
    };
    Medium::new(
        dense(sigma_a)?,
        dense(sigma_s)?,
        Phase::henyey_greenstein(g)?,
        None,
    )
    .map(Some)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The fit's ends: no multiple scattering, none single; white stays white; and it
    /// rises monotonically in between (more bounces, more colour).
    #[test]
    fn single_scatter_albedo_is_the_drafts_fit() {
        assert!(single_scatter_albedo(0.0).abs() < 1e-4);
        assert!((single_scatter_albedo(1.0) - 1.0).abs() < 1e-4);
        let mut previous = -1.0;
        for k in 0..=100 {
            let a = single_scatter_albedo(f64::from(k) / 100.0);
            assert!(a >= previous, "{k}");
            previous = a;
        }
        // A multi-scatter albedo of 0.5 needs single scattering of about 0.9.
        let half = single_scatter_albedo(0.5);
        assert!((0.85..0.95).contains(&half), "{half}");
    }
}
