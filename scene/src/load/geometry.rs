use std::sync::Arc;

use glam::{Mat4, Vec2, Vec3, Vec4};

use super::lights::{LightDesc, punctual};
use super::materials::{MaterialDesc, Upsampler, material};
use crate::camera::{Camera, Projection};

use super::prism_spectral::{self, Overlay, SpectralScene};
use super::{LoadError, base64};

/// The triangles of one mesh primitive placed by one node.
#[derive(Debug, Clone, PartialEq)]
pub struct MeshInstance {
    /// The node's name (or `node N`).
    pub node: String,
    /// The glTF material index, if any.
    pub material: Option<usize>,
    /// First triangle in [`LoadedGeometry::triangles`].
    pub first: usize,
    /// Number of triangles.
    pub count: usize,
}

/// The world-space triangles and cameras of the selected scene.
#[derive(Debug, Clone, Default)]
pub struct LoadedGeometry {
    /// Triangles in world space, instance after instance.
    pub triangles: Vec<[Vec3; 3]>,
    /// Unit shading normals at each triangle's vertices, world space (the geometric
    /// normal where the file gives none), one entry per triangle; empty when no primitive
    /// of the scene has normals (flat shading everywhere).
    pub normals: Vec<[Vec3; 3]>,
    /// Texture coordinates at each triangle's vertices (zero where the file gives none),
    /// one entry per triangle; empty when no primitive of the scene has them. The set is
    /// the one the material's base colour texture reads (else its first texture's):
    /// `TEXCOORD_0` in most files.
    pub uvs: Vec<[Vec2; 3]>,
    /// The second set, where a material's textures read two (a texture reads the set it
    /// names: see [`crate::textures::TexCoords`]); otherwise the first set's, and empty when
    /// no material reads two.
    pub uvs1: Vec<[Vec2; 3]>,
    /// `COLOR_0` (linear RGBA, factors of the base colour and its alpha) at each triangle's
    /// vertices, white where the file gives none; empty when no primitive has them.
    pub colors: Vec<[Vec4; 3]>,
    /// The coefficient table that upsamples vertex colours (present with `colors`).
    pub color_table: Option<std::sync::Arc<prism_upsample::CoefficientTable>>,
    /// Whether vertex colours blend as spectra between a triangle's corners (Mitsuba's
    /// mesh attributes) rather than as RGB (glTF's `COLOR_0`, the default).
    pub colors_blend_spectra: bool,
    /// Unit tangents at each triangle's vertices, world space, with glTF's handedness in
    /// w: `TANGENT` where the file gives it, else derived from the triangle's positions
    /// and texture coordinates (one tangent per triangle: a faceted frame on curved
    /// meshes where MikkTSpace would smooth it); one entry per triangle, empty unless a
    /// primitive's material has a normal texture (zero for the triangles of others).
    pub tangents: Vec<[Vec4; 3]>,
    /// Which node and primitive each range of triangles came from.
    pub instances: Vec<MeshInstance>,
    /// The cameras placed by the scene's nodes, in traversal order.
    pub cameras: Vec<Camera>,
    /// Every material of the file, in file order ([`MeshInstance::material`] indexes it).
    pub materials: Vec<MaterialDesc>,
    /// The lights: emissive instances, then punctual lights in traversal order.
    pub lights: Vec<LightDesc>,
    /// The polarized lights' emission, by index into `lights` (most scenes: none).
    pub light_polarization: Vec<(usize, crate::polarization::LinearPolarization)>,
    /// The punctual lights' schedules, by index into `lights` (most scenes: none).
    pub light_schedules: Vec<(usize, crate::world::Schedule)>,
    /// The scene-wide spectral description (the root's `PRISM_spectral`).
    pub spectral: SpectralScene,
    /// Media the file places itself, by material (Mitsuba's shapes' `interior` and
    /// `exterior`, its sensor's medium): when set, the scene's media are these, and the
    /// materials' and `spectral`'s media are not read.
    pub media: Option<crate::medium::Media>,
    /// What the caller should tell the user about the file: one line each, such as an
    /// extension that prism ignores.
    pub warnings: Vec<String>,
    /// The glTF features and extensions the file uses that change how it renders (alpha
    /// modes, vertex colours, quantized attributes, ...), each named once, in the order
    /// met: what `prism info` lists.
    pub gltf_features: Vec<String>,
}

