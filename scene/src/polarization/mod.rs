//! Polarization: Stokes vectors and Mueller matrices, the algebra a polarized renderer
//! carries along its paths (one Stokes vector per wavelength lane, one Mueller matrix per
//! interaction).
//!
//! ## Conventions (those of Mitsuba 3's polarized variants, so that images and tools agree)
//! - A Stokes vector S = (S0, S1, S2, S3) is measured in a **reference frame**: the
//!   direction of propagation w and a unit basis vector x perpendicular to it; y = w x x
//!   completes a right-handed frame (x, y, w). S0 is the intensity, S1 > 0 linear
//!   polarization along x (S1 < 0 along y), S2 > 0 linear along (x + y) / sqrt 2, S3 > 0
//!   circular polarization of positive helicity about w.
//! - A Mueller matrix maps a Stokes vector in its input frame to one in its output frame.
//!   Surfaces work in the **s-p frame** of the plane of incidence: x along s (perpendicular
//!   to the plane of incidence), for the incident and the outgoing light alike; a path
//!   rotates its Stokes vector into that frame with [`rotate_frame`] before the
//!   interaction ([`Mueller::rotator`] by the angle between the two basis vectors about w).
//! - Angles of linear elements (polarizers, retarders) are measured from x towards y.
//!
//! ## References
//! - E. Collett, *Field Guide to Polarization*, SPIE 2005, pp. 5-16 (Stokes parameters,
//!   Mueller matrices of polarizers, retarders and rotators).
//! - M. Born, E. Wolf, *Principles of Optics*, 7th ed., §1.5.2 (Fresnel's amplitude
//!   coefficients), §14.2 (metals: complex index).
//! - A. Wilkie, A. Weidlich, "Polarised light in computer graphics", SIGGRAPH Asia 2012
//!   courses (reference frames along paths).
//! - W. Jakob et al., Mitsuba 3 documentation, "Polarization" (the conventions above).

mod bsdf;
mod fresnel;
mod light;
mod mueller;
mod phase;
mod stokes;
mod surface;

pub use bsdf::{interactions, polarizes};
pub use fresnel::{FresnelAmplitudes, fresnel_amplitudes};
pub use light::LinearPolarization;
pub use mueller::Mueller;
pub use phase::phase_interaction;
pub use stokes::{Stokes, rotate_frame};
pub use surface::{Interaction, s_axis};
