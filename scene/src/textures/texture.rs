//! Colour textures: 8-bit sRGB texels sampled bilinearly in linear RGB, upsampled to a
//! reflectance or an emission spectrum per lookup (Jakob and Hanika's table), as pbrt-v4
//! does for RGB textures: RGB is filtered first, then turned into a spectrum.

use std::sync::{Arc, LazyLock};

use super::TexCoords;
use super::mipmap::{Level, pyramid};

use glam::Vec2;
use prism_spectrum::spectra::DenselySampled;
use prism_spectrum::{SampledSpectrum, SampledWavelengths, Spectrum};
use prism_upsample::sigmoid::sigmoid_polynomial_lanes;
use prism_upsample::{CoefficientTable, FitContext, RgbKind, RgbSpectrum, SigmoidPolynomial};

/// How texture coordinates outside [0, 1] wrap (glTF sampler modes).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Wrap {
    /// Repeat.
    Repeat,
    /// Clamp to the edge texel.
    Clamp,
    /// Repeat, mirroring every other copy.
    Mirror,
}

impl Wrap {
    /// The texel index for integer coordinate `i` of a side of `n` texels.
    pub(crate) fn texel(self, i: i64, n: u32) -> usize {
        let n = i64::from(n);
        // Inside the texture every mode is the identity; the wrap's division (an i64
        // remainder, two per filtered lookup) is left to coordinates outside it.
        if (0..n).contains(&i) {
            return i as usize;
        }
        (match self {
            Wrap::Repeat => i.rem_euclid(n),
            Wrap::Clamp => i.clamp(0, n - 1),
            Wrap::Mirror => {
                let m = i.rem_euclid(2 * n);
                if m < n { m } else { 2 * n - 1 - m }
            }
        }) as usize
    }
}

/// `KHR_texture_transform`: uv' = offset + rotation(scale * uv).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct UvTransform {
    /// Offset added last.
    pub offset: Vec2,
    /// Rotation, radians (counter-clockwise in the extension's convention).
    pub rotation: f32,
    /// Scale applied first.
    pub scale: Vec2,
}

impl Default for UvTransform {
    fn default() -> Self {
        Self {
            offset: Vec2::ZERO,
            rotation: 0.0,
            scale: Vec2::ONE,
        }
    }
}

impl UvTransform {
    /// The transformed coordinates (the extension's matrix T R S, with R's rows
    /// (cos, sin) and (-sin, cos)).
    pub fn apply(&self, uv: Vec2) -> Vec2 {
        self.apply_rotated(self.rotation.sin_cos(), uv)
    }

    /// [`UvTransform::apply`] with the rotation's (sin, cos) computed once by the caller.
    fn apply_rotated(&self, (sin, cos): (f32, f32), uv: Vec2) -> Vec2 {
        let s = uv * self.scale;
        self.offset + Vec2::new(cos * s.x + sin * s.y, -sin * s.x + cos * s.y)
    }
}

/// How a texture's bytes map to linear values.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Encoding {
    /// The sRGB transfer curve (IEC 61966-2-1): glTF's colour textures.
    #[default]
    Srgb,
    /// Linear, byte / 255: glTF's data textures (metallic-roughness).
    Linear,
}

impl Encoding {
    /// Every byte's linear value: a lookup per texel where the sRGB curve was a `powf`.
    pub(crate) fn table(self) -> &'static [f32; 256] {
        static SRGB: LazyLock<[f32; 256]> = LazyLock::new(|| {
            std::array::from_fn(|v| {
                let c = v as f32 / 255.0;
                if c <= 0.04045 {
                    c / 12.92
                } else {
                    ((c + 0.055) / 1.055).powf(2.4)
                }
            })
        });
        static LINEAR: LazyLock<[f32; 256]> =
            LazyLock::new(|| std::array::from_fn(|v| v as f32 / 255.0));
        match self {
            Encoding::Srgb => &SRGB,
            Encoding::Linear => &LINEAR,
        }
    }
}

