//! glTF materials in spectral form: RGB factors become sigmoid-polynomial spectra here (RGB
//! stops at the scene), constant colours by an exact fit rather than a table.

use std::sync::Arc;

use prism_spectrum::color::RgbSpaceId;
use prism_spectrum::spectra::DenselySampled;
use prism_upsample::{CoefficientTable, FitContext, RgbKind, RgbSpectrum, normalized_illuminant};

use super::LoadError;
use super::prism_spectral::{self, SpectralMaterial};
use crate::materials::{Alpha, AlphaMode, IridescenceDesc, Layers, NormalMap};
use crate::textures::{RgbTexture, SceneSpectrum};

use super::tex_coord_sets::TexCoordSets;
use super::textures::TextureLoader;

/// A glTF metallic-roughness material, spectral.
#[derive(Debug, Clone)]
pub struct MaterialDesc {
    /// The material's name (or `material N`).
    pub name: String,
    /// baseColorFactor (linear sRGB) as a reflectance spectrum.
    pub base_color: RgbSpectrum,
    /// metallicFactor in [0, 1].
    pub metallic: f32,
    /// roughnessFactor in [0, 1] (perceptual; alpha = roughness^2).
    pub roughness: f32,
    /// Index of refraction (`KHR_materials_ior`, default 1.5).
    pub ior: f32,
    /// transmissionFactor (`KHR_materials_transmission`, default 0).
    pub transmission: f32,
    /// transmissionTexture (linear; red multiplies the factor).
    pub transmission_texture: Option<Arc<RgbTexture>>,
    /// Whether transmission is thin-walled: no `KHR_materials_volume` (or a thickness of
    /// 0) and no `KHR_materials_dispersion` (which only a volume can show, so a file
    /// asking for it means a volume).
    pub thin_walled: bool,
    /// Whether the base colour is white (factor 1, no texture): clear glass, untinted.
    pub base_white: bool,
    /// emissiveFactor times `KHR_materials_emissive_strength` as an emission spectrum
    /// (sigmoid times the D65 illuminant normalized to luminance 1, so its XYZ is the
    /// colour's), or None when black.
    pub emission: Option<RgbSpectrum>,
    /// Whether both faces are front faces (emission from both sides).
    pub double_sided: bool,
    /// Whether a base colour texture is referenced.
    pub has_base_color_texture: bool,
    /// The base colour texture times baseColorFactor, as reflectance spectra (replaces
    /// `base_color` where present).
    pub base_color_texture: Option<SceneSpectrum>,
    /// The metallic-roughness texture with the two factors folded in (see
    /// [`crate::materials::Material::MetallicRoughness`]); it replaces `metallic` and
    /// `roughness` where present, except for transmissive materials (glass keeps the
    /// roughness factor).
    pub metallic_roughness_texture: Option<Arc<RgbTexture>>,
    /// The normal texture, which tilts shading normals (the mesh's tangents orient it).
    pub normal_texture: Option<Arc<NormalMap>>,
    /// The emissive texture times emissiveFactor and the strength, as emission spectra
    /// (replaces `emission` where present; None when the factor is black).
    pub emissive_texture: Option<SceneSpectrum>,
    /// `KHR_materials_dispersion`'s dispersion, 20 / V_d (0: none), for transmissive
    /// materials.
    pub dispersion: f32,
    /// `KHR_materials_volume` as an absorption coefficient per unit length,
    /// -ln(attenuationColor) / attenuationDistance per wavelength; None for thin walls
    /// (thickness 0), an infinite distance or a white attenuation colour.
    pub absorption: Option<SceneSpectrum>,
    /// `KHR_materials_volume_scatter`: the volume's scattering medium (None without the
    /// extension, a thickness of 0, or an attenuation of nothing). A `PRISM_spectral`
    /// medium replaces it.
    pub medium: Option<crate::medium::Medium>,
    /// The `PRISM_spectral` description, if the material (or an overlay) has one.
    pub spectral: Option<SpectralMaterial>,
    /// Alpha coverage (`alphaMode` MASK or BLEND), None for OPAQUE.
    pub alpha: Option<Alpha>,
    /// `KHR_materials_iridescence`: a thin film over the surface (None without the
    /// extension or with a factor of 0).
    pub iridescence: Option<IridescenceDesc>,
    /// `KHR_materials_specular`, `_anisotropy`, `_clearcoat` and `_sheen` (None without
    /// any of them).
    pub layers: Option<Layers>,
    /// The brightest channel of the RGB it emits (emissiveFactor times the strength, or
    /// an unlit base colour): at most 1 is a glow (a screen, an indicator), not a lamp.
    pub emission_peak: f32,
}

