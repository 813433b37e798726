//! Images of floating-point texels (one or three channels) looked up as Mitsuba 3's
//! `bitmap` texture looks them up: texel centres at half-integers, bilinear weights of the
//! four texels around a point or the one texel under it (`filter_type`), indices wrapped
//! per axis (`wrap_mode`), and coordinates first mapped by an affine `to_uv`.
//!
//! The lookups are Dr.Jit's `Texture::eval_nonaccel` and `eval_fetch_nonaccel`
//! (include/drjit/texture.h of mitsuba-renderer/drjit), which Mitsuba's bitmap plugin
//! calls (src/textures/bitmap.cpp of mitsuba-renderer/mitsuba3): a point at `uv` reads
//! position `uv * size - 0.5` bilinearly, or texel `floor(uv * size)` for nearest. Row 0
//! is the top of the image and v grows down it, as the image is stored. There is no
//! mipmapping: Mitsuba's bitmap does "bilinear interpolation, but no filtering".

use std::sync::Arc;

use glam::{Affine2, Vec2};

use super::Wrap;

/// How a lookup reads the texels around a point.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Filter {
    /// The texel under the point.
    Nearest,
    /// The four texels around it, weighted bilinearly.
    Bilinear,
}

/// Mitsuba's weights for luminance (`luminance()` in include/mitsuba/core/spectrum.h:
/// linear sRGB's Y row), what a three-channel texture gives where one number is asked.
pub const LUMINANCE: [f32; 3] = [0.212_671, 0.715_160, 0.072_169];

/// An image of `channels` floats per texel, rows from the top.
#[derive(Debug, Clone, PartialEq)]
pub struct Texels {
    width: u32,
    height: u32,
    channels: usize,
    data: Arc<Vec<f32>>,
    wrap: Wrap,
    filter: Filter,
    to_uv: Affine2,
}

/// The texels a lookup reads (indices of their first channel) and their weights.
struct Taps {
    index: [usize; 4],
    weight: [f32; 4],
    count: usize,
}

impl Texels {
    /// `width` x `height` texels of `channels` (1 or 3) floats each, row-major from the
    /// top-left. Errors for another channel count, a size that does not match, a
    /// non-finite texel or transform.
    pub fn new(
        width: u32,
        height: u32,
        channels: usize,
        data: Vec<f32>,
        wrap: Wrap,
        filter: Filter,
        to_uv: Affine2,
    ) -> Result<Self, String> {
        if channels != 1 && channels != 3 {
            return Err(format!("{channels} channels per texel (1 or 3 are read)"));
        }
        let expected = (width as usize)
            .checked_mul(height as usize)
            .and_then(|n| n.checked_mul(channels));
        if width == 0 || height == 0 || expected != Some(data.len()) {
            return Err(format!(
                "{} values for {width}x{height} texels of {channels} channels",
                data.len()
            ));
        }
        if !data.iter().all(|v| v.is_finite()) {
            return Err("a texel is not finite".into());
        }
        if !to_uv.is_finite() {
            return Err("the texture's to_uv transform is not finite".into());
        }
        Ok(Self {
            width,
            height,
            channels,
            data: Arc::new(data),
            wrap,
            filter,
            to_uv,
        })
    }

    /// Its size in texels (width, height).
    pub fn size(&self) -> (u32, u32) {
        (self.width, self.height)
    }

    /// Floats per texel.
    pub fn channels(&self) -> usize {
        self.channels
    }

    /// The texels, `channels` floats each, row-major from the top-left.
    pub fn data(&self) -> &[f32] {
        &self.data
    }

    /// The same image with every texel replaced by `f` of it (`f` gives `channels` floats;
    /// a non-finite result is 0).
    pub fn map(&self, channels: usize, f: impl Fn(&[f32]) -> [f32; 3]) -> Result<Self, String> {
        let mut data = Vec::with_capacity(self.data.len() / self.channels * channels);
        for texel in self.data.chunks_exact(self.channels) {
            let v = f(texel);
            data.extend(
                v[..channels]
                    .iter()
                    .map(|c| if c.is_finite() { *c } else { 0.0 }),
            );
        }
        Self::new(
            self.width,
            self.height,
            channels,
            data,
            self.wrap,
            self.filter,
            self.to_uv,
        )
    }

