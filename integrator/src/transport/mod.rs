//! Light transport: what every path of a render shares (`context`), what a path carries
//! (`throughput`, `light_throughput`), the path tracer (`path/`), the volumetric path
//! tracer (`volume/`), light paths for caustics (`light_path`) and what a camera path
//! records for path reuse (`reuse_record`).

pub(crate) mod clock;
pub(crate) mod context;
pub(crate) mod footprint;
pub(crate) mod light_path;
pub(crate) mod light_throughput;
pub(crate) mod path;
pub(crate) mod reuse_record;
pub(crate) mod throughput;
pub(crate) mod volume;
