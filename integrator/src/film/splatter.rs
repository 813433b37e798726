//! Light paths' splats on the film, weighted by the film's filter.

use glam::Vec2;

use crate::film::Film;
use crate::film::filter::FilterSampler;
use crate::film::sample_value::SampleValue;

/// Adds light-path splats to a film's sums with the film's filter: a splat at film
/// position x adds to pixel p with the filter's density at x minus p's centre, the weight
/// with which p's own samples would have landed at x (the tabulated filter camera samples
/// use, so both estimate the same filtered image).
pub(crate) struct Splatter<'a> {
    width: u32,
    height: u32,
    band_count: usize,
    sums: &'a mut [[f64; 3]],
    spectral: &'a mut [f64],
    energy: &'a mut [[f64; 2]],
    stokes: &'a mut [[[f64; 3]; 3]],
    /// The second replicate's sums (empty without the variance AOV).
    replica: &'a mut [[f64; 4]],
    filter: &'a FilterSampler,
}

impl<'a> Splatter<'a> {
    pub(crate) fn new(film: &'a mut Film, filter: &'a FilterSampler) -> Self {
        let (width, height) = (film.width(), film.height());
        let band_count = film.spectral_width();
        let sums = film.sums_mut();
        Self {
            width,
            height,
            band_count,
            sums: sums.xyz,
            spectral: sums.spectral,
            energy: sums.energy,
            stokes: sums.stokes,
            replica: sums.replica,
            filter,
        }
    }

    /// Adds `value` (clamped as camera samples are) at `film` in [0, 1)^2; `second`:
    /// whether it belongs to the second replicate (`Replicas`).
    pub(crate) fn add(
        &mut self,
        film: Vec2,
        value: &SampleValue,
        clamp: Option<f64>,
        second: bool,
    ) {
        let scale = value.clamp_scale(clamp);
        let at = Vec2::new(film.x * self.width as f32, film.y * self.height as f32);
        match self.filter.profile() {
            None => {
                let (x, y) = (at.x as u32, at.y as u32);
                if x < self.width && y < self.height {
                    self.add_to_pixel(x, y, value, scale, second);
                }
            }
            Some(profile) => {
                let (lo, hi) = profile.domain();
                let (lo, hi) = (lo as f32, hi as f32);
                let range = |c: f32, size: u32| {
                    let first = (c - hi - 0.5).ceil().max(0.0) as u32;
                    let last = ((c - lo - 0.5).floor().max(-1.0) as i64).min(i64::from(size) - 1);
                    first..(last + 1).max(0) as u32
                };
                for y in range(at.y, self.height) {
                    let wy = profile.pdf(f64::from(at.y - y as f32 - 0.5));
                    if wy <= 0.0 {
                        continue;
                    }
                    for x in range(at.x, self.width) {
                        let w = wy * profile.pdf(f64::from(at.x - x as f32 - 0.5));
                        if w > 0.0 {
                            self.add_to_pixel(x, y, value, scale * w, second);
                        }
                    }
                }
            }
        }
    }

    fn add_to_pixel(&mut self, x: u32, y: u32, value: &SampleValue, weight: f64, second: bool) {
        let i = y as usize * self.width as usize + x as usize;
        if let Some(r) = self.replica.get_mut(i).filter(|_| second) {
            for (a, b) in r.iter_mut().zip(value.xyz) {
                *a += b * weight;
            }
        }
        let spectral = self
            .spectral
            .get_mut(i * self.band_count..(i + 1) * self.band_count)
            .unwrap_or_default();
        value.add_to(
            weight,
            &mut self.sums[i],
            spectral,
            self.energy.get_mut(i),
            self.stokes.get_mut(i),
        );
    }
}