/// An 8-bit RGB texture (sRGB-encoded unless said otherwise), times a linear factor.
#[derive(Debug, Clone, PartialEq)]
pub struct RgbTexture {
    width: u32,
    height: u32,
    texels: Arc<Vec<[u8; 3]>>,
    wrap: [Wrap; 2],
    transform: UvTransform,
    factor: [f32; 3],
    encoding: Encoding,
    /// The transform's rotation as (sin, cos): a lookup's sine and cosine were a tenth of
    /// its instructions.
    rotation: (f32, f32),
    /// glTF's NEAREST magnification filter: the texel under the point, not a bilinear
    /// blend of four (pixel art, lookup tables, labels drawn at texel size).
    nearest: bool,
    /// The mipmap levels below the image, built on the first minified lookup.
    mips: std::sync::OnceLock<Arc<Vec<Level>>>,
    /// The texture coordinate set it reads (see [`TexCoords`]).
    set: usize,
}

impl RgbTexture {
    /// A texture of `width` x `height` texels (rows from the top), wrapping as `wrap`
    /// (s, t), its coordinates transformed by `transform`, its colour multiplied by
    /// `factor` (glTF's baseColorFactor). Errors if the texel count does not match.
    pub fn new(
        width: u32,
        height: u32,
        texels: Arc<Vec<[u8; 3]>>,
        wrap: [Wrap; 2],
        transform: UvTransform,
        factor: [f32; 3],
    ) -> Result<Self, String> {
        if width == 0 || height == 0 || texels.len() != width as usize * height as usize {
            return Err(format!(
                "{} texels for a {width}x{height} texture",
                texels.len()
            ));
        }
        if !(transform.offset.is_finite()
            && transform.scale.is_finite()
            && transform.rotation.is_finite()
            && factor.iter().all(|f| f.is_finite()))
        {
            return Err("texture transform or factor is not finite".into());
        }
        Ok(Self {
            width,
            height,
            texels,
            wrap,
            transform,
            factor,
            encoding: Encoding::Srgb,
            rotation: transform.rotation.sin_cos(),
            nearest: false,
            mips: std::sync::OnceLock::new(),
            set: 0,
        })
    }

    /// The same texture with its bytes read as `encoding`.
    pub fn encoded(self, encoding: Encoding) -> Self {
        Self { encoding, ..self }
    }

    /// The same texture read with nearest-texel filtering (glTF's NEAREST `magFilter`).
    pub fn nearest(self) -> Self {
        Self {
            nearest: true,
            ..self
        }
    }

    /// The same texture reading texture coordinate set `set` (of the
    /// [`TEX_COORD_SETS`](super::TEX_COORD_SETS) a scene keeps; a larger number reads the
    /// last).
    pub fn with_set(self, set: usize) -> Self {
        Self {
            set: set.min(super::TEX_COORD_SETS - 1),
            ..self
        }
    }

    /// The texture coordinate set it reads.
    pub fn set(&self) -> usize {
        self.set
    }

    /// Linear RGB at `at`, in the set the texture reads, filtered over the footprint
    /// there (see [`RgbTexture::sample_lod`]), times the factor.
    pub fn sample_at(&self, at: &TexCoords) -> [f32; 3] {
        let (uv, lod) = at.set(self.set);
        self.sample_lod(uv, lod + self.log2_resolution())
    }

    /// Whether it is read with nearest-texel filtering.
    pub fn is_nearest(&self) -> bool {
        self.nearest
    }

    /// Its wrap modes (s, t).
    pub fn wrap(&self) -> [Wrap; 2] {
        self.wrap
    }

    /// Its coordinate transform.
    pub fn transform(&self) -> UvTransform {
        self.transform
    }

    fn linear(&self, x: i64, y: i64) -> [f32; 3] {
        self.level_linear(self.width, self.height, &self.texels, x, y)
    }

    fn level_linear(
        &self,
        width: u32,
        height: u32,
        texels: &[[u8; 3]],
        x: i64,
        y: i64,
    ) -> [f32; 3] {
        let i = self.wrap[1].texel(y, height) * width as usize + self.wrap[0].texel(x, width);
        let table = self.encoding.table();
        texels[i].map(|v| table[usize::from(v)])
    }

