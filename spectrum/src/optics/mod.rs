//! Optics and energy: photon energy, radiometric <-> photometric conversion, refractive
//! index models (Sellmeier, Cauchy, Abbe number as glTF `KHR_materials_dispersion` defines
//! it), a catalogue of named glasses, and measured complex indices of metals.

mod energy;
mod glass;
mod ior;
mod metal;

pub use energy::{
    luminous_flux, photon_energy_ev, photon_energy_joules, radiant_scale_for_luminance,
};
pub use glass::{named_glass, Glass, GLASS_NAMES};
pub use ior::{abbe_number, Cauchy, Sellmeier, FRAUNHOFER_C_NM, FRAUNHOFER_D_NM, FRAUNHOFER_F_NM};
pub use metal::{named_metal, ComplexIor, METAL_NAMES};
