//! An environment image: radiance from every direction at infinity, read from an
//! equirectangular (latitude-longitude) image, upsampled per lookup as an illuminant
//! spectrum, and importance sampled in proportion to its luminance times sin(theta) (the
//! 2D piecewise-constant construction of pbrt-v4's image infinite light, *PBR* 4th ed.
//! §12.5.3, on the latitude-longitude parameterization of its §12.5.2 predecessor); light
//! samples, which MIS combines with BSDF sampling, in proportion to the luminance less
//! its mean (MIS compensation).
//!
//! Mapping (the convention of Blender's and three.js's equirectangular environments, so
//! that an HDRI lights a model as it does in a glTF viewer): +y is up and the top row is
//! the zenith; u runs left to right with the image's centre column looking along +x and
//! the column at u = 3/4 along +z. A direction's polar angle theta (from +y) is pi v, its
//! azimuth phi = 2 pi (u - 1/2) measured from +x towards +z. Mitsuba 3's `envmap` puts -z
//! at u = 0 and interpolates its texels otherwise: a map made by
//! [`EnvironmentMap::mitsuba`] reads the image as Mitsuba does (`latlong`).

use std::f32::consts::PI;
use std::sync::Arc;

use glam::{Mat3, Vec2, Vec3};
use prism_sampling::distribution::PiecewiseConstant2D;
use prism_spectrum::spectra::DenselySampled;
use prism_spectrum::{SampledSpectrum, SampledWavelengths};
use prism_upsample::{CoefficientTable, FitContext, RgbKind, RgbSpectrum};

use super::latlong::MitsubaLatLong;
use crate::textures::{SceneSpectrum, illuminant_spectrum};

/// Rec. 709 luminance weights of linear sRGB.
const LUMINANCE: [f32; 3] = [0.2126, 0.7152, 0.0722];

/// The largest texel value kept: radiance is f32 in the renderer, and bilinear weights
/// must not overflow when they sum four texels.
const MAX_TEXEL: f32 = f32::MAX / 8.0;

/// An equirectangular environment image, ready to look up and sample.
#[derive(Debug, Clone)]
pub struct EnvironmentMap {
    width: u32,
    height: u32,
    /// Linear sRGB radiance (emissive-colour units), strength folded in, rows from the
    /// top.
    texels: Vec<[f32; 3]>,
    /// (sin, cos) of the rotation about +y.
    rotation: (f32, f32),
    /// Mitsuba's frame, texel grid and spectra instead of the rotation and this
    /// convention's (a Mitsuba scene's `envmap`).
    mitsuba: Option<Box<MitsubaLatLong>>,
    table: Arc<CoefficientTable>,
    context: Arc<FitContext>,
    illuminant: Arc<DenselySampled>,
    /// Over (u, v) in [0, 1)^2, in proportion to luminance times sin(theta): where light
    /// paths leave the image. None when the image is black.
    distribution: Option<PiecewiseConstant2D>,
    /// The same less the image's mean (MIS compensation): what next-event estimation
    /// samples. None where it would be the same (a constant image) or empty.
    compensated: Option<PiecewiseConstant2D>,
    /// The spectrum of the solid-angle-weighted mean colour: the power light choice sees.
    mean: SceneSpectrum,
}

