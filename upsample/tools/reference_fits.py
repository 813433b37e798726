#!/usr/bin/env python3
"""Reference sigmoid-polynomial fits by an independent fitter, for prism-upsample's tests.

    pip install colour-science==0.4.6 numpy scipy
    python3 upsample/tools/reference_fits.py

Fits 40 sRGB colours with scipy.optimize.least_squares (MINPACK Levenberg-Marquardt, numerical
Jacobian) minimizing the CIELAB difference computed by colour-science: the spectrum
S(c0 t^2 + c1 t + c2), t = (l - 360) / 470, is evaluated at 1 nm over 360-830 nm under CIE
D65 (its table interpolated linearly, zero past 780 nm) and the CIE 1931 observer, and
compared with the target RGB taken relative to the D65 table's white. Writes
upsample/tests/fixtures/reference_fits.json with the coefficients for l in nm.
"""

import json
import warnings
from pathlib import Path

import numpy as np
from scipy.optimize import least_squares

warnings.filterwarnings("ignore")
import colour  # noqa: E402

WL = np.arange(360, 831, 1.0)
T = (WL - 360.0) / 470.0
cmfs = colour.MSDS_CMFS["CIE 1931 2 Degree Standard Observer"].values
d65 = colour.SDS_ILLUMINANTS["D65"]
illuminant = np.interp(WL, d65.wavelengths, d65.values, left=0.0, right=0.0)
weights = cmfs * illuminant[:, None]
k = 1.0 / weights[:, 1].sum()
white = weights.sum(axis=0) * k
white_xy = white[:2] / white.sum()
cs = colour.RGB_COLOURSPACES["sRGB"]
M = colour.normalised_primary_matrix(cs.primaries, white_xy)


def lab_of(c):
    x = c[0] * T * T + c[1] * T + c[2]
    s = 0.5 + x / (2.0 * np.sqrt(1.0 + x * x))
    return colour.XYZ_to_Lab((s @ weights) * k, white_xy)


def fit(rgb):
    target = colour.XYZ_to_Lab(M @ rgb, white_xy)
    result = least_squares(lambda c: lab_of(c) - target, np.zeros(3), method="lm", x_scale="jac", xtol=1e-15, ftol=1e-15, gtol=1e-15, max_nfev=20_000)
    c = result.x
    a, s = 360.0, 1.0 / 470.0
    nm = [c[0] * s * s, c[1] * s - 2 * c[0] * a * s * s, c[2] - c[1] * a * s + c[0] * a * a * s * s]
    de = float(colour.delta_E(lab_of(c), target, method="CIE 2000"))
    return nm, de


def main():
    rng = np.random.default_rng(7)
    colours = [list(v) for v in rng.uniform(0.02, 0.98, (32, 3))]
    colours += [[0.9, 0.1, 0.1], [0.1, 0.8, 0.2], [0.1, 0.2, 0.9], [0.95, 0.9, 0.2], [0.05, 0.05, 0.06], [0.5, 0.4, 0.3], [0.2, 0.6, 0.7], [0.7, 0.2, 0.6]]
    entries = []
    for rgb in colours:
        nm, de = fit(np.array(rgb))
        entries.append({"rgb": rgb, "coefficients_nm": nm, "delta_e_2000": de})
    out = {
        "generator": f"scipy.optimize.least_squares on colour-science {colour.__version__} colorimetry",
        "fits": entries,
    }
    path = Path(__file__).resolve().parents[1] / "tests" / "fixtures" / "reference_fits.json"
    path.write_text(json.dumps(out, indent=1))
    print(f"wrote {path}; worst reference dE2000 {max(e['delta_e_2000'] for e in entries):.2e}")


if __name__ == "__main__":
    main()
