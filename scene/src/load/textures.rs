//! glTF textures: images decoded once each, sampler wrap modes, `KHR_texture_transform`;
//! base colours upsampled through the loader's sRGB coefficient table (fitted once per
//! load, only when needed), metallic-roughness and normal textures read as linear data.

use std::cell::RefCell;
use std::collections::HashMap;
use std::sync::Arc;

use glam::Vec2;
use gltf::texture::WrappingMode;

use super::base64;
use super::images::decode_image;
use crate::world::{
    Encoding, NormalMap, RgbTexture, SceneSpectrum, SpectralTexture, UvTransform, Wrap,
};

/// A decoded image shared by the textures that use it: width, height, texels, and its
/// alpha channel (repeated in three channels, so that it is an [`RgbTexture`] too).
type SharedImage = (u32, u32, Arc<Vec<[u8; 3]>>, Option<Arc<Vec<[u8; 3]>>>);

/// Loads textures for one glTF file.
pub(crate) struct TextureLoader<'a> {
    pub buffers: &'a [Vec<u8>],
    pub resolve: &'a dyn Fn(&str) -> Result<Vec<u8>, String>,
    pub upsampler: &'a super::Upsampler,
    images: RefCell<HashMap<usize, SharedImage>>,
}

impl<'a> TextureLoader<'a> {
    pub(crate) fn new(
        buffers: &'a [Vec<u8>],
        resolve: &'a dyn Fn(&str) -> Result<Vec<u8>, String>,
        upsampler: &'a super::Upsampler,
    ) -> Self {
        Self {
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
    ) -> Result<SceneSpectrum, String> {
        let rgb = self.info(info, factor)?;
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
    ) -> Result<SceneSpectrum, String> {
        let rgb = self.info(info, factor)?;
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
    ) -> Result<RgbTexture, String> {
        Ok(self
            .info(info, [1.0, roughness, metallic])?
            .encoded(Encoding::Linear))
    }

    /// A normal texture (linear; tangent-space normals encoded as (n + 1) / 2) with its
    /// scale of the x and y components.
    pub(crate) fn normal(
        &self,
        normal: &gltf::material::NormalTexture,
    ) -> Result<NormalMap, String> {
        // The gltf crate offers KHR_texture_transform on texture infos only; a normal
        // texture's is read from its JSON.
        let transform = match normal.extension_value("KHR_texture_transform") {
            Some(v) => Some(
                serde_json::from_value::<gltf::json::extensions::texture::TextureTransform>(
                    v.clone(),
                )
                .map_err(|e| format!("normal texture: KHR_texture_transform: {e}"))?,
            ),
            None => None,
        };
        let uv = transform.map(|t| UvTransform {
            offset: Vec2::from(t.offset.0),
            rotation: t.rotation.0,
            scale: Vec2::from(t.scale.0),
        });
        let texture = self.rgb(normal.texture(), uv, [1.0; 3])?;
        NormalMap::new(texture.encoded(Encoding::Linear), normal.scale())
    }

    /// The texture `info` refers to, with its sampler and transform, times `factor`.
    fn info(&self, info: &gltf::texture::Info, factor: [f32; 3]) -> Result<RgbTexture, String> {
        let uv = info.texture_transform().map(|t| UvTransform {
            offset: Vec2::from(t.offset()),
            rotation: t.rotation(),
            scale: Vec2::from(t.scale()),
        });
        self.rgb(info.texture(), uv, factor)
    }

    /// The alpha channel of a base colour texture times `factor` (baseColorFactor's
    /// alpha), as a linear texture whose channels all hold it; None when the image has no
    /// alpha.
    pub(crate) fn alpha(
        &self,
        info: &gltf::texture::Info,
        factor: f32,
    ) -> Result<Option<RgbTexture>, String> {
        let texture = info.texture();
        let (width, height, _, alpha) = self.image(&texture.source())?;
        let Some(alpha) = alpha else {
            return Ok(None);
        };
        let colour = self.info(info, [factor; 3])?;
        let texture = RgbTexture::new(
            width,
            height,
            alpha,
            colour.wrap(),
            colour.transform(),
            [factor; 3],
        )?
        .encoded(Encoding::Linear);
        Ok(Some(if colour.is_nearest() {
            texture.nearest()
        } else {
            texture
        }))
    }

    /// `texture`, transformed by `uv`, times `factor`. Its coordinates are the set the
    /// primitive loaded (see the loader's `uv_set`).
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
        let decoded = decode_image(&bytes).map_err(|e| format!("{what}: {e}"))?;
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
