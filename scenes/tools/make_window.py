"""Writes scenes/window.gltf: a shop window on a sunny street, seen at Brewster's angle,
where the reflection of the street in the glass is polarized: what a polarizing filter
on a camera removes (docs/guide/polarization.md, "Polarization").

- The window: a pane of smooth glass (index 1.52, 1 cm thick) in the plane z = 0, the
  shop behind it (z < 0): a dim room lit by a warm lamp, with a display of coloured
  objects.
- The street in front (z > 0): a sunlit facade of red and white stripes on the camera's
  right, which the window reflects, a grey pavement, and the sky.
- The camera looks at the pane from 56.7 degrees off its normal (Brewster's angle for
  index 1.52, atan 1.52): light the glass reflects towards it is polarized across the
  plane of incidence, that is vertically, so a filter with a horizontal axis
  (`--camera-polarizer 0`) takes the reflection away and shows the display; with a
  vertical axis (`--camera-polarizer 90`) it keeps the reflection and dims the shop.

Units are metres; y is up. Run from the repository root:
python3 scenes/tools/make_window.py
"""

import math

from gltf_build import Document, box, facing, quad, sphere

IOR = 1.52
BREWSTER = math.atan(IOR)
EYE_HEIGHT = 1.1
TARGET = (0.0, 1.1, 0.0)
DISTANCE = 4.0


def diffuse(doc, name, rgb):
    return doc.material(name, pbrMetallicRoughness={"baseColorFactor": [*rgb, 1.0], "metallicFactor": 0.0, "roughnessFactor": 1.0})


def emitter(doc, name, spectrum, scale):
    return doc.material(
        name,
        extensions={"PRISM_spectral": {"type": "diffuse", "reflectance": 0.0, "emission": {"spectrum": spectrum, "scale": scale}}},
    )


def main():
    doc = Document("scenes/tools/make_window.py")
    glass = doc.material("window glass", extensions={"PRISM_spectral": {"type": "dielectric", "ior": IOR}})
    doc.mesh("window", box((-2.5, 0.0, -0.01), (2.5, 2.6, 0.0)), glass)
    # The shop: a room behind the window, its front wall the window's frame.
    shop = diffuse(doc, "shop walls", (0.55, 0.5, 0.45))
    room = box((-2.5, 0.0, -3.0), (2.5, 2.6, -0.011))
    # Walls facing into the room, without the face the window takes.
    inner = facing(room, lambda p: [-(p[0]), -(p[1] - 1.3), -(p[2] + 1.5)])
    inner = [t for i in range(0, len(inner), 3) for t in inner[i : i + 3] if not all(v[2] > -0.02 for v in inner[i : i + 3])]
    doc.mesh("shop room", inner, shop)
    frame = diffuse(doc, "facade", (0.35, 0.33, 0.3))
    doc.mesh(
        "shop facade",
        quad((-8.0, 2.6, 0.0), (8.0, 2.6, 0.0), (8.0, 5.0, 0.0), (-8.0, 5.0, 0.0))
        + quad((-8.0, 0.0, 0.0), (-2.5, 0.0, 0.0), (-2.5, 2.6, 0.0), (-8.0, 2.6, 0.0))
        + quad((2.5, 0.0, 0.0), (8.0, 0.0, 0.0), (8.0, 2.6, 0.0), (2.5, 2.6, 0.0)),
        frame,
    )
    lamp = emitter(doc, "shop lamp", "blackbody:3000", 0.08)
    doc.mesh("shop lamp", facing(quad((-1.5, 2.55, -2.2), (1.5, 2.55, -2.2), (1.5, 2.55, -0.8), (-1.5, 2.55, -0.8)), lambda p: [0, -1, 0]), lamp)
    # The display.
    positions, normals, indices = sphere((-0.9, 0.55, -1.2), 0.45)
    doc.mesh("display ball", positions, diffuse(doc, "blue", (0.05, 0.15, 0.7)), normals=normals, indices=indices)
    doc.mesh("display box", box((0.1, 0.0, -1.8), (0.9, 0.9, -1.0)), diffuse(doc, "yellow", (0.8, 0.6, 0.05)))
    positions, normals, indices = sphere((1.5, 0.35, -0.8), 0.35)
    doc.mesh("display apple", positions, diffuse(doc, "green", (0.1, 0.5, 0.08)), normals=normals, indices=indices)
    # The street: pavement, and the facade across the way that the window reflects.
    doc.mesh("pavement", facing(quad((-20.0, 0.0, 0.0), (20.0, 0.0, 0.0), (20.0, 0.0, 20.0), (-20.0, 0.0, 20.0)), lambda p: [0, 1, 0]), diffuse(doc, "pavement", (0.3, 0.3, 0.3)))
    red, white = diffuse(doc, "red stripe", (0.75, 0.05, 0.04)), diffuse(doc, "white stripe", (0.85, 0.85, 0.82))
    stripes = {red: [], white: []}
    for k in range(16):
        z0, z1 = 0.5 + 0.6 * k, 0.5 + 0.6 * (k + 1)
        stripes[red if k % 2 == 0 else white] += facing(quad((6.0, 0.0, z0), (6.0, 0.0, z1), (6.0, 6.0, z1), (6.0, 6.0, z0)), lambda p: [-1, 0, 0])
    for material, tris in stripes.items():
        doc.mesh("street facade", tris, material)
    # The sun, high behind the camera's left shoulder, lights the facade; the sky the rest.
    doc.light(
        "sun",
        (0.0, 20.0, 10.0),
        (0.6, -0.7, -0.35),
        {"type": "directional", "intensity": 0.0015, "extensions": {"PRISM_spectral": {"spectrum": "daylight:5500", "units": "radiometric"}}},
    )
    doc.root_extension["environment"] = {"spectrum": "daylight:6500", "scale": 0.0001}
    eye = (TARGET[0] - DISTANCE * math.sin(BREWSTER), EYE_HEIGHT, TARGET[2] + DISTANCE * math.cos(BREWSTER))
    doc.camera("camera", eye, TARGET, {"yfov": 0.7, "aspectRatio": 1.5, "znear": 0.01})
    doc.write("scenes/window.gltf")


if __name__ == "__main__":
    main()