impl LoadedGeometry {
    /// The camera called `name`, or the first one, or (for a scene without cameras) a
    /// default camera framing the geometry. Errors for an unknown name.
    pub fn camera(&self, name: Option<&str>) -> Result<Camera, LoadError> {
        match name {
            Some(n) => self
                .cameras
                .iter()
                .find(|c| c.name == n)
                .cloned()
                .ok_or_else(|| {
                    let names: Vec<&str> = self.cameras.iter().map(|c| c.name.as_str()).collect();
                    LoadError::Scene(format!(
                        "no camera '{n}' (cameras: {})",
                        if names.is_empty() {
                            "none".into()
                        } else {
                            names.join(", ")
                        }
                    ))
                }),
            None => Ok(self.cameras.first().cloned().unwrap_or_else(|| {
                let (lo, hi) = self.bounds();
                Camera::framing(lo, hi)
            })),
        }
    }

    /// The bounding box of the triangles.
    pub fn bounds(&self) -> (Vec3, Vec3) {
        self.triangles
            .iter()
            .flatten()
            .fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(lo, hi), v| {
                (lo.min(*v), hi.max(*v))
            })
    }
}

/// The geometry of scene `scene` (default: the file's default scene, else scene 0) of a
/// glTF (`.gltf` JSON or `.glb`) given as bytes, instancing every mesh under the scene's
/// node hierarchy with the composed transforms (TRS or matrix; mirroring transforms keep
/// their winding by swapping two vertices). `resolve` returns the bytes of an external
/// buffer URI (relative to the file); `data:` URIs and the GLB binary chunk are handled
/// here. Non-triangle primitive modes are errors.
pub fn load_geometry(
    bytes: &[u8],
    resolve: &super::Resolver,
    scene: Option<usize>,
) -> Result<LoadedGeometry, LoadError> {
    load_scene(
        bytes,
        resolve,
        &LoadOptions {
            scene,
            ..LoadOptions::default()
        },
    )
}

/// Choices made while loading: start from the default and change what you need (the
/// struct is `#[non_exhaustive]`, so options can be added without breaking callers).
///
/// ```
/// use prism_scene::load::{LoadOptions, Upsampling};
///
/// let options = LoadOptions::default().scene(Some(0)).upsampling(Upsampling::Table(32));
/// assert_eq!(options.scene, Some(0));
/// assert!(options.table.is_none()); // the table prism-upsample ships is used
/// ```
#[derive(Debug, Clone, Default)]
#[non_exhaustive]
pub struct LoadOptions<'a> {
    /// The glTF scene to load (default: the file's default scene, else scene 0).
    pub scene: Option<usize>,
    /// A TOML overlay to apply to the document first.
    pub overlay: Option<&'a Overlay>,
    /// How constant RGB colours become spectra.
    pub upsampling: super::Upsampling,
    /// A linear sRGB coefficient table to use for textures, vertex colours and the
    /// table modes, instead of the one prism-upsample ships (or, without its
    /// `srgb-table` feature or at another resolution, fits on first use). It must be
    /// for linear sRGB, and of the resolution `upsampling` names if it names one.
    pub table: Option<std::sync::Arc<prism_upsample::CoefficientTable>>,
}

impl<'a> LoadOptions<'a> {
    /// With [`LoadOptions::scene`] set.
    pub fn scene(mut self, scene: Option<usize>) -> Self {
        self.scene = scene;
        self
    }

    /// With [`LoadOptions::overlay`] set.
    pub fn overlay(mut self, overlay: Option<&'a Overlay>) -> Self {
        self.overlay = overlay;
        self
    }

    /// With [`LoadOptions::upsampling`] set.
    pub fn upsampling(mut self, upsampling: super::Upsampling) -> Self {
        self.upsampling = upsampling;
        self
    }

    /// With [`LoadOptions::table`] set.
    pub fn table(
        mut self,
        table: Option<std::sync::Arc<prism_upsample::CoefficientTable>>,
    ) -> Self {
        self.table = table;
        self
    }
}

