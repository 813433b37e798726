//! The feature pass: per camera sample, the first surface the camera sees and the first
//! one past the delta vertices, traced apart from the radiance's path.

use glam::Vec3;
use prism_sampling::stream::{SampleStream, SobolStream};
use prism_scene::bsdf::TransportMode;
use prism_spectrum::SampledSpectrum;
use rayon::prelude::*;
use std::sync::atomic::{AtomicBool, Ordering};

use crate::film::aov_sums::{AovRow, AovSums};
use crate::film::filter::FilterSampler;
use crate::pixels::sample::camera_sample;
use crate::pixels::sample_plan::SamplePlan;
use crate::transport::context::{
    DIMENSIONS_PER_BOUNCE, FIRST_BOUNCE_DIMENSION, Integrator, wavelengths,
};
use prism_scene::geometry::Frame;

/// Surfaces (and media boundaries) a feature ray passes at most: delta chains longer than
/// this (a hall of mirrors) keep the last weight and see nothing.
const MAX_VERTICES: u32 = 32;

/// What one camera sample sees.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(crate) struct Features {
    /// XYZ relative to the equal-energy white (see `AovSums::albedo`).
    pub albedo: [f64; 3],
    pub normal: [f64; 3],
    /// The first surface: its distance from the camera, its point, 1 + its material's
    /// index.
    pub first: Option<(f64, Vec3, u32)>,
}

impl Integrator<'_> {
    /// The features of sample `s` of pixel (`x`, `y`): its camera ray (the radiance's:
    /// the same film point, lens point and hero wavelength) followed through delta
    /// vertices by the BSDF numbers the radiance's path draws at each bounce, until a
    /// surface that is not a delta. Its directional albedo is estimated by one BSDF
    /// sample, f |cos| / pdf per wavelength, times the delta vertices' weights.
    pub(crate) fn features<const N: usize>(
        &self,
        filter: &FilterSampler,
        rows: &SamplePlan,
        x: u32,
        y: u32,
        s: u64,
    ) -> Features {
        let mut out = Features::default();
        let (mut stream, u_lambda, film) = camera_sample(filter, rows, x, y, s);
        let package = self.package::<N>(u_lambda);
        let Some(lambdas) = wavelengths(&package) else {
            return out;
        };
        let aspect = rows.width as f32 / rows.height as f32;
        let Some((mut ray, _)) = self.camera_ray(film, aspect, &stream, package.lambda[0]) else {
            return out;
        };
        // Each channel over the same wavelengths' estimate of a white's: a grey surface's
        // albedo is exact in every sample, and XYZ is relative to the equal-energy white,
        // whose X, Y and Z integrals are equal (CIE 015:2018 §7.1).
        let white = SampledSpectrum::<N>::splat(1.0).to_xyz(&lambdas, self.observer);
        let mut weight = SampledSpectrum::<N>::splat(1.0);
        let (mut travelled, mut depth) = (0.0f64, 0u64);
        for _ in 0..MAX_VERTICES {
            let Some(hit) = self.scene.intersect(&ray) else {
                break;
            };
            let length = f64::from(ray.direction.length());
            travelled += f64::from(hit.t) * length;
            if self.scene.is_interface(&hit) {
                ray = hit.spawn(ray.direction);
                continue;
            }
            if out.first.is_none() {
                let material = self.scene.material_index(&hit) + 1;
                out.first = Some((travelled, hit.p, material));
            }
            let bsdf = self.scene.bsdf(&hit, &lambdas, TransportMode::Radiance);
            let frame = Frame::from_normal(hit.shading_normal);
            let wo = frame.to_local(-ray.direction.normalize());
            let numbers = bounce_numbers(&mut stream, depth);
            let Some(sample) = bsdf.sample(wo, numbers.0, numbers.1) else {
                break;
            };
            let pdf = sample.pdf[0];
            if !(pdf > 0.0 && pdf.is_finite()) {
                break;
            }
            let bounce = sample.f * (sample.wi.z.abs() / pdf);
            if !bsdf.is_delta() {
                let albedo = (weight * bounce).to_xyz(&lambdas, self.observer);
                let ratio = |a: f64, w: f64| if w > 0.0 { a / w } else { 0.0 };
                out.albedo = [
                    ratio(albedo.x, white.x),
                    ratio(albedo.y, white.y),
                    ratio(albedo.z, white.z),
                ];
                out.normal = hit
                    .shading_normal
                    .normalize_or_zero()
                    .to_array()
                    .map(f64::from);
                break;
            }
            weight *= bounce;
            ray = hit.spawn(frame.to_world(sample.wi));
            depth += 1;
        }
        if !out.albedo.iter().chain(&out.normal).all(|v| v.is_finite()) {
            out.albedo = [0.0; 3];
            out.normal = [0.0; 3];
        }
        out
    }
}

/// The numbers the radiance's path chooses a BSDF lobe and direction with at bounce
/// `depth` (after its two light-sample numbers).
fn bounce_numbers(stream: &mut SobolStream, depth: u64) -> (f32, glam::Vec2) {
    stream.set_dimension(FIRST_BOUNCE_DIMENSION + depth * DIMENSIONS_PER_BOUNCE + 2);
    let u_lobe = stream.next_1d();
    (u_lobe, stream.next_2d())
}

/// Adds the features of `rows.samples` of every pixel to `sums`, rows in parallel (on the
/// caller's thread pool); stops between rows when `cancel` is set.
pub(crate) fn features_pass<const N: usize>(
    integrator: &Integrator,
    filter: &FilterSampler,
    rows: &SamplePlan,
    sums: &mut AovSums,
    cancel: &AtomicBool,
) {
    let width = rows.width as usize;
    let mut cut = sums.rows_mut(width, rows.height as usize);
    cut.par_iter_mut().enumerate().for_each(|(y, row)| {
        if cancel.load(Ordering::Relaxed) {
            return;
        }
        for x in 0..rows.width {
            for s in rows.samples.clone() {
                let f = integrator.features::<N>(filter, rows, x, y as u32, s);
                add(row, x as usize, s, &f);
            }
        }
    });
}

fn add(row: &mut AovRow, x: usize, s: u64, f: &Features) {
    let add3 = |sum: Option<&mut [f64; 3]>, v: [f64; 3]| {
        if let Some(sum) = sum {
            for (a, b) in sum.iter_mut().zip(v) {
                *a += b;
            }
        }
    };
    add3(row.albedo.get_mut(x), f.albedo);
    add3(row.normal.get_mut(x), f.normal);
    let (distance, p, material) = f.first.unwrap_or((0.0, Vec3::ZERO, 0));
    if f.first.is_some() {
        if let Some(h) = row.hits.get_mut(x) {
            *h += 1.0;
        }
        if let Some(d) = row.depth.get_mut(x) {
            *d += distance;
        }
        add3(row.position.get_mut(x), p.to_array().map(f64::from));
    }
    if let Some(m) = row.material.get_mut(x)
        && (s as f64) < m[0]
    {
        *m = [s as f64, f64::from(material)];
    }
}
