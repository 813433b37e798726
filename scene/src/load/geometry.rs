use std::sync::Arc;

use glam::{Mat3, Mat4, Vec2, Vec3, Vec4};

use super::lights::{LightDesc, punctual};
use super::materials::{MaterialDesc, Upsampler, material};
use super::tex_coord_sets::TexCoordSets;
use crate::camera::{Camera, Projection};
use crate::geometry::triangle_normal;
use crate::world::triangle_tangent;

use super::{LoadError, accessor, base64};
use crate::spectral::{self, Overlay, SpectralScene};

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
    /// names: see [`crate::world::TexCoords`]); otherwise the first set's, and empty when
    /// no material reads two.
    pub uvs1: Vec<[Vec2; 3]>,
    /// `COLOR_0` (linear RGBA, factors of the base colour and its alpha) at each triangle's
    /// vertices, white where the file gives none; empty when no primitive has them.
    pub colors: Vec<[Vec4; 3]>,
    /// The coefficient table that upsamples vertex colours (present with `colors`).
    pub color_table: Option<std::sync::Arc<prism_upsample::CoefficientTable>>,
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
    let mut buffers = gltf
        .buffers()
        .map(|buffer| {
            // EXT_meshopt_compression's placeholders are filled by decoding (below).
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
        .collect::<Result<Vec<_>, _>>()?;
    super::meshopt::decode_views(&gltf, &mut buffers)?;
    let scene = match scene {
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
    };
    super::instancing::check(&gltf, &scene)?;
    let mut out = LoadedGeometry {
        warnings,
        gltf_features,
        ..LoadedGeometry::default()
    };
    // Fitting needs a context; scenes without colours never build one.
    let has_lights = gltf.lights().is_some_and(|mut l| l.next().is_some());
    let root_spectral = gltf.extension_value(spectral::EXTENSION);
    let upsampler = (gltf.materials().len() > 0 || has_lights || root_spectral.is_some())
        .then(|| Upsampler::new(options.upsampling, options.table.clone()))
        .transpose()?;
    // The raw `PRISM_spectral` of each punctual light (the gltf crate keeps light
    // extensions as raw JSON).
    let light_spectral: Vec<Option<serde_json::Value>> = gltf
        .as_json()
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
                    map.remove(spectral::EXTENSION)
                })
                .collect()
        });
    if let Some(upsampler) = &upsampler {
        let cx = spectral::Context { resolve, upsampler };
        let textures = super::textures::TextureLoader::new(&gltf, &buffers, resolve, upsampler);
        out.materials = gltf
            .materials()
            .map(|m| material(&m, &cx, &textures))
            .collect::<Result<_, _>>()?;
        for m in &out.materials {
            if m.transmission > 0.0 && m.iridescence.is_some() {
                warn_once(
                    &mut out.warnings,
                    &format!(
                        "material {}: KHR_materials_iridescence on a transmissive material is not rendered (the glass is)",
                        m.name
                    ),
                );
            }
            if m.transmission > 0.0 && m.layers.is_some() {
                warn_once(
                    &mut out.warnings,
                    &format!(
                        "material {}: KHR_materials_specular, _anisotropy, _clearcoat, _sheen and _diffuse_transmission on a transmissive material are not rendered (the glass is)",
                        m.name
                    ),
                );
            }
        }
        if let Some(v) = root_spectral {
            out.spectral = spectral::scene(v, &cx).map_err(LoadError::Spectral)?;
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
                    let cx = spectral::Context { resolve, upsampler };
                    spectral::light(v, &cx).map_err(|e| {
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
            out.cameras.push(make_camera(&node, &camera, world)?);
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
                add_primitive(&mut out, &node, &primitive, world, &buffers, weights)?;
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
    Ok(out)
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

fn make_camera(node: &gltf::Node, camera: &gltf::Camera, world: Mat4) -> Result<Camera, LoadError> {
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
    Ok(Camera {
        name,
        to_world: world,
        projection,
        aspect_ratio,
    })
}

fn node_name(node: &gltf::Node) -> String {
    node.name()
        .map_or_else(|| format!("node {}", node.index()), str::to_string)
}

/// `COLOR_0` as linear RGBA (alpha 1 for RGB colours), if the primitive has it.
fn vertex_colors(primitive: &gltf::Primitive, buffers: &[Vec<u8>]) -> Option<Vec<Vec4>> {
    let a = primitive.get(&gltf::Semantic::Colors(0))?;
    match a.dimensions() {
        gltf::accessor::Dimensions::Vec3 => accessor::read_f32::<3>(&a, buffers)
            .map(|c| c.into_iter().map(|c| Vec3::from(c).extend(1.0)).collect()),
        _ => accessor::read_f32::<4>(&a, buffers).map(|c| c.into_iter().map(Vec4::from).collect()),
    }
}

/// Adds `feature` to a list of names unless it is there already.
fn note(features: &mut Vec<String>, feature: &str) {
    if !features.iter().any(|f| f == feature) {
        features.push(feature.to_string());
    }
}

/// Adds `warning` unless it is there already.
fn warn_once(warnings: &mut Vec<String>, warning: &str) {
    if !warnings.iter().any(|w| w == warning) {
        warnings.push(warning.to_string());
    }
}

/// `values` displaced by the primitive's morph targets of `semantic` (POSITION or NORMAL)
/// at `weights` (the node's, else the mesh's default weights): the shape a viewer shows
/// before any animation plays.
fn morph(
    primitive: &gltf::Primitive,
    weights: &[f32],
    normals: bool,
    mut values: Vec<Vec3>,
    buffers: &[Vec<u8>],
) -> Vec<Vec3> {
    for (target, &w) in primitive.morph_targets().zip(weights) {
        let accessor = if normals {
            target.normals()
        } else {
            target.positions()
        };
        let deltas = accessor
            .filter(|a| accessor::check(a, &accessor::MORPH_TARGET, "", buffers).is_ok())
            .and_then(|a| accessor::read_f32::<3>(&a, buffers));
        if w == 0.0 || !w.is_finite() {
            continue;
        }
        if let Some(deltas) = deltas.filter(|d| d.len() == values.len()) {
            for (v, d) in values.iter_mut().zip(deltas) {
                *v += w * Vec3::from(d);
            }
        }
    }
    values
}

fn add_primitive(
    out: &mut LoadedGeometry,
    node: &gltf::Node,
    primitive: &gltf::Primitive,
    world: Mat4,
    buffers: &[Vec<u8>],
    weights: &[f32],
) -> Result<(), LoadError> {
    let name = node_name(node);
    if primitive.mode() != gltf::mesh::Mode::Triangles {
        return Err(LoadError::Geometry(format!(
            "{name}: primitive mode {:?} is not supported (only TRIANGLES)",
            primitive.mode()
        )));
    }
    let material = primitive.material();
    let sets = TexCoordSets::of(&material);
    if let Some(w) = sets.warning(material.name().unwrap_or("(unnamed)")) {
        warn_once(&mut out.warnings, &format!("{name}: {w}"));
    }
    // The reader trusts the document; what it would panic on is an error here first.
    for (semantic, expected) in [
        (gltf::Semantic::Positions, &accessor::POSITION),
        (gltf::Semantic::Normals, &accessor::NORMAL),
        (gltf::Semantic::Tangents, &accessor::TANGENT),
        (gltf::Semantic::TexCoords(sets.first()), &accessor::TEXCOORD),
        (
            gltf::Semantic::TexCoords(sets.second().unwrap_or(sets.first())),
            &accessor::TEXCOORD,
        ),
        (gltf::Semantic::Colors(0), &accessor::COLOR),
    ] {
        if let Some(a) = primitive.get(&semantic) {
            accessor::check(&a, expected, &name, buffers)?;
        }
    }
    if let Some(a) = primitive.indices() {
        accessor::check(&a, &accessor::INDICES, &name, buffers)?;
    }
    let reader = primitive.reader(|b| buffers.get(b.index()).map(Vec::as_slice));
    // Quantized attributes (KHR_mesh_quantization) read as floats like any other.
    let attribute = |semantic: gltf::Semantic| primitive.get(&semantic);
    let positions: Vec<Vec3> = match attribute(gltf::Semantic::Positions) {
        None => {
            return Err(LoadError::Geometry(format!(
                "{name}: a primitive has no POSITION attribute"
            )));
        }
        Some(a) => accessor::read_f32::<3>(&a, buffers)
            .ok_or_else(|| {
                LoadError::Geometry(format!(
                    "{name}: POSITION accessor {} cannot be read (it runs past its buffer view or buffer)",
                    a.index()
                ))
            })?
            .into_iter()
            .map(Vec3::from)
            .collect(),
    };
    let morphed = primitive.morph_targets().next().is_some();
    if morphed {
        note(&mut out.gltf_features, "morph targets (default weights)");
        warn_once(
            &mut out.warnings,
            "morph targets are rendered at their default weights",
        );
    }
    let positions = if morphed {
        morph(primitive, weights, false, positions, buffers)
    } else {
        positions
    };
    if let Some(i) = positions.iter().position(|p| !p.is_finite()) {
        return Err(LoadError::Geometry(format!(
            "{name}: position {i} is not finite"
        )));
    }
    let indices: Vec<u32> = match (reader.read_indices(), primitive.indices()) {
        (Some(i), _) => i.into_u32().collect(),
        (None, None) => (0..positions.len() as u32).collect(),
        // Declared but unreadable: not a non-indexed primitive.
        (None, Some(accessor)) => {
            return Err(LoadError::Geometry(format!(
                "{name}: index accessor {} cannot be read (it runs past its buffer view or buffer)",
                accessor.index()
            )));
        }
    };
    if !indices.len().is_multiple_of(3) {
        return Err(LoadError::Geometry(format!(
            "{name}: {} indices do not form triangles",
            indices.len()
        )));
    }
    if let Some(bad) = indices.iter().find(|&&i| i as usize >= positions.len()) {
        return Err(LoadError::Geometry(format!(
            "{name}: index {bad} is past the {} vertices",
            positions.len()
        )));
    }
    let count = positions.len();
    let attribute_count = |what: &str, n: usize| {
        LoadError::Geometry(format!(
            "{name}: {what} has {n} entries for {count} vertices"
        ))
    };
    let normals: Option<Vec<Vec3>> = attribute(gltf::Semantic::Normals)
        .and_then(|a| accessor::read_f32::<3>(&a, buffers))
        .map(|n| n.into_iter().map(Vec3::from).collect())
        .map(|n| {
            if morphed {
                morph(primitive, weights, true, n, buffers)
            } else {
                n
            }
        });
    if let Some(n) = &normals
        && n.len() != count
    {
        return Err(attribute_count("NORMAL", n.len()));
    }
    let read_uvs = |set: u32| -> Result<Option<Vec<Vec2>>, LoadError> {
        let uvs: Option<Vec<Vec2>> = attribute(gltf::Semantic::TexCoords(set))
            .and_then(|a| accessor::read_f32::<2>(&a, buffers))
            .map(|t| t.into_iter().map(Vec2::from).collect());
        match uvs {
            Some(t) if t.len() != count => {
                Err(attribute_count(&format!("TEXCOORD_{set}"), t.len()))
            }
            uvs => Ok(uvs),
        }
    };
    let uvs = read_uvs(sets.first())?;
    let uvs1 = match sets.second() {
        Some(set) => {
            let second = read_uvs(set)?;
            if second.is_none() {
                warn_once(
                    &mut out.warnings,
                    &format!(
                        "{name}: a texture reads TEXCOORD_{set}, which the primitive does not have; it reads TEXCOORD_{} instead",
                        sets.first()
                    ),
                );
            }
            second
        }
        None => None,
    };
    let tangents: Option<Vec<Vec4>> = attribute(gltf::Semantic::Tangents)
        .and_then(|a| accessor::read_f32::<4>(&a, buffers))
        .map(|t| t.into_iter().map(Vec4::from).collect());
    if let Some(t) = &tangents
        && t.len() != count
    {
        return Err(attribute_count("TANGENT", t.len()));
    }
    let colors = vertex_colors(primitive, buffers);
    if colors.is_some() {
        note(&mut out.gltf_features, "COLOR_0");
    }
    for set in [Some(sets.first()), sets.second()].into_iter().flatten() {
        if set > 0 {
            note(&mut out.gltf_features, &format!("TEXCOORD_{set}"));
        }
    }
    if primitive.indices().is_none() {
        note(&mut out.gltf_features, "non-indexed primitives");
    }
    if primitive.attributes().any(|(_, a)| a.sparse().is_some()) {
        note(&mut out.gltf_features, "sparse accessors");
    }
    if let Some(c) = &colors
        && c.len() != count
    {
        return Err(attribute_count("COLOR_0", c.len()));
    }
    // Normals transform by the inverse transpose (correct under non-uniform scale and
    // mirroring), tangents (directions in the surface) by the matrix itself.
    let linear = Mat3::from_mat4(world);
    let normal_matrix = linear.inverse().transpose();
    // A mirroring transform flips the winding; swapping two vertices restores it so that
    // front faces stay front faces.
    let mirrored = world.determinant() < 0.0;
    let order = |t: [usize; 3]| if mirrored { [t[0], t[2], t[1]] } else { t };
    let first = out.triangles.len();
    // Attribute lists stay empty until a primitive has the attribute; the triangles before
    // it then get the defaults. Most scenes have no texture coordinates and many no
    // normals: 60 bytes a triangle that would be kept and interpolated at every hit.
    let keep_normals = normals.is_some() || !out.normals.is_empty();
    if keep_normals {
        let from = out.normals.len();
        let flat = |t: &[Vec3; 3]| [triangle_normal(*t); 3];
        out.normals.extend(out.triangles[from..].iter().map(flat));
    }
    let keep_uvs = uvs.is_some() || uvs1.is_some() || !out.uvs.is_empty();
    if keep_uvs {
        out.uvs.resize(first, [Vec2::ZERO; 3]);
    }
    // The second set stays empty until a primitive reads one; the triangles before it
    // then get their first set's.
    let keep_uvs1 = uvs1.is_some() || !out.uvs1.is_empty();
    if keep_uvs1 && out.uvs1.len() < first {
        let from = out.uvs1.len();
        let copied: Vec<[Vec2; 3]> = out.uvs[from..first].to_vec();
        out.uvs1.extend(copied);
    }
    let keep_colors = colors.is_some() || !out.colors.is_empty();
    if keep_colors {
        out.colors.resize(first, [Vec4::ONE; 3]);
    }
    // Tangents serve normal maps, anisotropy and a coat's normal texture.
    let normal_mapped = material.normal_texture().is_some() || oriented(&material);
    let keep_tangents = normal_mapped || !out.tangents.is_empty();
    if keep_tangents {
        out.tangents.resize(first, [Vec4::ZERO; 3]);
    }
    // Under mirroring the normal x tangent flips relative to the mirrored bitangent.
    let handedness = if mirrored { -1.0 } else { 1.0 };
    let triangles = indices.len() / 3;
    out.triangles.reserve(triangles);
    out.normals
        .reserve(if keep_normals { triangles } else { 0 });
    out.uvs.reserve(if keep_uvs { triangles } else { 0 });
    out.tangents
        .reserve(if keep_tangents { triangles } else { 0 });
    // Without TANGENT, a normal-mapped primitive gets MikkTSpace's (per corner, in the
    // primitive's own space), as glTF asks.
    // Tangents follow the u direction of the set the normal texture reads.
    let normal_set = material
        .normal_texture()
        .map_or(0, |n| sets.slot(super::tex_coord_sets::normal_set(&n)));
    let normal_uvs = if normal_set == 1 && uvs1.is_some() {
        &uvs1
    } else {
        &uvs
    };
    let mikktspace = match (&tangents, normal_uvs) {
        (None, Some(uvs)) if normal_mapped => {
            super::tangents::mikktspace(&positions, normals.as_deref(), uvs, &indices)
        }
        _ => None,
    };
    let corners = if mirrored { [0, 2, 1] } else { [0, 1, 2] };
    for (face, tri) in indices.chunks_exact(3).enumerate() {
        let t = order([tri[0] as usize, tri[1] as usize, tri[2] as usize]);
        let v = t.map(|i| world.transform_point3(positions[i]));
        out.triangles.push(v);
        if keep_normals {
            let geometric = triangle_normal(v);
            out.normals.push(match &normals {
                // Unusable normals (zero, non-finite) fall back to the face's own.
                Some(n) => t.map(|i| {
                    let w = (normal_matrix * n[i]).normalize_or_zero();
                    if w == Vec3::ZERO { geometric } else { w }
                }),
                None => [geometric; 3],
            });
        }
        let corner_uvs = |uvs: &Option<Vec<Vec2>>| {
            uvs.as_ref()
                .map(|uv| t.map(|i| if uv[i].is_finite() { uv[i] } else { Vec2::ZERO }))
        };
        let uv = corner_uvs(&uvs).unwrap_or([Vec2::ZERO; 3]);
        let uv1 = corner_uvs(&uvs1).unwrap_or(uv);
        if keep_uvs {
            out.uvs.push(uv);
        }
        if keep_uvs1 {
            out.uvs1.push(uv1);
        }
        let tangent_uv = if normal_set == 1 { uv1 } else { uv };
        if keep_colors {
            out.colors.push(match &colors {
                // Colours are linear factors in [0, 1]; anything else is clamped.
                Some(c) => t.map(|i| {
                    let v = c[i];
                    if v.is_finite() {
                        v.clamp(Vec4::ZERO, Vec4::ONE)
                    } else {
                        Vec4::ONE
                    }
                }),
                None => [Vec4::ONE; 3],
            });
        }
        if keep_tangents {
            out.tangents.push(if normal_mapped {
                let derived = triangle_tangent(v, tangent_uv, triangle_normal(v));
                // A tangent of the primitive's space in world space; unusable ones (zero,
                // non-finite) fall back to the triangle's derived tangent.
                let placed = |tangent: Vec4| {
                    let d = (linear * tangent.truncate()).normalize_or_zero();
                    let sign = if tangent.w < 0.0 { -1.0 } else { 1.0 };
                    if d == Vec3::ZERO {
                        derived
                    } else {
                        d.extend(sign * handedness)
                    }
                };
                match (&tangents, &mikktspace) {
                    (Some(tangent), _) => t.map(|i| placed(tangent[i])),
                    (None, Some(mikk)) => corners.map(|c| mikk[face][c].map_or(derived, placed)),
                    (None, None) => [derived; 3],
                }
            } else {
                [Vec4::ZERO; 3]
            });
        }
    }
    out.instances.push(MeshInstance {
        node: name,
        material: primitive.material().index(),
        first,
        count: out.triangles.len() - first,
    });
    Ok(())
}

/// Whether a material's extensions need the surface's tangents (anisotropy's direction, a
/// coat's normal texture).
fn oriented(material: &gltf::Material) -> bool {
    material
        .extension_value("KHR_materials_anisotropy")
        .is_some()
        || material
            .extension_value("KHR_materials_clearcoat")
            .is_some_and(|c| c.get("clearcoatNormalTexture").is_some())
}