impl MaterialDesc {
    /// A material that is `surface`, emitting `emission` from its front faces where given
    /// (as another scene format than glTF describes its materials): no glTF factor,
    /// texture or extension; its base colour, which only previews read, is grey.
    pub(crate) fn surface(
        name: String,
        surface: crate::materials::Material,
        emission: Option<SceneSpectrum>,
        upsampler: &Upsampler,
    ) -> Result<Self, LoadError> {
        let base_color = upsampler
            .fit([0.5; 3], RgbKind::Albedo)
            .map_err(|e| LoadError::Geometry(format!("material {name}: {e}")))?;
        Ok(Self {
            name,
            base_color,
            metallic: 0.0,
            roughness: 1.0,
            ior: 1.5,
            transmission: 0.0,
            transmission_texture: None,
            thin_walled: false,
            base_white: false,
            emission: None,
            double_sided: false,
            has_base_color_texture: false,
            base_color_texture: None,
            metallic_roughness_texture: None,
            normal_texture: None,
            emissive_texture: None,
            dispersion: 0.0,
            absorption: None,
            medium: None,
            spectral: Some(SpectralMaterial {
                surface: Some(surface),
                emission,
                ..SpectralMaterial::default()
            }),
            alpha: None,
            iridescence: None,
            layers: None,
            emission_peak: 0.0,
        })
    }

    /// Whether the material emits light (an RGB emissive colour or a spectral emission).
    pub fn emits(&self) -> bool {
        self.emission.is_some() || self.spectral.as_ref().is_some_and(|s| s.emission.is_some())
    }

    /// What the material emits: its `PRISM_spectral` emission, else its emissive texture,
    /// else its emissive colour (None where it does not emit).
    pub fn emission_spectrum(&self) -> Option<SceneSpectrum> {
        if let Some(s) = self.spectral.as_ref().and_then(|s| s.emission.clone()) {
            return Some(s);
        }
        match (&self.emissive_texture, &self.emission) {
            (Some(texture), _) => Some(texture.clone()),
            (None, Some(rgb)) => Some(SceneSpectrum::Rgb(Arc::new(rgb.clone()))),
            (None, None) => None,
        }
    }
}

/// `KHR_materials_dispersion`'s `dispersion` (the gltf crate does not know the extension, so
/// it is read from the raw JSON): 0 when absent; an error when not a finite number >= 0.
fn dispersion(material: &gltf::Material, name: &str) -> Result<f32, LoadError> {
    let Some(ext) = material
        .extensions()
        .and_then(|e| e.get("KHR_materials_dispersion"))
    else {
        return Ok(0.0);
    };
    match ext.get("dispersion") {
        None => Ok(0.0),
        Some(v) => match v.as_f64() {
            Some(d) if d.is_finite() && d >= 0.0 && d <= f64::from(f32::MAX) => Ok(d as f32),
            _ => Err(LoadError::Geometry(format!(
                "material {name}: KHR_materials_dispersion dispersion {v} must be a finite number >= 0"
            ))),
        },
    }
}

/// Beer-Lambert absorption from `KHR_materials_volume`: the colour (linear sRGB) is what
/// remains after `distance`, so sigma(l) = -ln(c(l)) / distance with c upsampled as a
/// reflectance (tabulated at 1 nm over 300-830 nm, clamped so black stays finite).
fn volume_absorption(
    color: [f32; 3],
    distance: f32,
    upsampler: &Upsampler,
) -> Result<Option<SceneSpectrum>, String> {
    let Some(c) = attenuation(color, distance, upsampler)? else {
        return Ok(None);
    };
    let sigma: Vec<f64> = (300..=830)
        .map(|nm| extinction(&c, distance, f64::from(nm)))
        .collect();
    let dense = DenselySampled::from_values(300.0, sigma).map_err(|e| e.to_string())?;
    Ok(Some(SceneSpectrum::Dense(Arc::new(dense))))
}

