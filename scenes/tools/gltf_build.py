"""Small helpers the scene generators share: triangle winding, orientations, and a glTF
document with one embedded (base64) buffer, so a generated scene is a single file.

Conventions: y is up; cameras look and KHR lights shine down their node's -z.
"""

import base64
import json
import math
import struct
import zlib


def quad(a, b, c, d):
    """Two triangles covering the quadrilateral a, b, c, d (in order around it)."""
    return [a, b, c, a, c, d]


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def normalize(v):
    n = math.sqrt(sum(x * x for x in v))
    return [x / n for x in v]


def facing(tris, outward):
    """The triangles, each wound so that its normal points along outward(centroid)."""
    fixed = []
    for i in range(0, len(tris), 3):
        a, b, c = tris[i : i + 3]
        n = cross([b[k] - a[k] for k in range(3)], [c[k] - a[k] for k in range(3)])
        centroid = [(a[k] + b[k] + c[k]) / 3 for k in range(3)]
        want = outward(centroid)
        fixed += [a, b, c] if sum(n[k] * want[k] for k in range(3)) > 0 else [a, c, b]
    return fixed


def box(lo, hi):
    """The six faces of an axis-aligned box, wound outwards."""
    x0, y0, z0 = lo
    x1, y1, z1 = hi
    c = [(x0 + x1) / 2, (y0 + y1) / 2, (z0 + z1) / 2]
    v = lambda i, j, k: ((x0, x1)[i], (y0, y1)[j], (z0, z1)[k])
    faces = [
        quad(v(0, 0, 0), v(0, 1, 0), v(0, 1, 1), v(0, 0, 1)),
        quad(v(1, 0, 0), v(1, 1, 0), v(1, 1, 1), v(1, 0, 1)),
        quad(v(0, 0, 0), v(1, 0, 0), v(1, 0, 1), v(0, 0, 1)),
        quad(v(0, 1, 0), v(1, 1, 0), v(1, 1, 1), v(0, 1, 1)),
        quad(v(0, 0, 0), v(1, 0, 0), v(1, 1, 0), v(0, 1, 0)),
        quad(v(0, 0, 1), v(1, 0, 1), v(1, 1, 1), v(0, 1, 1)),
    ]
    return facing(sum(faces, []), lambda p: [p[k] - c[k] for k in range(3)])


def sphere(centre, radius, rings=32, segments=64):
    """A UV sphere as (positions, normals, indices): smooth normals, wound outwards."""
    positions, normals = [], []
    for i in range(rings + 1):
        theta = math.pi * i / rings
        for j in range(segments + 1):
            phi = 2 * math.pi * j / segments
            n = (math.sin(theta) * math.cos(phi), math.cos(theta), -math.sin(theta) * math.sin(phi))
            positions.append(tuple(centre[k] + radius * n[k] for k in range(3)))
            normals.append(n)
    at = lambda i, j: i * (segments + 1) + j
    indices = []
    for i in range(rings):
        for j in range(segments):
            a, b, c, d = at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)
            # Rows at the poles collapse to a point: one triangle per cell there.
            if i != rings - 1:
                indices += [a, b, c]
            if i != 0:
                indices += [a, c, d]
    return positions, normals, indices


def uv_sphere(centre, radius, rings=48, segments=96):
    """`sphere` with texture coordinates: (positions, normals, uvs, indices), u around the
    axis, v from pole to pole (what MikkTSpace tangents need)."""
    positions, normals, indices = sphere(centre, radius, rings, segments)
    uvs = [(j / segments, i / rings) for i in range(rings + 1) for j in range(segments + 1)]
    return positions, normals, uvs, indices


def quaternion_mul(a, b):
    ax, ay, az, aw = a
    bx, by, bz, bw = b
    return (
        aw * bx + ax * bw + ay * bz - az * by,
        aw * by - ax * bz + ay * bw + az * bx,
        aw * bz + ax * by - ay * bx + az * bw,
        aw * bw - ax * bx - ay * by - az * bz,
    )


def looking_along(forward):
    """The rotation (x, y, z, w) that turns -z onto forward without roll (yaw, then pitch)."""
    f = normalize(forward)
    yaw = math.atan2(-f[0], -f[2])
    pitch = math.asin(max(-1.0, min(1.0, f[1])))
    qy = (0.0, math.sin(yaw / 2), 0.0, math.cos(yaw / 2))
    qx = (math.sin(pitch / 2), 0.0, 0.0, math.cos(pitch / 2))
    return quaternion_mul(qy, qx)


def png(width, height, texel):
    """An 8-bit RGB PNG of width x height whose texel (x, y) (y down) is texel(x, y)."""
    raw = b"".join(
        b"\x00" + bytes(c for x in range(width) for c in texel(x, y)) for y in range(height)
    )

    def chunk(kind, data):
        body = kind + data
        return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body))

    header = struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)
    return b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b"")


