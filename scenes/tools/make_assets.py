"""Writes scenes/assets/: small glTF files shaped like the models people download or export
from Blender (no lights, no camera, the glTF features real files use), each exercising one
feature so that a test can show it matters. The CLI tests render every file here; the
fuzz tool mutates them.

The Khronos sample models themselves are not reachable here; these follow the glTF 2.0
specification and the extensions' texts. Run from the repository root:

    python3 scenes/tools/make_assets.py
"""

import base64
import json
import math
import os
import struct

from gltf_build import box, png

OUT = "scenes/assets"


class Asset:
    """A glTF document with an embedded buffer, written by hand so that each file shows
    its feature plainly (accessor types, node trees, extensions)."""

    def __init__(self):
        self.blob = b""
        self.doc = {
            "asset": {"version": "2.0", "generator": "prism scenes/tools/make_assets.py"},
            "scene": 0,
            "scenes": [{"nodes": []}],
            "nodes": [],
            "meshes": [],
            "materials": [],
            "accessors": [],
            "bufferViews": [],
        }

    def view(self, data, stride=None):
        self.blob += b"\x00" * (-len(self.blob) % 4)
        view = {"buffer": 0, "byteOffset": len(self.blob), "byteLength": len(data)}
        if stride:
            view["byteStride"] = stride
        self.doc["bufferViews"].append(view)
        self.blob += data
        return len(self.doc["bufferViews"]) - 1

    def accessor(self, values, kind, component=5126, normalized=False, view=None, offset=0):
        """An accessor of `values` (tuples, or scalars for SCALAR) of glTF component type
        `component` (5120 byte, 5121 ubyte, 5122 short, 5123 ushort, 5125 uint, 5126
        float)."""
        fmt = {5120: "b", 5121: "B", 5122: "h", 5123: "H", 5125: "I", 5126: "f"}[component]
        flat = [v for t in values for v in (t if isinstance(t, (tuple, list)) else (t,))]
        if view is None:
            data = struct.pack(f"<{len(flat)}{fmt}", *flat)
            view = self.view(data)
        accessor = {"bufferView": view, "byteOffset": offset, "componentType": component, "count": len(values), "type": kind}
        if normalized:
            accessor["normalized"] = True
        if kind == "VEC3" and component == 5126:
            accessor["min"] = [min(v[i] for v in values) for i in range(3)]
            accessor["max"] = [max(v[i] for v in values) for i in range(3)]
        self.doc["accessors"].append(accessor)
        return len(self.doc["accessors"]) - 1

    def material(self, **fields):
        self.doc["materials"].append(fields)
        return len(self.doc["materials"]) - 1

    def mesh(self, primitives, name=None):
        mesh = {"primitives": primitives}
        if name:
            mesh["name"] = name
        self.doc["meshes"].append(mesh)
        return len(self.doc["meshes"]) - 1

    def node(self, root=True, **fields):
        self.doc["nodes"].append(fields)
        index = len(self.doc["nodes"]) - 1
        if root:
            self.doc["scenes"][0]["nodes"].append(index)
        return index

    def texture(self, png_bytes, sampler=None):
        doc = self.doc
        doc.setdefault("images", []).append({"bufferView": self.view(png_bytes), "mimeType": "image/png"})
        doc.setdefault("samplers", []).append(sampler or {})
        doc.setdefault("textures", []).append({"source": len(doc["images"]) - 1, "sampler": len(doc["samplers"]) - 1})
        return len(doc["textures"]) - 1

    def write(self, name):
        self.doc["buffers"] = [
            {"byteLength": len(self.blob), "uri": "data:application/octet-stream;base64," + base64.b64encode(self.blob).decode()}
        ]
        doc = {k: v for k, v in self.doc.items() if v != []}
        with open(os.path.join(OUT, name), "w") as f:
            json.dump(doc, f, indent=1)
            f.write("\n")


