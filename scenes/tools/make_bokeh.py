"""Writes scenes/bokeh.gltf: depth of field through a thin lens with a six-bladed
aperture (docs/guide/cameras.md, "Depth of field").

- A gold sphere and a glass sphere on a dark floor, 2.5 m from the camera, in focus.
- Behind them, 6 to 15 m away, and one in front, 1.2 m away, small lamps: warm 2700 K
  bulbs and a few narrow-band LEDs (red, green, blue). Out of focus, each spreads into
  a hexagon, the shape of the aperture, in its own colour.
- A soft panel above lights the spheres.

The camera is an 85 mm lens on full frame (a 16.1-degree vertical view at 3:2) at f/1.4,
six blades, focused at 2.5 m. Units are metres; y is up. Run from the repository root:
python3 scenes/tools/make_bokeh.py
"""

import math

from gltf_build import Document, facing, quad, sphere


def lamp_material(doc, name, emission):
    return doc.material(
        name,
        extensions={"PRISM_spectral": {"type": "diffuse", "reflectance": 0.0, "emission": emission}},
    )


def main():
    doc = Document("scenes/tools/make_bokeh.py")
    floor = doc.material(
        "floor", pbrMetallicRoughness={"baseColorFactor": [0.1, 0.1, 0.11, 1.0], "metallicFactor": 0.0, "roughnessFactor": 0.9}
    )
    doc.mesh("floor", facing(quad((-20, 0, -40), (20, 0, -40), (20, 0, 10), (-20, 0, 10)), lambda p: [0, 1, 0]), floor)
    gold = doc.material("gold", extensions={"PRISM_spectral": {"type": "conductor", "metal": "au"}})
    glass = doc.material("glass", extensions={"PRISM_spectral": {"type": "dielectric", "ior": "glass:bk7"}})
    for name, centre, radius, material in [
        ("gold sphere", (-0.14, 0.12, -2.5), 0.12, gold),
        ("glass sphere", (0.14, 0.12, -2.45), 0.12, glass),
    ]:
        positions, normals, indices = sphere(centre, radius, rings=48, segments=96)
        doc.mesh(name, positions, material, normals=normals, indices=indices)
    panel = lamp_material(doc, "panel", {"spectrum": "daylight:5000", "scale": 0.004})
    doc.mesh("panel", facing(quad((-0.5, 1.6, -3.0), (0.5, 1.6, -3.0), (0.5, 1.6, -2.0), (-0.5, 1.6, -2.0)), lambda p: [0, -1, 0]), panel)
    warm = lamp_material(doc, "warm bulb", {"spectrum": "blackbody:2700", "scale": 0.6})
    leds = [
        lamp_material(doc, "red LED", {"spectrum": "gaussian:630:12", "scale": 8.0}),
        lamp_material(doc, "green LED", {"spectrum": "gaussian:525:15", "scale": 5.0}),
        lamp_material(doc, "blue LED", {"spectrum": "gaussian:460:12", "scale": 8.0}),
    ]
    # A string of lamps receding behind the spheres, and a few scattered.
    lamps = []
    for k in range(12):
        t = k / 11
        lamps.append(((-1.5 + 3.2 * t, 0.45 + 0.35 * math.sin(5.0 * t), -6.0 - 9.0 * t), 0.025))
    lamps += [((-0.8, 0.25, -7.0), 0.025), ((0.9, 0.8, -9.0), 0.03), ((0.1, 1.1, -13.0), 0.035), ((-0.12, 0.08, -1.2), 0.005)]
    for i, (centre, radius) in enumerate(lamps):
        material = leds[i % 3] if i % 4 == 1 else warm
        positions, normals, indices = sphere(centre, radius, rings=12, segments=24)
        doc.mesh(f"lamp {i}", positions, material, normals=normals, indices=indices)
    yfov = 2 * math.atan(12.0 / 85.0)  # 24 mm sensor height behind an 85 mm lens
    doc.camera("camera", (0.0, 0.2, 0.0), (0.0, 0.16, -2.5), {"yfov": yfov, "aspectRatio": 1.5, "znear": 0.01})
    doc.cameras[-1]["extensions"] = {
        "PRISM_spectral": {"aperture": {"f_number": 1.4, "blades": 6, "rotation": 0}, "focus_distance": 2.5}
    }
    doc.write("scenes/bokeh.gltf")


if __name__ == "__main__":
    main()
