//! Which glTF extensions prism reads, and what it says about the others: an extension the
//! file requires (`extensionsRequired`) that prism cannot read is an error naming it; one
//! it only uses (`extensionsUsed`) is a one-line warning, once per extension, since the
//! file renders without it.

/// Extensions prism reads (through the gltf crate or from the raw JSON).
pub(crate) const READ: &[&str] = &[
    "KHR_lights_punctual",
    "KHR_materials_anisotropy",
    "KHR_materials_clearcoat",
    "KHR_materials_diffuse_transmission",
    "KHR_materials_dispersion",
    "KHR_materials_emissive_strength",
    "KHR_materials_ior",
    "KHR_materials_iridescence",
    "KHR_materials_pbrSpecularGlossiness",
    "KHR_materials_sheen",
    "KHR_materials_specular",
    "KHR_materials_transmission",
    "KHR_materials_unlit",
    "KHR_materials_volume",
    "KHR_materials_volume_scatter",
    "KHR_mesh_quantization",
    "KHR_texture_transform",
    "EXT_texture_webp",
    "EXT_meshopt_compression",
    super::prism_spectral::EXTENSION,
];

/// What a used but unread extension loses, where there is more to say than its name.
fn consequence(extension: &str) -> &'static str {
    match extension {
        "KHR_draco_mesh_compression" => "its uncompressed fallback geometry is rendered",
        "KHR_texture_basisu" | "EXT_texture_avif" => "its fallback images are used",
        "KHR_materials_variants" => "the default material of each primitive is rendered",
        _ => "the file renders without it",
    }
}

/// Errors for the first required extension prism does not read; warnings for every used
/// one it does not read.
pub(crate) fn check(required: &[String], used: &[String]) -> Result<Vec<String>, String> {
    if let Some(e) = required.iter().find(|e| !READ.contains(&e.as_str())) {
        return Err(format!(
            "the file requires glTF extension {e}, which prism does not support"
        ));
    }
    let mut warnings = Vec::new();
    if used
        .iter()
        .any(|e| e == "KHR_materials_pbrSpecularGlossiness")
    {
        warnings.push(
            "KHR_materials_pbrSpecularGlossiness is approximated: the diffuse colour as a \
             dielectric's base colour, roughness 1 - glossiness; the specular colour is not read"
                .to_string(),
        );
    }
    for e in used {
        let e = e.as_str();
        if !READ.contains(&e) && !warnings.iter().any(|w: &String| w.contains(e)) {
            warnings.push(format!(
                "glTF extension {e} is not supported; {}",
                consequence(e)
            ));
        }
    }
    Ok(warnings)
}
