"""Writes scenes/materials.gltf: the glTF material extensions prism renders per
wavelength, one sphere each on a grey floor under a sky image and a small warm light:

  plain (the base they all share: a rough red dielectric), clear coat (the same red under
  a smooth coat), sheen (dark velvet with a pink sheen), specular (a dark base whose
  reflection is tinted blue by specularColorFactor), anisotropy (brushed steel: the
  highlight stretched around the sphere), and iridescence (a soap bubble's film on a
  black base, its thickness varying from pole to pole).

It also writes scenes/assets/furnace-spheres.gltf (see `furnace`).

Every sphere carries texture coordinates, so MikkTSpace tangents orient the anisotropy.
Units are metres; y is up. Run from the repository root: python3 scenes/tools/make_materials.py
"""


from gltf_build import Document, png, quad, uv_sphere

RED = [0.6, 0.06, 0.04, 1.0]


def base(rgba, metallic=0.0, roughness=0.5):
    return {"baseColorFactor": rgba, "metallicFactor": metallic, "roughnessFactor": roughness}


EXTENSIONS = [
    "KHR_materials_clearcoat",
    "KHR_materials_diffuse_transmission",
    "KHR_materials_sheen",
    "KHR_materials_specular",
    "KHR_materials_anisotropy",
    "KHR_materials_iridescence",
]


def furnace():
    """scenes/assets/furnace-spheres.gltf: seven white spheres in a row, one per extension
    at full strength over a white dielectric base (plain, clear coat, sheen, specular
    with a coloured F0 above 1, anisotropy, a thin film, diffuse transmission), seen by an orthographic camera
    under a uniform environment of 1 and nothing else. Energy conserved, every sphere
    renders as 1 wherever it is seen (the white furnace)."""
    doc = Document("scenes/tools/make_materials.py")
    doc.extensions_used += EXTENSIONS
    white = base([1.0, 1.0, 1.0, 1.0], roughness=0.4)
    spheres = [
        ("plain", {}),
        ("clear coat", {"KHR_materials_clearcoat": {"clearcoatFactor": 1.0, "clearcoatRoughnessFactor": 0.1}}),
        ("sheen", {"KHR_materials_sheen": {"sheenColorFactor": [1.0, 1.0, 1.0], "sheenRoughnessFactor": 0.4}}),
        ("specular", {"KHR_materials_specular": {"specularFactor": 1.0, "specularColorFactor": [3.0, 1.0, 6.0]}}),
        ("anisotropy", {"KHR_materials_anisotropy": {"anisotropyStrength": 0.8, "anisotropyRotation": 0.5}}),
        ("iridescence", {"KHR_materials_iridescence": {"iridescenceFactor": 1.0, "iridescenceIor": 1.6, "iridescenceThicknessMaximum": 300.0}}),
        ("diffuse transmission", {"KHR_materials_diffuse_transmission": {"diffuseTransmissionFactor": 0.6}}),
    ]
    for k, (name, extensions) in enumerate(spheres):
        m = doc.material(name, pbrMetallicRoughness=white, extensions=extensions)
        positions, normals, uvs, indices = uv_sphere((-3.0 + k, 0.0, 0.0), 0.45, rings=24, segments=48)
        doc.mesh(f"{name} sphere", positions, m, normals, indices, uvs)
    doc.cameras.append({"type": "orthographic", "orthographic": {"xmag": 3.5, "ymag": 0.5, "znear": 0.1, "zfar": 10.0}})
    doc.nodes.append({"name": "camera", "camera": 0, "translation": [0.0, 0.0, 3.0]})
    doc.root_extension["environment"] = 1.0
    doc.write("scenes/assets/furnace-spheres.gltf")


def main():
    furnace()
    doc = Document("scenes/tools/make_materials.py")
    doc.extensions_used += EXTENSIONS
    # The film's thickness: green from 0 at v = 0 to 1 at v = 1 (iridescenceThicknessTexture
    # reads green), so the bubble's colours band from pole to pole.
    ramp = doc.texture(png(4, 64, lambda x, y: (0, int(255 * y / 63), 0)), wrap=33071)
    spheres = [
        ("plain", {"pbrMetallicRoughness": base(RED)}),
        (
            "clear coat",
            {
                "pbrMetallicRoughness": base(RED, roughness=0.6),
                "extensions": {"KHR_materials_clearcoat": {"clearcoatFactor": 1.0, "clearcoatRoughnessFactor": 0.03}},
            },
        ),
        (
            "sheen",
            {
                "pbrMetallicRoughness": base([0.05, 0.02, 0.08, 1.0], roughness=0.9),
                "extensions": {"KHR_materials_sheen": {"sheenColorFactor": [1.0, 0.45, 0.75], "sheenRoughnessFactor": 0.35}},
            },
        ),
        (
            "specular",
            {
                "pbrMetallicRoughness": base([0.12, 0.12, 0.12, 1.0], roughness=0.2),
                "extensions": {"KHR_materials_specular": {"specularFactor": 1.0, "specularColorFactor": [0.2, 0.6, 4.0]}},
            },
        ),
        (
            "anisotropy",
            {
                "pbrMetallicRoughness": base([0.85, 0.85, 0.88, 1.0], metallic=1.0, roughness=0.25),
                "extensions": {"KHR_materials_anisotropy": {"anisotropyStrength": 0.9, "anisotropyRotation": 0.0}},
            },
        ),
        (
            "iridescence",
            {
                "pbrMetallicRoughness": base([0.02, 0.02, 0.02, 1.0], roughness=0.05),
                "extensions": {
                    "KHR_materials_iridescence": {
                        "iridescenceFactor": 1.0,
                        "iridescenceIor": 1.33,
                        "iridescenceThicknessMinimum": 150.0,
                        "iridescenceThicknessMaximum": 700.0,
                        "iridescenceThicknessTexture": {"index": ramp},
                    }
                },
            },
        ),
    ]
    radius, spacing = 0.4, 1.0
    first = -spacing * (len(spheres) - 1) / 2
    for k, (name, fields) in enumerate(spheres):
        m = doc.material(name, **fields)
        positions, normals, uvs, indices = uv_sphere((first + k * spacing, radius, 0.0), radius)
        doc.mesh(f"{name} sphere", positions, m, normals, indices, uvs)
    floor = doc.material("floor", pbrMetallicRoughness=base([0.35, 0.35, 0.35, 1.0], roughness=1.0))
    doc.mesh("floor", quad((-5, 0, -4), (-5, 0, 3), (5, 0, 3), (5, 0, -4)), floor)
    doc.light(
        "key",
        (-2.0, 3.5, 3.0),
        None,
        {"type": "point", "color": [1.0, 0.85, 0.7], "intensity": 60.0},
    )
    doc.camera("camera", (0.0, 1.6, 7.4), (0.0, 0.4, 0.0), {"aspectRatio": 2.4, "yfov": 0.36, "znear": 0.01})
    doc.root_extension["environment"] = {"image": "sky.hdr", "strength": 0.6}
    doc.write("scenes/materials.gltf")


if __name__ == "__main__":
    main()
