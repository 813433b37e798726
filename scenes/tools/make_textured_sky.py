"""Writes scenes/textured-sky.gltf, the benchmark set's "textured asset lit by an HDR
environment" (benches/peer/compare.py's `textured`; benches/peer/mitsuba_kinds.py builds
the same scene in Mitsuba 3 from this file):

- a floor with a checkered base colour texture, repeated;
- a globe whose base colour texture is a band of hues from pole to pole;
- a rough gold sphere (GGX alpha 0.1) reflecting the sky and the globe;
- all under scenes/sky.hdr, the scene's only light: its sun lights the spheres from the
  front right and throws their shadows on the floor.

Every material is one both renderers define alike: glTF's Lambertian base (metallic 0,
roughness 1, which prism renders as a diffuse surface) with an sRGB texture, and a
conductor with Mitsuba's measured gold table (make_cornell_kinds.py's). The textures are
magnified on screen, so that filtering (prism's footprint, Mitsuba's bilinear lookup)
agrees.

  pip install mitsuba
  python3 scenes/tools/make_textured_sky.py
"""

import colorsys
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from gltf_build import Document, png, quad, uv_sphere  # noqa: E402
from make_cornell_kinds import conductor  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def checker(x, y):
    return (205, 200, 185) if (x // 4 + y // 4) % 2 == 0 else (60, 75, 105)


def hues(x, y):
    # Hue around the globe, saturation falling towards the poles.
    r, g, b = colorsys.hsv_to_rgb(x / 64.0, 0.75 * math.sin(math.pi * (y + 0.5) / 32.0), 0.85)
    return tuple(round(255 * c) for c in (r, g, b))


def main():
    doc = Document("prism scenes/tools/make_textured_sky.py")
    doc.extensions_used.remove("KHR_lights_punctual")
    doc.root_extension = {"environment": {"image": "sky.hdr"}}

    floor = doc.material(
        "checkered floor",
        pbrMetallicRoughness={"baseColorTexture": {"index": doc.texture(png(16, 16, checker))},
                              "metallicFactor": 0.0, "roughnessFactor": 1.0},
    )
    s = 4.0
    positions = quad((-s, 0.0, s), (s, 0.0, s), (s, 0.0, -s), (-s, 0.0, -s))
    uvs = [((p[0] + s) / (2 * s) * 3.0, (p[2] + s) / (2 * s) * 3.0) for p in positions]
    doc.mesh("floor", positions, floor, normals=[(0.0, 1.0, 0.0)] * 6, uvs=uvs)

    globe = doc.material(
        "globe",
        pbrMetallicRoughness={"baseColorTexture": {"index": doc.texture(png(64, 32, hues))},
                              "metallicFactor": 0.0, "roughnessFactor": 1.0},
    )
    positions, normals, uvs, indices = uv_sphere((-0.7, 0.6, 0.0), 0.6, rings=48, segments=96)
    doc.mesh("globe", positions, globe, normals=normals, indices=indices, uvs=uvs)

    gold = doc.material("rough-gold-sphere", extensions={"PRISM_spectral": conductor("Au", 0.1)})
    positions, normals, _, indices = uv_sphere((0.75, 0.5, 0.3), 0.5, rings=48, segments=96)
    doc.mesh("rough-gold-sphere", positions, gold, normals=normals, indices=indices)

    doc.camera("camera", (0.0, 1.3, 3.6), (0.0, 0.45, 0.0), {"yfov": 0.7, "znear": 0.05, "aspectRatio": 1.0})
    doc.write(os.path.join(ROOT, "scenes", "textured-sky.gltf"))


if __name__ == "__main__":
    main()
