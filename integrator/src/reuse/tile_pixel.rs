//! One pixel of a reuse tile: what its path left for the tile's gathering.

use prism_spectrum::SampledSpectrum;

use crate::film::sample_value::SampleValue;
use crate::transport::context::PathResult;
use crate::transport::reuse_record::ReuseRecord;

/// One pixel of a tile: its position, and what its path left.
pub(crate) struct TilePixel<'s, const N: usize> {
    pub x: u32,
    pub y: u32,
    pub result: PathResult,
    pub value: SampleValue,
    pub record: ReuseRecord<'s, N, SampledSpectrum<N>>,
}