/// `KHR_materials_volume`'s attenuation colour upsampled as a reflectance; None where it
/// attenuates nothing (an infinite distance or a white colour). A distance that is not
/// positive or a colour that is not finite is an error.
pub(super) fn attenuation(
    color: [f32; 3],
    distance: f32,
    upsampler: &Upsampler,
) -> Result<Option<RgbSpectrum>, String> {
    if distance.is_nan() || distance <= 0.0 || !color.iter().all(|c| c.is_finite()) {
        return Err(format!(
            "KHR_materials_volume attenuationDistance {distance} must be > 0 and the colour finite"
        ));
    }
    if distance.is_infinite() || color.iter().all(|&c| c >= 1.0) {
        return Ok(None);
    }
    upsampler
        .fit(color.map(f64::from), RgbKind::Albedo)
        .map(Some)
}

/// The extinction -ln(c(nm)) / distance of an attenuation colour `c` (black clamped so
/// that it stays finite).
pub(super) fn extinction(c: &RgbSpectrum, distance: f32, nm: f64) -> f64 {
    use prism_spectrum::Spectrum;
    -c.evaluate(nm).max(1e-6).ln() / f64::from(distance)
}

/// How a scene's constant RGB colours become spectra: the speed-accuracy trade of
/// upsampling (`prism trade` measures it). Textures always go through a table.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum Upsampling {
    /// An exact fit per colour (the default: colours are few, fits take microseconds).
    #[default]
    Exact,
    /// A trilinear lookup in a table of this resolution (16, 32, 64 or 128).
    Table(usize),
    /// A lookup in a table of this resolution refined by one solver step.
    Refined(usize),
}

impl Upsampling {
    /// Names accepted by [`Upsampling::from_name`].
    pub const NAMES: &'static str =
        "exact, table16, table32, table64, table128, refined16, refined32, refined64, refined128";

    /// Parses `exact`, `tableN` or `refinedN`.
    pub fn from_name(name: &str) -> Result<Self, LoadError> {
        let unknown = || LoadError::UnknownName {
            kind: "upsampling",
            name: name.to_string(),
            valid: Self::NAMES,
        };
        let resolution = |n: &str| match n.parse::<usize>() {
            Ok(r @ (16 | 32 | 64 | 128)) => Ok(r),
            _ => Err(unknown()),
        };
        match name {
            "exact" => Ok(Self::Exact),
            _ if name.starts_with("table") => Ok(Self::Table(resolution(&name[5..])?)),
            _ if name.starts_with("refined") => Ok(Self::Refined(resolution(&name[7..])?)),
            _ => Err(unknown()),
        }
    }

    /// The name [`Upsampling::from_name`] reads.
    pub fn name(self) -> String {
        match self {
            Upsampling::Exact => "exact".into(),
            Upsampling::Table(r) => format!("table{r}"),
            Upsampling::Refined(r) => format!("refined{r}"),
        }
    }

    /// The table resolution this mode uses, if any.
    fn resolution(self) -> Option<usize> {
        match self {
            Upsampling::Exact => None,
            Upsampling::Table(r) | Upsampling::Refined(r) => Some(r),
        }
    }
}

/// The table textures use when the mode names none: 32^3 renders with nearly the error of
/// exact fits, where 16^3 does not (docs/trade-offs.md, "RGB upsampling"), and it is the
/// resolution prism-upsample ships, so it costs no fitting.
const TEXTURE_TABLE_RESOLUTION: usize = prism_upsample::SHIPPED_RESOLUTION;

/// Everything upsampling needs, built once per load: glTF colours are linear sRGB.
pub(crate) struct Upsampler {
    pub(crate) context: Arc<FitContext>,
    pub(crate) illuminant: Arc<DenselySampled>,
    mode: Upsampling,
    /// The caller's table ([`super::LoadOptions::table`]), used when it fits the mode.
    given: Option<Arc<CoefficientTable>>,
    table: std::cell::OnceCell<Arc<CoefficientTable>>,
}

