"""Writes scene/tests/fixtures/thin_film_tmm.json: the unpolarized reflectance of a thin
film between air and a base, computed by the `tmm` package (Steven Byrnes' transfer-matrix
method, an implementation independent of prism's Airy summation), for prism's thin-film
test. Run from the repository root:

    pip install tmm numpy
    python3 scene/tools/thin_film_fixtures.py
"""

import json
import math

import tmm

FILMS = [1.3, 1.8, 2.4]
THICKNESSES_NM = [30.0, 120.0, 250.0, 400.0, 780.0]
ANGLES_DEG = [0.0, 35.0, 60.0, 85.0]
WAVELENGTHS_NM = [380.0, 450.0, 520.0, 590.0, 660.0, 780.0]
# (name, complex index): air on both sides (a soap bubble), glass, water, and two
# conductors (tmm's convention n + ik, k > 0 absorbing, as prism's).
BASES = [
    ("air", complex(1.0, 0.0)),
    ("glass", complex(1.5, 0.0)),
    ("water", complex(1.333, 0.0)),
    ("gold-like", complex(0.18, 3.0)),
    ("aluminium-like", complex(1.2, 7.0)),
]


def main():
    cases = []
    for _, base in BASES:
        for film in FILMS:
            for d in THICKNESSES_NM:
                for angle in ANGLES_DEG:
                    for lam in WAVELENGTHS_NM:
                        r = tmm.unpolarized_RT([1.0, film, base], [math.inf, d, math.inf], math.radians(angle), lam)["R"]
                        cases.append([base.real, base.imag, film, d, angle, lam, float(r)])
    with open("scene/tests/fixtures/thin_film_tmm.json", "w") as f:
        f.write('{"source": "tmm unpolarized_RT, n_list [1, film, base eta + i k], d_list [inf, thickness, inf]",\n')
        f.write(' "columns": ["base_eta", "base_k", "film", "thickness_nm", "angle_deg", "wavelength_nm", "reflectance"],\n')
        f.write(' "cases": [\n')
        f.write(",\n".join(json.dumps(c) for c in cases))
        f.write("\n]}\n")
    print(len(cases), "cases")


if __name__ == "__main__":
    main()
