"""Writes scenes/cornell-medium.gltf: the Cornell box whose large box is a block of milky,
tinted liquid without walls (an `interface` holding a medium), the volume scene that prism
and Mitsuba 3's `volpathmis` render alike (benches/peer/mitsuba_media.py builds the same
scene in Mitsuba from this file's medium, so the two cannot drift apart).

The medium is chromatic in both coefficients, as the mistakes the peers' trackers record
are about (a null-collision probability from one wavelength): scattering falls with
wavelength as (550 / lambda)^2 (fine droplets), absorption has a band at 600 nm (a
blue-green dye), and g = 0.5. At 550 nm sigma_t is about 3.4 per unit: the box (0.6 wide,
1.2 tall in the box's units) is two to seven mean free paths across, so light scatters
many times inside it.

Run from the repository root: python3 scenes/tools/make_cornell_medium.py
"""

import json
import math
import os

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
NODES = list(range(360, 831, 10))


def sigma_s(nm):
    return 3.0 * (550.0 / nm) ** 2


def sigma_a(nm):
    return 0.2 + 1.5 * math.exp(-(((nm - 600.0) / 40.0) ** 2))


def table(f):
    return [[nm, round(f(nm), 6)] for nm in NODES]


MEDIUM = {"sigma_a": table(sigma_a), "sigma_s": table(sigma_s), "g": 0.5}


def main():
    with open(os.path.join(ROOT, "scenes", "cornell-box.gltf")) as f:
        doc = json.load(f)
    doc["materials"].append(
        {"name": "milky-dye", "extensions": {"PRISM_spectral": {"type": "interface", "medium": MEDIUM}}}
    )
    index = len(doc["materials"]) - 1
    for mesh in doc["meshes"]:
        if mesh["name"] == "large-box":
            for primitive in mesh["primitives"]:
                primitive["material"] = index
    used = doc.setdefault("extensionsUsed", [])
    if "PRISM_spectral" not in used:
        used.append("PRISM_spectral")
    doc.setdefault("asset", {})["generator"] = "scenes/tools/make_cornell_medium.py"
    with open(os.path.join(ROOT, "scenes", "cornell-medium.gltf"), "w") as f:
        json.dump(doc, f, indent=1)
        f.write("\n")


if __name__ == "__main__":
    main()