impl Upsampler {
    /// The coefficient table of the mode's resolution (or the texture default): the
    /// caller's, else the one prism-upsample ships, else fitted on first use.
    pub(crate) fn table(&self) -> Result<Arc<CoefficientTable>, String> {
        if let Some(t) = self.table.get() {
            return Ok(t.clone());
        }
        let table = match (&self.given, self.mode.resolution()) {
            (Some(given), wanted) => {
                if !given.space().matches(&self.context) {
                    return Err(format!(
                        "the coefficient table given is for '{}', not linear sRGB",
                        given.space().name
                    ));
                }
                if let Some(r) = wanted.filter(|r| *r != given.resolution()) {
                    return Err(format!(
                        "the coefficient table given is {0}^3; upsampling {1} needs {r}^3",
                        given.resolution(),
                        self.mode.name()
                    ));
                }
                given.clone()
            }
            (None, wanted) => {
                let resolution = wanted.unwrap_or(TEXTURE_TABLE_RESOLUTION);
                match CoefficientTable::shipped(RgbSpaceId::Srgb)
                    .filter(|t| t.resolution() == resolution)
                {
                    Some(shipped) => shipped,
                    None => Arc::new(
                        CoefficientTable::fit(&self.context, resolution, &|_| {})
                            .map_err(|e| format!("fitting the sRGB upsampling table: {e}"))?
                            .0,
                    ),
                }
            }
        };
        Ok(self.table.get_or_init(|| table).clone())
    }

    pub(crate) fn new(
        mode: Upsampling,
        given: Option<Arc<CoefficientTable>>,
    ) -> Result<Self, LoadError> {
        let id = RgbSpaceId::Srgb;
        let to_error = |e: prism_upsample::UpsampleError| {
            LoadError::Geometry(format!("upsampling setup: {e}"))
        };
        Ok(Self {
            context: Arc::new(FitContext::new(id.space(), &id.illuminant()).map_err(to_error)?),
            illuminant: normalized_illuminant(&id.illuminant()).map_err(to_error)?,
            mode,
            given,
            table: std::cell::OnceCell::new(),
        })
    }

    /// A linear sRGB colour as a spectrum of `kind` (illuminants under the space's white).
    pub(crate) fn fit(&self, rgb: [f64; 3], kind: RgbKind) -> Result<RgbSpectrum, String> {
        let illuminant = (kind == RgbKind::Illuminant).then(|| self.illuminant.clone());
        let result = match self.mode {
            Upsampling::Exact => RgbSpectrum::fit(&self.context, rgb, kind, illuminant),
            Upsampling::Table(_) | Upsampling::Refined(_) => {
                let steps = u32::from(matches!(self.mode, Upsampling::Refined(_)));
                RgbSpectrum::from_table(
                    &*self.table()?,
                    &self.context,
                    rgb,
                    kind,
                    illuminant,
                    steps,
                )
            }
        };
        result.map_err(|e| format!("colour {rgb:?}: {e}"))
    }

    /// A linear sRGB emission colour as an illuminant spectrum.
    pub(crate) fn emission(&self, rgb: [f64; 3]) -> Result<RgbSpectrum, LoadError> {
        self.fit(rgb, RgbKind::Illuminant)
            .map_err(|e| LoadError::Geometry(format!("emission {e}")))
    }
}

fn finite(name: &str, what: &str, values: &[f32]) -> Result<(), LoadError> {
    match values.iter().find(|v| !v.is_finite()) {
        Some(v) => Err(LoadError::Geometry(format!(
            "material {name}: {what} {v} is not finite"
        ))),
        None => Ok(()),
    }
}