/// [`load_geometry`] with options: an optional TOML overlay applied to the document first
/// (its descriptions replace the file's own `PRISM_spectral` for the materials and lights
/// it names; files named in descriptions, `csv:PATH`, are read through `resolve` too), and
/// the upsampling mode.
pub fn load_scene(
    bytes: &[u8],
    resolve: &super::Resolver,
    options: &LoadOptions,
) -> Result<LoadedGeometry, LoadError> {
    let scene = options.scene;
    let (gltf, warnings) = parse(bytes, options.overlay)?;
    let mut gltf_features: Vec<String> = gltf
        .extensions_used()
        .filter(|e| super::extensions::READ.contains(e))
        .map(str::to_string)
        .collect();
    for m in gltf.materials() {
        match m.alpha_mode() {
            gltf::material::AlphaMode::Opaque => {}
            gltf::material::AlphaMode::Mask => note(&mut gltf_features, "alphaMode MASK"),
            gltf::material::AlphaMode::Blend => note(&mut gltf_features, "alphaMode BLEND"),
        }
    }
    let mut buffers = read_buffers(&gltf, resolve)?;
    super::meshopt::decode_views(&gltf, &mut buffers)?;
    let scene = select_scene(&gltf, scene)?;
    super::instancing::check(&gltf, &scene)?;
    let mut out = LoadedGeometry {
        warnings,
        gltf_features,
        ..LoadedGeometry::default()
    };
    // Fitting needs a context; scenes without colours never build one.
    let has_lights = gltf.lights().is_some_and(|mut l| l.next().is_some());
    let root_spectral = gltf.extension_value(prism_spectral::EXTENSION);
    let upsampler = (gltf.materials().len() > 0 || has_lights || root_spectral.is_some())
        .then(|| Upsampler::new(options.upsampling, options.table.clone()))
        .transpose()?;
    let light_spectral = punctual_spectral(&gltf);
    if let Some(upsampler) = &upsampler {
        let cx = prism_spectral::Context { resolve, upsampler };
        let textures = super::textures::TextureLoader::new(&gltf, &buffers, resolve, upsampler);
        out.materials = gltf
            .materials()
            .map(|m| material(&m, &cx, &textures))
            .collect::<Result<_, _>>()?;
        warn_unrendered_layers(&out.materials, &mut out.warnings);
        if let Some(v) = root_spectral {
            out.spectral = prism_spectral::scene(v, &cx).map_err(LoadError::Spectral)?;
        }
    }
    let mut punctual_lights = Vec::new();
    let mut stack: Vec<(gltf::Node, Mat4, usize)> =
        scene.nodes().map(|n| (n, Mat4::IDENTITY, 0)).collect();
    while let Some((node, parent, depth)) = stack.pop() {
        if depth > 256 {
            return Err(LoadError::Scene(
                "node hierarchy deeper than 256 levels".into(),
            ));
        }
        let local = Mat4::from_cols_array_2d(&node.transform().matrix());
        let world = parent * local;
        if !world.is_finite() {
            return Err(LoadError::Geometry(format!(
                "node {} has a non-finite transform",
                node_name(&node)
            )));
        }
        if let (Some(light), Some(upsampler)) = (node.light(), &upsampler) {
            let description = light_spectral
                .get(light.index())
                .and_then(Option::as_ref)
                .map(|v| {
                    let cx = prism_spectral::Context { resolve, upsampler };
                    prism_spectral::light(v, &cx).map_err(|e| {
                        LoadError::Spectral(format!(
                            "light {}: {e}",
                            light.name().unwrap_or("(unnamed)")
                        ))
                    })
                })
                .transpose()?;
            let polarization = description.as_ref().and_then(|d| d.polarization);
            let on = description.as_ref().and_then(|d| d.on.clone());
            punctual_lights.push(punctual(
                &node,
                &light,
                world,
                &|rgb| upsampler.emission(rgb),
                description,
            )?);
            if let Some(on) = on {
                out.light_schedules.push((punctual_lights.len() - 1, on));
            }
            if let Some((degree, angle)) = polarization {
                // Counted among the punctual lights; shifted past the area lights below.
                out.light_polarization.push((
                    punctual_lights.len() - 1,
                    crate::polarization::LinearPolarization {
                        degree,
                        angle,
                        axis: world.transform_vector3(Vec3::X).normalize_or(Vec3::X),
                    },
                ));
            }
        }
        if let Some(camera) = node.camera() {
            out.cameras
                .push(make_camera(&node, &camera, world, resolve)?);
        }
        if let Some(mesh) = node.mesh() {
            if node.skin().is_some() {
                note(&mut out.gltf_features, "skins (bind pose)");
                warn_once(
                    &mut out.warnings,
                    "skinned meshes are rendered in their bind pose (skins are not applied)",
                );
            }
            let weights = node.weights().or(mesh.weights()).unwrap_or(&[]);
            for primitive in mesh.primitives() {
                super::primitive::add_primitive(
                    &mut out, &node, &primitive, world, &buffers, weights,
                )?;
            }
        }
        stack.extend(node.children().map(|c| (c, world, depth + 1)));
    }
    if !out.colors.is_empty() {
        let fitted = match &upsampler {
            Some(u) => u.table(),
            None => Upsampler::new(options.upsampling, options.table.clone())?.table(),
        };
        out.color_table = Some(fitted.map_err(LoadError::Scene)?);
    }
    if out.triangles.is_empty() {
        return Err(LoadError::Scene(format!(
            "scene {} has no triangles",
            scene.index()
        )));
    }
    add_lights(&mut out, punctual_lights);
    Ok(out)
}

