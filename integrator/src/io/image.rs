//! Encoding a film as image bytes: OpenEXR (linear f32 RGB in a chosen space, with the
//! chromaticities attribute so readers know which) and PNG (exposure, tone map, the
//! space's transfer function, 8 bits). Bytes only: writing files is the caller's.

#[cfg(feature = "exr")]
use std::io::Cursor;

#[cfg(feature = "exr")]
use exr::meta::attribute::AttributeValue;
#[cfg(feature = "exr")]
use exr::prelude::{
    AnyChannel, AnyChannels, Encoding, FlatSamples, Image, Layer, LayerAttributes, SmallVec, Text,
    Vec2, WritableImage,
};
use prism_spectrum::color::{RgbColorSpace, ToneMap, display_8bit};
#[cfg(feature = "exr")]
use prism_spectrum::saturating_f32;

use crate::Film;
#[cfg(feature = "exr")]
use crate::RenderError;

/// Extra facts recorded in an EXR header.
#[cfg(feature = "exr")]
#[derive(Debug, Clone, Default)]
#[non_exhaustive]
pub struct ExrMetadata {
    /// Samples per pixel the image holds.
    pub spp: u64,
    /// Further `key=value` facts (no `;` or `=` in them), recorded after `spp=N` in the
    /// `comments` attribute as `prism: spp=N;key=value;...`.
    pub strings: Vec<(String, String)>,
}

#[cfg(feature = "exr")]
crate::settings::setters!(ExrMetadata {
    spp: u64,
    strings: Vec<(String, String)>,
});

