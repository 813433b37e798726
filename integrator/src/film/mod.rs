//! The film: per-pixel sums of XYZ samples, in f64 so that a million samples per pixel
//! lose nothing (the sum of 10^6 values near 1 keeps 10^-10 relative precision), with a
//! count of the samples rejected as non-finite and each pixel's coverage (the camera rays
//! that met geometry: the alpha channel).

pub(crate) mod aov;
pub(crate) mod aov_sums;
pub(crate) mod bands;
pub(crate) mod camera_response;
pub(crate) mod filter;
pub(crate) mod radiance;
pub(crate) mod sample_value;
pub(crate) mod splatter;

use prism_spectrum::color::RgbColorSpace;

use crate::SpectralBands;
use crate::film::aov::Aovs;
use crate::film::aov_sums::AovSums;
use prism_spectrum::colorimetry::Xyz;
use prism_spectrum::saturating_f32;

/// Mutable views of every per-pixel sum of a film.
pub(crate) struct FilmSums<'a> {
    pub xyz: &'a mut [[f64; 3]],
    pub spectral: &'a mut [f64],
    pub energy: &'a mut [[f64; 2]],
    pub stokes: &'a mut [[[f64; 3]; 3]],
    pub coverage: &'a mut [f64],
    /// The second replicate's colour and samples (empty without the variance AOV).
    pub replica: &'a mut [[f64; 4]],
}

/// Accumulated XYZ per pixel, row-major from the top-left.
#[derive(Debug, Clone, PartialEq)]
pub struct Film {
    width: u32,
    height: u32,
    /// Sum of the XYZ of every accepted sample.
    sums: Vec<[f64; 3]>,
    /// Per pixel, how many of its camera rays met geometry (the rest escaped to the
    /// environment or the void): its coverage, which EXR outputs write as alpha.
    coverage: Vec<f64>,
    /// Samples taken per pixel (accepted or rejected: a rejected sample counts as zero,
    /// which keeps the estimator's normalization and so its expectation honest).
    samples: u64,
    nonfinite: u64,
    /// Per-band sums of spectral radiance estimates (W m^-2 sr^-1 nm^-1 per sample),
    /// `bands.count()` values per pixel and Stokes component (S0's, then S1..S3's when
    /// polarized), when the film is spectral.
    spectral: Option<(SpectralBands, Vec<f64>)>,
    /// Per-pixel sums of (radiance W m^-2 sr^-1, photon radiance s^-1 m^-2 sr^-1)
    /// estimates, when the film records energy.
    energy: Option<Vec<[f64; 2]>>,
    /// Per-pixel colour sums of the Stokes components S1, S2 and S3 (the camera frame's
    /// linear horizontal-vertical, diagonal and circular polarization; `sums` is S0),
    /// when the render is polarized.
    stokes: Option<Vec<[[f64; 3]; 3]>>,
    /// Whether the three sums are a camera's raw channels (shown as they are) rather
    /// than XYZ.
    raw: bool,
    /// The feature buffers' sums (empty without AOVs).
    aovs: AovSums,
}

impl Film {
    /// A black film.
    pub fn new(width: u32, height: u32) -> Self {
        Self {
            width,
            height,
            sums: vec![[0.0; 3]; width as usize * height as usize],
            coverage: vec![0.0; width as usize * height as usize],
            samples: 0,
            nonfinite: 0,
            spectral: None,
            energy: None,
            stokes: None,
            raw: false,
            aovs: AovSums::default(),
        }
    }

    /// This film, also recording the AOVs `set`.
    pub fn with_aovs(mut self, set: Aovs) -> Self {
        self.aovs = AovSums::new(set, self.sums.len());
        self
    }

    /// The AOVs' sums.
    pub fn aovs(&self) -> &AovSums {
        &self.aovs
    }

    pub(crate) fn aovs_mut(&mut self) -> &mut AovSums {
        &mut self.aovs
    }

    /// This film with `aovs` as its AOV sums (read from an accumulation file).
    #[cfg(feature = "exr")]
    pub(crate) fn with_aov_sums(mut self, aovs: AovSums) -> Self {
        self.aovs = aovs;
        self
    }

    /// The relative MSE the image is expected to have against the converged one (per XYZ
    /// channel, as `compare_images` measures), from its variance AOV; None without it.
    pub fn estimated_relmse(&self) -> Option<f64> {
        self.aovs.estimated_relmse(self.samples, &self.sums)
    }