impl EnvironmentMap {
    /// A map of `width` x `height` linear sRGB texels (rows from the top) scaled by
    /// `strength` and turned by `rotation_degrees` about +y; texel colours become
    /// illuminant spectra through `table` as emissive textures' do (RGB (1, 1, 1) emits
    /// `illuminant`, normalized to luminance 1). Negative and NaN texel components count
    /// as 0, huge ones are capped. Errors for a size that does not match the texels or a
    /// non-finite rotation or strength.
    pub fn new(
        width: u32,
        height: u32,
        texels: Vec<[f32; 3]>,
        rotation_degrees: f64,
        strength: f64,
        upsampling: (Arc<CoefficientTable>, Arc<FitContext>, Arc<DenselySampled>),
    ) -> Result<Self, String> {
        if width == 0 || height == 0 || texels.len() != width as usize * height as usize {
            return Err(format!(
                "{} texels for a {width}x{height} environment image",
                texels.len()
            ));
        }
        if !(rotation_degrees.is_finite() && strength.is_finite() && strength >= 0.0) {
            return Err(format!(
                "environment rotation {rotation_degrees} and strength {strength} must be finite, \
                 the strength >= 0"
            ));
        }
        let strength = strength.min(f64::from(MAX_TEXEL)) as f32;
        let texels: Vec<[f32; 3]> = texels
            .into_iter()
            .map(|t| {
                t.map(|c| {
                    // inf x 0 is NaN, and NaN is no light.
                    let v = c * strength;
                    if v > 0.0 { v.min(MAX_TEXEL) } else { 0.0 }
                })
            })
            .collect();
        let (table, context, illuminant) = upsampling;
        let mean = solid_angle_mean(&texels, width, height);
        let mean = illuminant_spectrum(mean, &table, &context, &illuminant)
            .map_err(|e| format!("environment image: {e}"))?;
        let mut map = Self {
            width,
            height,
            texels,
            rotation: (rotation_degrees.to_radians() as f32).sin_cos(),
            mitsuba: None,
            table,
            context,
            illuminant,
            distribution: None,
            compensated: None,
            mean: SceneSpectrum::Rgb(Arc::new(mean)),
        };
        (map.distribution, map.compensated) = map.sampling_distributions();
        Ok(map)
    }

    /// A map of `width` x `height` linear sRGB texels (rows from the top) read as Mitsuba
    /// 3's `envmap` reads its image: in the frame `to_world` (a rotation or mirror; the
    /// linear part of the emitter's `to_world`), with Mitsuba's direction mapping, texel
    /// grid and spectra (see `latlong`), each texel scaled by `scale`. RGB (1, 1, 1) emits
    /// `upsampling`'s illuminant, as [`EnvironmentMap::new`]'s. Errors as `new` does, and
    /// for a frame that scales or shears.
    pub fn mitsuba(
        width: u32,
        height: u32,
        texels: Vec<[f32; 3]>,
        to_world: Mat3,
        scale: f64,
        upsampling: (Arc<CoefficientTable>, Arc<FitContext>, Arc<DenselySampled>),
    ) -> Result<Self, String> {
        let mut map = Self::new(width, height, texels, 0.0, scale, upsampling)?;
        map.mitsuba = Some(Box::new(MitsubaLatLong::new(
            to_world,
            width,
            height,
            &map.texels,
            &map.table,
            &map.context,
        )?));
        // The sampling densities follow the lookups, which have changed.
        (map.distribution, map.compensated) = map.sampling_distributions();
        Ok(map)
    }

    /// The image's size in texels.
    pub fn size(&self) -> (u32, u32) {
        (self.width, self.height)
    }

    /// The spectrum of the image's mean colour over the sphere (solid-angle weighted).
    pub fn mean(&self) -> &SceneSpectrum {
        &self.mean
    }

    /// The world direction `d` in the image's own frame (its rotation undone).
    fn to_local(&self, d: Vec3) -> Vec3 {
        let (sin, cos) = self.rotation;
        Vec3::new(d.x * cos - d.z * sin, d.y, d.x * sin + d.z * cos)
    }

    fn to_world(&self, d: Vec3) -> Vec3 {
        let (sin, cos) = self.rotation;
        Vec3::new(d.x * cos + d.z * sin, d.y, -d.x * sin + d.z * cos)
    }

    /// The image coordinates in [0, 1]^2 of unit world direction `d` ((0, 0) for a
    /// direction that is not finite).
    pub fn uv(&self, d: Vec3) -> Vec2 {
        if let Some(m) = &self.mitsuba {
            let uv = m.uv(d);
            return if uv.is_finite() { uv } else { Vec2::ZERO };
        }
        let d = self.to_local(d);
        let u = 0.5 + d.z.atan2(d.x) / (2.0 * PI);
        let v = d.y.clamp(-1.0, 1.0).acos() / PI;
        let uv = Vec2::new(u, v);
        if uv.is_finite() { uv } else { Vec2::ZERO }
    }

    /// The unit world direction of image coordinates `uv`, and sin(theta) there.
    pub fn direction(&self, uv: Vec2) -> (Vec3, f32) {
        let uv = if uv.is_finite() { uv } else { Vec2::ZERO };
        if let Some(m) = &self.mitsuba {
            return m.direction(uv);
        }
        let (sin_theta, cos_theta) = (PI * uv.y).sin_cos();
        let (sin_phi, cos_phi) = (2.0 * PI * (uv.x - 0.5)).sin_cos();
        let local = Vec3::new(sin_theta * cos_phi, cos_theta, sin_theta * sin_phi);
        (self.to_world(local), sin_theta)
    }