/// The bytes of every buffer: the GLB chunk, a base64 data URI or a file through
/// `resolve`, each at least as long as it declares (EXT_meshopt_compression's fallback
/// buffers are zeros until their views are decoded).
fn read_buffers(gltf: &gltf::Gltf, resolve: &super::Resolver) -> Result<Vec<Vec<u8>>, LoadError> {
    gltf.buffers()
        .map(|buffer| {
            // EXT_meshopt_compression's placeholders are filled by `meshopt::decode_views`.
            if super::meshopt::is_fallback(&buffer) {
                return Ok(vec![0; buffer.length().min(1 << 31)]);
            }
            let data = match buffer.source() {
                gltf::buffer::Source::Bin => gltf.blob.clone().ok_or_else(|| {
                    LoadError::Buffer(format!(
                        "buffer {} refers to a missing GLB binary chunk",
                        buffer.index()
                    ))
                })?,
                gltf::buffer::Source::Uri(uri) => match uri.strip_prefix("data:") {
                    Some(rest) => {
                        let payload =
                            rest.split_once(";base64,").map(|(_, p)| p).ok_or_else(|| {
                                LoadError::Buffer(format!(
                                    "buffer {}: only base64 data URIs are supported",
                                    buffer.index()
                                ))
                            })?;
                        base64::decode(payload).ok_or_else(|| {
                            LoadError::Buffer(format!(
                                "buffer {}: malformed base64 data URI",
                                buffer.index()
                            ))
                        })?
                    }
                    None => resolve(uri).map_err(|e| LoadError::Resource {
                        referrer: format!("buffer {}", buffer.index()),
                        uri: uri.to_string(),
                        source: Arc::new(e),
                    })?,
                },
            };
            if data.len() < buffer.length() {
                return Err(LoadError::Buffer(format!(
                    "buffer {} has {} bytes but declares {}",
                    buffer.index(),
                    data.len(),
                    buffer.length()
                )));
            }
            Ok(data)
        })
        .collect()
}

/// Scene `index` of the file, else its default scene, else its first.
fn select_scene(gltf: &gltf::Gltf, index: Option<usize>) -> Result<gltf::Scene<'_>, LoadError> {
    Ok(match index {
        Some(i) => gltf.scenes().nth(i).ok_or_else(|| {
            LoadError::Scene(format!(
                "no scene {i} (the file has {})",
                gltf.scenes().count()
            ))
        })?,
        None => gltf
            .default_scene()
            .or_else(|| gltf.scenes().next())
            .ok_or_else(|| LoadError::Scene("the file has no scene".into()))?,
    })
}

