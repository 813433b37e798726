"""Writes scenes/effects.gltf, the scene `prism render` renders without arguments: the
effects an RGB renderer cannot show, side by side on one stage.

- Left, a light booth of two bays, lit from above by a 2700 K blackbody panel and by a
  CIE D65 panel of the same luminance: the same white and coloured objects under each.
- Middle, a cabinet lined with black felt under a 365 nm UV panel: of the two spheres
  inside, split by a felt divider, the fluorescent one glows green (absorbed UV
  re-emitted around 515 nm); the white one beside it shows only the room's light.
- Right, white light (a narrow 5500 K spot) through a 60-degree SF11 prism: the beam
  leaves at minimum deviation and meets the back wall at a grazing angle, which spreads
  its spectrum, violet to red, over about a metre of the wall (a caustic seen directly,
  found by light paths).
- In front, the glTF material extensions (make_materials.py has the full set): a red
  base under a clear coat, velvet with a pink sheen, brushed steel (anisotropy), a soap
  film (iridescence), a blue specular tint on a dark base.

A large daylight panel high over the front lights the stage, from an area large enough
to be clean at the default 64 spp (the booth's and the cabinet's panels cover their
ceilings for the same reason), and meets the mid-grey back wall at a grazing angle, so
the spectrum on it keeps its contrast.

Units are metres; y is up; the back wall is the plane z = BACK. Run from the repository
root: python3 scenes/tools/make_effects.py
"""

import math

from gltf_build import Document, box, facing, png, quad, sphere, uv_sphere
from make_prism import minimum_deviation_geometry, prism_solid

BACK = -3.0
BEAM_Y = 1.3
# Where the 550 nm ray meets the back wall, its angle from the wall's normal there, and
# the distance it travels from the prism: a longer throw and a more grazing angle widen
# the spectrum on the wall.
LANDING_X = 2.35
GRAZING = math.radians(62.0)
THROW = 4.2
PRISM_HALF_HEIGHT = 0.3
CABINET_X = 0.5
UV_RADIANCE = 1.0  # W m^-2 sr^-1 nm^-1 at the LED's peak
SOFTBOX = 6e-4  # the daylight panel's scale (of the CIE daylight spectrum)

# Luminance integrals (cd m^-2 per unit of the spectrum's scale) of the booth's light
# spectra, so the two panels can be set to the same luminance: the integral of the CIE
# 1931 y-bar times the spectrum (D65 as tabulated, 300-830 nm at 1 nm: 10567) and times
# Planck's law at 2700 K normalized to its peak, computed by luminance_of_blackbody.
D65_Y_INTEGRAL = 10567.0


def ybar(nm):
    """CIE 1931 y-bar, the multi-lobe Gaussian fit of Wyman, Sloan and Shirley (JCGT 2(2),
    2013); within a few percent, enough to balance two lamps."""
    g = lambda x, mu, s1, s2: math.exp(-0.5 * ((x - mu) / (s1 if x < mu else s2)) ** 2)
    return 0.821 * g(nm, 568.8, 46.9, 40.5) + 0.286 * g(nm, 530.9, 16.3, 31.1)


def luminance_of_blackbody(kelvin):
    planck = lambda nm: 1.0 / ((nm * 1e-9) ** 5 * (math.exp(1.4387769e-2 / (nm * 1e-9 * kelvin)) - 1.0))
    peak = planck(2.8977719e-3 / kelvin * 1e9)
    return sum(ybar(nm) * planck(nm) / peak for nm in range(360, 831))


def matte(rgb):
    return {"pbrMetallicRoughness": {"baseColorFactor": [*rgb, 1], "metallicFactor": 0, "roughnessFactor": 1}}


def emitter(spectrum, scale):
    return {"extensions": {"PRISM_spectral": {"type": "diffuse", "reflectance": 0.0, "emission": {"spectrum": spectrum, "scale": scale}}}}