    /// The AOV images in `space` (see [`AovSums`]), as named EXR channels (`albedo.R`,
    /// ...) with their values, row-major.
    pub fn aov_images(&self, space: &RgbColorSpace) -> Vec<(String, Vec<f32>)> {
        self.aovs.images(self.samples, space, &self.sums)
    }

    /// This film, also recording the Stokes components S1, S2, S3 per pixel.
    pub fn with_polarization(mut self) -> Self {
        self.stokes = Some(vec![[[0.0; 3]; 3]; self.sums.len()]);
        if let Some((bands, sums)) = &mut self.spectral {
            *sums = vec![0.0; self.sums.len() * bands.count() * 4];
        }
        self
    }

    /// The spectral sums per pixel: the bands of each Stokes component kept.
    pub(crate) fn spectral_width(&self) -> usize {
        let components = if self.stokes.is_some() { 4 } else { 1 };
        self.bands().map_or(0, |b| b.count() * components)
    }

    /// The estimated spectral radiance of Stokes component `k` (0..4) of pixel (x, y) per
    /// band, when the film is spectral and (for k > 0) polarized.
    pub fn stokes_spectrum(&self, x: u32, y: u32, k: usize) -> Option<Vec<f64>> {
        let (bands, sums) = self.spectral.as_ref()?;
        let count = bands.count();
        if k * count >= self.spectral_width() {
            return None;
        }
        let n = self.samples.max(1) as f64;
        let at = (y * self.width + x) as usize * self.spectral_width() + k * count;
        Some(sums[at..at + count].iter().map(|v| v / n).collect())
    }

    /// Whether the film records polarization (a polarized render's).
    pub fn is_polarized(&self) -> bool {
        self.stokes.is_some()
    }

    /// Pixel (x, y)'s Stokes components S0..S3 as colours (XYZ, or a camera's raw
    /// channels, like [`Film::xyz`]) in the camera's polarization frame (see the
    /// README's "Polarization"), when the film records polarization.
    pub fn stokes(&self, x: u32, y: u32) -> Option<[[f64; 3]; 4]> {
        let sums = self.stokes.as_ref()?;
        let pixel = (y * self.width + x) as usize;
        let n = self.samples.max(1) as f64;
        let s = &sums[pixel];
        let s0 = self.sums[pixel];
        Some([s0, s[0], s[1], s[2]].map(|c| c.map(|v| v / n)))
    }

    /// This film holding a camera's raw channels instead of XYZ: `to_rgb` shows them as
    /// they are (false colour outside the visible).
    pub fn with_raw_channels(mut self) -> Self {
        self.raw = true;
        self
    }

    /// Whether the sums are a camera's raw channels.
    pub fn is_raw(&self) -> bool {
        self.raw
    }

    /// This film, also recording radiance and photon radiance per pixel.
    pub fn with_energy(mut self) -> Self {
        self.energy = Some(vec![[0.0; 2]; self.sums.len()]);
        self
    }

    /// Whether the film records energy.
    pub fn has_energy(&self) -> bool {
        self.energy.is_some()
    }

    /// Pixel (x, y)'s radiance integrated over the rendered range (W m^-2 sr^-1) and its
    /// photon radiance (photons s^-1 m^-2 sr^-1), when the film records energy.
    pub fn energy(&self, x: u32, y: u32) -> Option<[f64; 2]> {
        let sums = self.energy.as_ref()?;
        let n = self.samples.max(1) as f64;
        let e = sums[(y * self.width + x) as usize];
        Some([e[0] / n, e[1] / n])
    }

    /// A black film that also accumulates spectral radiance in `bands`.
    pub fn with_bands(width: u32, height: u32, bands: SpectralBands) -> Self {
        let pixels = width as usize * height as usize;
        Self {
            spectral: Some((bands, vec![0.0; pixels * bands.count()])),
            ..Self::new(width, height)
        }
    }

    /// A black film of the settings' size, spectral when they ask for bands, recording
    /// energy when they ask for it.
    pub fn for_settings(settings: &crate::RenderSettings) -> Self {
        let film = match settings.bands {
            Some(bands) => Self::with_bands(settings.width, settings.height, bands),
            None => Self::new(settings.width, settings.height),
        };
        let film = if settings.energy {
            film.with_energy()
        } else {
            film
        };
        let film = if settings.is_polarized() {
            film.with_polarization()
        } else {
            film
        };
        let film = film.with_aovs(settings.aovs);
        if settings.camera.is_some() {
            film.with_raw_channels()
        } else {
            film
        }
    }