/// The raw `PRISM_spectral` of each punctual light (the gltf crate keeps light extensions
/// as raw JSON).
fn punctual_spectral(gltf: &gltf::Gltf) -> Vec<Option<serde_json::Value>> {
    gltf.as_json()
        .extensions
        .as_ref()
        .and_then(|e| e.khr_lights_punctual.as_ref())
        .map_or_else(Vec::new, |l| {
            l.lights
                .iter()
                .map(|light| {
                    let raw = light.extensions.as_ref()?;
                    let mut map: serde_json::Map<String, serde_json::Value> =
                        serde_json::from_str(raw.get()).ok()?;
                    map.remove(prism_spectral::EXTENSION)
                })
                .collect()
        })
}

/// A warning for each transmissive material with layers prism renders only on opaque ones.
fn warn_unrendered_layers(materials: &[MaterialDesc], warnings: &mut Vec<String>) {
    for m in materials {
        if m.transmission > 0.0 && m.iridescence.is_some() {
            warn_once(
                warnings,
                &format!(
                    "material {}: KHR_materials_iridescence on a transmissive material is not rendered (the glass is)",
                    m.name
                ),
            );
        }
        if m.transmission > 0.0 && m.layers.is_some() {
            warn_once(
                warnings,
                &format!(
                    "material {}: KHR_materials_specular, _anisotropy, _clearcoat, _sheen and _diffuse_transmission on a transmissive material are not rendered (the glass is)",
                    m.name
                ),
            );
        }
    }
}

/// The scene's lights: an area light per instance of an emissive material, then the
/// punctual lights (whose polarization and schedule indices shift past the area lights).
fn add_lights(out: &mut LoadedGeometry, punctual_lights: Vec<LightDesc>) {
    let emissive = |i: &MeshInstance| {
        i.material
            .and_then(|m| out.materials.get(m))
            .and_then(|m| m.emits().then_some(m.double_sided))
    };
    out.lights = out
        .instances
        .iter()
        .enumerate()
        .filter_map(|(instance, i)| {
            emissive(i).map(|double_sided| LightDesc::Area {
                instance,
                double_sided,
            })
        })
        .collect();
    let areas = out.lights.len();
    for (index, _) in &mut out.light_polarization {
        *index += areas;
    }
    for (index, _) in &mut out.light_schedules {
        *index += areas;
    }
    out.lights.extend(punctual_lights);
}

/// Parses and validates a glTF or GLB, with the warnings its extensions call for. A
/// required extension prism does not read is an error. The gltf crate rejects files that
/// require an extension it does not know, so once prism has checked that it reads every
/// required one, `extensionsRequired` is emptied before the (otherwise unchanged)
/// validation.
fn parse(bytes: &[u8], overlay: Option<&Overlay>) -> Result<(gltf::Gltf, Vec<String>), LoadError> {
    // The gltf crate's validation errors begin with the words LoadError adds.
    let invalid = |e: gltf::Error| LoadError::Invalid {
        reason: e
            .to_string()
            .trim_start_matches("invalid glTF: ")
            .to_string(),
        source: Some(Arc::new(e)),
    };
    let gltf::Gltf { document, blob } =
        gltf::Gltf::from_slice_without_validation(bytes).map_err(invalid)?;
    let mut root = document.into_json();
    if let Some(overlay) = overlay {
        overlay.apply(&mut root)?;
    }
    let warnings = super::extensions::check(&root.extensions_required, &root.extensions_used)
        .map_err(LoadError::Unsupported)?;
    use_webp_sources(&mut root);
    // Every required extension is one prism reads (checked above); the gltf crate's
    // validation knows only some of them.
    root.extensions_required.clear();
    check_position_accessors(&root)?;
    let document = gltf::Document::from_json(root).map_err(invalid)?;
    Ok((gltf::Gltf { document, blob }, warnings))
}

/// `EXT_texture_webp`: a texture whose extension names a WebP image reads that image
/// (prism decodes WebP), whether or not it also has a PNG or JPEG fallback `source`.
fn use_webp_sources(root: &mut gltf::json::Root) {
    for texture in &mut root.textures {
        let webp = texture
            .extensions
            .as_ref()
            .and_then(|e| e.others.get("EXT_texture_webp"))
            .and_then(|v| v.get("source"))
            .and_then(serde_json::Value::as_u64)
            .and_then(|i| u32::try_from(i).ok());
        if let Some(i) = webp {
            texture.source = gltf::json::Index::new(i);
        }
    }
}