def upward(tris):
    return facing(tris, lambda c: [0.0, 1.0, 0.0])


def downward(tris):
    return facing(tris, lambda c: [0.0, -1.0, 0.0])


def placed_prism():
    """The prism turned and moved so that its 550 nm exit ray leaves towards the landing
    point at the grazing angle; returns its triangles, the beam's entry point and incident
    direction (x, z)."""
    incident, exit_, _, left_mid, right_mid = minimum_deviation_geometry()
    want = (math.sin(GRAZING), -math.cos(GRAZING))  # towards +x and the back wall
    # Mirror the prism's plane (v -> -v) so that the incident beam comes from the front.
    mirror = lambda uv: (uv[0], -uv[1])
    incident, exit_, left_mid, right_mid = map(mirror, (incident, exit_, left_mid, right_mid))
    angle = math.atan2(want[1], want[0]) - math.atan2(exit_[1], exit_[0])
    turn = lambda uv: (uv[0] * math.cos(angle) - uv[1] * math.sin(angle), uv[0] * math.sin(angle) + uv[1] * math.cos(angle))
    exit_point = (LANDING_X - THROW * want[0], BACK - THROW * want[1])
    shift = [exit_point[k] - turn(right_mid)[k] for k in range(2)]
    place = lambda uv: tuple(turn(uv)[k] + shift[k] for k in range(2))
    tris = prism_solid(BEAM_Y - PRISM_HALF_HEIGHT, BEAM_Y + PRISM_HALF_HEIGHT)
    world = []
    for x, y, z in tris:
        u, v = place(mirror((x, z)))
        world.append((u, y, v))
    centre = [sum(p[k] for p in world) / len(world) for k in range(3)]
    world = facing(world, lambda c: [c[k] - centre[k] for k in range(3)])
    return world, place(left_mid), turn(incident)


