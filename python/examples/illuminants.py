"""Colours under five illuminants: the sRGB colours of a few ColorChecker patches upsampled
to reflectance spectra by prism, seen under CIE D65, A, F2, F11 and D50 by colour-science,
adapted back to D65 (CAT02), and their CIEDE2000 differences from what D65 shows: how much
each patch shifts under each light (its colour inconstancy). Then the Cornell box rendered
from Python and saved as the command line saves it.

    pip install ./python colour-science
    python python/examples/illuminants.py   # from the repository root
"""

import warnings

import numpy as np

import prism

warnings.simplefilter("ignore")
import colour  # noqa: E402

PATCHES = {
    "dark skin": [0.1706, 0.0887, 0.0580],
    "foliage": [0.0980, 0.1470, 0.0656],
    "blue flower": [0.2293, 0.2164, 0.4139],
    "orange": [0.7454, 0.2017, 0.0236],
    "purplish blue": [0.0664, 0.1077, 0.4062],
    "yellow green": [0.3433, 0.4936, 0.0490],
}
ILLUMINANTS = ["D65", "A", "FL2", "FL11", "D50"]
CMFS = colour.MSDS_CMFS["CIE 1931 2 Degree Standard Observer"]
SHAPE = colour.SpectralShape(360, 780, 1)


def lab_under(reflectance, name):
    """CIELAB (D65 white) of a reflectance under an illuminant, adapted to D65 by CAT02."""
    illuminant = colour.SDS_ILLUMINANTS[name].copy().align(SHAPE)
    xyz = colour.sd_to_XYZ(reflectance, cmfs=CMFS, illuminant=illuminant) / 100
    white = colour.sd_to_XYZ(colour.sd_ones(SHAPE), cmfs=CMFS, illuminant=illuminant) / 100
    d65 = colour.CCS_ILLUMINANTS["CIE 1931 2 Degree Standard Observer"]["D65"]
    adapted = colour.chromatic_adaptation(xyz, white, colour.xy_to_XYZ(d65), method="Von Kries", transform="CAT02")
    return colour.XYZ_to_Lab(adapted, d65)


def main():
    print("patch".ljust(14) + "".join(name.rjust(8) for name in ILLUMINANTS[1:]))
    for patch, rgb in PATCHES.items():
        reflectance = prism.upsample_spectrum(rgb).to_colour().align(SHAPE)
        reference = lab_under(reflectance, "D65")
        shifts = [colour.delta_E(reference, lab_under(reflectance, name), method="CIE 2000") for name in ILLUMINANTS[1:]]
        print(patch.ljust(14) + "".join(f"{d:8.2f}" for d in shifts))
    scene = prism.load("scenes/cornell-box.gltf")
    image = prism.render(scene, spp=8, width=64, height=64)
    print(f"Cornell box: mean linear sRGB {image.rgb.mean(axis=(0, 1))}, {image.stats['paths']} paths")
    image.save("cornell-python.png")


if __name__ == "__main__":
    main()