    fn texel(&self, x: i64, y: i64) -> [f32; 3] {
        let x = x.rem_euclid(i64::from(self.width)) as usize;
        let y = y.clamp(0, i64::from(self.height) - 1) as usize;
        self.texels[y * self.width as usize + x]
    }

    /// Linear RGB at `uv`, bilinear between texel centres (u wraps around, v clamps at the
    /// poles).
    pub fn rgb(&self, uv: Vec2) -> [f32; 3] {
        let (x, y) = match &self.mitsuba {
            Some(m) => m.grid(uv).into(),
            None => (
                uv.x * self.width as f32 - 0.5,
                uv.y * self.height as f32 - 0.5,
            ),
        };
        let (x, y) = (x.clamp(-1e9, 1e9), y.clamp(-1e9, 1e9));
        let (x0, y0) = (x.floor(), y.floor());
        let (fx, fy) = (x - x0, y - y0);
        let (x0, y0) = (x0 as i64, y0 as i64);
        let c = [
            self.texel(x0, y0),
            self.texel(x0 + 1, y0),
            self.texel(x0, y0 + 1),
            self.texel(x0 + 1, y0 + 1),
        ];
        std::array::from_fn(|k| {
            let top = c[0][k] * (1.0 - fx) + c[1][k] * fx;
            let bottom = c[2][k] * (1.0 - fx) + c[3][k] * fx;
            top * (1.0 - fy) + bottom * fy
        })
    }

    /// Radiance arriving from unit world direction `d`, at the package's wavelengths.
    pub fn radiance<const N: usize>(
        &self,
        d: Vec3,
        wavelengths: &SampledWavelengths<N>,
    ) -> SampledSpectrum<N> {
        self.radiance_at(self.uv(d), wavelengths, &self.white(wavelengths))
    }

    /// The illuminant that RGB (1, 1, 1) emits, at the package's wavelengths: what every
    /// lookup multiplies the texels' spectral shapes by. A path looks the
    /// image up at the same wavelengths again and again, so callers keep this.
    pub fn white<const N: usize>(&self, wavelengths: &SampledWavelengths<N>) -> [f32; N] {
        self.illuminant.evaluate_lanes(wavelengths.lambdas())
    }

    /// Radiance at image coordinates `uv`, given [`EnvironmentMap::white`] at the same
    /// wavelengths.
    fn radiance_at<const N: usize>(
        &self,
        uv: Vec2,
        wavelengths: &SampledWavelengths<N>,
        white: &[f32; N],
    ) -> SampledSpectrum<N> {
        if let Some(m) = &self.mitsuba {
            let shape = m.shape(uv, wavelengths.lambdas());
            return SampledSpectrum(std::array::from_fn(|k| (shape[k] * white[k]).min(f32::MAX)));
        }
        let rgb = self.rgb(uv);
        if rgb == [0.0; 3] {
            return SampledSpectrum::splat(0.0);
        }
        // The illuminant shape without the illuminant, which `white` holds: the same
        // products in the same order as `RgbSpectrum::evaluate_lanes` with it.
        match RgbSpectrum::from_table(
            &self.table,
            &self.context,
            rgb.map(f64::from),
            RgbKind::Illuminant,
            None,
            0,
        ) {
            Ok(s) => {
                let shape = s.evaluate_lanes(wavelengths.lambdas());
                SampledSpectrum(std::array::from_fn(|k| (shape[k] * white[k]).min(f32::MAX)))
            }
            // Texels are finite: unreachable, and dark rather than a panic.
            Err(_) => SampledSpectrum::splat(0.0),
        }
    }

    /// Radiance arriving from unit world direction `d` and the density (solid angle) with
    /// which [`EnvironmentMap::sample`] picks it, from one conversion of `d` to image
    /// coordinates; `white` is [`EnvironmentMap::white`] at `wavelengths`.
    pub fn radiance_and_pdf<const N: usize>(
        &self,
        d: Vec3,
        wavelengths: &SampledWavelengths<N>,
        white: &[f32; N],
    ) -> (SampledSpectrum<N>, f32) {
        let uv = self.uv(d);
        (self.radiance_at(uv, wavelengths, white), self.pdf_at(uv))
    }

