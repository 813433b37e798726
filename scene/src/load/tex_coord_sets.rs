//! Which glTF texture coordinate sets a material's textures read (`texCoord`, or the
//! `texCoord` of their `KHR_texture_transform`, which overrides it), and where the scene
//! keeps each: the scene holds [`TEX_COORD_SETS`] sets per triangle, the base colour's set
//! first.

use crate::textures::TEX_COORD_SETS;

/// The distinct texture coordinate sets a material's textures read, in the order the
/// scene keeps them.
#[derive(Debug, Clone, Default, PartialEq)]
pub(crate) struct TexCoordSets {
    sets: Vec<u32>,
}

impl TexCoordSets {
    /// The sets `material`'s textures read: base colour, metallic-roughness, emissive and
    /// normal textures (the ones prism reads), in that order.
    pub(crate) fn of(material: &gltf::Material) -> Self {
        let pbr = material.pbr_metallic_roughness();
        let infos = [
            super::materials::base_colour(material).1,
            pbr.metallic_roughness_texture(),
            material.emissive_texture(),
        ];
        let mut sets: Vec<u32> = Vec::new();
        let named = infos
            .iter()
            .flatten()
            .map(info_set)
            .chain(material.normal_texture().as_ref().map(normal_set))
            .chain(extension_texture_sets(material));
        for set in named {
            if !sets.contains(&set) {
                sets.push(set);
            }
        }
        Self { sets }
    }

    /// The glTF set the scene keeps first (0 when no texture names one).
    pub(crate) fn first(&self) -> u32 {
        self.sets.first().copied().unwrap_or(0)
    }

    /// The glTF set the scene keeps second, if the textures read two.
    pub(crate) fn second(&self) -> Option<u32> {
        self.sets.get(1).copied()
    }

    /// Where the scene keeps glTF set `set`: 0 or 1 (a set beyond those the scene keeps
    /// reads the first, see [`TexCoordSets::warning`]).
    pub(crate) fn slot(&self, set: u32) -> usize {
        self.sets
            .iter()
            .position(|&s| s == set)
            .filter(|&p| p < TEX_COORD_SETS)
            .unwrap_or(0)
    }

    /// The warning for a material whose textures read more sets than the scene keeps.
    pub(crate) fn warning(&self, material: &str) -> Option<String> {
        (self.sets.len() > TEX_COORD_SETS).then(|| {
            let sets: Vec<String> = self.sets.iter().map(|s| format!("TEXCOORD_{s}")).collect();
            format!(
                "material {material}'s textures read {} texture coordinate sets ({}); prism keeps {TEX_COORD_SETS}, and the others read TEXCOORD_{}",
                sets.len(),
                sets.join(", "),
                self.first()
            )
        })
    }
}

/// The material extensions prism reads and the textures each may refer to.
pub(crate) const EXTENSION_TEXTURES: &[(&str, &[&str])] = &[
    (
        "KHR_materials_iridescence",
        &["iridescenceTexture", "iridescenceThicknessTexture"],
    ),
    (
        "KHR_materials_specular",
        &["specularTexture", "specularColorTexture"],
    ),
    ("KHR_materials_anisotropy", &["anisotropyTexture"]),
    ("KHR_materials_transmission", &["transmissionTexture"]),
    (
        "KHR_materials_diffuse_transmission",
        &[
            "diffuseTransmissionTexture",
            "diffuseTransmissionColorTexture",
        ],
    ),
    (
        "KHR_materials_clearcoat",
        &[
            "clearcoatTexture",
            "clearcoatRoughnessTexture",
            "clearcoatNormalTexture",
        ],
    ),
    (
        "KHR_materials_sheen",
        &["sheenColorTexture", "sheenRoughnessTexture"],
    ),
];

/// The sets the textures of `material`'s extensions read, in the order of
/// [`EXTENSION_TEXTURES`] (references that do not parse read none: the material loader
/// reports them).
fn extension_texture_sets(material: &gltf::Material) -> Vec<u32> {
    let mut sets = Vec::new();
    for (extension, fields) in EXTENSION_TEXTURES {
        let Some(value) = material.extension_value(extension) else {
            continue;
        };
        for field in *fields {
            if let Some(info) = value
                .get(*field)
                .and_then(|r| super::textures::texture_reference(r).ok())
            {
                sets.push(super::textures::reference_set(&info));
            }
        }
    }
    sets
}

/// The set a texture reference reads.
pub(crate) fn info_set(info: &gltf::texture::Info) -> u32 {
    info.texture_transform()
        .and_then(|t| t.tex_coord())
        .unwrap_or(info.tex_coord())
}

/// The set a normal texture reads (its transform is read from its JSON: the gltf crate
/// offers `KHR_texture_transform` on texture infos only).
pub(crate) fn normal_set(normal: &gltf::material::NormalTexture) -> u32 {
    normal_transform(normal)
        .ok()
        .flatten()
        .and_then(|t| t.tex_coord)
        .unwrap_or(normal.tex_coord())
}

/// A normal texture's `KHR_texture_transform`, if it has one.
pub(crate) fn normal_transform(
    normal: &gltf::material::NormalTexture,
) -> Result<Option<gltf::json::extensions::texture::TextureTransform>, String> {
    normal
        .extension_value("KHR_texture_transform")
        .map(|v| {
            serde_json::from_value(v.clone())
                .map_err(|e| format!("normal texture: KHR_texture_transform: {e}"))
        })
        .transpose()
}
