"""A large scene for measuring load time and memory: a bumpy n x n terrain (2 n^2
triangles, positions and indices only, no normals or texture coordinates) under a small
area light, with a camera. Not kept in the repository (n = 1400 is 70 MB); write it where
you measure:

    python3 scenes/tools/make_terrain.py /tmp/terrain.gltf --quads 1400
    /usr/bin/time -v target/release/prism render /tmp/terrain.gltf -o /tmp/t.png \
        --width 128 --height 128 --spp 4 --stats

Plain Python (array, json, math), so it runs wherever the other tools do.
"""

import argparse
import json
import math
import os
import sys
from array import array


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out", help="the .gltf to write (its .bin goes beside it)")
    parser.add_argument("--quads", type=int, default=1400, help="quads per side (default 1400: 3.9 M triangles)")
    args = parser.parse_args()
    n = args.quads
    if n < 1:
        parser.error("--quads must be at least 1")
    positions = array("f")
    for j in range(n + 1):
        z = -1 + 2 * j / n
        for i in range(n + 1):
            x = -1 + 2 * i / n
            y = 0.05 * math.sin(40 * x) * math.cos(37 * z) + 0.02 * math.sin(173 * x + 91 * z)
            positions.extend((x, y, z))
    indices = array("I")
    for j in range(n):
        for i in range(n):
            a = j * (n + 1) + i
            b, c, d = a + 1, a + n + 2, a + n + 1
            indices.extend((a, d, c, a, c, b))
    light = array("f", [-0.3, 1.5, -0.3, 0.3, 1.5, -0.3, 0.3, 1.5, 0.3, -0.3, 1.5, 0.3])
    light_indices = array("I", [0, 1, 2, 0, 2, 3])
    if sys.byteorder != "little":
        for a in (positions, indices, light, light_indices):
            a.byteswap()
    parts = [positions.tobytes(), indices.tobytes(), light.tobytes(), light_indices.tobytes()]
    offsets = [0]
    for p in parts:
        offsets.append(offsets[-1] + len(p))
    bin_name = os.path.splitext(os.path.basename(args.out))[0] + ".bin"
    with open(os.path.join(os.path.dirname(os.path.abspath(args.out)), bin_name), "wb") as f:
        for p in parts:
            f.write(p)
    ys = positions[1::3]
    doc = {
        "asset": {"version": "2.0", "generator": "prism scenes/tools/make_terrain.py"},
        "scene": 0,
        "scenes": [{"nodes": [0, 1, 2]}],
        "nodes": [
            {"mesh": 0},
            {"mesh": 1},
            {"camera": 0, "translation": [0, 1.2, 2.2], "rotation": [-0.2588, 0, 0, 0.9659]},
        ],
        "cameras": [{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.01, "aspectRatio": 1.0}}],
        "extensionsUsed": ["KHR_materials_emissive_strength"],
        "materials": [
            {"pbrMetallicRoughness": {"baseColorFactor": [0.6, 0.5, 0.4, 1], "metallicFactor": 0, "roughnessFactor": 1}},
            {
                "emissiveFactor": [1, 1, 1],
                "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 20}},
                "pbrMetallicRoughness": {"baseColorFactor": [0, 0, 0, 1], "metallicFactor": 0},
                "doubleSided": True,
            },
        ],
        "meshes": [
            {"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "material": 0}]},
            {"primitives": [{"attributes": {"POSITION": 2}, "indices": 3, "material": 1}]},
        ],
        "buffers": [{"uri": bin_name, "byteLength": offsets[-1]}],
        "bufferViews": [
            {"buffer": 0, "byteOffset": offsets[k], "byteLength": len(parts[k])} for k in range(4)
        ],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": (n + 1) ** 2, "type": "VEC3",
             "min": [-1, min(ys), -1], "max": [1, max(ys), 1]},
            {"bufferView": 1, "componentType": 5125, "count": len(indices), "type": "SCALAR"},
            {"bufferView": 2, "componentType": 5126, "count": 4, "type": "VEC3",
             "min": [-0.3, 1.5, -0.3], "max": [0.3, 1.5, 0.3]},
            {"bufferView": 3, "componentType": 5125, "count": 6, "type": "SCALAR"},
        ],
    }
    with open(args.out, "w") as f:
        json.dump(doc, f)
    print(f"{args.out}: {2 * n * n + 2} triangles")


if __name__ == "__main__":
    main()