    /// A direction for next-event estimation sampled with `u`, its density with respect to
    /// solid angle, and the radiance from it; None for a black image or a sample at a
    /// pole; `white` is [`EnvironmentMap::white`] at `wavelengths`. The density is
    /// luminance times sin(theta) less the image's mean where that is positive, 0 elsewhere
    /// (MIS compensation: Karlik et al., "MIS Compensation: Optimizing Sampling Techniques
    /// in Multiple Importance Sampling", SIGGRAPH Asia 2019; pbrt-v4's
    /// `ImageInfiniteLight` with `allowIncompletePDF`): directions a BSDF or phase
    /// function samples as well are left to it, and light samples go to the sun. Only
    /// for estimators combined by MIS with one whose density is positive wherever light
    /// arrives; light paths use [`EnvironmentMap::sample_emitted`].
    pub fn sample<const N: usize>(
        &self,
        u: Vec2,
        wavelengths: &SampledWavelengths<N>,
        white: &[f32; N],
    ) -> Option<(Vec3, f32, SampledSpectrum<N>)> {
        self.sample_from(self.for_light_samples()?, u, wavelengths, white)
    }

    /// A direction sampled with `u` in proportion to luminance times sin(theta) (positive
    /// wherever the image has light: the start of light paths), its density with respect
    /// to solid angle and the radiance from it, as [`EnvironmentMap::sample`] gives them.
    pub fn sample_emitted<const N: usize>(
        &self,
        u: Vec2,
        wavelengths: &SampledWavelengths<N>,
        white: &[f32; N],
    ) -> Option<(Vec3, f32, SampledSpectrum<N>)> {
        self.sample_from(self.distribution.as_ref()?, u, wavelengths, white)
    }

    /// The distribution of next-event estimation's samples.
    fn for_light_samples(&self) -> Option<&PiecewiseConstant2D> {
        self.compensated.as_ref().or(self.distribution.as_ref())
    }

    fn sample_from<const N: usize>(
        &self,
        distribution: &PiecewiseConstant2D,
        u: Vec2,
        wavelengths: &SampledWavelengths<N>,
        white: &[f32; N],
    ) -> Option<(Vec3, f32, SampledSpectrum<N>)> {
        let s = distribution.sample([f64::from(u.x), f64::from(u.y)]);
        let uv = Vec2::new(s.point[0] as f32, s.point[1] as f32);
        let (d, sin_theta) = self.direction(uv);
        let pdf = s.pdf as f32 / (2.0 * PI * PI * sin_theta);
        // The radiance is looked up by direction, as a ray that escapes towards it is:
        // both estimators of MIS see the same function.
        (pdf.is_finite() && pdf > 0.0 && d.is_finite())
            .then(|| (d, pdf, self.radiance_at(self.uv(d), wavelengths, white)))
    }

    /// The density (solid angle) with which [`EnvironmentMap::sample`] picks unit world
    /// direction `d`.
    pub fn pdf(&self, d: Vec3) -> f32 {
        self.pdf_at(self.uv(d))
    }

    /// The density (solid angle) with which [`EnvironmentMap::sample_emitted`] picks unit
    /// world direction `d`.
    pub fn pdf_emitted(&self, d: Vec3) -> f32 {
        self.density(self.distribution.as_ref(), self.uv(d))
    }

    /// The density of [`EnvironmentMap::sample`] at image coordinates `uv`.
    fn pdf_at(&self, uv: Vec2) -> f32 {
        self.density(self.for_light_samples(), uv)
    }

    /// `distribution`'s density (solid angle) at image coordinates `uv`.
    fn density(&self, distribution: Option<&PiecewiseConstant2D>, uv: Vec2) -> f32 {
        let Some(distribution) = distribution else {
            return 0.0;
        };
        let sin_theta = (PI * uv.y).sin();
        let pdf = distribution.pdf([f64::from(uv.x), f64::from(uv.y)]) as f32
            / (2.0 * PI * PI * sin_theta);
        if pdf.is_finite() { pdf } else { 0.0 }
    }
}

fn luminance(rgb: [f32; 3]) -> f64 {
    LUMINANCE
        .iter()
        .zip(rgb)
        .map(|(w, c)| f64::from(w * c))
        .sum()
}

/// The most cells of a sampling distribution finer than the image (16 bytes each).
const MAX_FINE_CELLS: usize = 1 << 21;