/// The spectral description of `material`.
pub(crate) fn material(
    material: &gltf::Material,
    cx: &prism_spectral::Context,
    textures: &TextureLoader,
) -> Result<MaterialDesc, LoadError> {
    let upsampler = cx.upsampler;
    let name = material.name().map_or_else(
        || format!("material {}", material.index().map_or(-1, |i| i as i64)),
        str::to_string,
    );
    let pbr = material.pbr_metallic_roughness();
    let (base, base_texture) = base_colour(material);
    let sets = TexCoordSets::of(material);
    // KHR_materials_pbrSpecularGlossiness (older assets): a dielectric whose roughness is
    // 1 - glossiness; its specular colour and texture are not read.
    let spec_gloss = material.pbr_specular_glossiness();
    let (metallic, roughness) = match &spec_gloss {
        Some(sg) => (0.0, 1.0 - sg.glossiness_factor()),
        None => (pbr.metallic_factor(), pbr.roughness_factor()),
    };
    let metallic_roughness_info = match spec_gloss {
        Some(_) => None,
        None => pbr.metallic_roughness_texture(),
    };
    let emissive = material.emissive_factor();
    let strength = material.emissive_strength().unwrap_or(1.0);
    let ior = material.ior().unwrap_or(1.5);
    let transmission = material
        .transmission()
        .map_or(0.0, |t| t.transmission_factor());
    finite(&name, "baseColorFactor component", &base)?;
    finite(&name, "metallic/roughness factor", &[metallic, roughness])?;
    finite(
        &name,
        "emissive factor or strength",
        &[emissive[0], emissive[1], emissive[2], strength],
    )?;
    finite(&name, "ior or transmission", &[ior, transmission])?;
    if ior < 1.0 {
        return Err(LoadError::Geometry(format!(
            "material {name}: ior {ior} is below 1"
        )));
    }
    let rgb = |c: [f32; 3]| c.map(f64::from);
    let fit = |c: [f64; 3], kind: RgbKind| {
        upsampler
            .fit(c, kind)
            .map_err(|e| LoadError::Geometry(format!("material {name}: {e}")))
    };
    let base_color = fit(rgb([base[0], base[1], base[2]]), RgbKind::Albedo)?;
    let emitted = rgb(emissive).map(|c| c * f64::from(strength.max(0.0)));
    let emission = if emitted.iter().all(|&c| c <= 0.0) {
        None
    } else {
        Some(fit(emitted, RgbKind::Illuminant)?)
    };
    let unit = |v: f32| v.clamp(0.0, 1.0);
    let dispersion = dispersion(material, &name)?;
    let spectral = material
        .extension_value(prism_spectral::EXTENSION)
        .map(|v| prism_spectral::material(v, cx))
        .transpose()
        .map_err(|e| LoadError::Spectral(format!("material {name}: {e}")))?;
    // With KHR_materials_volume_scatter the volume's attenuation is a scattering medium's
    // extinction; without it, Beer-Lambert absorption.
    let scatter = material.extension_value("KHR_materials_volume_scatter");
    let (absorption, medium) = match material.volume() {
        Some(v) if v.thickness_factor() > 0.0 => match scatter {
            Some(ext) => (
                None,
                super::volume_scatter::medium(
                    ext,
                    v.attenuation_color(),
                    v.attenuation_distance(),
                    upsampler,
                )
                .map_err(|e| LoadError::Geometry(format!("material {name}: {e}")))?,
            ),
            None => (
                volume_absorption(v.attenuation_color(), v.attenuation_distance(), upsampler)
                    .map_err(|e| LoadError::Geometry(format!("material {name}: {e}")))?,
                None,
            ),
        },
        _ => (None, None),
    };
    let base_color_texture = base_texture
        .as_ref()
        .map(|info| textures.base_color(info, [base[0], base[1], base[2]], &sets))
        .transpose()
        .map_err(|e| LoadError::Geometry(format!("material {name}: {e}")))?;
    let metallic_roughness_texture = metallic_roughness_info
        .map(|info| {
            textures
                .metallic_roughness(&info, unit(metallic), unit(roughness), &sets)
                .map(Arc::new)
        })
        .transpose()
        .map_err(|e| LoadError::Geometry(format!("material {name}: {e}")))?;
    let emissive_texture = match (&emission, material.emissive_texture()) {
        (Some(_), Some(info)) => Some(
            textures
                .emission(&info, emitted.map(|c| c as f32), &sets)
                .map_err(|e| LoadError::Geometry(format!("material {name}: {e}")))?,
        ),
        _ => None,
    };
    let normal_texture = material
        .normal_texture()
        .map(|normal| textures.normal(&normal, &sets).map(Arc::new))
        .transpose()
        .map_err(|e| LoadError::Geometry(format!("material {name}: {e}")))?;
    let alpha = alpha(material, base_texture.as_ref(), textures, &sets, base[3])
        .map_err(|e| LoadError::Geometry(format!("material {name}: {e}")))?;
    let emission_peak = emitted.iter().fold(0.0f64, |a, &c| a.max(c)) as f32;
    let iridescence = iridescence(material, textures, &sets).map_err(|e| {
        LoadError::Geometry(format!("material {name}: KHR_materials_iridescence: {e}"))
    })?;
    let layers =
        super::material_layers::layers(material, textures, &sets, upsampler, absorption.clone())
            .map_err(|e| LoadError::Geometry(format!("material {name}: {e}")))?;
    let (layers, iridescence) = spectral_layers(spectral.as_ref(), layers, iridescence)
        .map_err(|e| LoadError::Spectral(format!("material {name}: {e}")))?;
    let transmission_texture = material
        .transmission()
        .and_then(|t| t.transmission_texture())
        .map(|info| textures.linear(&info, [1.0; 3], &sets).map(Arc::new))
        .transpose()
        .map_err(|e| LoadError::Geometry(format!("material {name}: transmissionTexture: {e}")))?;
    let thin_walled = dispersion == 0.0
        && material
            .volume()
            .is_none_or(|v| v.thickness_factor() <= 0.0);
    let desc = MaterialDesc {
        transmission_texture,
        thin_walled,
        base_white: base_texture.is_none() && base[..3].iter().all(|&c| c == 1.0),
        layers,
        iridescence,
        emission_peak,
        alpha,
        name,
        base_color,
        metallic: unit(metallic),
        roughness: unit(roughness),
        ior,
        transmission: unit(transmission),
        emission,
        double_sided: material.double_sided(),
        has_base_color_texture: base_texture.is_some(),
        base_color_texture,
        metallic_roughness_texture,
        normal_texture,
        emissive_texture,
        absorption,
        medium,
        dispersion,
        spectral,
    };
    if material.unlit() {
        return unlit(desc, material, textures, upsampler);
    }
    Ok(desc)
}

