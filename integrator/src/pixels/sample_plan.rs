//! What a pass's samples depend on besides the tracer: the image, the seed, the sample
//! indices and how they are spread.

use std::ops::Range;
use std::sync::Arc;

use prism_sampling::stream::{Replicas, SobolStream};

use crate::adaptive::SampleMap;
use crate::film::sample_value::Outputs;

/// What a row's samples depend on besides the tracer.
pub(crate) struct SamplePlan {
    pub width: u32,
    pub height: u32,
    pub seed: u64,
    pub clamp: Option<f64>,
    pub samples: Range<u64>,
    /// How samples are split into independently scrambled groups: two when the film
    /// records its variance, whose estimate is their spread (`crate::film::aov`).
    pub replicas: Replicas,
    pub outputs: Outputs,
    /// Where adaptive sampling spreads the samples (None: one per pixel per pass).
    pub map: Option<Arc<SampleMap>>,
}

impl SamplePlan {
    /// The stream of sample `s` of `pixel` under `seed` (the render's, or a stream's own
    /// seed derived from it).
    #[inline]
    pub(crate) fn stream(&self, seed: u64, pixel: u64, s: u64) -> SobolStream {
        self.replicas.stream(seed, pixel, s)
    }
}