    fn taps(&self, uv: Vec2) -> Taps {
        let uv = self.to_uv.transform_point2(uv);
        let uv = if uv.is_finite() { uv } else { Vec2::ZERO };
        let size = Vec2::new(self.width as f32, self.height as f32);
        let at = |x: i64, y: i64| {
            let column = self.wrap.texel(x, self.width);
            let row = self.wrap.texel(y, self.height);
            (row * self.width as usize + column) * self.channels
        };
        // Kept within i64 for absurd coordinates; wrapping makes the exact multiple moot.
        let floor = |v: f32| v.clamp(-1e9, 1e9).floor();
        match self.filter {
            Filter::Nearest => {
                let p = uv * size;
                Taps {
                    index: [at(floor(p.x) as i64, floor(p.y) as i64), 0, 0, 0],
                    weight: [1.0, 0.0, 0.0, 0.0],
                    count: 1,
                }
            }
            Filter::Bilinear => {
                let p = uv * size - 0.5;
                let (x0, y0) = (floor(p.x), floor(p.y));
                let (w1x, w1y) = (p.x - x0, p.y - y0);
                let (w0x, w0y) = (1.0 - w1x, 1.0 - w1y);
                let (x0, y0) = (x0 as i64, y0 as i64);
                Taps {
                    index: [
                        at(x0, y0),
                        at(x0 + 1, y0),
                        at(x0, y0 + 1),
                        at(x0 + 1, y0 + 1),
                    ],
                    weight: [w0x * w0y, w1x * w0y, w0x * w1y, w1x * w1y],
                    count: 4,
                }
            }
        }
    }

    /// The weighted sum of `f` of each texel read at `uv` (f maps a texel's floats to a
    /// value): how a lookup filters anything derived from texels.
    pub fn filtered<T>(&self, uv: Vec2, f: impl Fn(&[f32]) -> T) -> T
    where
        T: std::ops::Mul<f32, Output = T> + std::ops::Add<Output = T>,
    {
        let taps = self.taps(uv);
        let texel = |k: usize| &self.data[taps.index[k]..taps.index[k] + self.channels];
        let mut sum = f(texel(0)) * taps.weight[0];
        for k in 1..taps.count {
            sum = sum + f(texel(k)) * taps.weight[k];
        }
        sum
    }

    /// The texels' values at `uv` (three channels; a one-channel image's value thrice),
    /// as Mitsuba's `eval_3` of a raw texture.
    pub fn rgb(&self, uv: Vec2) -> [f32; 3] {
        let v = self.filtered(uv, |t| glam::Vec3::from(texel_rgb(t)));
        v.to_array()
    }

    /// One number at `uv`: the value of a one-channel image, the luminance of a
    /// three-channel one (Mitsuba's `eval_1`).
    pub fn scalar(&self, uv: Vec2) -> f32 {
        self.filtered(uv, texel_scalar)
    }

    /// The gradient of [`Texels::scalar`] with respect to (u, v) at `uv`, as Mitsuba's
    /// `eval_1_grad` computes it (zero for nearest lookups): the bilinear patch's slopes
    /// in texels, taken through the transposed `to_uv` and scaled by the size.
    pub fn gradient(&self, uv: Vec2) -> Vec2 {
        if self.filter == Filter::Nearest {
            return Vec2::ZERO;
        }
        let taps = self.taps(uv);
        let f = |k: usize| texel_scalar(&self.data[taps.index[k]..taps.index[k] + self.channels]);
        let (f00, f10, f01, f11) = (f(0), f(1), f(2), f(3));
        // The weights are (w0x w0y, w1x w0y, w0x w1y, w1x w1y); recover w1x and w1y.
        let t = self.to_uv.transform_point2(uv);
        let t = if t.is_finite() { t } else { Vec2::ZERO };
        let p = t * Vec2::new(self.width as f32, self.height as f32) - 0.5;
        let w1 = p - p.clamp(Vec2::splat(-1e9), Vec2::splat(1e9)).floor();
        let w0 = Vec2::ONE - w1;
        let dx = w0.y * (f10 - f00) + w1.y * (f11 - f01);
        let dy = w0.x * (f01 - f00) + w1.x * (f11 - f10);
        let m = self.to_uv.matrix2;
        let du = m.x_axis.x * dx + m.x_axis.y * dy;
        let dv = m.y_axis.x * dx + m.y_axis.y * dy;
        let g = Vec2::new(du * self.width as f32, dv * self.height as f32);
        if g.is_finite() { g } else { Vec2::ZERO }
    }

    /// The mean of `f` over (at most about 65536 evenly strided) texels.
    pub fn mean_of(&self, f: impl Fn(&[f32]) -> f64) -> f64 {
        let texels = self.data.len() / self.channels;
        let stride = texels.div_ceil(1 << 16).max(1);
        let (mut sum, mut n) = (0.0, 0usize);
        for texel in self.data.chunks_exact(self.channels).step_by(stride) {
            sum += f(texel);
            n += 1;
        }
        sum / n.max(1) as f64
    }
}