def cube_primitive(asset, material, half=0.5):
    """An indexed cube with per-face normals and UVs, as exporters write it."""
    positions, normals, uvs, indices = [], [], [], []
    for axis in range(3):
        for sign in (-1.0, 1.0):
            n = [0.0, 0.0, 0.0]
            n[axis] = sign
            u = [0.0, 0.0, 0.0]
            u[(axis + 1) % 3] = 1.0
            v = [n[1] * u[2] - n[2] * u[1], n[2] * u[0] - n[0] * u[2], n[0] * u[1] - n[1] * u[0]]
            base = len(positions)
            for a, b in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
                positions.append(tuple(half * (n[i] + a * u[i] + b * v[i]) for i in range(3)))
                normals.append(tuple(n))
                uvs.append(((a + 1) / 2, (1 - b) / 2))
            indices += [base, base + 1, base + 2, base, base + 2, base + 3]
    return {
        "attributes": {
            "POSITION": asset.accessor(positions, "VEC3"),
            "NORMAL": asset.accessor(normals, "VEC3"),
            "TEXCOORD_0": asset.accessor(uvs, "VEC2"),
        },
        "indices": asset.accessor(indices, "SCALAR", 5123),
        "material": material,
    }


def quad_primitive(asset, material, corners, extra=None):
    positions = [tuple(c) for c in corners]
    uvs = [(0.0, 1.0), (1.0, 1.0), (1.0, 0.0), (0.0, 0.0)]
    attributes = {"POSITION": asset.accessor(positions, "VEC3"), "TEXCOORD_0": asset.accessor(uvs, "VEC2")}
    attributes.update(extra or {})
    return {"attributes": attributes, "indices": asset.accessor([0, 1, 2, 0, 2, 3], "SCALAR", 5123), "material": material}


def boxed():
    """The Khronos "Box": a red cube under a node with a matrix (Y-up from Z-up), no light,
    no camera."""
    a = Asset()
    red = a.material(name="Red", pbrMetallicRoughness={"baseColorFactor": [0.8, 0.0, 0.0, 1.0], "metallicFactor": 0.0})
    mesh = a.mesh([cube_primitive(a, red)], "Mesh")
    child = a.node(root=False, mesh=mesh)
    a.node(children=[child], matrix=[1, 0, 0, 0, 0, 0, -1, 0, 0, 1, 0, 0, 0, 0, 0, 1])
    a.write("box.gltf")


def orientation():
    """Like "OrientationTest": cubes along +x, +y, +z (red, green, blue) around a grey
    centre, spread far from the origin, so a default camera must frame them all."""
    a = Asset()
    grey = a.material(name="grey", pbrMetallicRoughness={"baseColorFactor": [0.6, 0.6, 0.6, 1.0], "metallicFactor": 0.0})
    colours = [[0.8, 0.1, 0.1, 1.0], [0.1, 0.8, 0.1, 1.0], [0.1, 0.1, 0.8, 1.0]]
    a.node(mesh=a.mesh([cube_primitive(a, grey)]), translation=[10.0, 20.0, 0.0])
    for axis, colour in enumerate(colours):
        m = a.material(pbrMetallicRoughness={"baseColorFactor": colour, "metallicFactor": 0.0})
        t = [10.0, 20.0, 0.0]
        t[axis] += 3.0
        a.node(mesh=a.mesh([cube_primitive(a, m, 0.4)]), translation=t)
    a.write("orientation.gltf")


def unlit():
    """KHR_materials_unlit: a quad that shows its base colour exactly, filling the view of
    an orthographic camera."""
    a = Asset()
    a.doc["extensionsUsed"] = ["KHR_materials_unlit"]
    m = a.material(
        name="unlit",
        pbrMetallicRoughness={"baseColorFactor": [0.2, 0.5, 0.8, 1.0]},
        extensions={"KHR_materials_unlit": {}},
    )
    s = 2.0
    a.node(mesh=a.mesh([quad_primitive(a, m, [(-s, -s, 0), (s, -s, 0), (s, s, 0), (-s, s, 0)])]))
    a.doc["cameras"] = [{"type": "orthographic", "orthographic": {"xmag": 1.0, "ymag": 1.0, "znear": 0.1, "zfar": 10.0}}]
    a.node(camera=0, translation=[0.0, 0.0, 2.0])
    a.write("unlit.gltf")