/// `PRISM_spectral`'s measured spectra in place of the extensions' colours and index: a
/// sheen colour (the material needs `KHR_materials_sheen`), a specular colour (adding
/// `KHR_materials_specular` at its defaults where absent), a film index (the material
/// needs `KHR_materials_iridescence`).
fn spectral_layers(
    spectral: Option<&SpectralMaterial>,
    layers: Option<Layers>,
    mut iridescence: Option<IridescenceDesc>,
) -> Result<(Option<Layers>, Option<IridescenceDesc>), String> {
    let Some(spectral) = spectral else {
        return Ok((layers, iridescence));
    };
    let mut layers = layers.unwrap_or_default();
    if let Some(color) = &spectral.sheen_color {
        let sheen = layers
            .sheen
            .as_mut()
            .ok_or("PRISM_spectral sheen_color needs KHR_materials_sheen (with a sheen colour) on the material")?;
        sheen.color = color.clone();
    }
    if let Some(color) = &spectral.specular_color {
        let specular = layers
            .specular
            .get_or_insert(crate::materials::SpecularDesc {
                factor: 1.0,
                texture: None,
                color: SceneSpectrum::Constant(1.0),
            });
        specular.color = color.clone();
    }
    if let Some(ior) = &spectral.film_ior {
        let film = iridescence
            .as_mut()
            .ok_or("PRISM_spectral film_ior needs KHR_materials_iridescence on the material")?;
        film.ior_spectrum = Some(ior.clone());
    }
    Ok(((!layers.is_empty()).then_some(layers), iridescence))
}

/// `KHR_materials_iridescence` (the gltf crate does not know it; read from the raw JSON):
/// None without it or with a factor of 0; an error for a value that is not a finite
/// number in its range (factor in [0, 1], index > 0, thicknesses >= 0).
fn iridescence(
    material: &gltf::Material,
    textures: &TextureLoader,
    sets: &TexCoordSets,
) -> Result<Option<IridescenceDesc>, String> {
    let Some(ext) = material.extension_value("KHR_materials_iridescence") else {
        return Ok(None);
    };
    let number = |key: &str, default: f32, valid: &dyn Fn(f32) -> bool| -> Result<f32, String> {
        match ext.get(key) {
            None => Ok(default),
            Some(v) => match v.as_f64().map(|x| x as f32) {
                Some(x) if x.is_finite() && valid(x) => Ok(x),
                _ => Err(format!("{key} {v} is out of range")),
            },
        }
    };
    let factor = number("iridescenceFactor", 0.0, &|x| (0.0..=1.0).contains(&x))?;
    let ior = number("iridescenceIor", 1.3, &|x| x > 0.0)?;
    let thickness_min_nm = number("iridescenceThicknessMinimum", 100.0, &|x| x >= 0.0)?;
    let thickness_max_nm = number("iridescenceThicknessMaximum", 400.0, &|x| x >= 0.0)?;
    if factor == 0.0 {
        return Ok(None);
    }
    let texture = |key: &str| {
        ext.get(key)
            .map(|r| textures.extension_texture(r, [1.0; 3], sets).map(Arc::new))
            .transpose()
            .map_err(|e| format!("{key}: {e}"))
    };
    Ok(Some(IridescenceDesc {
        factor,
        factor_texture: texture("iridescenceTexture")?,
        ior,
        thickness_min_nm,
        thickness_max_nm,
        thickness_texture: texture("iridescenceThicknessTexture")?,
        ior_spectrum: None,
    }))
}