    /// The base-2 logarithm of the texture's resolution in texels per unit of texture
    /// coordinates, sqrt(width x height) scaled by its transform's scale: a lookup whose
    /// footprint spans f units of texture coordinates reads level log2(f) + this.
    pub fn log2_resolution(&self) -> f32 {
        let scale = (self.transform.scale.x * self.transform.scale.y).abs();
        0.5 * ((self.width as f32) * (self.height as f32) * scale).log2()
    }

    /// Linear RGB at `uv` read at mipmap level `lod` (0: the image itself, each level up
    /// half the resolution; fractional levels blend the two around them, trilinear
    /// filtering), times the factor. `lod` <= 0 or NaN reads the image as
    /// [`RgbTexture::sample`] does.
    pub fn sample_lod(&self, uv: Vec2, lod: f32) -> [f32; 3] {
        // NaN reads the image too.
        if lod.is_nan() || lod <= 0.0 {
            return self.sample(uv);
        }
        let levels = self.mips.get_or_init(|| {
            let base = Level {
                width: self.width,
                height: self.height,
                texels: self.texels.clone(),
            };
            Arc::new(pyramid(&base, self.encoding))
        });
        let uv = self.transform.apply_rotated(self.rotation, uv);
        let uv = if uv.is_finite() { uv } else { Vec2::ZERO };
        let lod = lod.min(levels.len() as f32);
        let below = lod.floor();
        let t = lod - below;
        let at = |l: usize| -> [f32; 3] {
            match l.checked_sub(1).and_then(|i| levels.get(i)) {
                Some(level) => self.bilinear(level.width, level.height, &level.texels, uv),
                None => self.bilinear(self.width, self.height, &self.texels, uv),
            }
        };
        let (a, b) = (at(below as usize), at(below as usize + 1));
        std::array::from_fn(|k| (a[k] * (1.0 - t) + b[k] * t) * self.factor[k])
    }

    /// Bilinear filtering of texels `texels` (`width` x `height`) at transformed `uv`.
    fn bilinear(&self, width: u32, height: u32, texels: &[[u8; 3]], uv: Vec2) -> [f32; 3] {
        let x = (uv.x * width as f32 - 0.5).clamp(-1e9, 1e9);
        let y = (uv.y * height as f32 - 0.5).clamp(-1e9, 1e9);
        let (x0, y0) = (x.floor(), y.floor());
        let (fx, fy) = (x - x0, y - y0);
        let (x0, y0) = (x0 as i64, y0 as i64);
        let c = [
            self.level_linear(width, height, texels, x0, y0),
            self.level_linear(width, height, texels, x0 + 1, y0),
            self.level_linear(width, height, texels, x0, y0 + 1),
            self.level_linear(width, height, texels, x0 + 1, y0 + 1),
        ];
        std::array::from_fn(|k| {
            let top = c[0][k] * (1.0 - fx) + c[1][k] * fx;
            let bottom = c[2][k] * (1.0 - fx) + c[3][k] * fx;
            top * (1.0 - fy) + bottom * fy
        })
    }

    /// Linear RGB at `uv` (glTF: u right, v down from the top-left), bilinearly filtered
    /// between texel centres, times the factor. Finite for every input.
    pub fn sample(&self, uv: Vec2) -> [f32; 3] {
        let uv = self.transform.apply_rotated(self.rotation, uv);
        let uv = if uv.is_finite() { uv } else { Vec2::ZERO };
        if self.nearest {
            // Texel centres sit at half-integers; keep the integer part within i64 even
            // for absurd coordinates (wrapping makes the exact multiple irrelevant).
            let x = (uv.x * self.width as f32).clamp(-1e9, 1e9).floor();
            let y = (uv.y * self.height as f32).clamp(-1e9, 1e9).floor();
            let c = self.linear(x as i64, y as i64);
            return std::array::from_fn(|k| c[k] * self.factor[k]);
        }
        let c = self.bilinear(self.width, self.height, &self.texels, uv);
        std::array::from_fn(|k| c[k] * self.factor[k])
    }

