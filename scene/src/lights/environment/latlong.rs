//! Mitsuba 3's latitude-longitude environment (its `envmap` emitter,
//! `src/emitters/envmap.cpp` of mitsuba-renderer/mitsuba3), as an [`super::EnvironmentMap`]
//! reads it when a Mitsuba scene names one:
//!
//! - **Directions.** In the emitter's frame (its `to_world` undone), u = atan2(x, -z) /
//!   (2 pi) and v = acos(y) / pi: the top row is +y, u = 0 looks along -z, u = 1/4 along
//!   +x, u = 1/2 along +z (`direction_to_uv` / `uv_to_direction`). The image's own
//!   (glTF) convention puts +x at u = 1/2: the same direction is a quarter turn apart.
//! - **Texels.** Columns are texel-centred (column x at u = (x + 1/2) / W, wrapping) and
//!   rows are corner-aligned (row y at v = y / (H - 1), clamped): `eval_spectrum`'s
//!   lookup position.
//! - **Spectra.** Each texel's colour is split once into a scale f = 2 max(r, g, b) and
//!   the sigmoid coefficients of the colour over f (a reflectance, the sRGB model's
//!   table); a lookup interpolates the four corners' sigmoid spectra and, apart, their
//!   scales, and multiplies the two and the D65 illuminant: (sum w s_i) (sum w f_i) D65.
//!   That is not the spectrum of the interpolated colour, so it is done as Mitsuba does.

use std::f32::consts::PI;

use glam::{Mat3, Vec2, Vec3};
use prism_upsample::sigmoid::sigmoid_polynomial_lanes;
use prism_upsample::{CoefficientTable, FitContext, RgbKind, RgbSpectrum};

/// How far a `to_world` may be from orthonormal (each entry of M^T M - I).
const ORTHONORMAL: f32 = 1e-4;

/// One texel as Mitsuba stores it for spectral rendering.
#[derive(Debug, Clone, Copy)]
struct Texel {
    /// Sigmoid polynomial coefficients of the colour over `scale`; None for black.
    shape: Option<[f32; 3]>,
    /// 2 max(r, g, b).
    scale: f32,
}

/// Mitsuba's frame, texel grid and per-texel spectra of an environment image.
#[derive(Debug, Clone)]
pub(crate) struct MitsubaLatLong {
    to_world: Mat3,
    to_local: Mat3,
    width: u32,
    height: u32,
    texels: Vec<Texel>,
}

impl MitsubaLatLong {
    /// The frame `to_world` (its linear part; a rotation or a mirror, as directions stay
    /// unit) and the spectral texels of `rgb` (`width` x `height`, rows from the top,
    /// already scaled and cleaned), fitted through `table`.
    pub(crate) fn new(
        to_world: Mat3,
        width: u32,
        height: u32,
        rgb: &[[f32; 3]],
        table: &CoefficientTable,
        context: &FitContext,
    ) -> Result<Self, String> {
        let gram = to_world.transpose() * to_world - Mat3::IDENTITY;
        if !(to_world.is_finite() && gram.to_cols_array().iter().all(|e| e.abs() < ORTHONORMAL)) {
            return Err(
                "an environment's to_world must be a rotation (or a mirror): no scale or shear"
                    .into(),
            );
        }
        let texels = rgb
            .iter()
            .map(|t| {
                let s = RgbSpectrum::from_table(
                    table,
                    context,
                    t.map(f64::from),
                    RgbKind::Unbounded,
                    None,
                    0,
                )
                .map_err(|e| format!("environment image: {e}"))?;
                Ok(Texel {
                    shape: s.shape().map(|p| p.coefficients.map(|c| c as f32)),
                    scale: s.scale() as f32,
                })
            })
            .collect::<Result<Vec<_>, String>>()?;
        Ok(Self {
            to_world,
            to_local: to_world.transpose(),
            width,
            height,
            texels,
        })
    }

    /// Image coordinates in [0, 1]^2 of unit world direction `d`.
    pub(crate) fn uv(&self, d: Vec3) -> Vec2 {
        let d = self.to_local * d;
        let u = d.x.atan2(-d.z) / (2.0 * PI);
        Vec2::new(u - u.floor(), d.y.clamp(-1.0, 1.0).acos() / PI)
    }

    /// The unit world direction of image coordinates `uv`, and sin(theta) there.
    pub(crate) fn direction(&self, uv: Vec2) -> (Vec3, f32) {
        let (sin_theta, cos_theta) = (PI * uv.y).sin_cos();
        let (sin_phi, cos_phi) = (2.0 * PI * uv.x).sin_cos();
        let local = Vec3::new(sin_phi * sin_theta, cos_theta, -cos_phi * sin_theta);
        (self.to_world * local, sin_theta)
    }

    /// The position of `uv` on the texel grid, in texels: columns centred, rows on the
    /// corners (v = 0 is row 0's centre, v = 1 the last row's).
    pub(crate) fn grid(&self, uv: Vec2) -> Vec2 {
        let u = uv.x - uv.x.floor();
        let v = uv.y.clamp(0.0, 1.0);
        Vec2::new(u * self.width as f32 - 0.5, v * (self.height as f32 - 1.0))
    }

    fn texel(&self, x: i64, y: i64) -> Texel {
        let x = x.rem_euclid(i64::from(self.width)) as usize;
        let y = y.clamp(0, i64::from(self.height) - 1) as usize;
        self.texels[y * self.width as usize + x]
    }

    /// The spectrum at `uv` at wavelengths `lambda`, without the illuminant: the corners'
    /// sigmoid spectra and scales interpolated apart, then multiplied.
    pub(crate) fn shape<const N: usize>(&self, uv: Vec2, lambda: &[f32; N]) -> [f32; N] {
        let p = self.grid(uv).clamp(Vec2::splat(-1e9), Vec2::splat(1e9));
        let (x0, y0) = (p.x.floor(), p.y.floor());
        let (fx, fy) = (p.x - x0, p.y - y0);
        let (x0, y0) = (x0 as i64, y0 as i64);
        let corners = [
            (self.texel(x0, y0), (1.0 - fx) * (1.0 - fy)),
            (self.texel(x0 + 1, y0), fx * (1.0 - fy)),
            (self.texel(x0, y0 + 1), (1.0 - fx) * fy),
            (self.texel(x0 + 1, y0 + 1), fx * fy),
        ];
        let mut spectrum = [0.0f32; N];
        let mut scale = 0.0f32;
        for (texel, w) in corners {
            if w == 0.0 {
                continue;
            }
            scale += w * texel.scale;
            if let Some(c) = texel.shape {
                let s = sigmoid_polynomial_lanes(c, lambda);
                for (acc, s) in spectrum.iter_mut().zip(s) {
                    *acc += w * s;
                }
            }
        }
        spectrum.map(|s| (s * scale).min(f32::MAX))
    }
}
