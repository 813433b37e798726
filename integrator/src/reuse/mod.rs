//! Path reuse across a tile of pixels (Bekaert, Sbert and Halton, "Accelerating path
//! tracing by re-using paths", EGWR 2002): the pixels of a T x T tile trace sample s
//! with the same wavelengths, and each pixel's first vertex x1_i gathers the light
//! reflected at every tile pixel's second vertex x2_k, not only at its own.
//!
//! Each x2_k was sampled by pixel k's BSDF at x1_k (cosine sampling, or a plastic's two
//! lobes). Seen from pixel i it is one sample of T^2 techniques, one per first vertex of
//! the tile, and the balance heuristic combines them (the multi-sample estimator of
//! Veach's thesis, §9.2.2, one sample per technique): pixel i adds
//!
//!   f_i(x1_i -> x2_k) |cos theta_i| G(x1_i, x2_k) V(x1_i, x2_k) S_k / sum_m p_m(x2_k)
//!
//! for every k, where p_m(x) = pdf_m(direction) |cos theta_x| / d^2 is technique m's
//! density of x in area measure (zero where x is hidden from x1_m or seen from its other
//! side) and S_k the radiance x2_k reflects, estimated by pixel k's path beyond it. This
//! is unbiased provided S_k is the same towards every x1_i that counts it: x2 must reflect
//! alike in every direction on a side ([`prism_scene::world::Scene::reflects_alike`]: a
//! Lambertian material of one reflectance), and a point counts as two, one per side of
//! its shading normal. Second vertices of any other kind (glass, metal, a texture, an
//! emitter's own light, the sky) stay their own pixel's, weighted 1, and so does the
//! whole path of a pixel whose first vertex cannot share ([`shares_first`]: Lambertian,
//! or a plastic under a rough coating, whose density each pair asks of its BSDF): the
//! domain is partitioned,
//! and on each part every technique that can sample it is counted.
//!
//! What it costs: a shadow ray per pair of first and second vertices of different
//! pixels, T^2 - 1 per pixel and sample. What it buys: each pixel's indirect light is
//! estimated from T^2 continuations instead of one; on the Cornell box the error per
//! sample falls several times over for a fraction more time, the more the larger the tile
//! (docs/trade-offs.md, "Path reuse across tiles of pixels").
//!
//! The tiles stay in place from sample to sample, so that the second vertices a pixel
//! gathers over its samples come from a few Sobol streams, each stratified over the
//! samples: tiles that moved with every sample (their corner cycling through the T^2
//! offsets) raised the Cornell box's error, and so did tiles that moved every few
//! samples (docs/trade-offs.md, "Tried and not kept"). The price is that within a tile the
//! noise is shared: at a few samples per pixel the image shows it as faint T x T blocks. A
//! tile's wavelengths are its corner pixel's (that pixel's wavelength dimension),
//! stratified over the samples.

use prism_sampling::stream::SampleStream;
use prism_scene::world::EmissionCache;
use prism_spectrum::{SampledSpectrum, SampledWavelengths};

mod gather;
pub(crate) mod pass;
mod tile_pixel;

use gather::Gathering;
use tile_pixel::TilePixel;

use crate::film::filter::FilterSampler;
use crate::film::sample_value::SampleValue;
use crate::pixels::sample::camera_sample;
use crate::pixels::sample_plan::SamplePlan;
use crate::transport::context::{FIRST_BOUNCE_DIMENSION, Integrator, PathResult};
use crate::transport::reuse_record::ReuseRecord;
use crate::transport::volume::FlightStreams;

/// A tile's pixels and the buffers of its gathering, kept from tile to tile.
pub(crate) struct Tile<'s, const N: usize> {
    pixels: Vec<TilePixel<'s, N>>,
    /// The spectra the tile's paths evaluate, kept from path to path: they share their
    /// wavelengths (the cache refills where the next tile's differ).
    emission: EmissionCache<N>,
    len: usize,
    gathering: Gathering<N>,
}

impl<'s, const N: usize> Tile<'s, N> {
    pub(crate) fn new() -> Self {
        Self {
            pixels: Vec::new(),
            emission: EmissionCache::new(),
            len: 0,
            gathering: Gathering::new(),
        }
    }

    /// The last tile's pixels, row by row.
    pub(crate) fn pixels(&self) -> &[TilePixel<'s, N>] {
        &self.pixels[..self.len]
    }
}