def main():
    doc = Document("scenes/tools/make_effects.py")
    white = doc.material("white", **matte([0.8, 0.8, 0.8]))
    floor = doc.material("floor", **matte([0.2, 0.2, 0.22]))
    dark = doc.material("dark", **matte([0.05, 0.05, 0.05]))

    doc.mesh("floor", upward(quad((-7, 0, BACK), (7, 0, BACK), (7, 0, 6), (-7, 0, 6))), floor)
    # A mid-grey back wall: the room light leaves it dim, so the spectrum on it shows.
    wall = doc.material("wall", **matte([0.35, 0.35, 0.35]))
    doc.mesh("back wall", facing(quad((-7, 0, BACK), (7, 0, BACK), (7, 5, BACK), (-7, 5, BACK)), lambda c: [0, 0, 1]), wall)

    # The light booth: two bays under a shared top, split by a divider.
    x0, x1, depth, height = -4.0, -1.8, 1.5, 1.3
    xm = (x0 + x1) / 2
    z0, z1 = BACK, BACK + depth
    booth = box((x0 - 0.04, 0, z0), (x0, height, z1)) + box((x1, 0, z0), (x1 + 0.04, height, z1))
    booth += box((xm - 0.02, 0, z0), (xm + 0.02, height, z1)) + box((x0 - 0.04, height, z0), (x1 + 0.04, height + 0.04, z1))
    doc.mesh("booth", booth, white)
    warm = D65_Y_INTEGRAL / luminance_of_blackbody(2700.0)
    # Panels covering most of each bay's ceiling: large sources light the bays evenly at
    # few samples.
    panel = lambda a, b: downward(quad((a + 0.06, height - 0.001, z0 + 0.1), (b - 0.06, height - 0.001, z0 + 0.1), (b - 0.06, height - 0.001, z1 - 0.15), (a + 0.06, height - 0.001, z1 - 0.15)))
    scale = 0.0003
    doc.mesh("2700 K panel", panel(x0, xm), doc.material("2700 K", **emitter("blackbody:2700", scale * warm)))
    doc.mesh("D65 panel", panel(xm, x1), doc.material("D65", **emitter("illuminant:D65", scale)))
    red = doc.material("red", **matte([0.7, 0.08, 0.06]))
    blue = doc.material("blue", **matte([0.08, 0.2, 0.7]))
    for name, a, b in [("warm", x0, xm), ("daylight", xm, x1)]:
        c = (a + b) / 2
        positions, normals, indices = sphere((c - 0.3, 0.22, z0 + 0.75), 0.22)
        doc.mesh(f"{name} white sphere", positions, white, normals, indices)
        doc.mesh(f"{name} red cube", box((c + 0.1, 0, z0 + 0.35), (c + 0.45, 0.35, z0 + 0.7)), red)
        doc.mesh(f"{name} blue cube", box((c + 0.12, 0.35, z0 + 0.4), (c + 0.42, 0.65, z0 + 0.68)), blue)

    # The blacklight cabinet: an open-fronted box lined with black felt, a UV spot in its
    # top, a fluorescent sphere and a white one inside. The lining keeps the glow from
    # lighting the stage (a small bright source that camera paths only find by chance).
    fluorescent = doc.material(
        "fluorescent",
        extensions={
            "PRISM_spectral": {
                "type": "fluorescent",
                "reflectance": 0.08,
                "absorption": {"spectrum": "gaussian:370:60", "scale": 0.9},
                "reemission": "gaussian:515:35",
                "quantum_yield": 0.9,
            }
        },
    )
    felt = doc.material("felt", **matte([0.02, 0.02, 0.02]))
    cx, cz0, cz1, ch, half = CABINET_X, -0.9, 0.5, 1.1, 0.95
    t = 0.03
    cabinet = box((cx - half - t, 0, cz0), (cx - half, ch, cz1)) + box((cx + half, 0, cz0), (cx + half + t, ch, cz1))
    cabinet += box((cx - half - t, ch, cz0), (cx + half + t, ch + t, cz1)) + box((cx - half - t, 0, cz0 - t), (cx + half + t, ch + t, cz0))
    cabinet += box((cx - half, 0, cz0), (cx + half, 0.01, cz1))
    doc.mesh("cabinet", cabinet, felt)
    for name, dx, material in [("fluorescent sphere", -0.42, fluorescent), ("white sphere", 0.42, white)]:
        positions, normals, indices = sphere((cx + dx, 0.01 + 0.32, (cz0 + cz1) / 2), 0.32)
        doc.mesh(name, positions, material, normals, indices)
    # A felt divider between them: the white sphere shows what the UV does to a plain
    # white (nothing), not the green glow its neighbour throws on it.
    doc.mesh("cabinet divider", box((cx - 0.015, 0.01, cz0), (cx + 0.015, ch, cz1 - 0.25)), felt)
    # The blacklight: a UV tube (a 365 nm LED band) along the cabinet's ceiling. An area
    # light rather than a spot, so that camera paths leaving the fluorescent sphere find
    # it by BSDF sampling as well as by light sampling (MIS).
    zc = (cz0 + cz1) / 2
    tube = downward(quad((cx - 0.85, ch - 0.005, zc - 0.35), (cx + 0.85, ch - 0.005, zc - 0.35), (cx + 0.85, ch - 0.005, zc + 0.35), (cx - 0.85, ch - 0.005, zc + 0.35)))
    doc.mesh("blacklight", tube, doc.material("UV tube", **emitter("gaussian:365:12", UV_RADIANCE)))

    # The prism on a dark stand, and the beam that enters it.
    prism, entry, incident = placed_prism()
    glass = doc.material("SF11 prism", extensions={"PRISM_spectral": {"type": "dielectric", "ior": "glass:sf11"}})
    doc.mesh("prism", prism, glass)
    centre = [sum(p[k] for p in prism) / len(prism) for k in range(3)]
    doc.mesh("stand", box((centre[0] - 0.08, 0, centre[2] - 0.08), (centre[0] + 0.08, BEAM_Y - PRISM_HALF_HEIGHT, centre[2] + 0.08)), dark)
    origin = (entry[0] - 2.5 * incident[0], BEAM_Y, entry[1] - 2.5 * incident[1])
    doc.light(
        "white beam",
        origin,
        (incident[0], 0.0, incident[1]),
        {
            "type": "spot",
            "intensity": 150.0,
            "spot": {"innerConeAngle": 0.004, "outerConeAngle": 0.009},
            "extensions": {"PRISM_spectral": {"spectrum": "blackbody:5500", "units": "radiometric"}},
        },
    )

    materials_row(doc)
    # A soft daylight panel high over the front of the stage: it lights the material row
    # and the floor from a large area (clean at few samples), and the back wall only at a
    # grazing angle, so the spectrum there keeps its contrast.
    doc.mesh(
        "softbox",
        downward(quad((-4.5, 4.2, 2.5), (4.5, 4.2, 2.5), (4.5, 4.2, 6.0), (-4.5, 4.2, 6.0))),
        doc.material("softbox", **emitter("daylight:6500", SOFTBOX)),
    )
    doc.camera("camera", (0.0, 1.8, 7.6), (0.0, 0.6, -1.0), {"aspectRatio": 4 / 3, "yfov": 0.74, "znear": 0.01})
    doc.root_extension["environment"] = {"spectrum": "daylight:6500", "scale": 1e-6}
    doc.write("scenes/effects.gltf")