def white_plane():
    """A white Lambertian square (base colour 1, roughness 1, not metallic) filling the
    view of an orthographic camera: under an environment of emissive-colour value v it
    shows RGB v."""
    a = Asset()
    m = a.material(name="white", pbrMetallicRoughness={"baseColorFactor": [1.0, 1.0, 1.0, 1.0], "metallicFactor": 0.0, "roughnessFactor": 1.0})
    s = 50.0
    a.node(mesh=a.mesh([quad_primitive(a, m, [(-s, -s, 0), (s, -s, 0), (s, s, 0), (-s, s, 0)])]))
    a.doc["cameras"] = [{"type": "orthographic", "orthographic": {"xmag": 1.0, "ymag": 1.0, "znear": 0.1, "zfar": 10.0}}]
    a.node(camera=0, translation=[0.0, 0.0, 2.0])
    a.write("white-plane.gltf")


def requires_draco():
    """A file that requires KHR_draco_mesh_compression: prism must refuse it by name."""
    a = Asset()
    m = a.material(pbrMetallicRoughness={"baseColorFactor": [0.8, 0.8, 0.8, 1.0]})
    a.node(mesh=a.mesh([cube_primitive(a, m)]))
    a.doc["extensionsUsed"] = ["KHR_draco_mesh_compression"]
    a.doc["extensionsRequired"] = ["KHR_draco_mesh_compression"]
    a.write("requires-draco.gltf")


def uses_unknown():
    """A file that uses (but does not require) extensions prism does not read: it renders,
    with one warning per extension."""
    a = Asset()
    m = a.material(
        pbrMetallicRoughness={"baseColorFactor": [0.8, 0.7, 0.2, 1.0], "metallicFactor": 0.0},
        extensions={"KHR_materials_sss": {"scatterDistance": 0.01}, "VENDOR_made_up": {}},
    )
    a.node(mesh=a.mesh([cube_primitive(a, m)]), rotation=[0.2, 0.3, 0.0, math.sqrt(1 - 0.13)])
    a.doc["extensionsUsed"] = ["KHR_materials_sss", "VENDOR_made_up"]
    a.write("uses-unknown.gltf")


def ortho_camera(a):
    a.doc["cameras"] = [{"type": "orthographic", "orthographic": {"xmag": 1.0, "ymag": 1.0, "znear": 0.1, "zfar": 10.0}}]
    a.node(camera=0, translation=[0.0, 0.0, 2.0])


def vertex_colors():
    """COLOR_0 multiplying a white Lambertian base: the left half of the view has
    normalized UNSIGNED_BYTE RGBA colours (255, 64, 0, 255), the right half FLOAT RGB
    (0.2, 0.6, 0.9); under a grey environment of 1 each half shows its colour."""
    a = Asset()
    m = a.material(name="white", pbrMetallicRoughness={"baseColorFactor": [1.0, 1.0, 1.0, 1.0], "metallicFactor": 0.0, "roughnessFactor": 1.0})
    s = 50.0
    left = [(-s, -s, 0), (0, -s, 0), (0, s, 0), (-s, s, 0)]
    right = [(0, -s, 0), (s, -s, 0), (s, s, 0), (0, s, 0)]
    bytes_colour = a.accessor([(255, 64, 0, 255)] * 4, "VEC4", 5121, normalized=True)
    float_colour = a.accessor([(0.2, 0.6, 0.9)] * 4, "VEC3")
    a.node(mesh=a.mesh([
        quad_primitive(a, m, left, {"COLOR_0": bytes_colour}),
        quad_primitive(a, m, right, {"COLOR_0": float_colour}),
    ]))
    ortho_camera(a)
    a.write("vertex-colors.gltf")


