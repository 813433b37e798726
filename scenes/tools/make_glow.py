"""Writes scenes/glow.gltf: glow-in-the-dark objects in a room whose lamp switches off,
for `prism render --at SECONDS` (docs/guide/time.md, "Phosphorescence").

- A small grey room lit by a daylight ceiling panel that is on from 0 s to 10 s.
- On the floor, a sphere and a star-shaped block painted with a strontium-aluminate-like
  phosphor (absorbs violet and blue, glows green at 520 nm, quantum yield 0.9; a fast and
  a slow decay, 2 s and 30 s, weighted 0.6 and 0.4), beside a white sphere that is only
  paint.

At 5 s the room is lit and the phosphor is charging (1 - exp(-t / tau) per component);
after 10 s the room is dark but for the phosphor's glow, which fades by the weighted sum
of its two exponentials.

Units are metres; y is up. Run from the repository root: python3 scenes/tools/make_glow.py
"""

import math

from gltf_build import Document, box, facing, quad, sphere

LAMP_ON = [[0.0, 10.0]]


def main():
    doc = Document("scenes/tools/make_glow.py")
    walls = doc.material(
        "walls", pbrMetallicRoughness={"baseColorFactor": [0.55, 0.55, 0.55, 1.0], "metallicFactor": 0.0, "roughnessFactor": 1.0}
    )
    room = box((-2.0, 0.0, -2.0), (2.0, 2.5, 2.0))
    doc.mesh("room", facing(room, lambda p: [-p[0], -(p[1] - 1.25), -p[2]]), walls)
    lamp = doc.material(
        "ceiling lamp",
        extensions={
            "PRISM_spectral": {
                "type": "diffuse",
                "reflectance": 0.0,
                "emission": {"spectrum": "daylight:6500", "scale": 0.001},
                "on": LAMP_ON,
            }
        },
    )
    doc.mesh("ceiling lamp", facing(quad((-0.8, 2.49, -0.8), (0.8, 2.49, -0.8), (0.8, 2.49, 0.8), (-0.8, 2.49, 0.8)), lambda p: [0, -1, 0]), lamp)
    phosphor = doc.material(
        "glow paint",
        extensions={
            "PRISM_spectral": {
                "type": "fluorescent",
                "reflectance": {"rgb": [0.2, 0.25, 0.15]},
                "absorption": {"spectrum": "gaussian:400:70", "scale": 0.7},
                "reemission": "gaussian:520:40",
                "quantum_yield": 0.9,
                "lifetimes": [[2.0, 0.6], [30.0, 0.4]],
            }
        },
    )
    positions, normals, indices = sphere((-0.7, 0.45, 0.0), 0.45, rings=48, segments=96)
    doc.mesh("glowing ball", positions, phosphor, normals=normals, indices=indices)
    # A five-pointed star block.
    star = []
    points = [
        (0.6 + (0.45 if k % 2 == 0 else 0.2) * math.sin(math.pi * k / 5), 0.55 + (0.45 if k % 2 == 0 else 0.2) * math.cos(math.pi * k / 5))
        for k in range(10)
    ]
    centre = (0.6, 0.55)
    z0, z1 = -0.6, -0.4
    for k in range(10):
        (x0, y0), (x1, y1) = points[k], points[(k + 1) % 10]
        star += [(centre[0], centre[1], z1), (x0, y0, z1), (x1, y1, z1)]
        star += [(centre[0], centre[1], z0), (x1, y1, z0), (x0, y0, z0)]
        star += quad((x0, y0, z0), (x1, y1, z0), (x1, y1, z1), (x0, y0, z1))
    star = [(x, y - 0.1 + 0.0, z) for (x, y, z) in star]
    doc.mesh("glowing star", facing(star, lambda p: [p[0] - centre[0], p[1] - centre[1] + 0.1, p[2] + 0.5]), phosphor)
    white = doc.material(
        "white paint", pbrMetallicRoughness={"baseColorFactor": [0.8, 0.8, 0.8, 1.0], "metallicFactor": 0.0, "roughnessFactor": 0.6}
    )
    positions, normals, indices = sphere((1.2, 0.3, 0.6), 0.3, rings=32, segments=64)
    doc.mesh("white ball", positions, white, normals=normals, indices=indices)
    doc.camera("camera", (0.0, 1.4, 1.95), (0.15, 0.45, -0.2), {"yfov": 0.95, "aspectRatio": 1.5, "znear": 0.01})
    doc.write("scenes/glow.gltf")


if __name__ == "__main__":
    main()