    /// The mean linear colour over the texels, times the factor.
    pub fn mean(&self) -> [f32; 3] {
        let mut sum = [0.0f64; 3];
        let table = self.encoding.table();
        for t in self.texels.iter() {
            for k in 0..3 {
                sum[k] += f64::from(table[usize::from(t[k])]);
            }
        }
        let n = self.texels.len() as f64;
        std::array::from_fn(|k| (sum[k] / n) as f32 * self.factor[k])
    }
}

/// The reflectance spectrum of linear RGB `rgb` (clamped to [0, 1]) through `table` at
/// the package's wavelengths, in f32 lanes as constant colours are evaluated: exact for
/// greys, the table's sigmoid otherwise. Colour textures and vertex colours share it.
pub(crate) fn reflectance_lanes<const N: usize>(
    rgb: [f32; 3],
    table: &CoefficientTable,
    wavelengths: &SampledWavelengths<N>,
) -> SampledSpectrum<N> {
    match Reflectance::of(rgb, table) {
        Reflectance::Constant(v) => SampledSpectrum::splat(v),
        Reflectance::Sigmoid(s) => SampledSpectrum(sigmoid_polynomial_lanes(
            s.coefficients.map(|c| c as f32),
            wavelengths.lambdas(),
        )),
    }
}

/// The emission spectrum of linear RGB `rgb` through `table`: an illuminant-kind
/// spectrum under `illuminant` (normalized to luminance 1), so that RGB (1, 1, 1) emits
/// the illuminant itself. Emissive textures and environment images share it.
pub(crate) fn illuminant_spectrum(
    rgb: [f32; 3],
    table: &CoefficientTable,
    context: &FitContext,
    illuminant: &Arc<DenselySampled>,
) -> Result<RgbSpectrum, prism_upsample::UpsampleError> {
    RgbSpectrum::from_table(
        table,
        context,
        rgb.map(f64::from),
        RgbKind::Illuminant,
        Some(illuminant.clone()),
        0,
    )
}

/// A colour texture upsampled through a coefficient table at every lookup: a reflectance
/// (base colour), or an emission (an illuminant-kind spectrum, as the scene's constant
/// emissive colours are). As a function of wavelength alone (the [`Spectrum`] impl) it is
/// the spectrum of its mean colour, which is what light selection and reports need.
#[derive(Debug, Clone)]
pub struct SpectralTexture {
    rgb: RgbTexture,
    table: Arc<CoefficientTable>,
    kind: TextureKind,
}

#[derive(Debug, Clone)]
enum TextureKind {
    Reflectance {
        mean: Reflectance,
    },
    Emission {
        context: Arc<FitContext>,
        illuminant: Arc<DenselySampled>,
        mean: RgbSpectrum,
        /// An upper bound of every texel's spectrum.
        max: f64,
    },
}

/// The spectrum of one linear RGB reflectance: exact for black and greys (the table is
/// not needed there), the table's sigmoid otherwise.
#[derive(Debug, Clone, Copy)]
enum Reflectance {
    Constant(f32),
    Sigmoid(SigmoidPolynomial),
}

impl Reflectance {
    fn of(rgb: [f32; 3], table: &CoefficientTable) -> Self {
        let rgb = rgb.map(|c| if c.is_nan() { 0.0 } else { c.clamp(0.0, 1.0) });
        if rgb[0] == rgb[1] && rgb[1] == rgb[2] {
            Reflectance::Constant(rgb[0])
        } else {
            Reflectance::Sigmoid(table.lookup(rgb.map(f64::from)))
        }
    }

    fn evaluate(&self, lambda: f64) -> f64 {
        match self {
            Reflectance::Constant(v) => f64::from(*v),
            Reflectance::Sigmoid(s) => s.evaluate(lambda),
        }
    }
}

