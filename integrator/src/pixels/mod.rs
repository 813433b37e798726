//! The pixels' samples: what a pass's samples depend on (`sample_plan`), one camera
//! sample traced by the tracer the scene needs (`sample`), rows of pixels summed in order
//! (`rows`) and light paths' splats collected per row (`splats`).

pub(crate) mod features;
pub(crate) mod rows;
pub(crate) mod sample;
pub(crate) mod sample_plan;
pub(crate) mod splats;