    /// The spectral bands, when the film is spectral.
    pub fn bands(&self) -> Option<SpectralBands> {
        self.spectral.as_ref().map(|(b, _)| *b)
    }

    /// The per-band sums, `bands().count()` per pixel (S0's; then S1's, S2's and S3's
    /// when polarized), empty when not spectral.
    pub fn spectral_sums(&self) -> &[f64] {
        self.spectral.as_ref().map_or(&[], |(_, s)| s)
    }

    /// The estimated spectral radiance of pixel (x, y) per band, when the film is spectral.
    pub fn spectrum(&self, x: u32, y: u32) -> Option<Vec<f64>> {
        self.stokes_spectrum(x, y, 0)
    }

    /// A film from its parts (merging and resuming): sums per pixel, samples per pixel,
    /// non-finite count; every sample counted as covered (see [`Film::with_coverage`]).
    /// None when the sums do not fit the size or are not finite.
    pub fn from_parts(
        width: u32,
        height: u32,
        sums: Vec<[f64; 3]>,
        samples: u64,
        nonfinite: u64,
    ) -> Option<Self> {
        (sums.len() == width as usize * height as usize
            && sums.iter().flatten().all(|v| v.is_finite()))
        .then_some(Self {
            width,
            height,
            coverage: vec![samples as f64; sums.len()],
            sums,
            samples,
            nonfinite,
            spectral: None,
            energy: None,
            stokes: None,
            raw: false,
            aovs: AovSums::default(),
        })
    }

    /// Every sum and count back to zero, the buffers kept.
    pub(crate) fn clear(&mut self) {
        self.sums.fill([0.0; 3]);
        self.coverage.fill(0.0);
        self.samples = 0;
        self.nonfinite = 0;
        if let Some((_, s)) = &mut self.spectral {
            s.fill(0.0);
        }
        if let Some(e) = &mut self.energy {
            e.fill([0.0; 2]);
        }
        if let Some(s) = &mut self.stokes {
            s.fill([[0.0; 3]; 3]);
        }
        self.aovs.clear();
    }

    /// A black film with this one's size and channels (bands, energy, raw or XYZ).
    #[cfg(feature = "exr")]
    pub(crate) fn black_like(&self) -> Self {
        Self {
            spectral: self
                .spectral
                .as_ref()
                .map(|(bands, sums)| (*bands, vec![0.0; sums.len()])),
            energy: self.energy.as_ref().map(|e| vec![[0.0; 2]; e.len()]),
            stokes: self.stokes.as_ref().map(|e| vec![[[0.0; 3]; 3]; e.len()]),
            raw: self.raw,
            aovs: AovSums::new(self.aovs.set(), self.sums.len()),
            ..Self::new(self.width, self.height)
        }
    }

    /// This film with spectral sums `sums` in `bands` (`bands.count()` per pixel), or None
    /// when they do not fit its size or are not finite (decoding accumulation files).
    #[cfg(feature = "exr")]
    pub(crate) fn with_spectral_sums(
        mut self,
        bands: SpectralBands,
        sums: Vec<f64>,
    ) -> Option<Self> {
        let components = if self.stokes.is_some() { 4 } else { 1 };
        let fits = sums.len() == self.sums.len() * bands.count() * components;
        (fits && sums.iter().all(|v| v.is_finite())).then(|| {
            self.spectral = Some((bands, sums));
            self
        })
    }

    /// This film with per-pixel coverage counts `coverage` (camera rays that met
    /// geometry), or None when they do not fit its size or are not finite and
    /// non-negative.
    pub fn with_coverage(mut self, coverage: Vec<f64>) -> Option<Self> {
        let fits = coverage.len() == self.sums.len();
        (fits && coverage.iter().all(|v| v.is_finite() && *v >= 0.0)).then(|| {
            self.coverage = coverage;
            self
        })
    }

    /// The per-pixel coverage counts (camera rays that met geometry).
    pub fn coverage(&self) -> &[f64] {
        &self.coverage
    }

    /// Pixel (x, y)'s alpha: the fraction of its camera rays that met geometry (0 before
    /// any sample).
    pub fn alpha(&self, x: u32, y: u32) -> f64 {
        self.alpha_at((y * self.width + x) as usize)
    }

    fn alpha_at(&self, pixel: usize) -> f64 {
        let n = self.samples.max(1) as f64;
        (self.coverage[pixel] / n).clamp(0.0, 1.0)
    }