/// The film as a linear RGB EXR in `space`, f32 channels R, G, B, and A: each pixel's
/// coverage, the fraction of its camera rays that met geometry (the environment or the
/// void behind the rest still shows in R, G and B); for a spectral film
/// also one channel per band in the spectral OpenEXR layout of Fichet, Pacanowski and
/// Wilkie ("An OpenEXR layout for spectral images", JCGT 10(3), 2021): `S0.<nm>nm` with
/// the wavelength written with a decimal comma (`S0.560,000000nm`), spectral radiance in
/// W m^-2 sr^-1 nm^-1, the attributes `spectralLayoutVersion` = "1.0" and `emissiveUnits`
/// = "W.m^-2.sr^-1", and R, G, B as the preview.
///
/// A film that records energy adds `energy.radiance` (W m^-2 sr^-1 over the rendered
/// wavelength range), `energy.eV` (the same in eV s^-1 m^-2 sr^-1) and `energy.photons`
/// (photons s^-1 m^-2 sr^-1).
///
/// A polarized spectral film writes the bands of every Stokes component, `S0.<nm>nm` to
/// `S3.<nm>nm` (the layout's polarized form), besides S0..S3 in RGB. The layout's
/// `polarisationHandedness` attribute is not written: both attribute maps already hold
/// their one entry (see below). prism's S3 sign is Mitsuba 3's (S3 > 0: positive
/// helicity about the direction of travel, as `polarization`'s documentation defines).
///
/// A polarized film adds the Stokes components as RGB images in `space`, `S0.R`, `S0.G`,
/// `S0.B` (equal to R, G, B), `S1.R`, ..., `S3.B`: the layout Mitsuba 3's `stokes`
/// integrator writes, in the same camera frame (x = ray x camera up, so S1 > 0 is light
/// polarized along the image's rows, S2 > 0 along the diagonal from its bottom left to
/// top right, S3 > 0 circular of positive helicity about the direction of travel).
///
/// A film with AOVs adds their layers (`albedo.R`, ..., `normal.X`, ..., `depth.Z`,
/// `position.X`, ..., `material_id.ID`, `variance.R`, ...; see [`crate::Aovs`]).
///
/// prism's facts (`spp=N;...`) go in the typed `comments` attribute: the exr crate keeps
/// other attributes in a HashMap whose order changes per process, so each of its maps holds
/// at most one entry and the file's bytes stay a function of the image.
///
/// ```
/// # use prism_integrator::glam::Vec3;
/// # use prism_integrator::prism_scene::camera::Camera;
/// # use prism_integrator::prism_scene::world::{Material, SceneBuilder, SceneSpectrum};
/// # let v = Vec3::new;
/// # let mut builder = SceneBuilder::new(Camera::look_at(v(0.0, 1.0, 3.0), Vec3::ZERO, Vec3::Y, 0.8));
/// # let grey = builder.material(Material::Diffuse { reflectance: SceneSpectrum::Constant(0.5) });
/// # builder.triangles(&[[v(-2.0, 0.0, 2.0), v(2.0, 0.0, 2.0), v(2.0, 0.0, -2.0)], [v(-2.0, 0.0, 2.0), v(2.0, 0.0, -2.0), v(-2.0, 0.0, -2.0)]], grey);
/// # builder.emitter(&[[v(-0.5, 2.0, -0.5), v(0.5, 2.0, -0.5), v(0.5, 2.0, 0.5)]], SceneSpectrum::Constant(1.0), false);
/// # let scene = builder.build().unwrap();
/// use prism_integrator::{compare_images, decode_exr, encode_exr, render, ExrMetadata, RenderSettings};
/// use prism_spectrum::color::RgbSpaceId;
///
/// let settings = RenderSettings::default().width(8).height(6).samples(0..4);
/// let (film, _) = render(&scene, &settings)?;
/// let metadata = ExrMetadata::default().spp(4);
/// let bytes = encode_exr(&film, RgbSpaceId::Srgb.space(), &metadata)?;
/// let image = decode_exr(&bytes)?;
/// assert_eq!((image.width, image.height), (8, 6));
/// assert!(["R", "G", "B", "A"].iter().all(|c| image.channels.iter().any(|(n, _)| n == c)));
/// // An image compared with itself has no error.
/// let same = compare_images(&image, &image)?;
/// assert!(same.relmse == 0.0);
/// # Ok::<(), prism_integrator::RenderError>(())
/// ```
#[cfg(feature = "exr")]
pub fn encode_exr(
    film: &Film,
    space: &RgbColorSpace,
    metadata: &ExrMetadata,
) -> Result<Vec<u8>, RenderError> {
    let (w, h) = (film.width() as usize, film.height() as usize);
    let rgb = film.to_rgb(space);
    let channel = |name: &str, k: usize| {
        AnyChannel::new(name, FlatSamples::F32(rgb.iter().map(|p| p[k]).collect()))
    };
    let mut list = vec![
        channel("R", 0),
        channel("G", 1),
        channel("B", 2),
        AnyChannel::new("A", FlatSamples::F32(film.alphas())),
    ];
    if let Some(bands) = film.bands() {
        let n = film.samples().max(1) as f64;
        let count = bands.count();
        let width = film.spectral_width();
        let sums = film.spectral_sums();
        // Band b of Stokes component k (only S0 unless polarized).
        for i in 0..width {
            let (k, b) = (i / count, i % count);
            let name = format!(
                "S{k}.{}nm",
                format!("{:.6}", bands.center(b)).replace('.', ",")
            );
            let values = (0..w * h)
                .map(|p| saturating_f32(sums[p * width + i] / n))
                .collect();
            list.push(AnyChannel::new(name.as_str(), FlatSamples::F32(values)));
        }
    }
    for k in 1..=3 {
        let Some(component) = film.stokes_rgb(space, k) else {
            break;
        };
        if k == 1 {
            for (c, name) in ["S0.R", "S0.G", "S0.B"].iter().enumerate() {
                list.push(channel(name, c));
            }
        }
        for (c, colour) in ["R", "G", "B"].iter().enumerate() {
            let values = component.iter().map(|p| p[c]).collect();
            list.push(AnyChannel::new(
                format!("S{k}.{colour}").as_str(),
                FlatSamples::F32(values),
            ));
        }
    }
    if film.has_energy() {
        // Radiance over the rendered range in W m^-2 sr^-1, the same in eV s^-1 m^-2
        // sr^-1, and photons s^-1 m^-2 sr^-1.
        let per_pixel: Vec<[f64; 2]> = (0..h as u32)
            .flat_map(|y| (0..w as u32).map(move |x| (x, y)))
            .map(|(x, y)| film.energy(x, y).unwrap_or_default())
            .collect();
        let ev = prism_spectrum::constants::ELEMENTARY_CHARGE;
        for (name, f) in [
            (
                "energy.radiance",
                &(|e: [f64; 2]| e[0]) as &dyn Fn([f64; 2]) -> f64,
            ),
            ("energy.eV", &|e: [f64; 2]| e[0] / ev),
            ("energy.photons", &|e: [f64; 2]| e[1]),
        ] {
            let values = per_pixel.iter().map(|&e| saturating_f32(f(e))).collect();
            list.push(AnyChannel::new(name, FlatSamples::F32(values)));
        }
    }
    for (name, values) in film.aov_images(space) {
        list.push(AnyChannel::new(name.as_str(), FlatSamples::F32(values)));
    }
    let mut facts = format!("spp={}", metadata.spp);
    for (k, v) in &metadata.strings {
        facts.push_str(&format!(";{k}={v}"));
    }
    let mut layer_attributes = LayerAttributes {
        software_name: Some(Text::from("prism")),
        comments: Some(Text::from(format!("prism: {facts}").as_str())),
        ..LayerAttributes::default()
    };
    if film.bands().is_some() {
        layer_attributes.other.insert(
            Text::from("emissiveUnits"),
            AttributeValue::Text(Text::from("W.m^-2.sr^-1")),
        );
    }
    let layer = Layer::new(
        (w, h),
        layer_attributes,
        Encoding::SMALL_LOSSLESS,
        AnyChannels::sort(SmallVec::from_vec(list)),
    );
    let mut image = Image::from_layer(layer);
    let xy = |c: prism_spectrum::colorimetry::Chromaticity| Vec2(c.x as f32, c.y as f32);
    let p = space.primaries();
    image.attributes.chromaticities = Some(exr::meta::attribute::Chromaticities {
        red: xy(p[0]),
        green: xy(p[1]),
        blue: xy(p[2]),
        white: xy(space.white().xy()),
    });
    if film.bands().is_some() {
        image.attributes.other.insert(
            Text::from("spectralLayoutVersion"),
            AttributeValue::Text(Text::from("1.0")),
        );
    }
    let mut bytes = Cursor::new(Vec::new());
    image
        .write()
        .to_buffered(&mut bytes)
        .map_err(|e| RenderError::exr_encode("EXR", e))?;
    Ok(bytes.into_inner())
}

