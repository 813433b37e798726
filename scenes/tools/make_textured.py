"""Writes scenes/textured.gltf: glTF's four textures prism reads, in one small scene.

- a checkered floor: a base colour texture, repeated four times across the floor;
- a ball whose metallic-roughness texture bands it with polished gold and matte ochre
  (green is roughness, blue metallic), and whose normal texture dimples it;
- a sign on the back wall: an emissive texture of red, green, blue and white bars on
  black, the scene's only area light (emissiveFactor 1, strength 6);
- a point light above for fill, and a dim grey sky.

The textures are small PNGs made here (zlib, no imaging library), embedded with the
geometry, so the file stands alone. Run from the repository root:

    python3 scenes/tools/make_textured.py
"""

import math

from gltf_build import Document, png, quad, sphere


def checker(x, y):
    return (200, 200, 190) if (x // 4 + y // 4) % 2 == 0 else (40, 60, 90)


def bands(x, y):
    # Rows down the image: polished metal (roughness 0.15, metallic 1), then matte
    # dielectric (roughness 0.85, metallic 0).
    return (0, 38, 255) if (y // 6) % 2 == 0 else (0, 217, 0)


def dimples(x, y):
    # Tangent-space normals of a field of round dimples, encoded as (n + 1) / 2.
    cx, cy = (x % 8) - 3.5, (y % 8) - 3.5
    r = math.hypot(cx, cy)
    tilt = 0.6 * math.sin(math.pi * min(r / 4.0, 1.0))
    nx, ny = (-cx / r * tilt, cy / r * tilt) if r > 0 else (0.0, 0.0)
    nz = math.sqrt(max(0.0, 1.0 - nx * nx - ny * ny))
    return tuple(round(255 * (c + 1) / 2) for c in (nx, ny, nz))


def sign(x, y):
    colours = [(255, 40, 30), (40, 255, 60), (40, 80, 255), (255, 255, 255)]
    if y in (0, 7) or x % 8 in (0, 7):
        return (0, 0, 0)
    return colours[x // 8]


def main():
    doc = Document("prism scenes/tools/make_textured.py")
    doc.extensions_used.append("KHR_materials_emissive_strength")
    # A dim grey sky, so that the polished bands have something to reflect.
    doc.root_extension = {"environment": 0.003}

    floor_texture = doc.texture(png(32, 32, checker))
    floor = doc.material(
        "checkered floor",
        pbrMetallicRoughness={"baseColorTexture": {"index": floor_texture}, "metallicFactor": 0.0, "roughnessFactor": 1.0},
    )
    s = 2.0
    corners = [(-s, 0.0, s), (s, 0.0, s), (s, 0.0, -s), (-s, 0.0, -s)]
    positions = quad(*corners)
    uvs = [((p[0] + s) / s * 2.0, (p[2] + s) / s * 2.0) for p in positions]
    doc.mesh("floor", positions, floor, normals=[(0.0, 1.0, 0.0)] * 6, uvs=uvs)

    ball = doc.material(
        "banded ball",
        pbrMetallicRoughness={
            "baseColorFactor": [1.0, 0.72, 0.3, 1.0],
            "metallicFactor": 1.0,
            "roughnessFactor": 1.0,
            "metallicRoughnessTexture": {"index": doc.texture(png(1, 36, bands))},
        },
        normalTexture={"index": doc.texture(png(64, 32, dimples)), "scale": 1.0},
    )
    rings, segments = 48, 96
    positions, normals, indices = sphere((0.0, 0.6, 0.0), 0.6, rings, segments)
    uvs = [(j / segments, i / rings) for i in range(rings + 1) for j in range(segments + 1)]
    doc.mesh("ball", positions, ball, normals=normals, indices=indices, uvs=uvs)

    sign_material = doc.material(
        "sign",
        emissiveFactor=[1.0, 1.0, 1.0],
        emissiveTexture={"index": doc.texture(png(32, 8, sign), wrap=33071)},
        extensions={"KHR_materials_emissive_strength": {"emissiveStrength": 6.0}},
        pbrMetallicRoughness={"baseColorFactor": [0.0, 0.0, 0.0, 1.0], "metallicFactor": 0.0},
    )
    w, y0, y1, z = 1.6, 0.9, 1.7, -1.5
    positions = quad((-w, y0, z), (w, y0, z), (w, y1, z), (-w, y1, z))
    uvs = [((p[0] + w) / (2 * w), (y1 - p[1]) / (y1 - y0)) for p in positions]
    doc.mesh("sign", positions, sign_material, normals=[(0.0, 0.0, 1.0)] * 6, uvs=uvs)

    doc.light("fill", (0.0, 3.0, 1.5), None, {"type": "point", "color": [1.0, 0.95, 0.9], "intensity": 15.0})
    doc.camera("camera", (0.0, 1.3, 3.2), (0.0, 0.7, 0.0), {"yfov": 0.75, "znear": 0.05, "aspectRatio": 4 / 3})
    doc.write("scenes/textured.gltf")


if __name__ == "__main__":
    main()