    /// Every pixel's alpha, row-major.
    pub fn alphas(&self) -> Vec<f32> {
        (0..self.coverage.len())
            .map(|p| self.alpha_at(p) as f32)
            .collect()
    }

    /// This film with energy sums `sums` (one pair per pixel), or None when they do not
    /// fit its size or are not finite (decoding accumulation files).
    #[cfg(feature = "exr")]
    pub(crate) fn with_energy_sums(mut self, sums: Vec<[f64; 2]>) -> Option<Self> {
        let fits = sums.len() == self.sums.len();
        (fits && sums.iter().flatten().all(|v| v.is_finite())).then(|| {
            self.energy = Some(sums);
            self
        })
    }

    /// This film with Stokes sums `sums` (S1, S2, S3 colours per pixel), or None when
    /// they do not fit its size or are not finite (decoding accumulation files).
    #[cfg(feature = "exr")]
    pub(crate) fn with_stokes_sums(mut self, sums: Vec<[[f64; 3]; 3]>) -> Option<Self> {
        let fits = sums.len() == self.sums.len();
        (fits && sums.iter().flatten().flatten().all(|v| v.is_finite())).then(|| {
            self.stokes = Some(sums);
            self
        })
    }

    /// The Stokes sums, S1, S2, S3 colours per pixel (empty unless polarized).
    #[cfg(feature = "exr")]
    pub(crate) fn stokes_sums(&self) -> &[[[f64; 3]; 3]] {
        self.stokes.as_deref().unwrap_or(&[])
    }

    /// The energy sums, one (radiance, photon radiance) pair per pixel (empty without
    /// energy).
    #[cfg(feature = "exr")]
    pub(crate) fn energy_sums(&self) -> &[[f64; 2]] {
        self.energy.as_deref().unwrap_or(&[])
    }

    /// Width in pixels.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Height in pixels.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// Samples per pixel accumulated.
    pub fn samples(&self) -> u64 {
        self.samples
    }

    /// Samples rejected because their value was NaN or infinite.
    pub fn nonfinite(&self) -> u64 {
        self.nonfinite
    }

    /// The per-pixel sums.
    pub fn sums(&self) -> &[[f64; 3]] {
        &self.sums
    }

