"""Writes scenes/prism.gltf: white light through a 60-degree SF11 prism onto a wall.

A narrow spot light (a 5500 K blackbody, cone 0.3 degrees) meets the prism's left face at
the angle of minimum deviation for 550 nm; the wall stands 4 units past the right face,
square to the 550 nm exit ray, so the spectrum spreads across it (about 3.5 degrees from
450 to 650 nm for SF11). The geometry follows integrator/tests/dispersion.rs: prism base
along x, apex towards +z, all in the plane y = 1 (the beam's height).

Run from the repository root: python3 scenes/tools/make_prism.py
"""

import base64
import json
import math
import struct

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


def quad(a, b, c, d):
    return [a, b, c, a, c, d]


def facing(tris, outward):
    """The triangles, each wound so that its normal points along outward(centroid)."""
    fixed = []
    for i in range(0, len(tris), 3):
        a, b, c = tris[i : i + 3]
        e1 = [b[k] - a[k] for k in range(3)]
        e2 = [c[k] - a[k] for k in range(3)]
        n = [e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]]
        centroid = [(a[k] + b[k] + c[k]) / 3 for k in range(3)]
        want = outward(centroid)
        fixed += [a, b, c] if sum(n[k] * want[k] for k in range(3)) > 0 else [a, c, b]
    return fixed


