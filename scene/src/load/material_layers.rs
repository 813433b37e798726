//! `KHR_materials_specular`, `KHR_materials_anisotropy`, `KHR_materials_clearcoat` and
//! `KHR_materials_sheen`, read from the raw JSON (their texts in the Khronos glTF
//! repository, `extensions/2.0/Khronos/`): factors with their defaults and ranges, every
//! texture each defines, colours upsampled to spectra.

use std::sync::Arc;

use prism_upsample::RgbKind;

use super::Upsampler;
use super::tex_coord_sets::TexCoordSets;
use super::textures::TextureLoader;
use crate::materials::{
    AnisotropyDesc, ClearcoatDesc, DiffuseTransmissionDesc, Layers, NormalMap, SheenDesc,
    SpecularDesc,
};
use crate::textures::SceneSpectrum;

/// One extension's JSON object and what reading it needs.
struct Extension<'a> {
    name: &'static str,
    json: &'a serde_json::Value,
    textures: &'a TextureLoader<'a>,
    sets: &'a TexCoordSets,
}

impl Extension<'_> {
    fn error(&self, what: String) -> String {
        format!("{}: {what}", self.name)
    }

    /// A number with its default; an error for one that is not a finite number where
    /// `valid` holds.
    fn number(&self, key: &str, default: f32, valid: &dyn Fn(f32) -> bool) -> Result<f32, String> {
        match self.json.get(key) {
            None => Ok(default),
            Some(v) => match v.as_f64().map(|x| x as f32) {
                Some(x) if x.is_finite() && valid(x) => Ok(x),
                _ => Err(self.error(format!("{key} {v} is out of range"))),
            },
        }
    }

    /// A colour (three finite numbers >= 0) with its default.
    fn colour(&self, key: &str, default: [f32; 3]) -> Result<[f32; 3], String> {
        let Some(v) = self.json.get(key) else {
            return Ok(default);
        };
        let values: Option<Vec<f32>> = v.as_array().filter(|a| a.len() == 3).map(|a| {
            a.iter()
                .filter_map(|x| x.as_f64().map(|x| x as f32))
                .collect()
        });
        match values {
            Some(c) if c.len() == 3 && c.iter().all(|x| x.is_finite() && *x >= 0.0) => {
                Ok([c[0], c[1], c[2]])
            }
            _ => Err(self.error(format!("{key} {v} must be three numbers >= 0"))),
        }
    }

    /// A linear data texture times `factor`.
    fn data(
        &self,
        key: &str,
        factor: [f32; 3],
    ) -> Result<Option<Arc<crate::textures::RgbTexture>>, String> {
        self.json
            .get(key)
            .map(|r| {
                self.textures
                    .extension_texture(r, factor, self.sets)
                    .map(Arc::new)
            })
            .transpose()
            .map_err(|e| self.error(format!("{key}: {e}")))
    }

    /// The alpha channel of a texture times `factor` (None without the texture, or
    /// when its image has no alpha, which reads as 1).
    fn alpha(
        &self,
        key: &str,
        factor: f32,
    ) -> Result<Option<Arc<crate::textures::RgbTexture>>, String> {
        Ok(self
            .json
            .get(key)
            .map(|r| self.textures.extension_alpha(r, factor, self.sets))
            .transpose()
            .map_err(|e| self.error(format!("{key}: {e}")))?
            .flatten()
            .map(Arc::new))
    }

    /// A colour factor times its (sRGB) colour texture, as a reflectance spectrum; factors
    /// above 1 scale a spectrum fitted to the colour over its largest component.
    fn spectrum(
        &self,
        key: &str,
        texture: &str,
        factor: [f32; 3],
        upsampler: &Upsampler,
    ) -> Result<SceneSpectrum, String> {
        let peak = factor.iter().fold(0.0f32, |a, &c| a.max(c));
        let scale = peak.max(1.0);
        let unit = factor.map(|c| c / scale);
        let spectrum = match self.json.get(texture) {
            Some(r) => self
                .textures
                .extension_color(r, unit, self.sets)
                .map_err(|e| self.error(format!("{texture}: {e}")))?,
            None => SceneSpectrum::Rgb(Arc::new(
                upsampler
                    .fit(unit.map(f64::from), RgbKind::Albedo)
                    .map_err(|e| self.error(format!("{key}: {e}")))?,
            )),
        };
        Ok(if scale > 1.0 {
            SceneSpectrum::Scaled(Arc::new(spectrum), f64::from(scale))
        } else {
            spectrum
        })
    }
}

