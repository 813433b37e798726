//! Materials of a render-ready scene (`material`: [`Material`], and the BSDF each becomes
//! at a hit), the glTF material extensions layered on the metallic-roughness base
//! (`layers/`), normal textures (`normal_map`) and alpha coverage (`alpha`: cut-outs and
//! stochastic transparency).

mod alpha;
mod layers;
mod material;
mod normal_map;
mod perturbation;
mod principled;

pub(crate) use alpha::blend_number;
pub use alpha::{Alpha, AlphaMode};
pub use layers::{
    AnisotropyDesc, ClearcoatDesc, DiffuseTransmissionDesc, IridescenceDesc, Layers, SheenDesc,
    SpecularDesc, SurfaceFrame, TransmissionDesc,
};
pub use material::Material;
pub use normal_map::NormalMap;
#[cfg(feature = "gltf")]
pub(crate) use normal_map::triangle_tangent;
pub use perturbation::{Perturbation, PerturbationInput};
pub use principled::{PrincipledDesc, PrincipledThinDesc};
