"""Writes scenes/media.gltf: what only participating media can show, per wavelength
(docs/guide/media.md, "Participating media").

- Left, a column of dilute milk (an `interface` cylinder: a glass wall would bend the
  beam into a caustic, which only light paths find, and they stay off in scenes with
  media) whose fine droplets scatter as Rayleigh's law says, sigma_s ~ lambda^-4 (16 per metre at 400 nm, 1.7 at
  700 nm), lit from the left by a white (5500 K) spotlight. Blue is scattered out of the
  beam's sides, so the column glows blue; what passes straight through has lost its blue,
  and lights a white card behind it orange: a sunset in a glass.
- Middle, a column of water with a fluorescent dye (absorbing around 370 nm, re-emitting
  green at 520 nm, quantum yield 0.9) under an ultraviolet lamp (365 nm) that the eye
  cannot see: the dye glows green, brightest near the top where the UV enters.
- Right, a hot plume: the repository's smoke grid (scenes/smoke.vol, from
  make_smoke.py) as both density and temperature (2160 K where densest), absorbing and
  scattering a little; where it absorbs it glows as a black body at its temperature
  (Kirchhoff), so the dense core burns yellow-white and the thin edges dull red, with no
  light source at all.
- A dim grey floor and back wall, a faint daylight environment.

Units are metres; y is up. Run from the repository root (after make_smoke.py):
python3 scenes/tools/make_media.py
"""

import math

from gltf_build import Document, box, facing, quad

NODES = list(range(360, 841, 20))


def cylinder(centre, radius, height, segments=96):
    """A closed cylinder on the floor at centre (x, z), wound outwards."""
    cx, cz = centre
    tris = []
    for i in range(segments):
        a0, a1 = 2 * math.pi * i / segments, 2 * math.pi * (i + 1) / segments
        p0 = (cx + radius * math.cos(a0), cz + radius * math.sin(a0))
        p1 = (cx + radius * math.cos(a1), cz + radius * math.sin(a1))
        tris += quad((p0[0], 0.0, p0[1]), (p1[0], 0.0, p1[1]), (p1[0], height, p1[1]), (p0[0], height, p0[1]))
        tris += [(cx, height, cz), (p0[0], height, p0[1]), (p1[0], height, p1[1])]
        tris += [(cx, 0.0, cz), (p1[0], 0.0, p1[1]), (p0[0], 0.0, p0[1])]
    mid = height / 2
    return facing(tris, lambda p: [p[0] - cx, 0.0 if 0.001 < p[1] < height - 0.001 else p[1] - mid, p[2] - cz])


def diffuse(doc, name, value):
    return doc.material(name, extensions={"PRISM_spectral": {"type": "diffuse", "reflectance": value}})


def main():
    doc = Document("scenes/tools/make_media.py")
    doc.mesh("floor", facing(quad((-4, 0, -3), (4, 0, -3), (4, 0, 3), (-4, 0, 3)), lambda p: [0, 1, 0]), diffuse(doc, "floor", 0.15))
    doc.mesh("back wall", facing(quad((-4, 0, -1.2), (4, 0, -1.2), (4, 3, -1.2), (-4, 3, -1.2)), lambda p: [0, 0, 1]), diffuse(doc, "wall", 0.12))
    card = diffuse(doc, "white card", 0.85)
    # Across the beam, turned half towards the camera so that it shows its lit face.
    doc.mesh("card", facing(quad((-0.55, 0.0, -0.75), (-0.25, 0.0, -0.05), (-0.25, 0.8, -0.05), (-0.55, 0.8, -0.75)), lambda p: [-1, 0, 0.5]), card)
    milk = doc.material(
        "dilute milk",
        extensions={"PRISM_spectral": {"type": "interface", "medium": {
            "phase": "rayleigh",
            "sigma_a": 0.02,
            "sigma_s": [[nm, round(16.0 * (400.0 / nm) ** 4, 4)] for nm in NODES],
        }}},
    )
    doc.mesh("glass of milk", cylinder((-1.05, -0.35), 0.2, 0.7), milk)
    dye = doc.material(
        "fluorescent dye",
        extensions={"PRISM_spectral": {"type": "interface", "medium": {
            "sigma_s": 0.3,
            "fluorescence": {"absorption": {"spectrum": "gaussian:370:50", "scale": 12.0},
                             "reemission": "gaussian:520:35", "quantum_yield": 0.9},
        }}},
    )
    doc.mesh("dye column", cylinder((0.2, -0.35), 0.2, 0.7), dye)
    doc.light(
        "ultraviolet lamp",
        (0.2, 1.6, -0.35),
        (0.0, -1.0, 0.0),
        {"type": "spot", "intensity": 4.0, "spot": {"innerConeAngle": 0.15, "outerConeAngle": 0.2},
         "extensions": {"PRISM_spectral": {"spectrum": "gaussian:365:12", "units": "radiometric"}}},
    )
    plume = doc.material(
        "hot plume",
        extensions={"PRISM_spectral": {"type": "interface", "medium": {
            "sigma_a": 6.0,
            "sigma_s": 3.0,
            "g": 0.4,
            "density": {"file": "smoke.vol", "bounds": [[0.7, 0.0, -1.0], [1.9, 1.5, 0.2]]},
            "temperature": {"file": "smoke.vol", "scale": 3600.0, "bounds": [[0.7, 0.0, -1.0], [1.9, 1.5, 0.2]]},
        }}},
    )
    doc.mesh("plume box", box((0.69, 0.001, -1.01), (1.91, 1.51, 0.21)), plume)
    # The beam: a spot light from the left, level with the glass, aimed through it at the card.
    doc.light(
        "beam",
        (-2.6, 0.4, -0.35),
        (1.0, 0.0, 0.0),
        {"type": "spot", "intensity": 10.0, "spot": {"innerConeAngle": 0.1, "outerConeAngle": 0.13},
         "extensions": {"PRISM_spectral": {"spectrum": "blackbody:5500", "units": "radiometric"}}},
    )
    doc.root_extension["environment"] = {"spectrum": "daylight:6500", "scale": 0.00002}
    doc.camera("camera", (0.3, 1.0, 3.4), (0.3, 0.45, -0.35), {"yfov": 0.55, "aspectRatio": 1.6, "znear": 0.01})
    doc.write("scenes/media.gltf")


if __name__ == "__main__":
    main()
