#!/usr/bin/env python3
"""Writes the Mitsuba scenes that check prism's reading of Mitsuba's shapes against
Mitsuba's own renders, and the small meshes they use:

  scenes/mitsuba/shapes-analytic.xml   sphere, disk (an emitter facing down by
      flip_normals), cylinder, cube and rectangle (an emitter facing down because its
      to_world mirrors z), and a shapegroup of a sphere and a cylinder placed by three
      instances, one of them mirroring
  scenes/mitsuba/shapes-meshes.xml     an OBJ torus of quads without normals (Mitsuba
      computes them; its texture coordinates flipped), a binary PLY icosphere shown by its
      vertex colours and, mirrored (so that Mitsuba's computed normals turn in), by its
      face colours (the mesh_attribute texture), and
      a serialized hemisphere with its own normals and texture coordinates, once smooth
      and once with face_normals
  scenes/mitsuba/meshes/torus.obj, icosphere.ply, hemisphere.serialized

Every surface is a twosided diffuse, so that the images do not depend on which side of a
surface Mitsuba's one-sided diffuse BSDF would leave black; which side a shape faces shows
in the emitters, which emit from their front only. Each file is loaded by pip Mitsuba
before it is kept. The references are Mitsuba's renders of these files:

  /tmp/venv/bin/python scenes/tools/make_mitsuba_shapes.py
  /tmp/venv/bin/python scenes/tools/make_mitsuba_ztest_refs.py \\
      scenes/mitsuba/shapes-analytic.xml scenes/mitsuba/shapes-meshes.xml
"""

import math
import os
import struct
import zlib

import mitsuba as mi

mi.set_variant("scalar_spectral")

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
OUT = os.path.join(ROOT, "scenes", "mitsuba")
MESHES = os.path.join(OUT, "meshes")


def torus_obj(major=1.0, minor=0.4, around=24, tube=12):
    """A torus of quads in the z = 0 plane, texture coordinates on a grid with seam
    vertices, no normals."""
    lines = ["# A torus of quads without normals, written by scenes/tools/make_mitsuba_shapes.py"]
    for i in range(around + 1):
        for j in range(tube + 1):
            u, v = 2 * math.pi * i / around, 2 * math.pi * j / tube
            r = major + minor * math.cos(v)
            lines.append(f"v {r * math.cos(u):.6f} {r * math.sin(u):.6f} {minor * math.sin(v):.6f}")
            lines.append(f"vt {i / around:.6f} {j / tube:.6f}")
    for i in range(around):
        for j in range(tube):
            a = i * (tube + 1) + j + 1
            b = a + tube + 1
            lines.append(f"f {a}/{a} {b}/{b} {b + 1}/{b + 1} {a + 1}/{a + 1}")
    return "\n".join(lines) + "\n"