    /// The XYZ sums, the spectral sums (empty when not spectral), the energy sums (empty
    /// without energy), the Stokes sums (empty unless polarized) and the coverage counts,
    /// for filling by rows.
    pub(crate) fn sums_mut(&mut self) -> FilmSums<'_> {
        let spectral: &mut [f64] = match &mut self.spectral {
            Some((_, s)) => s,
            None => &mut [],
        };
        let energy: &mut [[f64; 2]] = match &mut self.energy {
            Some(e) => e,
            None => &mut [],
        };
        let stokes: &mut [[[f64; 3]; 3]] = match &mut self.stokes {
            Some(s) => s,
            None => &mut [],
        };
        FilmSums {
            xyz: &mut self.sums,
            spectral,
            energy,
            stokes,
            coverage: &mut self.coverage,
            replica: &mut self.aovs.replica,
        }
    }

    pub(crate) fn finish_pass(&mut self, samples: u64, nonfinite: u64) {
        self.samples += samples;
        self.nonfinite += nonfinite;
    }

    /// The estimate of pixel (x, y): its sum over the samples taken, as CIE XYZ with
    /// X = the integral of L(lambda) xbar(lambda) d lambda over 360-830 nm, L in W m^-2
    /// sr^-1 nm^-1 (unnormalized: a radiance of 1 at every wavelength gives Y = 106.86;
    /// multiply Y by 683 lm/W for luminance in cd m^-2).
    pub fn xyz(&self, x: u32, y: u32) -> Xyz {
        let s = self.sums[(y * self.width + x) as usize];
        let n = self.samples.max(1) as f64;
        Xyz::new(s[0] / n, s[1] / n, s[2] / n)
    }

    /// The image as linear RGB in `space` (no chromatic adaptation: XYZ is converted with
    /// the space's own matrix), row-major.
    pub fn to_rgb(&self, space: &RgbColorSpace) -> Vec<[f32; 3]> {
        self.sums.iter().map(|s| self.rgb(space, s)).collect()
    }

    /// Stokes component `k` (1, 2 or 3) as linear RGB in `space`, row-major (signed: the
    /// RGB of the polarized part's colour), when the film records polarization.
    pub fn stokes_rgb(&self, space: &RgbColorSpace, k: usize) -> Option<Vec<[f32; 3]>> {
        let sums = self.stokes.as_ref()?;
        let component = k.checked_sub(1).filter(|c| *c < 3)?;
        Some(
            sums.iter()
                .map(|s| self.rgb(space, &s[component]))
                .collect(),
        )
    }

    fn rgb(&self, space: &RgbColorSpace, sum: &[f64; 3]) -> [f32; 3] {
        let n = self.samples.max(1) as f64;
        let rgb = if self.raw {
            sum.map(|v| v / n)
        } else {
            space.xyz_to_rgb(Xyz::new(sum[0] / n, sum[1] / n, sum[2] / n))
        };
        rgb.map(saturating_f32)
    }

    /// This film with every XYZ sum transformed by `m` (white balance: a chromatic
    /// adaptation matrix); spectral and energy sums are physical and stay as they are.
    pub fn adapted(&self, m: &prism_spectrum::color::Mat3) -> Film {
        let mut film = self.clone();
        for s in &mut film.sums {
            *s = m.apply(*s);
        }
        for s in film.stokes.iter_mut().flatten().flatten() {
            *s = m.apply(*s);
        }
        film.aovs.adapt(m);
        film
    }

    /// Adds another film of the same size (sample ranges rendered apart).
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
    /// use prism_integrator::{render, RenderSettings};
    ///
    /// // Samples 0..8 rendered in two halves (on two machines, say) and merged are the
    /// // image of samples 0..8 rendered at once.
    /// let half = |samples| RenderSettings::default().width(8).height(6).samples(samples);
    /// let (mut film, _) = render(&scene, &half(0..4))?;
    /// film.merge(&render(&scene, &half(4..8))?.0)?;
    /// let (whole, _) = render(&scene, &half(0..8))?;
    /// assert_eq!(film.samples(), whole.samples());
    /// let (a, b) = (film.xyz(4, 5).y, whole.xyz(4, 5).y);
    /// assert!(b > 0.0 && (a - b).abs() <= 1e-9 * b);
    /// // Films of different sizes do not add up.
    /// let small = render(&scene, &half(0..1).width(4))?.0;
    /// assert!(film.merge(&small).is_err());
    /// # Ok::<(), prism_integrator::RenderError>(())
    /// ```
    pub fn merge(&mut self, other: &Film) -> Result<(), crate::RenderError> {
        if (self.width, self.height) != (other.width, other.height) {
            return Err(crate::RenderError::Merge(format!(
                "film sizes differ: {}x{} and {}x{}",
                self.width, self.height, other.width, other.height
            )));
        }
        match (&mut self.spectral, &other.spectral) {
            (Some((mine, a)), Some((theirs, b))) if mine == theirs => {
                for (x, y) in a.iter_mut().zip(b) {
                    *x += y;
                }
            }
            (None, None) => {}
            _ => {
                return Err(crate::RenderError::Merge(
                    "films differ in their spectral bands".into(),
                ));
            }
        }
        if self.raw != other.raw {
            return Err(crate::RenderError::Merge(
                "one film holds a camera's raw channels and the other XYZ".into(),
            ));
        }
        match (&mut self.energy, &other.energy) {
            (Some(a), Some(b)) => {
                for (x, y) in a.iter_mut().zip(b) {
                    x[0] += y[0];
                    x[1] += y[1];
                }
            }
            (None, None) => {}
            _ => {
                return Err(crate::RenderError::Merge(
                    "one film records energy and the other does not".into(),
                ));
            }
        }
        match (&mut self.stokes, &other.stokes) {
            (Some(a), Some(b)) => {
                for (x, y) in a
                    .iter_mut()
                    .flatten()
                    .flatten()
                    .zip(b.iter().flatten().flatten())
                {
                    *x += y;
                }
            }
            (None, None) => {}
            _ => {
                return Err(crate::RenderError::Merge(
                    "one film is polarized and the other is not".into(),
                ));
            }
        }
        for (a, b) in self.sums.iter_mut().zip(&other.sums) {
            for (acc, v) in a.iter_mut().zip(b) {
                *acc += v;
            }
        }
        self.aovs
            .merge(&other.aovs)
            .map_err(crate::RenderError::Merge)?;
        for (a, b) in self.coverage.iter_mut().zip(&other.coverage) {
            *a += b;
        }
        self.samples += other.samples;
        self.nonfinite += other.nonfinite;
        Ok(())
    }
}