def quantized():
    """KHR_mesh_quantization: the white plane with SHORT positions (unnormalized, scaled
    by the node), BYTE normalized normals and UNSIGNED_SHORT normalized texture
    coordinates, as gltfpack writes them."""
    a = Asset()
    a.doc["extensionsUsed"] = ["KHR_mesh_quantization"]
    a.doc["extensionsRequired"] = ["KHR_mesh_quantization"]
    m = a.material(name="white", pbrMetallicRoughness={"baseColorFactor": [1.0, 1.0, 1.0, 1.0], "metallicFactor": 0.0, "roughnessFactor": 1.0})
    q = 1000
    # VEC3 of SHORT is 6 bytes; vertex attributes must be 4-byte aligned, so pad to 8.
    positions = [(-q, -q, 0, 0), (q, -q, 0, 0), (q, q, 0, 0), (-q, q, 0, 0)]
    view = a.view(struct.pack("<16h", *[c for p in positions for c in p]), stride=8)
    pos = a.accessor([p[:3] for p in positions], "VEC3", 5122, view=view)
    a.doc["accessors"][pos]["min"] = [-q, -q, 0]
    a.doc["accessors"][pos]["max"] = [q, q, 0]
    normals = a.view(struct.pack("<16b", *([0, 0, 127, 0] * 4)), stride=4)
    nrm = a.accessor([(0, 0, 127)] * 4, "VEC3", 5120, normalized=True, view=normals)
    uvs = a.accessor([(0, 65535), (65535, 65535), (65535, 0), (0, 0)], "VEC2", 5123, normalized=True)
    primitive = {
        "attributes": {"POSITION": pos, "NORMAL": nrm, "TEXCOORD_0": uvs},
        "indices": a.accessor([0, 1, 2, 0, 2, 3], "SCALAR", 5123),
        "material": m,
    }
    a.node(mesh=a.mesh([primitive]), scale=[0.05, 0.05, 0.05])
    ortho_camera(a)
    a.write("quantized.gltf")


def sphere_primitive(a, material, centre, radius, rings=24, segments=48):
    positions, normals, uvs, indices = [], [], [], []
    for i in range(rings + 1):
        theta = math.pi * i / rings
        for j in range(segments + 1):
            phi = 2.0 * math.pi * j / segments
            n = (math.sin(theta) * math.cos(phi), math.cos(theta), math.sin(theta) * math.sin(phi))
            positions.append(tuple(centre[k] + radius * n[k] for k in range(3)))
            normals.append(n)
            uvs.append((j / segments, i / rings))
    for i in range(rings):
        for j in range(segments):
            a0, b0 = i * (segments + 1) + j, (i + 1) * (segments + 1) + j
            indices += [a0, a0 + 1, b0, a0 + 1, b0 + 1, b0]
    return {
        "attributes": {
            "POSITION": a.accessor(positions, "VEC3"),
            "NORMAL": a.accessor(normals, "VEC3"),
            "TEXCOORD_0": a.accessor(uvs, "VEC2"),
        },
        "indices": a.accessor(indices, "SCALAR", 5123),
        "material": material,
    }