fn texel_rgb(t: &[f32]) -> [f32; 3] {
    match t {
        [r, g, b] => [*r, *g, *b],
        [v, ..] => [*v; 3],
        [] => [0.0; 3],
    }
}

fn texel_scalar(t: &[f32]) -> f32 {
    match t {
        [r, g, b] => LUMINANCE[0] * r + LUMINANCE[1] * g + LUMINANCE[2] * b,
        [v, ..] => *v,
        [] => 0.0,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn image(width: u32, height: u32, data: Vec<f32>, wrap: Wrap, filter: Filter) -> Texels {
        Texels::new(width, height, 1, data, wrap, filter, Affine2::IDENTITY).unwrap()
    }

    /// Texel centres sit at (i + 0.5) / size; between them values blend linearly; row 0
    /// is at v = 0.
    #[test]
    fn bilinear_lookups_blend_between_texel_centres() {
        let t = image(
            2,
            2,
            vec![0.0, 1.0, 2.0, 3.0],
            Wrap::Clamp,
            Filter::Bilinear,
        );
        assert_eq!(t.scalar(Vec2::new(0.25, 0.25)), 0.0);
        assert_eq!(t.scalar(Vec2::new(0.75, 0.25)), 1.0);
        assert_eq!(t.scalar(Vec2::new(0.25, 0.75)), 2.0);
        assert_eq!(t.scalar(Vec2::new(0.5, 0.25)), 0.5);
        assert_eq!(t.scalar(Vec2::new(0.5, 0.5)), 1.5);
        // Clamped beyond the edge centres.
        assert_eq!(t.scalar(Vec2::new(-3.0, 0.25)), 0.0);
        // The gradient in u is the step between columns over a texel (1 / 2 of u).
        assert_eq!(t.gradient(Vec2::new(0.5, 0.25)), Vec2::new(2.0, 4.0));
    }

    /// Repeat wraps the neighbour across the edge; mirror reflects with the edge texel
    /// repeated; nearest reads the texel under the point.
    #[test]
    fn wrap_modes_and_nearest_follow_drjit() {
        let row = vec![0.0, 1.0, 2.0, 3.0];
        let repeat = image(4, 1, row.clone(), Wrap::Repeat, Filter::Bilinear);
        // At u = 0 the point is halfway between texel -1 (= 3) and texel 0.
        assert_eq!(repeat.scalar(Vec2::new(0.0, 0.5)), 1.5);
        let mirror = image(4, 1, row.clone(), Wrap::Mirror, Filter::Nearest);
        let at = |u: f32| mirror.scalar(Vec2::new(u, 0.5));
        assert_eq!([at(1.1), at(1.9), at(-0.1), at(-0.9)], [3.0, 0.0, 0.0, 3.0]);
        let nearest = image(4, 1, row, Wrap::Clamp, Filter::Nearest);
        assert_eq!(nearest.scalar(Vec2::new(0.49, 0.5)), 1.0);
        assert_eq!(nearest.gradient(Vec2::new(0.49, 0.5)), Vec2::ZERO);
    }

    /// to_uv maps coordinates before the lookup; three channels give luminance as one
    /// number; every input gives a finite value.
    #[test]
    fn transforms_luminance_and_finiteness() {
        let scaled = Texels::new(
            2,
            1,
            3,
            vec![1.0, 0.0, 0.0, 0.0, 1.0, 0.0],
            Wrap::Repeat,
            Filter::Nearest,
            Affine2::from_scale(Vec2::new(2.0, 1.0)),
        )
        .unwrap();
        assert_eq!(scaled.rgb(Vec2::new(0.3, 0.5)), [0.0, 1.0, 0.0]);
        assert_eq!(scaled.scalar(Vec2::new(0.1, 0.5)), LUMINANCE[0]);
        for uv in [
            Vec2::NAN,
            Vec2::INFINITY,
            Vec2::splat(3e38),
            Vec2::splat(-1e20),
        ] {
            assert!(scaled.scalar(uv).is_finite());
            assert!(scaled.gradient(uv).is_finite());
        }
        assert!(
            Texels::new(
                2,
                2,
                1,
                vec![0.0; 3],
                Wrap::Repeat,
                Filter::Nearest,
                Affine2::IDENTITY
            )
            .is_err()
        );
        assert!(
            Texels::new(
                1,
                1,
                2,
                vec![0.0; 2],
                Wrap::Repeat,
                Filter::Nearest,
                Affine2::IDENTITY
            )
            .is_err()
        );
        assert!(
            Texels::new(
                1,
                1,
                1,
                vec![f32::NAN],
                Wrap::Repeat,
                Filter::Nearest,
                Affine2::IDENTITY
            )
            .is_err()
        );
    }
}
