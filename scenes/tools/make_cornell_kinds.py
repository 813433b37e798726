"""Writes the Cornell box's scene kinds, the benchmark set prism and Mitsuba 3 render
alike (benches/peer/compare.py; benches/peer/mitsuba_kinds.py builds each in Mitsuba
from these files, meshes and materials included, so the two cannot drift apart):

- scenes/cornell-specular.gltf: the two boxes replaced by a smooth glass sphere (index
  1.5) and a smooth gold sphere;
- scenes/cornell-glossy.gltf: rough gold (GGX alpha 0.05), rough copper (alpha 0.15) and
  rough aluminium (alpha 0.3) spheres, and a rough glass sphere (alpha 0.1);
- scenes/cornell-caustic.gltf: one large glass sphere on the floor under the ceiling
  light, focusing it into a caustic;
- scenes/cornell-plastic.gltf: plastics (a diffuse substrate under a clear coating of
  index 1.49) at GGX alpha 0.05, 0.15 and 0.3, and a smooth one.

The walls, light and camera are scenes/cornell-box.gltf's (its buffer is shared); the
spheres are one embedded triangle mesh with smooth normals, placed by their nodes. The metals'
complex indices are the tables Mitsuba 3 ships (`mitsuba/data/ior`, from luxpop.com),
sampled every 10 nm, so both renderers shade with the same numbers.

  pip install mitsuba
  python3 scenes/tools/make_cornell_kinds.py
"""

import base64
import json
import os
import struct
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from gltf_build import sphere  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
NODES = list(range(360, 831, 10))


def mitsuba_table(name):
    """Mitsuba's measured table (nm, value), linearly interpolated at NODES."""
    import mitsuba

    path = os.path.join(os.path.dirname(mitsuba.__file__), "data", "ior", name)
    pairs = []
    with open(path) as f:
        for line in f:
            line = line.strip()
            if line and not line.startswith("#"):
                nm, v = map(float, line.split()[:2])
                pairs.append((nm, v))
    pairs.sort()

    def at(nm):
        for (a, va), (b, vb) in zip(pairs, pairs[1:]):
            if a <= nm <= b:
                return va + (vb - va) * (nm - a) / (b - a)
        return pairs[0][1] if nm < pairs[0][0] else pairs[-1][1]

    return [[nm, round(at(nm), 5)] for nm in NODES]


def conductor(metal, alpha):
    d = {"type": "conductor", "eta": mitsuba_table(f"{metal}.eta.spd"), "k": mitsuba_table(f"{metal}.k.spd")}
    if alpha:
        d["roughness"] = round(alpha**0.5, 6)  # glTF's perceptual roughness: alpha = r^2
    return d


def glass(alpha=0.0):
    d = {"type": "dielectric", "ior": 1.5}
    if alpha:
        d["roughness"] = round(alpha**0.5, 6)
    return d


RED = [[400, 0.05], [550, 0.06], [600, 0.5], [700, 0.7]]
BLUE = [[400, 0.6], [480, 0.55], [550, 0.1], [700, 0.05]]
YELLOW = [[400, 0.05], [500, 0.3], [550, 0.7], [700, 0.8]]


def plastic(reflectance, alpha):
    d = {"type": "plastic", "reflectance": reflectance, "ior": 1.49}
    if alpha:
        d["roughness"] = round(alpha**0.5, 6)
    return d