def checker(x, y):
    return (230, 230, 220) if (x // 8 + y // 8) % 2 == 0 else (30, 60, 110)


def product_glb():
    """A binary glTF like a downloaded product model: a polished gold sphere, a
    checker-textured matte cube and a red plastic sphere on a round grey plinth; no light,
    no camera. The README renders it under scenes/sky.hdr."""
    a = Asset()
    gold = a.material(name="gold", pbrMetallicRoughness={"baseColorFactor": [1.0, 0.78, 0.34, 1.0], "metallicFactor": 1.0, "roughnessFactor": 0.25})
    plastic = a.material(name="red plastic", pbrMetallicRoughness={"baseColorFactor": [0.7, 0.05, 0.04, 1.0], "metallicFactor": 0.0, "roughnessFactor": 0.35})
    checked = a.material(
        name="checker",
        pbrMetallicRoughness={"baseColorTexture": {"index": a.texture(png(64, 64, checker))}, "metallicFactor": 0.0, "roughnessFactor": 0.8},
    )
    grey = a.material(name="plinth", pbrMetallicRoughness={"baseColorFactor": [0.5, 0.5, 0.5, 1.0], "metallicFactor": 0.0, "roughnessFactor": 0.6})
    parts = [
        a.node(root=False, mesh=a.mesh([sphere_primitive(a, gold, (-0.65, 0.45, 0.0), 0.45)]), name="gold ball"),
        a.node(root=False, mesh=a.mesh([sphere_primitive(a, plastic, (0.75, 0.3, 0.45), 0.3)]), name="red ball"),
        a.node(root=False, mesh=a.mesh([cube_primitive(a, checked, 0.35)]), translation=[0.35, 0.35, -0.45], rotation=[0.0, 0.38268343, 0.0, 0.92387953], name="cube"),
    ]
    # A flat plinth: a disc of 64 segments.
    n = 64
    positions = [(0.0, 0.0, 0.0)] + [(1.6 * math.cos(2 * math.pi * k / n), 0.0, 1.6 * math.sin(2 * math.pi * k / n)) for k in range(n)]
    indices = [i for k in range(n) for i in (0, 1 + (k + 1) % n, 1 + k)]
    parts.append(a.node(root=False, mesh=a.mesh([{
        "attributes": {"POSITION": a.accessor(positions, "VEC3"), "NORMAL": a.accessor([(0.0, 1.0, 0.0)] * len(positions), "VEC3")},
        "indices": a.accessor(indices, "SCALAR", 5123),
        "material": grey,
    }]), name="plinth"))
    # The whole set tilted 20 degrees towards the viewer, as a product shot is framed.
    a.node(children=parts, name="product", rotation=[0.17364818, 0.0, 0.0, 0.98480775])
    # As a GLB: the JSON chunk, then the binary chunk, each padded to 4 bytes.
    a.doc["buffers"] = [{"byteLength": len(a.blob)}]
    doc = {k: v for k, v in a.doc.items() if v != []}
    text = json.dumps(doc).encode()
    text += b" " * (-len(text) % 4)
    blob = a.blob + b"\x00" * (-len(a.blob) % 4)
    total = 12 + 8 + len(text) + 8 + len(blob)
    with open(os.path.join(OUT, "product.glb"), "wb") as f:
        f.write(struct.pack("<4sII", b"glTF", 2, total))
        f.write(struct.pack("<I4s", len(text), b"JSON") + text)
        f.write(struct.pack("<I4s", len(blob), b"BIN\x00") + blob)


def png_rgba(width, height, texel):
    """An 8-bit RGBA PNG whose texel (x, y) (y down) is texel(x, y)."""
    import zlib
    raw = b"".join(b"\x00" + bytes(c for x in range(width) for c in texel(x, y)) for y in range(height))

    def chunk(kind, data):
        body = kind + data
        return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body))

    header = struct.pack(">IIBBBBB", width, height, 8, 6, 0, 0, 0)
    return b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b"")


def alpha_mask():
    """alphaMode MASK: a white leaf above a red floor whose base colour texture's alpha is
    0 on its left half and 1 on its right: the floor shows through the left half."""
    a = Asset()
    red = a.material(name="red floor", pbrMetallicRoughness={"baseColorFactor": [0.8, 0.1, 0.1, 1.0], "metallicFactor": 0.0, "roughnessFactor": 1.0})
    leaf_texture = a.texture(png_rgba(8, 8, lambda x, y: (255, 255, 255, 0 if x < 4 else 255)), {"magFilter": 9728, "minFilter": 9728, "wrapS": 33071, "wrapT": 33071})
    leaf = a.material(
        name="leaf",
        alphaMode="MASK",
        alphaCutoff=0.5,
        doubleSided=True,
        pbrMetallicRoughness={"baseColorTexture": {"index": leaf_texture}, "metallicFactor": 0.0, "roughnessFactor": 1.0},
    )
    s = 50.0
    a.node(mesh=a.mesh([quad_primitive(a, red, [(-s, -s, 0), (s, -s, 0), (s, s, 0), (-s, s, 0)])]))
    # The leaf spans the view; its UVs put the texture's halves left and right.
    a.node(mesh=a.mesh([quad_primitive(a, leaf, [(-1.0, -1.0, 0.5), (1.0, -1.0, 0.5), (1.0, 1.0, 0.5), (-1.0, 1.0, 0.5)])]))
    ortho_camera(a)
    a.write("alpha-mask.gltf")