impl<'a> Integrator<'a> {
    /// Traces sample `s` of the tile of pixels `xs` x `ys` with the wavelengths drawn
    /// with `lambda` into `tile`.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn trace_tile<const N: usize>(
        &self,
        filter: &FilterSampler,
        rows: &SamplePlan,
        xs: std::ops::Range<u32>,
        ys: std::ops::Range<u32>,
        s: u64,
        lambda: f32,
        tile: &mut Tile<'a, N>,
    ) {
        let (w, h) = (rows.width, rows.height);
        let aspect = w as f32 / h as f32;
        let mut lambdas: Option<SampledWavelengths<N>> = None;
        // The tile's paths share their wavelengths: drawn once.
        let package = self.package::<N>(lambda);
        tile.len = 0;
        for y in ys.clone() {
            for x in xs.clone() {
                // The pixel's own wavelength number stays unused: the tile's is shared.
                let (mut stream, _, film) = camera_sample(filter, rows, x, y, s);
                if tile.len == tile.pixels.len() {
                    tile.pixels.push(TilePixel {
                        x,
                        y,
                        result: PathResult::nothing(false),
                        value: SampleValue::default(),
                        record: ReuseRecord::new(SampledSpectrum::splat(0.0)),
                    });
                }
                let here = &mut tile.pixels[tile.len];
                tile.len += 1;
                here.x = x;
                here.y = y;
                here.value.clear();
                here.record.first = None;
                here.record.second = None;
                let value = &mut here.value;
                let mut sink = |radiance: &SampledSpectrum<N>, l: &SampledWavelengths<N>| {
                    lambdas = Some(*l);
                    value.add(self.sensor(), rows.outputs, radiance, l);
                };
                here.result = if self.scene.features().media {
                    let pixel = u64::from(y) * u64::from(w) + u64::from(x);
                    self.trace_volume::<N, false, true, SampledSpectrum<N>>(
                        &mut stream,
                        FIRST_BOUNCE_DIMENSION,
                        &package,
                        film,
                        aspect,
                        &mut sink,
                        &mut here.record,
                        &mut tile.emission,
                        &mut FlightStreams::new(rows.seed, pixel, s),
                    )
                } else {
                    self.trace::<N, false, false, true, SampledSpectrum<N>>(
                        &mut stream,
                        FIRST_BOUNCE_DIMENSION,
                        &package,
                        film,
                        aspect,
                        &mut sink,
                        &mut here.record,
                        &mut tile.emission,
                    )
                };
            }
        }
        if let Some(lambdas) = lambdas {
            let pixels = &mut tile.pixels[..tile.len];
            let gathered = tile.gathering.gather(self.scene, pixels);
            for (pixel, light) in pixels.iter_mut().zip(gathered) {
                if !light.is_black() {
                    pixel
                        .value
                        .add(self.sensor(), rows.outputs, light, &lambdas);
                }
            }
        }
    }
}

/// Traces sample `s` of the tile `xs` x `ys` with its corner's wavelengths, as a render
/// does (the pilot's tiles).
#[allow(clippy::too_many_arguments)]
pub(crate) fn trace_tile_at<'a, const N: usize>(
    integrator: &Integrator<'a>,
    filter: &FilterSampler,
    rows: &SamplePlan,
    xs: std::ops::Range<u32>,
    ys: std::ops::Range<u32>,
    s: u64,
    tile: &mut Tile<'a, N>,
) {
    let corner = u64::from(ys.start) * u64::from(rows.width) + u64::from(xs.start);
    let lambda = rows.stream(rows.seed, corner, s).next_1d();
    integrator.trace_tile::<N>(filter, rows, xs, ys, s, lambda, tile);
}

/// Traces pass `s` of every pixel of the rows `ys` (one row of tiles) in tiles `size`
/// pixels wide (one sample, or adaptive sampling's samples of the pass), and hands each
/// pixel's sample to `add` with its index and weight.
pub(crate) fn trace_band<const N: usize>(
    integrator: &Integrator,
    filter: &FilterSampler,
    rows: &SamplePlan,
    size: u32,
    ys: std::ops::Range<u32>,
    s: u64,
    add: &mut impl FnMut(&TilePixel<'_, N>, u64, f64),
) {
    let mut tile = Tile::new();
    for x0 in (0..rows.width).step_by(size as usize) {
        let xs = x0..(x0 + size).min(rows.width);
        // A tile of reuse lies in one tile of adaptive sampling's rates.
        let (samples, weight) = crate::adaptive::samples_of(rows.map.as_deref(), x0, ys.start, s);
        for sample in samples {
            trace_tile_at::<N>(
                integrator,
                filter,
                rows,
                xs.clone(),
                ys.clone(),
                sample,
                &mut tile,
            );
            for pixel in tile.pixels() {
                add(pixel, sample, weight);
            }
        }
    }
}
