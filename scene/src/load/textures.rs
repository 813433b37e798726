//! glTF textures: images decoded once each, sampler wrap modes, `KHR_texture_transform`;
//! base colours upsampled through the loader's sRGB coefficient table (fitted once per
//! load, only when needed), metallic-roughness and normal textures read as linear data.

use std::cell::RefCell;
use std::collections::HashMap;
use std::sync::Arc;

use glam::Vec2;
use gltf::texture::WrappingMode;

use super::base64;
use super::tex_coord_sets::{TexCoordSets, info_set, normal_set, normal_transform};
use crate::materials::NormalMap;
use crate::textures::{Encoding, RgbTexture, SceneSpectrum, SpectralTexture, UvTransform, Wrap};

/// A decoded image shared by the textures that use it: width, height, texels, and its
/// alpha channel (repeated in three channels, so that it is an [`RgbTexture`] too).
type SharedImage = (u32, u32, Arc<Vec<[u8; 3]>>, Option<Arc<Vec<[u8; 3]>>>);

/// Loads textures for one glTF file.
pub(crate) struct TextureLoader<'a> {
    pub document: &'a gltf::Document,
    pub buffers: &'a [Vec<u8>],
    pub resolve: &'a crate::load::Resolver<'a>,
    pub upsampler: &'a super::Upsampler,
    images: RefCell<HashMap<usize, SharedImage>>,
}

impl<'a> TextureLoader<'a> {
    pub(crate) fn new(
        document: &'a gltf::Document,
        buffers: &'a [Vec<u8>],
        resolve: &'a crate::load::Resolver<'a>,
        upsampler: &'a super::Upsampler,
    ) -> Self {
        Self {
            document,
            buffers,
            resolve,
            upsampler,
            images: RefCell::new(HashMap::new()),
        }
    }

    /// The reflectance spectrum of a base colour texture times `factor`.
    pub(crate) fn base_color(
        &self,
        info: &gltf::texture::Info,
        factor: [f32; 3],
        sets: &TexCoordSets,
    ) -> Result<SceneSpectrum, String> {
        let rgb = self.info(info, factor, sets)?;
        Ok(SceneSpectrum::Texture(Arc::new(SpectralTexture::new(
            rgb,
            self.upsampler.table()?,
        ))))
    }

    /// The emission spectra of an emissive texture times `factor` (emissiveFactor times
    /// the strength).
    pub(crate) fn emission(
        &self,
        info: &gltf::texture::Info,
        factor: [f32; 3],
        sets: &TexCoordSets,
    ) -> Result<SceneSpectrum, String> {
        let rgb = self.info(info, factor, sets)?;
        Ok(SceneSpectrum::Texture(Arc::new(SpectralTexture::emission(
            rgb,
            self.upsampler.table()?,
            self.upsampler.context.clone(),
            self.upsampler.illuminant.clone(),
        )?)))
    }

    /// A metallic-roughness texture (linear; green is roughness, blue metallic) times the
    /// material's factors.
    pub(crate) fn metallic_roughness(
        &self,
        info: &gltf::texture::Info,
        metallic: f32,
        roughness: f32,
        sets: &TexCoordSets,
    ) -> Result<RgbTexture, String> {
        self.linear(info, [1.0, roughness, metallic], sets)
    }

    /// A data texture (linear) times `factor` per channel (`transmissionTexture`...).
    pub(crate) fn linear(
        &self,
        info: &gltf::texture::Info,
        factor: [f32; 3],
        sets: &TexCoordSets,
    ) -> Result<RgbTexture, String> {
        Ok(self.info(info, factor, sets)?.encoded(Encoding::Linear))
    }

    /// A normal texture (linear; tangent-space normals encoded as (n + 1) / 2) with its
    /// scale of the x and y components.
    pub(crate) fn normal(
        &self,
        normal: &gltf::material::NormalTexture,
        sets: &TexCoordSets,
    ) -> Result<NormalMap, String> {
        let uv = normal_transform(normal)?.map(|t| UvTransform {
            offset: Vec2::from(t.offset.0),
            rotation: t.rotation.0,
            scale: Vec2::from(t.scale.0),
        });
        let texture = self
            .rgb(normal.texture(), uv, [1.0; 3])?
            .with_set(sets.slot(normal_set(normal)));
        NormalMap::new(texture.encoded(Encoding::Linear), normal.scale()).map_err(|e| e.to_string())
    }