# Spheres resting on the floor (y = -1) of the box [-1, 1]^3: (name, centre, radius, material).
KINDS = {
    "specular": [
        ("glass-sphere", (-0.42, -0.62, -0.25), 0.38, glass()),
        ("gold-sphere", (0.45, -0.65, 0.3), 0.35, "Au"),
    ],
    "glossy": [
        ("rough-gold-sphere", (-0.5, -0.7, -0.35), 0.3, ("Au", 0.05)),
        ("rough-copper-sphere", (0.5, -0.7, -0.35), 0.3, ("Cu", 0.15)),
        ("rough-aluminium-sphere", (-0.35, -0.75, 0.4), 0.25, ("Al", 0.3)),
        ("rough-glass-sphere", (0.4, -0.75, 0.4), 0.25, glass(0.1)),
    ],
    "caustic": [
        ("glass-sphere", (0.0, -0.55, 0.0), 0.45, glass()),
    ],
    "plastic": [
        ("red-plastic-sphere", (-0.5, -0.7, -0.35), 0.3, plastic(RED, 0.05)),
        ("blue-plastic-sphere", (0.5, -0.7, -0.35), 0.3, plastic(BLUE, 0.15)),
        ("white-plastic-sphere", (-0.35, -0.75, 0.4), 0.25, plastic(0.8, 0.3)),
        ("yellow-plastic-sphere", (0.4, -0.75, 0.4), 0.25, plastic(YELLOW, 0.0)),
    ],
}


def material(description):
    if description == "Au":
        return conductor("Au", 0.0)
    if isinstance(description, tuple):
        return conductor(*description)
    return description


def write(kind, spheres):
    with open(os.path.join(ROOT, "scenes", "cornell-box.gltf")) as f:
        doc = json.load(f)
    # Drop the boxes (their meshes stay unused in the shared buffer's views).
    boxes = {i for i, n in enumerate(doc["nodes"]) if n["name"] in ("small-box", "large-box")}
    doc["scenes"][0]["nodes"] = [i for i in doc["scenes"][0]["nodes"] if i not in boxes]
    blob = b""
    buffer = len(doc["buffers"])

    def view(data, target):
        nonlocal blob
        doc["bufferViews"].append({"buffer": buffer, "byteOffset": len(blob), "byteLength": len(data), "target": target})
        blob += data + b"\x00" * (-len(data) % 4)
        return len(doc["bufferViews"]) - 1

    def accessor(vectors):
        data = b"".join(struct.pack("<3f", *v) for v in vectors)
        doc["accessors"].append({"bufferView": view(data, 34962), "componentType": 5126, "count": len(vectors),
                                 "type": "VEC3", "min": [min(v[k] for v in vectors) for k in range(3)],
                                 "max": [max(v[k] for v in vectors) for k in range(3)]})
        return len(doc["accessors"]) - 1

    # One unit sphere shared by every sphere's mesh, placed by its node.
    positions, normals, indices = sphere((0.0, 0.0, 0.0), 1.0, rings=48, segments=96)
    index_data = struct.pack(f"<{len(indices)}H", *indices)
    doc["accessors"].append({"bufferView": view(index_data, 34963), "componentType": 5123,
                             "count": len(indices), "type": "SCALAR"})
    shared = {"indices": len(doc["accessors"]) - 1,
              "attributes": {"POSITION": accessor(positions), "NORMAL": accessor(normals)}}
    for name, centre, radius, description in spheres:
        doc["materials"].append({"name": name, "extensions": {"PRISM_spectral": material(description)}})
        primitive = {**shared, "material": len(doc["materials"]) - 1}
        doc["meshes"].append({"name": name, "primitives": [primitive]})
        doc["nodes"].append({"name": name, "mesh": len(doc["meshes"]) - 1,
                             "translation": list(centre), "scale": [radius] * 3})
        doc["scenes"][0]["nodes"].append(len(doc["nodes"]) - 1)
    doc["buffers"].append({"byteLength": len(blob),
                           "uri": "data:application/octet-stream;base64," + base64.b64encode(blob).decode()})
    used = doc.setdefault("extensionsUsed", [])
    if "PRISM_spectral" not in used:
        used.append("PRISM_spectral")
    doc["asset"]["generator"] = "scenes/tools/make_cornell_kinds.py"
    with open(os.path.join(ROOT, "scenes", f"cornell-{kind}.gltf"), "w") as f:
        json.dump(doc, f, indent=1)
        f.write("\n")


def main():
    for kind, spheres in KINDS.items():
        write(kind, spheres)


if __name__ == "__main__":
    main()