def materials_row(doc):
    """The glTF material extensions, one sphere each along the front of the stage: a red
    base under a clear coat, velvet with a sheen, brushed steel (anisotropy), a soap film
    (iridescence) and a blue specular tint on a dark base."""
    ramp = doc.texture(png(4, 64, lambda x, y: (0, int(255 * y / 63), 0)), wrap=33071)
    doc.extensions_used += [
        "KHR_materials_clearcoat",
        "KHR_materials_sheen",
        "KHR_materials_anisotropy",
        "KHR_materials_iridescence",
        "KHR_materials_specular",
    ]
    pbr = lambda rgb, metallic, roughness: {"baseColorFactor": [*rgb, 1], "metallicFactor": metallic, "roughnessFactor": roughness}
    spheres = [
        ("clear coat", pbr([0.6, 0.05, 0.04], 0.0, 0.6), {"KHR_materials_clearcoat": {"clearcoatFactor": 1.0, "clearcoatRoughnessFactor": 0.03}}),
        ("sheen", pbr([0.05, 0.02, 0.08], 0.0, 0.9), {"KHR_materials_sheen": {"sheenColorFactor": [1.0, 0.45, 0.75], "sheenRoughnessFactor": 0.35}}),
        ("anisotropy", pbr([0.85, 0.85, 0.88], 1.0, 0.3), {"KHR_materials_anisotropy": {"anisotropyStrength": 0.9}}),
        (
            "iridescence",
            pbr([0.02, 0.02, 0.02], 0.0, 0.05),
            {"KHR_materials_iridescence": {"iridescenceFactor": 1.0, "iridescenceIor": 1.33, "iridescenceThicknessMinimum": 150.0, "iridescenceThicknessMaximum": 700.0, "iridescenceThicknessTexture": {"index": ramp}}},
        ),
        ("specular", pbr([0.12, 0.12, 0.12], 0.0, 0.2), {"KHR_materials_specular": {"specularColorFactor": [0.2, 0.6, 4.0]}}),
    ]
    radius = 0.25
    for k, (name, base, extensions) in enumerate(spheres):
        m = doc.material(name, pbrMetallicRoughness=base, extensions=extensions)
        positions, normals, uvs, indices = uv_sphere((-2.0 + 1.0 * k, radius, 1.9), radius)
        doc.mesh(f"{name} sphere", positions, m, normals, indices, uvs)


if __name__ == "__main__":
    main()
