//! Textures and the spectra a scene is described with: colour textures upsampled to
//! spectra per lookup (`texture`), their mipmaps (`mipmap`), where a hit is in texture
//! space (`tex_coords`), and the spectra behind one type the integrator samples
//! (`spectrum`: [`SceneSpectrum`]).

mod mipmap;
mod spectrum;
mod tex_coords;
mod texture;

pub use spectrum::SceneSpectrum;
pub use tex_coords::{TEX_COORD_SETS, TexCoords};
pub use texture::{Encoding, RgbTexture, SpectralTexture, UvTransform, Wrap};
pub(crate) use texture::{illuminant_spectrum, reflectance_lanes};