def icosphere():
    """An icosahedron subdivided once onto the unit sphere: 42 vertices, 80 faces."""
    t = (1 + 5 ** 0.5) / 2
    verts = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t),
             (0, -1, -t), (0, 1, -t), (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    verts = [tuple(c / math.sqrt(sum(x * x for x in v)) for c in v) for v in verts]
    faces = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4),
             (11, 10, 2), (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8),
             (3, 8, 9), (4, 9, 5), (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    middle = {}

    def mid(a, b):
        key = (min(a, b), max(a, b))
        if key not in middle:
            m = [(p + q) / 2 for p, q in zip(verts[a], verts[b])]
            n = math.sqrt(sum(x * x for x in m))
            verts.append(tuple(x / n for x in m))
            middle[key] = len(verts) - 1
        return middle[key]

    out = []
    for a, b, c in faces:
        ab, bc, ca = mid(a, b), mid(b, c), mid(c, a)
        out += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
    return verts, out


def icosphere_ply():
    """Binary little-endian PLY with vertex colours (color_0..2) and face colours, which
    Mitsuba names vertex_color and face_color."""
    verts, faces = icosphere()
    header = (
        "ply\nformat binary_little_endian 1.0\n"
        "comment written by scenes/tools/make_mitsuba_shapes.py\n"
        f"element vertex {len(verts)}\nproperty float x\nproperty float y\nproperty float z\n"
        "property float color_0\nproperty float color_1\nproperty float color_2\n"
        f"element face {len(faces)}\nproperty list uchar int vertex_indices\n"
        "property float color_0\nproperty float color_1\nproperty float color_2\n"
        "end_header\n"
    ).encode()
    body = b""
    for x, y, z in verts:
        # A colour that varies smoothly over the sphere, each channel in [0.05, 0.95].
        colour = (0.5 + 0.45 * x, 0.5 + 0.45 * y, 0.5 + 0.45 * z)
        body += struct.pack("<6f", x, y, z, *colour)
    for k, f in enumerate(faces):
        colour = ((k * 37 % 80) / 80 * 0.9 + 0.05, (k * 11 % 80) / 80 * 0.9 + 0.05, 0.3)
        body += struct.pack("<B3i3f", 3, *f, *colour)
    return header + body


def hemisphere_serialized(around=16, rings=6):
    """Mitsuba's serialized format, version 4, single precision: the upper half of the unit
    sphere with its normals and (phi, theta) texture coordinates."""
    positions, normals, uvs, tris = [], [], [], []
    for i in range(rings + 1):
        theta = 0.5 * math.pi * i / rings
        for j in range(around + 1):
            phi = 2 * math.pi * j / around
            p = (math.sin(theta) * math.cos(phi), math.sin(theta) * math.sin(phi), math.cos(theta))
            positions += p
            normals += p
            uvs += (j / around, i / rings)
    for i in range(rings):
        for j in range(around):
            a = i * (around + 1) + j
            b = a + around + 1
            tris += (a, b, b + 1, a, b + 1, a + 1)
    n = len(positions) // 3
    plain = struct.pack("<I", 0x0001 | 0x0002 | 0x1000) + b"hemisphere\0"
    plain += struct.pack("<QQ", n, len(tris) // 3)
    plain += struct.pack(f"<{len(positions)}f", *positions)
    plain += struct.pack(f"<{len(normals)}f", *normals)
    plain += struct.pack(f"<{len(uvs)}f", *uvs)
    plain += struct.pack(f"<{len(tris)}I", *tris)
    return struct.pack("<HH", 0x041C, 4) + zlib.compress(plain) + struct.pack("<QI", 0, 1)


HEAD = """<!-- {what}, written by scenes/tools/make_mitsuba_shapes.py -->
<scene version="3.0.0">
    <integrator type="path">
        <integer name="max_depth" value="3"/>
    </integrator>
    <sensor type="perspective">
        <float name="fov" value="{fov}"/>
        <transform name="to_world">
            <lookat origin="{origin}" target="{target}" up="0, 0, 1"/>
        </transform>
        <sampler type="independent">
            <integer name="sample_count" value="64"/>
        </sampler>
        <film type="hdrfilm">
            <integer name="width" value="32"/>
            <integer name="height" value="32"/>
            <rfilter type="box"/>
        </film>
    </sensor>
    <emitter type="constant">
        <rgb name="radiance" value="0.3"/>
    </emitter>
"""


def bsdf(rgb, id=None):
    ident = f' id="{id}"' if id else ""
    return (f'<bsdf type="twosided"{ident}><bsdf type="diffuse">'
            f'<rgb name="reflectance" value="{rgb}"/></bsdf></bsdf>')


ANALYTIC = HEAD.format(what="Mitsuba's analytic shapes and instances", fov=45,
                       origin="0, -6, 2.5", target="0, 0, 0.4") + f"""
    {bsdf("0.6, 0.6, 0.6", "grey")}
    <shape type="rectangle">
        <transform name="to_world"><scale value="4"/></transform>
        <ref id="grey"/>
    </shape>
    <!-- A light facing down only because its normals are flipped. -->
    <shape type="disk">
        <boolean name="flip_normals" value="true"/>
        <transform name="to_world"><scale value="1.2"/><translate z="3.5"/></transform>
        <emitter type="area"><rgb name="radiance" value="6"/></emitter>
    </shape>
    <!-- A light facing down only because its to_world mirrors z. -->
    <shape type="rectangle">
        <transform name="to_world"><scale x="0.4" y="0.4" z="-1"/><translate x="1.5" y="1" z="3"/></transform>
        <emitter type="area"><rgb name="radiance" value="10, 6, 3"/></emitter>
    </shape>
    <shape type="sphere">
        <point name="center" x="-1.4" y="0" z="0.6"/>
        <float name="radius" value="0.6"/>
        {bsdf("0.8, 0.25, 0.2")}
    </shape>
    <shape type="cylinder">
        <point name="p0" x="0" y="0.5" z="0"/>
        <point name="p1" x="0.3" y="0.8" z="1.4"/>
        <float name="radius" value="0.35"/>
        {bsdf("0.2, 0.7, 0.3")}
    </shape>
    <shape type="cube">
        <transform name="to_world">
            <scale value="0.35"/><rotate z="1" angle="30"/><translate x="1.4" y="-0.6" z="0.35"/>
        </transform>
        {bsdf("0.2, 0.3, 0.8")}
    </shape>
    <shape type="disk">
        <transform name="to_world">
            <scale value="0.5"/><rotate x="1" angle="70"/><translate x="0.2" y="-1.2" z="0.6"/>
        </transform>
        {bsdf("0.9, 0.8, 0.2")}
    </shape>
    <shape type="shapegroup" id="pair">
        <shape type="sphere">
            <float name="radius" value="0.25"/>
            <transform name="to_world"><translate z="0.25"/></transform>
            {bsdf("0.7, 0.4, 0.8")}
        </shape>
        <shape type="cylinder">
            <float name="radius" value="0.1"/>
            <transform name="to_world"><translate x="0.35"/></transform>
            {bsdf("0.3, 0.7, 0.8")}
        </shape>
    </shape>
    <shape type="instance">
        <ref id="pair"/>
        <transform name="to_world"><translate x="0.9" y="1.2"/></transform>
    </shape>
    <shape type="instance">
        <ref id="pair"/>
        <transform name="to_world"><rotate z="1" angle="90"/><scale value="1.5"/><translate x="-0.4" y="-1.8"/></transform>
    </shape>
    <shape type="instance">
        <ref id="pair"/>
        <transform name="to_world"><scale x="-1"/><translate x="2.2" y="0.8"/></transform>
    </shape>
</scene>
"""

MESHES_SCENE = HEAD.format(what="Mitsuba's mesh files: OBJ, PLY with mesh attributes, serialized",
                           fov=45, origin="0, -6, 3", target="0, 0, 0.5") + f"""
    {bsdf("0.6, 0.6, 0.6", "grey")}
    <shape type="rectangle">
        <transform name="to_world"><scale value="4"/></transform>
        <ref id="grey"/>
    </shape>
    <shape type="rectangle">
        <boolean name="flip_normals" value="true"/>
        <transform name="to_world"><scale value="0.8"/><translate z="3.5"/></transform>
        <emitter type="area"><rgb name="radiance" value="8"/></emitter>
    </shape>
    <shape type="obj">
        <string name="filename" value="meshes/torus.obj"/>
        <transform name="to_world">
            <scale value="0.7"/><rotate x="1" angle="60"/><translate x="0" y="0.6" z="0.9"/>
        </transform>
        {bsdf("0.85, 0.5, 0.2")}
    </shape>
    <shape type="ply">
        <string name="filename" value="meshes/icosphere.ply"/>
        <transform name="to_world"><scale value="0.55"/><translate x="-1.5" y="-0.3" z="0.55"/></transform>
        <bsdf type="twosided">
            <bsdf type="diffuse">
                <texture type="mesh_attribute" name="reflectance">
                    <string name="name" value="vertex_color"/>
                </texture>
            </bsdf>
        </bsdf>
    </shape>
    <shape type="ply">
        <string name="filename" value="meshes/icosphere.ply"/>
        <transform name="to_world"><scale x="-0.55" y="0.55" z="0.55"/><translate x="1.5" y="-0.3" z="0.55"/></transform>
        <bsdf type="twosided">
            <bsdf type="diffuse">
                <texture type="mesh_attribute" name="reflectance">
                    <string name="name" value="face_color"/>
                    <float name="scale" value="0.9"/>
                </texture>
            </bsdf>
        </bsdf>
    </shape>
    <shape type="serialized">
        <string name="filename" value="meshes/hemisphere.serialized"/>
        <transform name="to_world"><scale value="0.5"/><translate x="-0.5" y="-1.4"/></transform>
        {bsdf("0.3, 0.6, 0.8")}
    </shape>
    <shape type="serialized">
        <string name="filename" value="meshes/hemisphere.serialized"/>
        <boolean name="face_normals" value="true"/>
        <transform name="to_world"><scale value="0.5"/><translate x="0.6" y="-1.4"/></transform>
        {bsdf("0.8, 0.7, 0.3")}
    </shape>
</scene>
"""


def main():
    os.makedirs(MESHES, exist_ok=True)
    files = {
        "torus.obj": torus_obj().encode(),
        "icosphere.ply": icosphere_ply(),
        "hemisphere.serialized": hemisphere_serialized(),
    }
    for name, data in files.items():
        with open(os.path.join(MESHES, name), "wb") as f:
            f.write(data)
    for name, text in (("shapes-analytic.xml", ANALYTIC), ("shapes-meshes.xml", MESHES_SCENE)):
        path = os.path.join(OUT, name)
        with open(path, "w") as f:
            f.write(text)
        scene = mi.load_file(path)
        faces = sum(s.face_count() for s in scene.shapes() if hasattr(s, "face_count"))
        print(f"wrote {path}: {len(scene.shapes())} shapes, {faces} mesh triangles")


if __name__ == "__main__":
    main()