def alpha_blend():
    """alphaMode BLEND: a white square of alpha 0.25 above a black floor: seen through it,
    the pixel is a quarter of the white's radiance (stochastic transparency on average)."""
    a = Asset()
    black = a.material(name="black floor", pbrMetallicRoughness={"baseColorFactor": [0.0, 0.0, 0.0, 1.0], "metallicFactor": 0.0, "roughnessFactor": 1.0})
    glass = a.material(
        name="quarter white",
        alphaMode="BLEND",
        pbrMetallicRoughness={"baseColorFactor": [1.0, 1.0, 1.0, 0.25], "metallicFactor": 0.0, "roughnessFactor": 1.0},
    )
    s = 50.0
    a.node(mesh=a.mesh([quad_primitive(a, black, [(-s, -s, 0), (s, -s, 0), (s, s, 0), (-s, s, 0)])]))
    a.node(mesh=a.mesh([quad_primitive(a, glass, [(-s, -s, 0.5), (s, -s, 0.5), (s, s, 0.5), (-s, s, 0.5)])]))
    ortho_camera(a)
    a.write("alpha-blend.gltf")


def webp_texture():
    """EXT_texture_webp, required and without a fallback: the white plane's base colour is
    a lossless 2 x 1 WebP, red on the left and blue on the right (NEAREST). Needs Pillow
    to encode the WebP; without it the committed file stays as it is."""
    try:
        from PIL import Image
    except ImportError:
        print("Pillow is missing: webp-texture.gltf not rewritten")
        return
    import io

    image = Image.new("RGB", (2, 1))
    image.putpixel((0, 0), (255, 0, 0))
    image.putpixel((1, 0), (0, 0, 255))
    buffer = io.BytesIO()
    image.save(buffer, "WEBP", lossless=True)
    a = Asset()
    a.doc["extensionsUsed"] = ["EXT_texture_webp"]
    a.doc["extensionsRequired"] = ["EXT_texture_webp"]
    a.doc["images"] = [{"bufferView": a.view(buffer.getvalue()), "mimeType": "image/webp"}]
    a.doc["samplers"] = [{"magFilter": 9728, "minFilter": 9728, "wrapS": 33071, "wrapT": 33071}]
    a.doc["textures"] = [{"sampler": 0, "extensions": {"EXT_texture_webp": {"source": 0}}}]
    m = a.material(name="webp", pbrMetallicRoughness={"baseColorTexture": {"index": 0}, "metallicFactor": 0.0, "roughnessFactor": 1.0})
    s = 1.0
    a.node(mesh=a.mesh([quad_primitive(a, m, [(-s, -s, 0), (s, -s, 0), (s, s, 0), (-s, s, 0)])]))
    ortho_camera(a)
    a.write("webp-texture.gltf")


def checkerboard(name, repeats):
    """A white-and-black 2 x 2 checker repeated `repeats` times (KHR_texture_transform)
    across a plane filling an orthographic view: at 512 repeats over 32 pixels, each pixel
    covers 32 texels each way (texture filtering must average them); at 1, each texel
    spans 16 pixels (magnification must stay sharp)."""
    a = Asset()
    a.doc["extensionsUsed"] = ["KHR_texture_transform"]
    # NEAREST magnification: magnified squares must stay sharp.
    tex = a.texture(png(2, 2, lambda x, y: (255, 255, 255) if (x + y) % 2 == 0 else (0, 0, 0)), {"magFilter": 9728})
    m = a.material(
        name="checker",
        pbrMetallicRoughness={
            "baseColorTexture": {"index": tex, "extensions": {"KHR_texture_transform": {"scale": [repeats, repeats]}}},
            "metallicFactor": 0.0,
            "roughnessFactor": 1.0,
        },
    )
    s = 1.0
    a.node(mesh=a.mesh([quad_primitive(a, m, [(-s, -s, 0), (s, -s, 0), (s, s, 0), (-s, s, 0)])]))
    ortho_camera(a)
    a.write(name)


