//! The film's files: EXR and PNG images, accumulation files that resume and merge renders,
//! image comparison (and Mitsuba's per-pixel z-test), and a denoised image's EXR.

#[cfg(feature = "exr")]
pub(crate) mod accumulation;
pub(crate) mod compare;
#[cfg(feature = "exr")]
pub(crate) mod denoised;
pub(crate) mod image;
pub(crate) mod png;
pub(crate) mod ztest;