/// How a film becomes a displayable 8-bit picture. The default: exposure 0, Khronos PBR
/// Neutral tone mapping, no alpha channel.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct DisplaySettings {
    /// Exposure in stops (the image is multiplied by 2^exposure).
    pub exposure: f64,
    /// Tone map.
    pub tone_map: ToneMap,
    /// Whether the PNG carries the film's alpha (RGBA, straight alpha: the film's
    /// premultiplied colour divided by its coverage).
    pub alpha: bool,
}

crate::settings::setters!(DisplaySettings {
    exposure: f64,
    tone_map: ToneMap,
    alpha: bool,
});

impl Default for DisplaySettings {
    fn default() -> Self {
        Self {
            exposure: 0.0,
            tone_map: ToneMap::PbrNeutral,
            alpha: false,
        }
    }
}

/// The film as an 8-bit RGB PNG in `space` (encoded with the space's transfer function),
/// or RGBA when `display.alpha`: the colour of each pixel is then its film colour over its
/// coverage (PNG's alpha is straight), tone mapped, and the alpha its coverage.
pub fn encode_png(film: &Film, space: &RgbColorSpace, display: DisplaySettings) -> Vec<u8> {
    encode_png_rgb(
        film.width(),
        film.height(),
        &film.to_rgb(space),
        &film.alphas(),
        space,
        display,
    )
}

/// A `w` x `h` image of linear RGB in `space` (`rgb`, row-major) with its coverage
/// (`alphas`), as [`encode_png`] encodes a film's (a denoised image, say).
pub fn encode_png_rgb(
    w: u32,
    h: u32,
    rgb: &[[f32; 3]],
    alphas: &[f32],
    space: &RgbColorSpace,
    display: DisplaySettings,
) -> Vec<u8> {
    let weights = space.luminance_weights();
    let transfer = space.transfer();
    let channels = if display.alpha { 4 } else { 3 };
    // Each scanline starts with filter type 0 (none).
    let mut raw = Vec::with_capacity((w as usize * channels + 1) * h as usize);
    for (y, row) in rgb.chunks(w.max(1) as usize).enumerate() {
        raw.push(0u8);
        for (x, p) in row.iter().enumerate() {
            let alpha = f64::from(alphas.get(y * w as usize + x).copied().unwrap_or(1.0));
            let unpremultiply = if display.alpha && alpha > 0.0 {
                1.0 / alpha
            } else {
                1.0
            };
            let px = display_8bit(
                p.map(|c| f64::from(c) * unpremultiply),
                display.exposure,
                display.tone_map,
                weights,
                transfer,
            );
            raw.extend_from_slice(&px);
            if display.alpha {
                raw.push((alpha.clamp(0.0, 1.0) * 255.0).round() as u8);
            }
        }
    }
    crate::io::png::encode_8bit(w, h, channels == 4, &raw)
}