/// The gltf crate's validation reads each primitive's `POSITION` accessor by indexing
/// (gltf-json 1.4's `primitive_validate_hook`), so an index past the accessors would panic
/// inside it; such a file is rejected here first, with the path the validator would name.
fn check_position_accessors(root: &gltf::json::Root) -> Result<(), LoadError> {
    for (m, mesh) in root.meshes.iter().enumerate() {
        for (p, primitive) in mesh.primitives.iter().enumerate() {
            let position = gltf::json::validation::Checked::Valid(gltf::Semantic::Positions);
            if let Some(index) = primitive.attributes.get(&position)
                && index.value() >= root.accessors.len()
            {
                return Err(LoadError::Invalid {
                    reason: format!(
                        "meshes[{m}].primitives[{p}].attributes[\"POSITION\"]: accessor {} does \
                         not exist ({} accessors)",
                        index.value(),
                        root.accessors.len()
                    ),
                    source: None,
                });
            }
        }
    }
    Ok(())
}

fn make_camera(
    node: &gltf::Node,
    camera: &gltf::Camera,
    world: Mat4,
    resolve: &super::Resolver,
) -> Result<Camera, LoadError> {
    let name = node
        .name()
        .map_or_else(|| format!("camera {}", camera.index()), str::to_string);
    let (projection, aspect_ratio) = match camera.projection() {
        gltf::camera::Projection::Perspective(p) => {
            let yfov = p.yfov();
            if !(yfov > 0.0 && yfov < std::f32::consts::PI) {
                return Err(LoadError::Geometry(format!(
                    "camera {name}: yfov {yfov} is not in (0, pi)"
                )));
            }
            let aspect = p.aspect_ratio();
            if let Some(a) = aspect
                && !(a.is_finite() && (1.0 / 64.0..=64.0).contains(&a))
            {
                return Err(LoadError::Geometry(format!(
                    "camera {name}: aspectRatio {a} is not in [1/64, 64]"
                )));
            }
            (Projection::Perspective { yfov }, aspect)
        }
        gltf::camera::Projection::Orthographic(o) => {
            let (xmag, ymag) = (o.xmag(), o.ymag());
            if !(xmag.is_finite() && ymag.is_finite() && xmag != 0.0 && ymag != 0.0) {
                return Err(LoadError::Geometry(format!(
                    "camera {name}: xmag {xmag}, ymag {ymag} must be finite and non-zero"
                )));
            }
            let aspect = (xmag / ymag).abs();
            let projection = Projection::Orthographic {
                xmag: xmag.abs(),
                ymag: ymag.abs(),
            };
            (
                projection,
                Some(aspect).filter(|a| (1.0 / 64.0..=64.0).contains(a)),
            )
        }
    };
    let optics = match camera.extension_value(prism_spectral::EXTENSION) {
        None => prism_spectral::Optics::Pinhole,
        Some(description) => prism_spectral::optics(description, resolve).map_err(|e| {
            LoadError::Geometry(format!("camera {name}: {}: {e}", prism_spectral::EXTENSION))
        })?,
    };
    let (lens, system) = match optics {
        prism_spectral::Optics::Pinhole => (None, None),
        prism_spectral::Optics::Thin(lens) => (Some(lens), None),
        prism_spectral::Optics::System(system) => (None, Some(system)),
    };
    if (lens.is_some() || system.is_some()) && matches!(projection, Projection::Orthographic { .. })
    {
        return Err(LoadError::Geometry(format!(
            "camera {name}: a lens needs a perspective camera"
        )));
    }
    Ok(Camera {
        name,
        to_world: world,
        projection,
        aspect_ratio,
        lens,
        system,
    })
}

pub(super) fn node_name(node: &gltf::Node) -> String {
    node.name()
        .map_or_else(|| format!("node {}", node.index()), str::to_string)
}

/// Adds `feature` to a list of names unless it is there already.
pub(super) fn note(features: &mut Vec<String>, feature: &str) {
    if !features.iter().any(|f| f == feature) {
        features.push(feature.to_string());
    }
}

/// Adds `warning` unless it is there already.
pub(super) fn warn_once(warnings: &mut Vec<String>, warning: &str) {
    if !warnings.iter().any(|w| w == warning) {
        warnings.push(warning.to_string());
    }
}