impl EnvironmentMap {
    /// The sampling density over the image: the bilinearly filtered luminance's mean over
    /// each cell of a grid, times sin(theta) at the cell's centre (the latitude-longitude
    /// map's area element), so that the density is the filtered image's integral per
    /// cell (*PBR* 4th ed. §12.5.3 computes the same by averaging lookups): positive
    /// wherever the image has light. Images up to a million texels get 2 or 4 cells a
    /// texel per axis: each cell then lies within one bilinear patch, where the mean is
    /// the value at the cell's centre, and a sun a few texels wide (whose filtered light
    /// falls off across a texel) is sampled where its light is rather than uniformly over
    /// the texels around it (measured on a 64 x 32 sky with a 2 x 2 texel sun: with one
    /// cell a texel, a plane's per-pixel spread at 16 spp is above the 10% bound of the
    /// integrator's environment tests). Larger images get one cell a texel, whose mean is
    /// 3/4 of the texel and 1/8 of each neighbour per axis.
    ///
    /// Returns that distribution and its MIS-compensated twin (see
    /// [`EnvironmentMap::sample`]): each cell's mean less the image's mean over the sphere
    /// (solid-angle weighted), where positive, times sin(theta); None when no cell is above
    /// the mean (a constant image).
    fn sampling_distributions(&self) -> (Option<PiecewiseConstant2D>, Option<PiecewiseConstant2D>) {
        let (w, h) = (self.width as usize, self.height as usize);
        let k = [4usize, 2]
            .into_iter()
            .find(|k| (w * k).saturating_mul(h * k) <= MAX_FINE_CELLS)
            .unwrap_or(1);
        let (fw, fh) = (w * k, h * k);
        let mut values = vec![0.0; fw * fh];
        for y in 0..fh {
            let v = (y as f64 + 0.5) / fh as f64;
            for x in 0..fw {
                let mean = if k > 1 {
                    let u = (x as f64 + 0.5) / fw as f64;
                    luminance(self.rgb(Vec2::new(u as f32, v as f32)))
                } else {
                    const WEIGHTS: [f64; 3] = [0.125, 0.75, 0.125];
                    let mut mean = 0.0f64;
                    for (dy, wy) in (-1i64..=1).zip(WEIGHTS) {
                        for (dx, wx) in (-1i64..=1).zip(WEIGHTS) {
                            mean += wy * wx * luminance(self.texel(x as i64 + dx, y as i64 + dy));
                        }
                    }
                    mean
                };
                values[y * fw + x] = mean;
            }
        }
        let sin_theta = |y: usize| (std::f64::consts::PI * (y as f64 + 0.5) / fh as f64).sin();
        let (mut sum, mut weight) = (0.0f64, 0.0f64);
        for (y, row) in values.chunks(fw).enumerate() {
            sum += row.iter().sum::<f64>() * sin_theta(y);
            weight += sin_theta(y) * fw as f64;
        }
        let average = sum / weight.max(f64::MIN_POSITIVE);
        let weighted = |offset: f64| -> Option<PiecewiseConstant2D> {
            let cells: Vec<f64> = values
                .chunks(fw)
                .enumerate()
                .flat_map(|(y, row)| {
                    row.iter()
                        .map(move |v| (v - offset).max(0.0) * sin_theta(y))
                })
                .collect();
            cells.iter().any(|&c| c > 0.0).then_some(())?;
            PiecewiseConstant2D::new(&cells, fw, fh, [[0.0, 1.0], [0.0, 1.0]]).ok()
        };
        (weighted(0.0), weighted(average))
    }
}

/// The mean colour over the sphere: texels weighted by the solid angle they cover.
fn solid_angle_mean(texels: &[[f32; 3]], width: u32, height: u32) -> [f32; 3] {
    let (w, h) = (width as usize, height as usize);
    let mut sum = [0.0f64; 3];
    let mut weight = 0.0f64;
    for (y, row) in texels.chunks(w).enumerate() {
        let sin_theta = (std::f64::consts::PI * (y as f64 + 0.5) / h as f64).sin();
        for t in row {
            for k in 0..3 {
                sum[k] += f64::from(t[k]) * sin_theta;
            }
            weight += sin_theta;
        }
    }
    sum.map(|s| (s / weight.max(f64::MIN_POSITIVE)).min(f64::from(MAX_TEXEL)) as f32)
}