impl SpectralTexture {
    /// Reflectance spectra of `rgb` through `table` (fitted for the texture's colour
    /// space, sRGB for glTF).
    pub fn new(rgb: RgbTexture, table: Arc<CoefficientTable>) -> Self {
        let mean = Reflectance::of(rgb.mean(), &table);
        Self {
            rgb,
            table,
            kind: TextureKind::Reflectance { mean },
        }
    }

    /// Emission spectra of `rgb` (its factor may exceed 1: emissive strength) through
    /// `table` (fitted in `context`'s space), times `illuminant` normalized to luminance 1
    /// ([`prism_upsample::normalized_illuminant`]): a texel of RGB (1, 1, 1) emits the
    /// illuminant. Errors for a non-finite mean colour.
    pub fn emission(
        rgb: RgbTexture,
        table: Arc<CoefficientTable>,
        context: Arc<FitContext>,
        illuminant: Arc<DenselySampled>,
    ) -> Result<Self, String> {
        let mean = illuminant_spectrum(rgb.mean(), &table, &context, &illuminant)
            .map_err(|e| format!("emissive texture: {e}"))?;
        // Illuminant spectra are 2 max(r, g, b) times a sigmoid (at most 1) times the
        // illuminant: bounded by the brightest texel channel.
        let brightest = rgb
            .texels
            .iter()
            .flat_map(|t| {
                (0..3).map(move |k| rgb.encoding.table()[usize::from(t[k])] * rgb.factor[k])
            })
            .fold(0.0f32, f32::max);
        let max = 2.0 * f64::from(brightest) * illuminant.max_value();
        Ok(Self {
            rgb,
            table,
            kind: TextureKind::Emission {
                context,
                illuminant,
                mean,
                max,
            },
        })
    }

    /// The relative luminance (Rec. 709 weights) of the texture's colour at `uv`, and
    /// (None) of its mean colour: how light choice weighs emitters' parts.
    pub(crate) fn luminance(&self, uv: Option<Vec2>) -> f64 {
        let rgb = uv.map_or_else(|| self.rgb.mean(), |uv| self.rgb.sample(uv));
        [0.2126, 0.7152, 0.0722]
            .iter()
            .zip(rgb)
            .map(|(w, c)| w * f64::from(c))
            .sum()
    }

    /// The texture coordinate set it reads.
    pub fn set(&self) -> usize {
        self.rgb.set()
    }

    /// Whether the texture is an emission.
    pub fn emits(&self) -> bool {
        matches!(self.kind, TextureKind::Emission { .. })
    }

    /// The spectrum at `at` (in the set the texture reads, filtered over its footprint
    /// there: see [`RgbTexture::sample_at`]), at the package's wavelengths.
    pub fn at<const N: usize>(
        &self,
        at: impl Into<TexCoords>,
        wavelengths: &SampledWavelengths<N>,
    ) -> SampledSpectrum<N> {
        let rgb = self.rgb.sample_at(&at.into());
        match &self.kind {
            // In f32 lanes, as constant colours are evaluated (RgbSpectrum::evaluate_lanes).
            TextureKind::Reflectance { .. } => reflectance_lanes(rgb, &self.table, wavelengths),
            TextureKind::Emission {
                context,
                illuminant,
                ..
            } => match illuminant_spectrum(rgb, &self.table, context, illuminant) {
                Ok(s) => SampledSpectrum(s.evaluate_lanes(wavelengths.lambdas())),
                // Texels are finite: unreachable, and dark rather than a panic.
                Err(_) => SampledSpectrum::splat(0.0),
            },
        }
    }
}

impl Spectrum for SpectralTexture {
    fn evaluate(&self, lambda_nm: f64) -> f64 {
        match &self.kind {
            TextureKind::Reflectance { mean } => mean.evaluate(lambda_nm),
            TextureKind::Emission { mean, .. } => mean.evaluate(lambda_nm),
        }
    }

    fn max_value(&self) -> f64 {
        match &self.kind {
            TextureKind::Reflectance { .. } => 1.0,
            TextureKind::Emission { max, .. } => *max,
        }
    }
}
