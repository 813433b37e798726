"""Mueller matrices from Mitsuba 3 (an independent implementation), the fixture of
scene/tests/polarization.rs: specular reflection off dielectrics (below and beyond the
critical angle) and conductors, specular transmission, polarizers, retarders, rotators and
the rotation of Stokes reference frames.

    pip install mitsuba==3.9.1
    python3 scene/tools/make_mueller_fixtures.py > scene/tests/fixtures/mueller_mitsuba3.json

Mitsuba's scalar variants compute in float32: compare to ~1e-5."""
import json
import math

import mitsuba as mi

mi.set_variant("scalar_spectral_polarized")
M = mi.mueller


def rows(m):
    return [[float(m[r, c]) for c in range(4)] for r in range(4)]


cosines = [1.0, 0.95, 0.8, 0.6, 0.45, 0.3, 0.2, 0.1, 0.03, 0.0]
out = {"mitsuba": mi.__version__, "reflection": [], "transmission": [], "elements": [],
       "frames": []}
for eta in [1.5, 1.333, 1 / 1.5, 1 / 1.333, 2.4]:
    for c in cosines:
        out["reflection"].append({"cos_i": c, "eta": [eta, 0.0],
                                  "m": rows(M.specular_reflection(c, mi.Complex2f(eta, 0.0)))})
        sin_t2 = (1 - c * c) / (eta * eta)
        if sin_t2 < 1 and c > 0:
            out["transmission"].append({"cos_i": c, "eta": eta,
                                        "m": rows(M.specular_transmission(c, eta))})
for eta, k in [(0.2, 3.0), (0.18, 3.42), (2.9, 3.1), (1.2, 7.0)]:
    for c in cosines:
        out["reflection"].append({"cos_i": c, "eta": [eta, k],
                                  "m": rows(M.specular_reflection(c, mi.Complex2f(eta, k)))})
for theta in [0.0, 0.3, math.pi / 4, 1.2, -0.7]:
    out["elements"].append({"kind": "rotator", "value": theta, "m": rows(M.rotator(theta))})
    out["elements"].append({"kind": "rotated_polarizer", "value": theta,
                            "m": rows(M.rotated_element(theta, M.linear_polarizer(1.0)))})
for phase in [0.0, math.pi / 2, math.pi, 0.4]:
    out["elements"].append({"kind": "retarder", "value": phase,
                            "m": rows(M.linear_retarder(phase))})
out["elements"].append({"kind": "polarizer", "value": 1.0, "m": rows(M.linear_polarizer(1.0))})
out["elements"].append({"kind": "depolarizer", "value": 0.7, "m": rows(M.depolarizer(0.7))})
out["elements"].append({"kind": "diattenuator", "value": [0.9, 0.2],
                        "m": rows(M.diattenuator(0.9, 0.2))})
for w, a, b in [((0, 0, 1), (1, 0, 0), (0, 1, 0)),
                ((0, 0, 1), (1, 0, 0), (0.6, -0.8, 0)),
                ((0.6, 0, 0.8), (0, 1, 0), (-0.8, 0, 0.6)),
                ((0.6, 0, 0.8), (0, 1, 0), (0.8, 0.6 * 0.0, -0.6))]:
    out["frames"].append({"w": w, "from": a, "to": b,
                          "m": rows(M.rotate_stokes_basis(mi.Vector3f(w), mi.Vector3f(a),
                                                          mi.Vector3f(b)))})
print(json.dumps(out, indent=1))
