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
pub use glass::{GLASS_NAMES, Glass, named_glass};
pub use ior::{Cauchy, FRAUNHOFER_C_NM, FRAUNHOFER_D_NM, FRAUNHOFER_F_NM, Sellmeier, abbe_number};
pub use metal::{ComplexIor, METAL_NAMES, named_metal};
