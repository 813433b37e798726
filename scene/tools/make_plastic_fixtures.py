"""The fixture of scene/tests/plastic.rs, from two independent sources:

- Mitsuba 3's smooth `plastic` (an independent implementation of the model prism's plastic
  follows): the diffuse component's value f cos(theta_o) at pairs of directions, per
  index (1.49, 1.8), linear and nonlinear;
- a brute-force quadrature here (numpy, over the outgoing hemisphere, not over visible
  normals as prism's tables are made): the directional albedo E(mu) of the rough
  coating's GGX reflection with height-correlated masking, per roughness and index.

Mitsuba's `roughplastic` is not a reference for rough coatings: its substrate term takes
the internal reflectance from single-scattering microfacets, which lose what masking
removes, and a white substrate reflects 0.96 at alpha 0.05, 0.91 at 0.1 and 0.69 at 0.3
in a white furnace (mitsuba3 issue #1155); its smooth `plastic` reflects 1.000.

    pip install mitsuba==3.9.1 numpy
    python3 scene/tools/make_plastic_fixtures.py > scene/tests/fixtures/plastic.json
"""
import json
import math

import mitsuba as mi
import numpy as np

mi.set_variant("scalar_rgb")

DIRECTIONS = [(0.0, 1.0), (0.3, 0.95), (0.8, 0.6), (0.95, 0.31), (0.995, 0.1)]


def direction(sin_cos, phi):
    s, c = sin_cos
    n = math.hypot(s, c)
    return mi.Vector3f(s / n * math.cos(phi), s / n * math.sin(phi), c / n)


def evaluate(bsdf, wi, wo):
    si = mi.SurfaceInteraction3f()
    si.wi = wi
    si.sh_frame = mi.Frame3f(mi.Vector3f(0, 0, 1))
    return float(bsdf.eval(mi.BSDFContext(), si, wo)[0])


def fresnel(c, eta):
    c = np.clip(c, 0.0, 1.0)
    s2 = (1 - c * c) / eta**2
    ct = np.sqrt(np.maximum(0.0, 1 - s2))
    rp = (eta * c - ct) / (eta * c + ct)
    rs = (c - eta * ct) / (c + eta * ct)
    return np.where(s2 >= 1, 1.0, 0.5 * (rp * rp + rs * rs))


def lam(mu, a):
    mu = np.clip(mu, 1e-12, 1.0)
    return (np.sqrt(1 + a * a * (1 - mu * mu) / (mu * mu)) - 1) / 2


# Outgoing directions: Gauss-Legendre in cos(theta) and midpoints in phi (the lobe is
# symmetric about the plane of incidence: phi over [0, pi], doubled).
COS, COS_W = np.polynomial.legendre.leggauss(400)
COS, COS_W = 0.5 * (COS + 1), 0.5 * COS_W
PHI = (np.arange(400) + 0.5) / 400 * np.pi
C, P = np.meshgrid(COS, PHI, indexing="ij")
S = np.sqrt(1 - C * C)
WO = np.stack([S * np.cos(P), S * np.sin(P), C], -1)
DW = COS_W[:, None] * (np.pi / 400) * 2


def albedo(mu, a, eta):
    """E(mu): int F D G / (4 mu cos_o) cos_o dw_o with G = 1 / (1 + Lambda_i + Lambda_o)."""
    wi = np.array([math.sqrt(max(0.0, 1 - mu * mu)), 0.0, mu])
    h = WO + wi
    h /= np.linalg.norm(h, axis=-1, keepdims=True)
    d = 1 / (np.pi * a * a * ((h[..., 0] ** 2 + h[..., 1] ** 2) / (a * a) + h[..., 2] ** 2) ** 2)
    g = 1 / (1 + lam(mu, a) + lam(WO[..., 2], a))
    f = fresnel((wi * h).sum(-1), eta) * d * g / (4 * mu)
    return float((f * DW).sum())


out = {"mitsuba": mi.__version__, "smooth": [], "coating": []}
for ior in [1.49, 1.8]:
    for nonlinear in [False, True]:
        bsdf = mi.load_dict({"type": "plastic", "int_ior": ior, "ext_ior": 1.0, "nonlinear": nonlinear,
                             "diffuse_reflectance": {"type": "rgb", "value": [0.6, 0.6, 0.6]}})
        pairs = []
        for a in DIRECTIONS:
            for b in DIRECTIONS:
                wi, wo = direction(a, 0.0), direction(b, 2.5)
                pairs.append({"wi": list(wi), "wo": list(wo), "diffuse": evaluate(bsdf, wi, wo)})
        out["smooth"].append({"ior": ior, "nonlinear": nonlinear, "reflectance": 0.6, "pairs": pairs})
for alpha in [0.05, 0.2, 0.5]:
    for ior in [1.49, 1.8]:
        albedos = [{"mu": mu, "albedo": albedo(mu, alpha, ior)} for mu in [1.0, 0.8, 0.5, 0.3, 0.1]]
        out["coating"].append({"alpha": alpha, "ior": ior, "albedo": albedos})
print(json.dumps(out, indent=1))