/// The four extensions of `material`; None when it has none of them (or only ones
/// without effect: a zero clear coat, a black sheen, zero anisotropy).
pub(crate) fn layers(
    material: &gltf::Material,
    textures: &TextureLoader,
    sets: &TexCoordSets,
    upsampler: &Upsampler,
    volume: Option<SceneSpectrum>,
) -> Result<Option<Layers>, String> {
    let extension = |name: &'static str| {
        material.extension_value(name).map(|json| Extension {
            name,
            json,
            textures,
            sets,
        })
    };
    let mut layers = Layers::default();
    if let Some(e) = extension("KHR_materials_specular") {
        let factor = e.number("specularFactor", 1.0, &|x| (0.0..=1.0).contains(&x))?;
        let colour = e.colour("specularColorFactor", [1.0; 3])?;
        layers.specular = Some(SpecularDesc {
            factor,
            texture: e.alpha("specularTexture", factor)?,
            color: e.spectrum(
                "specularColorFactor",
                "specularColorTexture",
                colour,
                upsampler,
            )?,
        });
    }
    if let Some(e) = extension("KHR_materials_anisotropy") {
        let strength = e.number("anisotropyStrength", 0.0, &|x| (0.0..=1.0).contains(&x))?;
        let rotation = e.number("anisotropyRotation", 0.0, &|_| true)?;
        let texture = e.data("anisotropyTexture", [1.0; 3])?;
        if strength > 0.0 {
            layers.anisotropy = Some(AnisotropyDesc {
                strength,
                rotation,
                texture,
            });
        }
    }
    if let Some(e) = extension("KHR_materials_clearcoat") {
        let factor = e.number("clearcoatFactor", 0.0, &|x| (0.0..=1.0).contains(&x))?;
        let roughness = e.number("clearcoatRoughnessFactor", 0.0, &|x| {
            (0.0..=1.0).contains(&x)
        })?;
        let normal_texture = match e.json.get("clearcoatNormalTexture") {
            Some(r) => {
                let scale = r.get("scale").and_then(|s| s.as_f64()).unwrap_or(1.0) as f32;
                let texture = textures
                    .extension_texture(r, [1.0; 3], sets)
                    .map_err(|err| e.error(format!("clearcoatNormalTexture: {err}")))?;
                Some(Arc::new(NormalMap::new(texture, scale).map_err(|err| {
                    e.error(format!("clearcoatNormalTexture: {err}"))
                })?))
            }
            None => None,
        };
        if factor > 0.0 {
            layers.clearcoat = Some(ClearcoatDesc {
                factor,
                texture: e.data("clearcoatTexture", [1.0; 3])?,
                roughness,
                roughness_texture: e.data("clearcoatRoughnessTexture", [1.0; 3])?,
                normal_texture,
            });
        }
    }
    if let Some(e) = extension("KHR_materials_sheen") {
        let colour = e.colour("sheenColorFactor", [0.0; 3])?;
        let roughness = e.number("sheenRoughnessFactor", 0.0, &|x| (0.0..=1.0).contains(&x))?;
        if colour.iter().any(|&c| c > 0.0) {
            layers.sheen = Some(SheenDesc {
                color: e.spectrum(
                    "sheenColorFactor",
                    "sheenColorTexture",
                    colour.map(|c| c.min(1.0)),
                    upsampler,
                )?,
                roughness,
                roughness_texture: e.alpha("sheenRoughnessTexture", roughness)?,
            });
        }
    }
    if let Some(e) = extension("KHR_materials_diffuse_transmission") {
        let factor = e.number("diffuseTransmissionFactor", 0.0, &|x| {
            (0.0..=1.0).contains(&x)
        })?;
        let colour = e.colour("diffuseTransmissionColorFactor", [1.0; 3])?;
        if factor > 0.0 {
            layers.diffuse_transmission = Some(DiffuseTransmissionDesc {
                factor,
                texture: e.alpha("diffuseTransmissionTexture", factor)?,
                color: e.spectrum(
                    "diffuseTransmissionColorFactor",
                    "diffuseTransmissionColorTexture",
                    colour.map(|c| c.min(1.0)),
                    upsampler,
                )?,
                absorption: volume.clone(),
            });
        }
    }
    Ok((!layers.is_empty()).then_some(layers))
}