def main():
    incident, exit_, (b0, b1, apex), left_mid, right_mid = minimum_deviation_geometry()
    # (u, v) in the prism's plane is world (x, z).
    w = lambda uv, y: (uv[0], y, uv[1])
    lo, hi = HEIGHT
    prism = []
    for a, b in [(b0, b1), (b1, apex), (apex, b0)]:
        # Side faces wound to face outwards (counter-clockwise seen from outside).
        prism += quad(w(a, lo), w(b, lo), w(b, hi), w(a, hi))
    prism += [w(b0, hi), w(b1, hi), w(apex, hi)]
    prism += [w(b0, lo), w(apex, lo), w(b1, lo)]

    distance = 4.0
    centre = (right_mid[0] + distance * exit_[0], right_mid[1] + distance * exit_[1])
    # The wall faces back along the exit ray; its width runs perpendicular to it.
    across = (exit_[1], -exit_[0])
    half = 1.4
    p = lambda s, y: (centre[0] + s * across[0], y, centre[1] + s * across[1])
    wall = quad(p(half, 0.0), p(-half, 0.0), p(-half, 2.2), p(half, 2.2))
    floor = quad((-4, 0, -4), (-4, 0, 4), (4, 0, 4), (4, 0, -4))

    middle = ((b0[0] + b1[0] + apex[0]) / 3, (lo + hi) / 2, (b0[1] + b1[1] + apex[1]) / 3)
    prism = facing(prism, lambda c: [c[k] - middle[k] for k in range(3)])
    wall = facing(wall, lambda c: [-exit_[0], 0.0, -exit_[1]])
    floor = facing(floor, lambda c: [0.0, 1.0, 0.0])
    meshes_data = [("prism", prism, 0), ("wall", wall, 1), ("floor", floor, 2)]
    blob = b""
    buffer_views, accessors, meshes, nodes = [], [], [], []
    for name, tris, material in meshes_data:
        data = b"".join(struct.pack("<3f", *v) for v in tris)
        lo_v = [min(v[i] for v in tris) for i in range(3)]
        hi_v = [max(v[i] for v in tris) for i in range(3)]
        buffer_views.append({"buffer": 0, "byteOffset": len(blob), "byteLength": len(data)})
        accessors.append(
            {
                "bufferView": len(buffer_views) - 1,
                "componentType": 5126,
                "count": len(tris),
                "type": "VEC3",
                "min": lo_v,
                "max": hi_v,
            }
        )
        blob += data
        meshes.append(
            {
                "name": name,
                "primitives": [{"attributes": {"POSITION": len(accessors) - 1}, "material": material}],
            }
        )
        nodes.append({"name": name, "mesh": len(meshes) - 1})

    # The spot light: KHR lights shine down their node's -z; rotate -z onto the incident
    # direction (a rotation about y).
    origin = (left_mid[0] - 2.0 * incident[0], left_mid[1] - 2.0 * incident[1])
    direction = (incident[0], 0.0, incident[1])
    yaw = math.atan2(-direction[0], -direction[2])
    nodes.append(
        {
            "name": "spot",
            "translation": [origin[0], BEAM_Y, origin[1]],
            "rotation": [0.0, math.sin(yaw / 2), 0.0, math.cos(yaw / 2)],
            "extensions": {"KHR_lights_punctual": {"light": 0}},
        }
    )
    # The camera: in front of the wall, looking at it past the prism.
    back, side = 4.6, -1.6
    eye = (centre[0] - back * exit_[0] + side * across[0], 1.7, centre[1] - back * exit_[1] + side * across[1])
    target = (centre[0] - 0.9 * exit_[0], 0.9, centre[1] - 0.9 * exit_[1])
    f = [target[i] - eye[i] for i in range(3)]
    n = math.sqrt(sum(x * x for x in f))
    f = [x / n for x in f]
    cam_yaw = math.atan2(-f[0], -f[2])
    pitch = math.asin(f[1])
    qy = (0.0, math.sin(cam_yaw / 2), 0.0, math.cos(cam_yaw / 2))
    qx = (math.sin(pitch / 2), 0.0, 0.0, math.cos(pitch / 2))

    def mul(a, b):
        ax, ay, az, aw = a
        bx, by, bz, bw = b
        return (
            aw * bx + ax * bw + ay * bz - az * by,
            aw * by - ax * bz + ay * bw + az * bx,
            aw * bz + ax * by - ay * bx + az * bw,
            aw * bw - ax * bx - ay * by - az * bz,
        )

    nodes.append(
        {"name": "camera", "camera": 0, "translation": list(eye), "rotation": list(mul(qy, qx))}
    )

    doc = {
        "asset": {"version": "2.0", "generator": "scenes/tools/make_prism.py"},
        "extensionsUsed": ["KHR_lights_punctual", "PRISM_spectral"],
        "extensions": {
            "KHR_lights_punctual": {
                "lights": [
                    {
                        "name": "white beam",
                        "type": "spot",
                        "intensity": 60.0,
                        "spot": {"innerConeAngle": 0.002, "outerConeAngle": 0.006},
                        "extensions": {
                            "PRISM_spectral": {"spectrum": "blackbody:5500", "units": "radiometric"}
                        },
                    }
                ]
            },
            "PRISM_spectral": {"environment": {"spectrum": "daylight:6500", "scale": 2e-5}},
        },
        "scene": 0,
        "scenes": [{"nodes": list(range(len(nodes)))}],
        "nodes": nodes,
        "cameras": [{"type": "perspective", "perspective": {"yfov": 0.75, "znear": 0.01}}],
        "meshes": meshes,
        "materials": [
            {
                "name": "prism",
                "extensions": {"PRISM_spectral": {"type": "dielectric", "ior": "glass:sf11"}},
            },
            {"name": "wall", "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.8, 0.8, 1], "metallicFactor": 0, "roughnessFactor": 1}},
            {"name": "floor", "pbrMetallicRoughness": {"baseColorFactor": [0.2, 0.2, 0.22, 1], "metallicFactor": 0, "roughnessFactor": 1}},
        ],
        "accessors": accessors,
        "bufferViews": buffer_views,
        "buffers": [
            {
                "byteLength": len(blob),
                "uri": "data:application/octet-stream;base64," + base64.b64encode(blob).decode(),
            }
        ],
    }
    with open("scenes/prism.gltf", "w") as f:
        json.dump(doc, f, indent=1)
        f.write("\n")


if __name__ == "__main__":
    main()
