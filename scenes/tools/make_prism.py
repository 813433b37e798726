"""Writes scenes/prism.gltf: white light through a 60-degree SF11 prism onto a wall.

A narrow spot light (a 5500 K blackbody, cone 0.3 degrees) meets the prism's left face at
the angle of minimum deviation for 550 nm; the wall stands 4 units past the right face,
square to the 550 nm exit ray, so the spectrum spreads across it (about 3.5 degrees from
450 to 650 nm for SF11). The geometry follows integrator/tests/dispersion.rs: prism base
along x, apex towards +z, all in the plane y = 1 (the beam's height).

Run from the repository root: python3 scenes/tools/make_prism.py
"""

import math

from gltf_build import Document, facing, quad

N_550 = 1.7847  # SF11 at 550 nm (Sellmeier, Schott), for placing the light and wall only
SCALE = 0.35
HEIGHT = (0.55, 1.45)  # the prism's extent along y
BEAM_Y = 1.0


def minimum_deviation_geometry():
    theta = math.asin(N_550 * math.sin(math.pi / 6))
    alpha = theta - math.pi / 6
    incident = (math.cos(alpha), math.sin(alpha))
    exit_ = (math.cos(alpha), -math.sin(alpha))
    b0, b1, apex = (-SCALE, 0.0), (SCALE, 0.0), (0.0, SCALE * math.sqrt(3))
    left_mid = ((b0[0] + apex[0]) / 2, (b0[1] + apex[1]) / 2)
    right_mid = ((b1[0] + apex[0]) / 2, (b1[1] + apex[1]) / 2)
    return incident, exit_, (b0, b1, apex), left_mid, right_mid


def prism_solid(lo, hi):
    """The prism's triangles between heights lo and hi, wound outwards; (u, v) of
    minimum_deviation_geometry is (x, z)."""
    _, _, (b0, b1, apex), _, _ = minimum_deviation_geometry()
    w = lambda uv, y: (uv[0], y, uv[1])
    prism = []
    for a, b in [(b0, b1), (b1, apex), (apex, b0)]:
        prism += quad(w(a, lo), w(b, lo), w(b, hi), w(a, hi))
    prism += [w(b0, hi), w(b1, hi), w(apex, hi)]
    prism += [w(b0, lo), w(apex, lo), w(b1, lo)]
    middle = ((b0[0] + b1[0] + apex[0]) / 3, (lo + hi) / 2, (b0[1] + b1[1] + apex[1]) / 3)
    return facing(prism, lambda c: [c[k] - middle[k] for k in range(3)])


def main():
    incident, exit_, _, left_mid, right_mid = minimum_deviation_geometry()
    lo, hi = HEIGHT
    prism = prism_solid(lo, hi)

    distance = 4.0
    centre = (right_mid[0] + distance * exit_[0], right_mid[1] + distance * exit_[1])
    # The wall faces back along the exit ray; its width runs perpendicular to it.
    across = (exit_[1], -exit_[0])
    half = 1.4
    p = lambda s, y: (centre[0] + s * across[0], y, centre[1] + s * across[1])
    wall = quad(p(half, 0.0), p(-half, 0.0), p(-half, 2.2), p(half, 2.2))
    floor = quad((-4, 0, -4), (-4, 0, 4), (4, 0, 4), (4, 0, -4))

    wall = facing(wall, lambda c: [-exit_[0], 0.0, -exit_[1]])
    floor = facing(floor, lambda c: [0.0, 1.0, 0.0])
    doc = Document("scenes/tools/make_prism.py")
    glass = doc.material("prism", extensions={"PRISM_spectral": {"type": "dielectric", "ior": "glass:sf11"}})
    matte = lambda rgb: {"pbrMetallicRoughness": {"baseColorFactor": [*rgb, 1], "metallicFactor": 0, "roughnessFactor": 1}}
    doc.mesh("prism", prism, glass)
    doc.mesh("wall", wall, doc.material("wall", **matte([0.8, 0.8, 0.8])))
    doc.mesh("floor", floor, doc.material("floor", **matte([0.2, 0.2, 0.22])))

    # The spot light: KHR lights shine down their node's -z, turned onto the incident
    # direction.
    origin = (left_mid[0] - 2.0 * incident[0], left_mid[1] - 2.0 * incident[1])
    beam = {
        "type": "spot",
        "intensity": 60.0,
        "spot": {"innerConeAngle": 0.002, "outerConeAngle": 0.006},
        "extensions": {"PRISM_spectral": {"spectrum": "blackbody:5500", "units": "radiometric"}},
    }
    doc.light("white beam", (origin[0], BEAM_Y, origin[1]), (incident[0], 0.0, incident[1]), beam)
    # The camera: in front of the wall, looking at it past the prism.
    back, side = 4.6, -1.6
    eye = (centre[0] - back * exit_[0] + side * across[0], 1.7, centre[1] - back * exit_[1] + side * across[1])
    target = (centre[0] - 0.9 * exit_[0], 0.9, centre[1] - 0.9 * exit_[1])
    doc.camera("camera", eye, target, {"yfov": 0.75, "znear": 0.01})
    doc.root_extension["environment"] = {"spectrum": "daylight:6500", "scale": 2e-5}
    doc.write("scenes/prism.gltf")


if __name__ == "__main__":
    main()