def sparse_interleaved():
    """The white plane as a non-indexed primitive (six vertices) whose POSITION and NORMAL
    are interleaved in one buffer view (byteStride 24), and whose POSITION accessor is
    sparse: the stored positions put two corners far off, and the sparse substitution
    puts them back. Read correctly it fills the orthographic view."""
    a = Asset()
    m = a.material(name="white", pbrMetallicRoughness={"baseColorFactor": [1.0, 1.0, 1.0, 1.0], "metallicFactor": 0.0, "roughnessFactor": 1.0})
    s = 50.0
    good = [(-s, -s, 0), (s, -s, 0), (s, s, 0), (-s, -s, 0), (s, s, 0), (-s, s, 0)]
    stored = list(good)
    stored[2] = (0.0, 0.0, -500.0)
    stored[4] = (0.0, 0.0, -500.0)
    data = b"".join(struct.pack("<6f", *p, 0.0, 0.0, 1.0) for p in stored)
    view = a.view(data, stride=24)
    pos = a.accessor(stored, "VEC3", view=view, offset=0)
    a.doc["accessors"][pos]["min"] = [-s, -s, -500.0]
    a.doc["accessors"][pos]["max"] = [s, s, 0.0]
    nrm = a.accessor([(0.0, 0.0, 1.0)] * 6, "VEC3", view=view, offset=12)
    del a.doc["accessors"][nrm]["min"], a.doc["accessors"][nrm]["max"]
    indices_view = a.view(struct.pack("<2H", 2, 4))
    values_view = a.view(struct.pack("<6f", *good[2], *good[4]))
    a.doc["accessors"][pos]["sparse"] = {
        "count": 2,
        "indices": {"bufferView": indices_view, "componentType": 5123},
        "values": {"bufferView": values_view},
    }
    a.node(mesh=a.mesh([{"attributes": {"POSITION": pos, "NORMAL": nrm}, "material": m}]))
    ortho_camera(a)
    a.write("sparse-interleaved.gltf")


def spec_gloss():
    """KHR_materials_pbrSpecularGlossiness (older assets): the white plane's colour comes
    from diffuseFactor (0.2, 0.6, 0.9); glossiness 0 makes it matte. Without the
    extension the material would be glTF's default white metal."""
    a = Asset()
    a.doc["extensionsUsed"] = ["KHR_materials_pbrSpecularGlossiness"]
    m = a.material(
        name="spec-gloss",
        extensions={"KHR_materials_pbrSpecularGlossiness": {"diffuseFactor": [0.2, 0.6, 0.9, 1.0], "specularFactor": [0.0, 0.0, 0.0], "glossinessFactor": 0.0}},
    )
    s = 50.0
    a.node(mesh=a.mesh([quad_primitive(a, m, [(-s, -s, 0), (s, -s, 0), (s, s, 0), (-s, s, 0)])]))
    ortho_camera(a)
    a.write("spec-gloss.gltf")


