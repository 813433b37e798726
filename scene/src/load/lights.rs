//! Lights: emissive instances (area lights) and `KHR_lights_punctual`, whose photometric
//! intensities (candela for point and spot lights, lux for directional ones) become
//! radiometric spectra: the colour is upsampled as an illuminant and scaled so that
//! 683 lm/W times its y-bar integral is the given value.

use glam::{Mat4, Vec3};
use prism_spectrum::optics::radiant_scale_for_luminance;
use std::sync::Arc;

use super::prism_spectral::SpectralLight;
use crate::textures::SceneSpectrum;

use super::LoadError;

/// A light of the scene.
#[derive(Debug, Clone)]
#[non_exhaustive]
pub enum LightDesc {
    /// The triangles of an emissive instance: `instance` indexes
    /// [`super::LoadedGeometry::instances`]; they emit from their front face only unless
    /// `double_sided`.
    Area {
        /// The instance.
        instance: usize,
        /// Whether both faces emit.
        double_sided: bool,
    },
    /// A point light with spectral radiant intensity `intensity` (W sr^-1 nm^-1 = the
    /// spectrum times `scale`).
    Point {
        /// Position.
        position: Vec3,
        /// Spectral shape (illuminant kind).
        spectrum: SceneSpectrum,
        /// Factor making the spectrum radiant intensity.
        scale: f64,
    },
    /// A spot light: a point light limited to a cone around `direction`, with glTF's
    /// smooth falloff between the inner and outer cone angles.
    Spot {
        /// Position.
        position: Vec3,
        /// Unit direction of the cone's axis.
        direction: Vec3,
        /// Inner cone angle, radians.
        inner: f32,
        /// Outer cone angle, radians.
        outer: f32,
        /// Spectral shape.
        spectrum: SceneSpectrum,
        /// Factor making the spectrum radiant intensity on the axis.
        scale: f64,
        /// How the intensity falls off between the cones.
        falloff: crate::lights::SpotFalloff,
        /// A texture it projects (None: none).
        texture: Option<std::sync::Arc<crate::lights::SpotTexture>>,
    },
    /// A directional light arriving along -`direction`... with spectral irradiance
    /// (W m^-2 nm^-1) the spectrum times `scale`.
    Directional {
        /// Unit direction the light travels in.
        direction: Vec3,
        /// Spectral shape.
        spectrum: SceneSpectrum,
        /// Factor making the spectrum irradiance.
        scale: f64,
    },
}

/// Below this luminous efficacy (lm/W; a 750 nm LED has about 0.1, the eye's peak 683) a
/// photometric intensity would scale the spectrum by an absurd factor.
const MIN_PHOTOMETRIC_EFFICACY: f64 = 0.01;

/// Luminous flux per watt of `spectrum`, its radiant power integrated at 1 nm over
/// 200-2500 nm.
fn luminous_efficacy(spectrum: &SceneSpectrum) -> f64 {
    use prism_spectrum::Spectrum;
    let radiant: f64 = (200..=2500)
        .map(|nm| spectrum.evaluate(f64::from(nm)))
        .sum();
    if radiant > 0.0 {
        prism_spectrum::optics::luminous_flux(spectrum) / radiant
    } else {
        0.0
    }
}

/// The punctual light of `node` placed by `world`.
pub(crate) fn punctual(
    node: &gltf::Node,
    light: &gltf::khr_lights_punctual::Light,
    world: Mat4,
    fit: &dyn Fn([f64; 3]) -> Result<prism_upsample::RgbSpectrum, LoadError>,
    spectral: Option<SpectralLight>,
) -> Result<LightDesc, LoadError> {
    let name = node
        .name()
        .map_or_else(|| format!("node {}", node.index()), str::to_string);
    let color = light.color();
    let intensity = light.intensity();
    if !(color.iter().all(|c| c.is_finite() && *c >= 0.0)
        && intensity.is_finite()
        && intensity >= 0.0)
    {
        return Err(LoadError::Geometry(format!(
            "light {name}: colour {color:?} and intensity {intensity} must be finite and >= 0"
        )));
    }
    let (spectrum, radiometric) = match spectral {
        Some(s) => (s.spectrum, s.radiometric),
        None if color.iter().all(|&c| c == 0.0) => (SceneSpectrum::Constant(0.0), true),
        None => (
            SceneSpectrum::Rgb(Arc::new(fit(color.map(f64::from))?)),
            false,
        ),
    };
    // Photometric -> radiometric: the intensity is the photometric value of the spectrum.
    let scale = if radiometric || intensity == 0.0 {
        f64::from(intensity)
    } else {
        let efficacy = luminous_efficacy(&spectrum);
        if efficacy.is_nan() || efficacy < MIN_PHOTOMETRIC_EFFICACY {
            return Err(LoadError::Geometry(format!(
                "light {name}: its spectrum's luminous efficacy is {efficacy:.3e} lm/W, too little light for a photometric intensity to mean anything (a UV or infrared source needs \"units\": \"radiometric\")"
            )));
        }
        radiant_scale_for_luminance(&spectrum, f64::from(intensity))
            .map_err(|e| LoadError::Geometry(format!("light {name}: {e}")))?
    };
    let position = world.transform_point3(Vec3::ZERO);
    // glTF lights point down their node's -z.
    let direction = world.transform_vector3(-Vec3::Z).normalize_or(-Vec3::Z);
    Ok(match light.kind() {
        gltf::khr_lights_punctual::Kind::Point => LightDesc::Point {
            position,
            spectrum,
            scale,
        },
        gltf::khr_lights_punctual::Kind::Directional => LightDesc::Directional {
            direction,
            spectrum,
            scale,
        },
        gltf::khr_lights_punctual::Kind::Spot {
            inner_cone_angle,
            outer_cone_angle,
        } => {
            if !(0.0 <= inner_cone_angle
                && inner_cone_angle < outer_cone_angle
                && outer_cone_angle <= std::f32::consts::FRAC_PI_2)
            {
                return Err(LoadError::Geometry(format!(
                    "light {name}: spot cone angles {inner_cone_angle}, {outer_cone_angle} must satisfy 0 <= inner < outer <= pi/2"
                )));
            }
            LightDesc::Spot {
                position,
                direction,
                inner: inner_cone_angle,
                outer: outer_cone_angle,
                spectrum,
                scale,
                falloff: crate::lights::SpotFalloff::Smooth,
                texture: None,
            }
        }
    })
}
