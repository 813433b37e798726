//! Textures and the spectra a scene is described with: colour textures upsampled to
//! spectra per lookup (`texture`), their mipmaps (`mipmap`), where a hit is in texture
//! space (`tex_coords`), and the spectra behind one type the integrator samples
//! (`spectrum`: [`SceneSpectrum`]); images of float texels looked up as Mitsuba's bitmap
//! texture does (`texels`) and the spectra that vary over a surface as Mitsuba's textures
//! do (`pattern`).

mod float_texture;
mod mipmap;
mod pattern;
mod spectrum;
mod tex_coords;
mod texels;
mod texture;

pub use float_texture::FloatTexture;
pub use pattern::Pattern;
pub use spectrum::SceneSpectrum;
pub use tex_coords::{TEX_COORD_SETS, TexCoords};
pub use texels::{Filter, LUMINANCE, Texels};
pub use texture::{Encoding, RgbTexture, SpectralTexture, UvTransform, Wrap};
pub(crate) use texture::{illuminant_spectrum, reflectance_lanes};
