"""Writes scenes/rainbow.gltf: Descartes' experiment, a drop of water lit through a hole in
a screen casts the primary and secondary rainbows back onto the screen as rings.

A narrow spot light (a 5800 K blackbody, sunlight's colour temperature) 6 units behind the
screen shines through a small square hole onto a water sphere (`glass:water`, Sellmeier)
2 units in front of it. Rays that refract into the drop, reflect once inside and refract
out leave at about 138 degrees from the beam, so they meet the screen on a ring 42 degrees
from the beam's axis as seen from the drop: radius 2 tan(42) = 1.8 units, red outside
(42.4 degrees at 700 nm), violet inside (40.6 degrees at 400 nm). Two internal reflections
give the fainter secondary bow at about 51 degrees (radius 2.5), its colours reversed,
with Alexander's dark band between the two.

The drop subtends 0.5 degrees from the light (like the sun from the earth), which blurs
each wavelength's ring by about that much: less than the bow's 1.8 degree spread of
colour. The drop is a smooth-shaded UV sphere of 96 x 192 cells. Its facets still show as
faint concentric rings in the bright disk inside the bow: the interpolated normals are
continuous but their derivative is not, and a caustic's brightness follows that
derivative. 160 x 320 cells made them no fainter to the eye and the file three times
larger.

The light reaches the screen only through specular (delta) bounces in the drop, so the
rings are rendered by prism's light paths (light -> delta surfaces -> diffuse -> camera).

Run from the repository root: python3 scenes/tools/make_rainbow.py
"""

import math

from gltf_build import Document, facing, quad, sphere

DROP_CENTRE = (0.0, 1.0, 0.0)
DROP_RADIUS = 0.05
SCREEN_Z = 2.0  # the screen's plane, facing the drop (-z)
HOLE = 0.06  # half-width of the hole the beam passes through
LIGHT_Z = 8.0


def screen():
    """The screen as four quads around the square hole on the beam's axis."""
    x0, y0 = DROP_CENTRE[0], DROP_CENTRE[1]
    lo_x, hi_x, lo_y, hi_y = x0 - 3.2, x0 + 3.2, y0 - 2.6, y0 + 2.6
    z = SCREEN_Z
    p = lambda x, y: (x, y, z)
    parts = [
        quad(p(lo_x, lo_y), p(hi_x, lo_y), p(hi_x, y0 - HOLE), p(lo_x, y0 - HOLE)),
        quad(p(lo_x, y0 + HOLE), p(hi_x, y0 + HOLE), p(hi_x, hi_y), p(lo_x, hi_y)),
        quad(p(lo_x, y0 - HOLE), p(x0 - HOLE, y0 - HOLE), p(x0 - HOLE, y0 + HOLE), p(lo_x, y0 + HOLE)),
        quad(p(x0 + HOLE, y0 - HOLE), p(hi_x, y0 - HOLE), p(hi_x, y0 + HOLE), p(x0 + HOLE, y0 + HOLE)),
    ]
    return facing(sum(parts, []), lambda c: [0.0, 0.0, -1.0])


def main():
    doc = Document("scenes/tools/make_rainbow.py")
    water = doc.material("water", extensions={"PRISM_spectral": {"type": "dielectric", "ior": "glass:water"}})
    matte = {"pbrMetallicRoughness": {"baseColorFactor": [0.85, 0.85, 0.85, 1], "metallicFactor": 0, "roughnessFactor": 1}}
    positions, normals, indices = sphere(DROP_CENTRE, DROP_RADIUS, rings=96, segments=192)
    doc.mesh("drop", positions, water, normals=normals, indices=indices)
    doc.mesh("screen", screen(), doc.material("screen", **matte))

    distance = LIGHT_Z - DROP_CENTRE[2]
    cone = math.atan(DROP_RADIUS / distance)
    beam = {
        "type": "spot",
        "intensity": 4000.0,
        "spot": {"innerConeAngle": 1.15 * cone, "outerConeAngle": 1.3 * cone},
        "extensions": {"PRISM_spectral": {"spectrum": "blackbody:5800", "units": "radiometric"}},
    }
    doc.light("sun", (DROP_CENTRE[0], DROP_CENTRE[1], LIGHT_Z), (0.0, 0.0, -1.0), beam)
    # The camera: behind the drop and a little aside, looking at the screen's centre.
    eye = (0.35, 1.25, -2.2)
    doc.camera("camera", eye, (0.0, 1.0, SCREEN_Z), {"yfov": 1.05, "aspectRatio": 4 / 3, "znear": 0.01})
    doc.write("scenes/rainbow.gltf")


if __name__ == "__main__":
    main()