    /// The texture `info` refers to, with its sampler, transform and texture coordinate
    /// set (where `sets` keeps it), times `factor`.
    fn info(
        &self,
        info: &gltf::texture::Info,
        factor: [f32; 3],
        sets: &TexCoordSets,
    ) -> Result<RgbTexture, String> {
        let uv = info.texture_transform().map(|t| UvTransform {
            offset: Vec2::from(t.offset()),
            rotation: t.rotation(),
            scale: Vec2::from(t.scale()),
        });
        Ok(self
            .rgb(info.texture(), uv, factor)?
            .with_set(sets.slot(info_set(info))))
    }

    /// A texture that a material extension refers to (`reference`: glTF's textureInfo
    /// JSON, `{"index", "texCoord", "extensions"}`), linear, times `factor`: the
    /// extensions' factor textures (iridescence, clearcoat, sheen...) hold data, not
    /// colour.
    pub(crate) fn extension_texture(
        &self,
        reference: &serde_json::Value,
        factor: [f32; 3],
        sets: &TexCoordSets,
    ) -> Result<RgbTexture, String> {
        Ok(self
            .extension_rgb(reference, factor, sets)?
            .1
            .encoded(Encoding::Linear))
    }

    /// A colour texture that a material extension refers to (sRGB-encoded, as glTF's
    /// colour textures are: `specularColorTexture`, `sheenColorTexture`), times `factor`,
    /// as reflectance spectra.
    pub(crate) fn extension_color(
        &self,
        reference: &serde_json::Value,
        factor: [f32; 3],
        sets: &TexCoordSets,
    ) -> Result<SceneSpectrum, String> {
        let (_, rgb) = self.extension_rgb(reference, factor, sets)?;
        Ok(SceneSpectrum::Texture(Arc::new(SpectralTexture::new(
            rgb,
            self.upsampler.table()?,
        ))))
    }

    /// The alpha channel of a texture that a material extension refers to, times
    /// `factor`, linear, in every channel (`specularTexture`, `sheenRoughnessTexture`);
    /// None when its image has no alpha (which reads as 1).
    pub(crate) fn extension_alpha(
        &self,
        reference: &serde_json::Value,
        factor: f32,
        sets: &TexCoordSets,
    ) -> Result<Option<RgbTexture>, String> {
        let (texture, colour) = self.extension_rgb(reference, [factor; 3], sets)?;
        self.alpha_of(&texture, &colour, factor)
    }

    /// The texture a material extension's textureInfo names, and it read as an sRGB
    /// texture times `factor` on its set with its transform.
    fn extension_rgb(
        &self,
        reference: &serde_json::Value,
        factor: [f32; 3],
        sets: &TexCoordSets,
    ) -> Result<(gltf::texture::Texture<'a>, RgbTexture), String> {
        let info = texture_reference(reference)?;
        let texture = self
            .document
            .textures()
            .nth(info.index.value())
            .ok_or_else(|| format!("texture {} does not exist", info.index.value()))?;
        let transform = info
            .extensions
            .as_ref()
            .and_then(|e| e.texture_transform.as_ref());
        let uv = transform.map(|t| UvTransform {
            offset: Vec2::from(t.offset.0),
            rotation: t.rotation.0,
            scale: Vec2::from(t.scale.0),
        });
        let rgb = self
            .rgb(texture.clone(), uv, factor)?
            .with_set(sets.slot(reference_set(&info)));
        Ok((texture, rgb))
    }

