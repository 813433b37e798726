//! Where a hit is in texture space. glTF lets every texture of a material name its own
//! texture coordinate set (`TEXCOORD_n`, or `KHR_texture_transform`'s `texCoord`); a
//! scene keeps two sets per triangle, and each texture reads one of them (its
//! [`RgbTexture::set`](super::RgbTexture::set)): what the files that use more than one
//! set do (a detail or lightmap layer over a base layer, in glTF's MultiUVTest).

use glam::Vec2;

/// How many texture coordinate sets a scene keeps per triangle.
pub const TEX_COORD_SETS: usize = 2;

/// A point's coordinates in each texture coordinate set, and the footprint around it in
/// each (base-2 logarithm of its width in units of that set's coordinates; `-inf` reads
/// texels unfiltered).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TexCoords {
    /// The coordinates, set by set.
    pub uv: [Vec2; TEX_COORD_SETS],
    /// The footprints, set by set.
    pub lod: [f32; TEX_COORD_SETS],
}

impl TexCoords {
    /// The same coordinates `uv` in every set, read unfiltered.
    pub fn new(uv: Vec2) -> Self {
        Self {
            uv: [uv; TEX_COORD_SETS],
            lod: [f32::NEG_INFINITY; TEX_COORD_SETS],
        }
    }

    /// Set `set`'s coordinates and footprint (the last set for a larger number).
    pub fn set(&self, set: usize) -> (Vec2, f32) {
        let s = set.min(TEX_COORD_SETS - 1);
        (self.uv[s], self.lod[s])
    }

    /// The coordinates at barycentrics `b` of a triangle whose vertices have `vertices`
    /// (set by set), read unfiltered.
    pub(crate) fn interpolate(vertices: [[Vec2; 3]; TEX_COORD_SETS], b: [f32; 3]) -> Self {
        Self {
            uv: vertices.map(|t| b[0] * t[0] + b[1] * t[1] + b[2] * t[2]),
            lod: [f32::NEG_INFINITY; TEX_COORD_SETS],
        }
    }
}

impl Default for TexCoords {
    fn default() -> Self {
        Self::new(Vec2::ZERO)
    }
}

impl From<Vec2> for TexCoords {
    fn from(uv: Vec2) -> Self {
        Self::new(uv)
    }
}