/// The base colour factor and texture: `KHR_materials_pbrSpecularGlossiness`'s diffuse
/// ones where the material has that extension, else the metallic-roughness base colour.
pub(super) fn base_colour<'a>(
    material: &gltf::Material<'a>,
) -> ([f32; 4], Option<gltf::texture::Info<'a>>) {
    match material.pbr_specular_glossiness() {
        Some(sg) => (sg.diffuse_factor(), sg.diffuse_texture()),
        None => {
            let pbr = material.pbr_metallic_roughness();
            (pbr.base_color_factor(), pbr.base_color_texture())
        }
    }
}

/// glTF's `alphaMode` (§3.9.4): MASK with `alphaCutoff` (default 0.5) or BLEND, the
/// alpha being baseColorFactor's times the base colour texture's alpha channel; None for
/// OPAQUE.
fn alpha(
    material: &gltf::Material,
    base_texture: Option<&gltf::texture::Info>,
    textures: &TextureLoader,
    sets: &TexCoordSets,
    factor: f32,
) -> Result<Option<Alpha>, String> {
    let mode = match material.alpha_mode() {
        gltf::material::AlphaMode::Opaque => return Ok(None),
        gltf::material::AlphaMode::Mask => {
            let cutoff = material.alpha_cutoff().unwrap_or(0.5);
            if !cutoff.is_finite() {
                return Err(format!("alphaCutoff {cutoff} is not finite"));
            }
            AlphaMode::Mask { cutoff }
        }
        gltf::material::AlphaMode::Blend => AlphaMode::Blend,
    };
    let factor = factor.clamp(0.0, 1.0);
    let texture = base_texture
        .map(|info| textures.alpha(info, factor, sets))
        .transpose()?
        .flatten()
        .map(Arc::new);
    Ok(Some(Alpha {
        mode,
        factor,
        texture,
        opacity: None,
    }))
}

/// `KHR_materials_unlit` as the extension suggests for renderers that light everything
/// physically: the surface emits its base colour (factor times texture, an emissive
/// colour) and reflects nothing, so it is seen with exactly its authored colour.
fn unlit(
    mut desc: MaterialDesc,
    material: &gltf::Material,
    textures: &TextureLoader,
    upsampler: &Upsampler,
) -> Result<MaterialDesc, LoadError> {
    let name = desc.name.clone();
    let error = |e: String| LoadError::Geometry(format!("material {name}: unlit base colour: {e}"));
    let (base, base_texture) = base_colour(material);
    let colour = [base[0], base[1], base[2]];
    desc.emission_peak = colour.iter().fold(0.0f32, |a, &c| a.max(c));
    desc.emission = if colour.iter().all(|&c| c <= 0.0) {
        None
    } else {
        Some(
            upsampler
                .fit(colour.map(f64::from), RgbKind::Illuminant)
                .map_err(error)?,
        )
    };
    desc.emissive_texture = match (&desc.emission, base_texture) {
        (Some(_), Some(info)) => Some(
            textures
                .emission(&info, colour, &TexCoordSets::of(material))
                .map_err(error)?,
        ),
        _ => None,
    };
    desc.base_color = upsampler.fit([0.0; 3], RgbKind::Albedo).map_err(error)?;
    desc.base_color_texture = None;
    desc.metallic_roughness_texture = None;
    desc.normal_texture = None;
    desc.metallic = 0.0;
    desc.roughness = 1.0;
    desc.transmission = 0.0;
    Ok(desc)
}
