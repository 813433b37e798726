"""The fixture of scene/tests/principled.rs: Mitsuba 3's own `principled` and
`principledthin` (scalar_rgb, so that a colour's three channels are three lanes of
prism's) evaluated at pairs of directions: eval (f cos(theta_o)) per channel and pdf,
for parameter sets that turn each lobe on, from the front and from the back.

    pip install mitsuba==3.9.1
    python3 scene/tools/make_principled_fixtures.py > scene/tests/fixtures/principled.json
"""
import json
import math

import mitsuba as mi

mi.set_variant("scalar_rgb")

BASE = [0.8, 0.4, 0.2]

PRINCIPLED = [
    {},
    {"metallic": 0.7, "roughness": 0.3},
    {"spec_trans": 0.6, "roughness": 0.25, "eta": 1.4},
    {"clearcoat": 0.8, "clearcoat_gloss": 0.4, "roughness": 0.6},
    {"sheen": 0.7, "sheen_tint": 0.5, "flatness": 0.6, "roughness": 0.8},
    {"spec_tint": 0.6, "metallic": 0.2, "specular": 0.7, "roughness": 0.4},
    {"anisotropic": 0.8, "roughness": 0.4, "metallic": 0.5},
    {"spec_trans": 1.0, "roughness": 0.1, "eta": 1.5},
]

THIN = [
    {},
    {"spec_trans": 0.6, "roughness": 0.3, "eta": 1.33},
    {"diff_trans": 1.4, "sheen": 0.5, "sheen_tint": 0.3},
    {"spec_trans": 0.4, "spec_tint": 0.5, "anisotropic": 0.6, "flatness": 0.5,
     "diff_trans": 0.6, "eta": 1.6},
]


def direction(theta, phi):
    return [math.sin(theta) * math.cos(phi), math.sin(theta) * math.sin(phi), math.cos(theta)]


# (wi, wo) in Mitsuba's naming: wi towards the viewer, wo towards the light.
PAIRS = []
for ti in (0.1, 0.7, 1.3):
    for to, po in ((0.2, 2.0), (0.9, 3.3), (1.2, 0.4), (math.pi - 0.3, 3.0),
                   (math.pi - 0.9, 0.7)):
        PAIRS.append((direction(ti, 0.3), direction(to, po)))
# From the back.
for ti in (math.pi - 0.2, math.pi - 1.0):
    for to, po in ((0.3, 3.0), (0.8, 0.2), (math.pi - 0.4, 2.5), (math.pi - 1.1, 4.0)):
        PAIRS.append((direction(ti, 1.1), direction(to, po)))


def cases(kind, sets):
    out = []
    for params in sets:
        d = {"type": kind, "base_color": {"type": "rgb", "value": BASE}}
        d.update(params)
        bsdf = mi.load_dict(d)
        pairs = []
        for wi, wo in PAIRS:
            si = mi.SurfaceInteraction3f()
            si.wi = mi.Vector3f(wi)
            si.sh_frame = mi.Frame3f(mi.Vector3f(0, 0, 1))
            ctx = mi.BSDFContext()
            value = bsdf.eval(ctx, si, mi.Vector3f(wo))
            pdf = bsdf.pdf(ctx, si, mi.Vector3f(wo))
            pairs.append({"wi": wi, "wo": wo, "eval": [float(v) for v in value],
                          "pdf": float(pdf)})
        out.append({"params": params, "pairs": pairs})
    return out


lum = 0.212671 * BASE[0] + 0.715160 * BASE[1] + 0.072169 * BASE[2]
print(json.dumps({"base": BASE, "luminance": lum,
                  "principled": cases("principled", PRINCIPLED),
                  "principledthin": cases("principledthin", THIN)}, indent=1))
