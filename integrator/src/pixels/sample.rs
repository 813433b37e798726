//! One camera sample: its stream, wavelengths and film point, traced by the path tracer
//! or, in a scene with media, the volumetric one (the one place that chooses).

use glam::Vec2;
use prism_sampling::stream::{SampleStream, SobolStream};
use prism_scene::world::EmissionCache;

use crate::film::filter::FilterSampler;
use crate::film::sample_value::SampleValue;
use crate::pixels::sample_plan::SamplePlan;
use crate::transport::context::{FIRST_BOUNCE_DIMENSION, Integrator, PathResult};
use crate::transport::reuse_record::ReuseRecord;
use crate::transport::throughput::Throughput;
use crate::transport::volume::FlightStreams;

/// Sample `s` of pixel (`x`, `y`): its stream (positioned after the film dimensions),
/// the number that chooses its wavelengths and its point on the film (in [0, 1]^2).
pub(crate) fn camera_sample(
    filter: &FilterSampler,
    settings: &SamplePlan,
    x: u32,
    y: u32,
    s: u64,
) -> (SobolStream, f32, Vec2) {
    let (w, h) = (settings.width, settings.height);
    let pixel = u64::from(y) * u64::from(w) + u64::from(x);
    let mut stream = settings.stream(settings.seed, pixel, s);
    let u_lambda = stream.next_1d();
    let offset = filter.offset(stream.next_2d());
    let film = Vec2::new(
        (x as f32 + 0.5 + offset.x) / w as f32,
        (y as f32 + 0.5 + offset.y) / h as f32,
    );
    (stream, u_lambda, film)
}

/// Traces sample `s` of pixel (`x`, `y`) into `value` (cleared first).
pub(crate) fn trace_sample<const N: usize, const FLUORESCENCE: bool, T: Throughput<N>>(
    integrator: &Integrator,
    filter: &FilterSampler,
    settings: &SamplePlan,
    x: u32,
    y: u32,
    s: u64,
    value: &mut SampleValue,
) -> PathResult {
    let (w, h) = (settings.width, settings.height);
    let (mut stream, u_lambda, film) = camera_sample(filter, settings, x, y, s);
    value.clear();
    let aspect = w as f32 / h as f32;
    let mut sink = |radiance: &T::Radiance, lambdas: &_| {
        value.add(integrator.sensor(), settings.outputs, radiance, lambdas)
    };
    if integrator.scene.features().media {
        let pixel = u64::from(y) * u64::from(w) + u64::from(x);
        return integrator.trace_volume::<N, FLUORESCENCE, false, T>(
            &mut stream,
            FIRST_BOUNCE_DIMENSION,
            &integrator.package(u_lambda),
            film,
            aspect,
            &mut sink,
            &mut ReuseRecord::new(T::black()),
            &mut EmissionCache::new(),
            &mut FlightStreams::new(settings.seed, pixel, s),
        );
    }
    // Unsplit renders run a path tracer compiled without the splitting code.
    let trace = if integrator.splits > 1 {
        Integrator::trace::<N, FLUORESCENCE, true, false, T>
    } else {
        Integrator::trace::<N, FLUORESCENCE, false, false, T>
    };
    trace(
        integrator,
        &mut stream,
        FIRST_BOUNCE_DIMENSION,
        &integrator.package(u_lambda),
        film,
        aspect,
        &mut sink,
        &mut ReuseRecord::new(T::black()),
        &mut EmissionCache::new(),
    )
}