class Document:
    """A glTF 2.0 document under construction: meshes with one material each, nodes,
    punctual lights and cameras, written with its buffer embedded."""

    def __init__(self, generator):
        self.generator = generator
        self.blob = b""
        self.buffer_views, self.accessors, self.meshes, self.nodes = [], [], [], []
        self.materials, self.lights, self.cameras = [], [], []
        self.images, self.textures, self.samplers = [], [], []
        self.root_extension = {}
        self.extensions_used = ["KHR_lights_punctual", "PRISM_spectral"]

    def texture(self, png_bytes, wrap=10497):
        """A texture of an embedded PNG with one wrap mode for both axes (glTF's enums:
        10497 repeat, 33071 clamp, 33648 mirror); its index for material texture infos."""
        self.buffer_views.append({"buffer": 0, "byteOffset": len(self.blob), "byteLength": len(png_bytes)})
        self.blob += png_bytes
        # Keep later views aligned to 4 bytes (accessors of floats need it).
        self.blob += b"\x00" * (-len(self.blob) % 4)
        self.images.append({"bufferView": len(self.buffer_views) - 1, "mimeType": "image/png"})
        self.samplers.append({"wrapS": wrap, "wrapT": wrap})
        self.textures.append({"source": len(self.images) - 1, "sampler": len(self.samplers) - 1})
        return len(self.textures) - 1

    def material(self, name, **fields):
        self.materials.append({"name": name, **fields})
        return len(self.materials) - 1

    def _accessor(self, vectors):
        n = len(vectors[0])
        data = b"".join(struct.pack(f"<{n}f", *v) for v in vectors)
        self.buffer_views.append({"buffer": 0, "byteOffset": len(self.blob), "byteLength": len(data)})
        self.accessors.append(
            {
                "bufferView": len(self.buffer_views) - 1,
                "componentType": 5126,
                "count": len(vectors),
                "type": f"VEC{n}",
                "min": [min(v[i] for v in vectors) for i in range(n)],
                "max": [max(v[i] for v in vectors) for i in range(n)],
            }
        )
        self.blob += data
        return len(self.accessors) - 1

    def mesh(self, name, positions, material, normals=None, indices=None, uvs=None):
        attributes = {"POSITION": self._accessor(positions)}
        if normals is not None:
            attributes["NORMAL"] = self._accessor(normals)
        if uvs is not None:
            attributes["TEXCOORD_0"] = self._accessor(uvs)
        primitive = {"attributes": attributes, "material": material}
        if indices is not None:
            data = struct.pack(f"<{len(indices)}I", *indices)
            self.buffer_views.append({"buffer": 0, "byteOffset": len(self.blob), "byteLength": len(data)})
            self.accessors.append(
                {"bufferView": len(self.buffer_views) - 1, "componentType": 5125, "count": len(indices), "type": "SCALAR"}
            )
            self.blob += data
            primitive["indices"] = len(self.accessors) - 1
        self.meshes.append({"name": name, "primitives": [primitive]})
        self.nodes.append({"name": name, "mesh": len(self.meshes) - 1})

    def light(self, name, at, forward, light):
        self.lights.append({"name": name, **light})
        node = {"name": name, "translation": list(at)}
        if forward is not None:
            node["rotation"] = list(looking_along(forward))
        node["extensions"] = {"KHR_lights_punctual": {"light": len(self.lights) - 1}}
        self.nodes.append(node)

    def camera(self, name, eye, target, perspective):
        self.cameras.append({"type": "perspective", "perspective": perspective})
        forward = [target[i] - eye[i] for i in range(3)]
        self.nodes.append(
            {"name": name, "camera": len(self.cameras) - 1, "translation": list(eye), "rotation": list(looking_along(forward))}
        )

    def write(self, path):
        extensions = {}
        if self.lights:
            extensions["KHR_lights_punctual"] = {"lights": self.lights}
        if self.root_extension:
            extensions["PRISM_spectral"] = self.root_extension
        doc = {
            "asset": {"version": "2.0", "generator": self.generator},
            "extensionsUsed": self.extensions_used,
            "extensions": extensions,
            "scene": 0,
            "scenes": [{"nodes": list(range(len(self.nodes)))}],
            "nodes": self.nodes,
            "cameras": self.cameras,
            "meshes": self.meshes,
            "materials": self.materials,
            **({"images": self.images, "samplers": self.samplers, "textures": self.textures} if self.textures else {}),
            "accessors": self.accessors,
            "bufferViews": self.buffer_views,
            "buffers": [
                {
                    "byteLength": len(self.blob),
                    "uri": "data:application/octet-stream;base64," + base64.b64encode(self.blob).decode(),
                }
            ],
        }
        with open(path, "w") as f:
            json.dump(doc, f, indent=1)
            f.write("\n")