    /// The alpha channel of a base colour texture times `factor` (baseColorFactor's
    /// alpha), as a linear texture whose channels all hold it; None when the image has no
    /// alpha.
    pub(crate) fn alpha(
        &self,
        info: &gltf::texture::Info,
        factor: f32,
        sets: &TexCoordSets,
    ) -> Result<Option<RgbTexture>, String> {
        let colour = self.info(info, [factor; 3], sets)?;
        self.alpha_of(&info.texture(), &colour, factor)
    }

    /// The alpha channel of `texture`'s image read as `colour` reads its colour (wrap,
    /// transform, set, filter), times `factor`; None when the image has no alpha.
    fn alpha_of(
        &self,
        texture: &gltf::texture::Texture,
        colour: &RgbTexture,
        factor: f32,
    ) -> Result<Option<RgbTexture>, String> {
        let (width, height, _, alpha) = self.image(&texture.source())?;
        let Some(alpha) = alpha else {
            return Ok(None);
        };
        let texture = RgbTexture::new(
            width,
            height,
            alpha,
            colour.wrap(),
            colour.transform(),
            [factor; 3],
        )?
        .encoded(Encoding::Linear)
        .with_set(colour.set());
        Ok(Some(if colour.is_nearest() {
            texture.nearest()
        } else {
            texture
        }))
    }

    /// `texture`, transformed by `uv`, times `factor`, reading the first texture
    /// coordinate set.
    fn rgb(
        &self,
        texture: gltf::texture::Texture,
        uv: Option<UvTransform>,
        factor: [f32; 3],
    ) -> Result<RgbTexture, String> {
        let sampler = texture.sampler();
        let wrap = [sampler.wrap_s(), sampler.wrap_t()].map(|w| match w {
            WrappingMode::ClampToEdge => Wrap::Clamp,
            WrappingMode::MirroredRepeat => Wrap::Mirror,
            WrappingMode::Repeat => Wrap::Repeat,
        });
        let (width, height, texels, _) = self.image(&texture.source())?;
        let rgb = RgbTexture::new(width, height, texels, wrap, uv.unwrap_or_default(), factor)?;
        Ok(match sampler.mag_filter() {
            Some(gltf::texture::MagFilter::Nearest) => rgb.nearest(),
            _ => rgb,
        })
    }

    fn image(&self, image: &gltf::Image) -> Result<SharedImage, String> {
        if let Some(found) = self.images.borrow().get(&image.index()) {
            return Ok(found.clone());
        }
        let what = format!("image {}", image.index());
        let bytes = match image.source() {
            gltf::image::Source::View { view, .. } => {
                let buffer = self
                    .buffers
                    .get(view.buffer().index())
                    .ok_or_else(|| format!("{what}: its buffer is missing"))?;
                let (start, length) = (view.offset(), view.length());
                buffer
                    .get(start..start.saturating_add(length))
                    .ok_or_else(|| format!("{what}: its buffer view runs past the buffer"))?
                    .to_vec()
            }
            gltf::image::Source::Uri { uri, .. } => {
                base64::uri_bytes(uri, self.resolve).map_err(|e| format!("{what}: {e}"))?
            }
        };
        let decoded = super::images::decode(&bytes).map_err(|e| format!("{what}: {e}"))?;
        let alpha = decoded
            .alpha
            .map(|a| Arc::new(a.into_iter().map(|v| [v; 3]).collect()));
        let entry = (decoded.width, decoded.height, Arc::new(decoded.rgb), alpha);
        self.images
            .borrow_mut()
            .insert(image.index(), entry.clone());
        Ok(entry)
    }
}

/// A textureInfo as a material extension writes it.
pub(crate) fn texture_reference(
    reference: &serde_json::Value,
) -> Result<gltf::json::texture::Info, String> {
    serde_json::from_value(reference.clone())
        .map_err(|e| format!("texture reference {reference}: {e}"))
}

/// The set a textureInfo reads (its transform's `texCoord` overriding its own).
pub(crate) fn reference_set(info: &gltf::json::texture::Info) -> u32 {
    info.extensions
        .as_ref()
        .and_then(|e| e.texture_transform.as_ref())
        .and_then(|t| t.tex_coord)
        .unwrap_or(info.tex_coord)
}