/// The polarization of a polarized film as an 8-bit RGB PNG: per pixel, the hue is the
/// angle of linear polarization (0 degrees, along the image's rows: red; 60: yellow; 90,
/// along its columns: cyan; 120: blue), the saturation its degree (grey: unpolarized, full
/// colour: fully polarized) and the brightness the tone-mapped intensity, all read from
/// luminance (Y; a camera's channels' mean). None for a film without polarization.
pub fn encode_polarization_png(
    film: &Film,
    space: &RgbColorSpace,
    display: DisplaySettings,
) -> Option<Vec<u8>> {
    let (w, h) = (film.width(), film.height());
    let weights = space.luminance_weights();
    let transfer = space.transfer();
    let mut raw = Vec::with_capacity((w as usize * 3 + 1) * h as usize);
    for y in 0..h {
        raw.push(0u8);
        for x in 0..w {
            let stokes = film.stokes(x, y)?;
            let [s0, s1, s2] = [0, 1, 2].map(|k| {
                let c = stokes[k];
                if film.is_raw() {
                    (c[0] + c[1] + c[2]) / 3.0
                } else {
                    c[1]
                }
            });
            let (degree, angle) = linear_polarization(s0, s1, s2);
            let grey = display_8bit(
                [s0; 3],
                display.exposure,
                display.tone_map,
                weights,
                transfer,
            );
            let value = f64::from(grey[1]) / 255.0;
            raw.extend_from_slice(&hsv_8bit(angle / std::f64::consts::PI, degree, value));
        }
    }
    Some(crate::io::png::encode_8bit(w, h, false, &raw))
}

/// Degree in [0, 1] and angle in [0, pi) of linear polarization of (s0, s1, s2); (0, 0)
/// where there is no light.
fn linear_polarization(s0: f64, s1: f64, s2: f64) -> (f64, f64) {
    if !(s0 > 0.0 && s1.is_finite() && s2.is_finite()) {
        return (0.0, 0.0);
    }
    let degree = (s1.hypot(s2) / s0).min(1.0);
    let angle = (0.5 * s2.atan2(s1)).rem_euclid(std::f64::consts::PI);
    (degree, if angle.is_finite() { angle } else { 0.0 })
}

/// HSV (hue as a fraction of the circle) to 8-bit RGB.
fn hsv_8bit(hue: f64, saturation: f64, value: f64) -> [u8; 3] {
    let h = hue.rem_euclid(1.0) * 6.0;
    let sector = h.floor();
    let f = h - sector;
    let (v, s) = (value.clamp(0.0, 1.0), saturation.clamp(0.0, 1.0));
    let (p, q, t) = (v * (1.0 - s), v * (1.0 - s * f), v * (1.0 - s * (1.0 - f)));
    let rgb = match sector as u32 % 6 {
        0 => [v, t, p],
        1 => [q, v, p],
        2 => [p, v, t],
        3 => [p, q, v],
        4 => [t, p, v],
        _ => [v, p, q],
    };
    rgb.map(|c| (c * 255.0).round() as u8)
}

#[cfg(test)]
mod polarization_png_tests {
    use super::*;

    #[test]
    fn hue_follows_the_angle_and_saturation_the_degree() {
        assert_eq!(hsv_8bit(0.0, 1.0, 1.0), [255, 0, 0]);
        assert_eq!(hsv_8bit(0.5, 1.0, 1.0), [0, 255, 255]);
        assert_eq!(hsv_8bit(0.3, 0.0, 0.5), [128, 128, 128]);
        // Horizontal, vertical and diagonal polarization; none; no light.
        let close =
            |(d, a): (f64, f64), (e, b): (f64, f64)| (d - e).abs() < 1e-12 && (a - b).abs() < 1e-12;
        assert!(close(linear_polarization(1.0, 1.0, 0.0), (1.0, 0.0)));
        assert!(close(
            linear_polarization(2.0, -1.0, 0.0),
            (0.5, std::f64::consts::FRAC_PI_2)
        ));
        assert!(close(
            linear_polarization(1.0, 0.0, 0.5),
            (0.5, std::f64::consts::FRAC_PI_4)
        ));
        assert!(close(
            linear_polarization(1.0, 0.0, -1.0),
            (1.0, 3.0 * std::f64::consts::FRAC_PI_4)
        ));
        assert!(close(linear_polarization(0.0, 0.0, 0.0), (0.0, 0.0)));
        assert!(close(linear_polarization(1.0, f64::NAN, 0.0), (0.0, 0.0)));
    }
}