def multi_uv():
    """Like "MultiUVTest": textures that read TEXCOORD_1. Each quad's TEXCOORD_0 is one
    point of the red left half of a texture, its TEXCOORD_1 spans it (red left, green
    right): read from the right set, the right half of the view is green. The top quad's
    material reads both sets: a grey base colour texture (and a flat normal texture) on set
    0 and the red-green texture as its emission on set 1 (so a texture on the scene's
    second set shows). The bottom quad is unlit and names set 0 overridden to 1 by
    KHR_texture_transform."""
    a = Asset()
    a.doc["extensionsUsed"] = ["KHR_texture_transform", "KHR_materials_unlit"]
    nearest = {"magFilter": 9728, "minFilter": 9728, "wrapS": 33071, "wrapT": 33071}
    halves = a.texture(png_rgba(2, 1, lambda x, y: (204, 25, 25, 255) if x == 0 else (25, 204, 25, 255)), nearest)
    grey = a.texture(png_rgba(1, 1, lambda x, y: (128, 128, 128, 255)))
    flat = a.texture(png_rgba(1, 1, lambda x, y: (128, 128, 255, 255)))
    lit = a.material(
        name="grey on set 0, glowing on set 1",
        pbrMetallicRoughness={"baseColorTexture": {"index": grey, "texCoord": 0}, "metallicFactor": 0.0, "roughnessFactor": 1.0},
        normalTexture={"index": flat, "texCoord": 0},
        emissiveTexture={"index": halves, "texCoord": 1},
        emissiveFactor=[1.0, 1.0, 1.0],
    )
    unlit = a.material(
        name="unlit, set 0 overridden to 1",
        pbrMetallicRoughness={"baseColorTexture": {"index": halves, "texCoord": 0, "extensions": {"KHR_texture_transform": {"texCoord": 1}}}},
        extensions={"KHR_materials_unlit": {}},
    )
    for material, (y0, y1) in ((lit, (0.0, 1.0)), (unlit, (-1.0, 0.0))):
        point = a.accessor([(0.25, 0.5)] * 4, "VEC2")
        spans = a.accessor([(0.0, 1.0), (1.0, 1.0), (1.0, 0.0), (0.0, 0.0)], "VEC2")
        corners = [(-1.0, y0, 0.0), (1.0, y0, 0.0), (1.0, y1, 0.0), (-1.0, y1, 0.0)]
        primitive = quad_primitive(a, material, corners, {"TEXCOORD_0": point, "TEXCOORD_1": spans})
        primitive["attributes"]["NORMAL"] = a.accessor([(0.0, 0.0, 1.0)] * 4, "VEC3")
        a.node(mesh=a.mesh([primitive]))
    ortho_camera(a)
    a.write("multi-uv.gltf")


def thin_film():
    """KHR_materials_iridescence: a smooth black dielectric quad (index 1.5) under a soap-
    like film (index 1.3, 500 nm: iridescenceThicknessMaximum, no thickness texture),
    filling an orthographic view that looks straight at it, under a flat spectral
    environment of 1 W m^-2 sr^-1 nm^-1: what it reflects towards the camera is the film's
    normal-incidence Airy reflectance, band by band."""
    a = Asset()
    a.doc["extensionsUsed"] = ["KHR_materials_iridescence", "PRISM_spectral"]
    a.doc["extensions"] = {"PRISM_spectral": {"environment": 1.0}}
    m = a.material(
        name="film",
        pbrMetallicRoughness={"baseColorFactor": [0.0, 0.0, 0.0, 1.0], "metallicFactor": 0.0, "roughnessFactor": 0.0},
        extensions={"KHR_materials_iridescence": {"iridescenceFactor": 1.0, "iridescenceIor": 1.3, "iridescenceThicknessMaximum": 500.0}},
    )
    s = 2.0
    a.node(mesh=a.mesh([quad_primitive(a, m, [(-s, -s, 0), (s, -s, 0), (s, s, 0), (-s, s, 0)])]))
    ortho_camera(a)
    a.write("thin-film.gltf")


def grey_sky():
    """An 8 x 4 Radiance .hdr whose texels are all 0.5 (RGBE 128 128 128 128): as an
    environment image it must light the white plane as `--environment 0.5` does."""
    header = b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 4 +X 8\n"
    with open(os.path.join(OUT, "grey-0.5.hdr"), "wb") as f:
        f.write(header + bytes([128, 128, 128, 128]) * 32)


def main():
    os.makedirs(OUT, exist_ok=True)
    boxed()
    orientation()
    unlit()
    white_plane()
    grey_sky()
    vertex_colors()
    quantized()
    product_glb()
    alpha_mask()
    alpha_blend()
    webp_texture()
    sparse_interleaved()
    spec_gloss()
    multi_uv()
    thin_film()
    checkerboard("checker-minified.gltf", 512)
    checkerboard("checker-magnified.gltf", 1)
    requires_draco()
    uses_unknown()


if __name__ == "__main__":
    main()
