#!/usr/bin/env python3
"""Writes scenes/mitsuba/bsdfs-<name>.xml: Mitsuba's Cornell box (mi.cornell_box(), as
make_mitsuba_scenes.py writes it) at 32 x 32 with its two cubes given the BSDFs under test,
and renders each with Mitsuba 3's scalar_spectral variant into the references
cli/tests/mitsuba_ztests.rs z-tests prism's renders against
(scenes/mitsuba/references/bsdfs-<name>-ref.exr and -var.exr, by make_mitsuba_ztest_refs.py).

beckmann-* use Mitsuba's default distribution; roughplastic is Mitsuba's model (prism's
own plastic keeps the energy Mitsuba's loses, and reads only `plastic`).

  /tmp/venv/bin/python scenes/tools/make_mitsuba_bsdfs.py [name ...]
"""

import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import make_mitsuba_scenes as base  # noqa: E402  (sets the scalar_spectral variant)
import make_mitsuba_ztest_refs as refs  # noqa: E402

for kind in ("roughconductor", "roughdielectric", "plastic", "roughplastic", "principled",
             "principledthin", "thindielectric", "blendbsdf"):
    base.CLASSES[kind] = "bsdf"
base.CLASSES["checkerboard"] = "texture"


def checker(a, b):
    return {"type": "checkerboard", "color0": a, "color1": b}


# (small cube, large cube) per scene.
SCENES = {
    "dielectric": (
        {"type": "dielectric"},  # bk7 in air, Mitsuba's defaults
        {"type": "dielectric", "int_ior": "water", "ext_ior": "air"},
    ),
    "conductor": (
        {"type": "conductor", "material": "Au"},
        {"type": "conductor"},  # material "none": a perfect mirror
    ),
    "conductor-eta-k": (
        {"type": "conductor", "eta": 0.2, "k": 3.0},
        {"type": "conductor", "eta": 1.1, "k": 2.2},
    ),
    "roughconductor": (
        {"type": "roughconductor", "distribution": "ggx", "alpha": 0.1, "eta": 0.2, "k": 3.0},
        {"type": "roughconductor", "distribution": "ggx", "alpha": 0.4, "eta": 1.5, "k": 2.0},
    ),
    "roughdielectric": (
        {"type": "roughdielectric", "distribution": "ggx", "alpha": 0.1},
        {"type": "roughdielectric", "distribution": "ggx", "alpha": 0.3, "int_ior": 1.33},
    ),
    "plastic": (
        {"type": "plastic", "diffuse_reflectance": {"type": "rgb", "value": [0.2, 0.4, 0.8]}},
        {"type": "plastic", "int_ior": "bk7", "nonlinear": True},
    ),
    # Every lobe of Mitsuba's principled BSDF, parameters textured as the render suite's
    # test_texturedprincipled scenes (anisotropy along dp/du, Mitsuba's shading frame).
    "principled": (
        {"type": "principled", "base_color": {"type": "rgb", "value": [0.2, 0.8, 0.1]},
         "roughness": 0.3, "metallic": checker(0.7, 0.1), "clearcoat": checker(0.9, 0.1),
         "sheen": checker(0.2, 0.9), "specular": 0.7, "anisotropic": checker(0.05, 0.8)},
        {"type": "principled", "base_color": {"type": "rgb", "value": [0.3, 0.6, 0.8]},
         "roughness": 0.2, "spec_trans": checker(0.7, 0.1), "flatness": 0.4, "eta": 1.4},
    ),
    # Rough: a narrow transmission lobe focuses the light into caustics that 488 samples
    # per pixel resolve in neither renderer (Mitsuba fails its own z-test at roughness
    # 0.25). No spec_tint or sheen_tint: Mitsuba divides the tint by a luminance of the path's
    # few sampled wavelengths, which no other renderer's wavelength sampling reproduces.
    "principledthin": (
        {"type": "principledthin", "base_color": {"type": "rgb", "value": [0.7, 0.1, 0.1]},
         "spec_trans": checker(0.2, 0.8), "diff_trans": checker(0.4, 1.4),
         "sheen": checker(0.1, 0.8), "eta": 1.33, "roughness": 0.7},
        {"type": "principledthin", "base_color": {"type": "rgb", "value": [0.8, 0.7, 0.3]},
         "roughness": 0.6, "spec_trans": 0.5},
    ),
    "beckmann-conductor": (
        {"type": "roughconductor", "alpha": 0.1, "eta": 0.2, "k": 3.0},
        {"type": "roughconductor", "alpha": 0.4, "eta": 1.5, "k": 2.0},
    ),
    "beckmann-dielectric": (
        {"type": "roughdielectric", "alpha": 0.1},
        {"type": "roughdielectric", "alpha": 0.3, "int_ior": 1.33},
    ),
    "roughplastic": (
        {"type": "roughplastic",
         "diffuse_reflectance": {"type": "rgb", "value": [0.2, 0.4, 0.8]}},
        {"type": "roughplastic", "distribution": "ggx", "alpha": 0.3, "int_ior": "bk7",
         "nonlinear": True},
    ),
    "blendbsdf": (
        {"type": "blendbsdf", "weight": 0.3,
         "a": {"type": "diffuse", "reflectance": {"type": "rgb", "value": [0.8, 0.3, 0.1]}},
         "b": {"type": "roughconductor", "distribution": "ggx", "alpha": 0.2}},
        {"type": "blendbsdf", "weight": 0.7,
         "a": {"type": "plastic"},
         "b": {"type": "conductor", "material": "Au"}},
    ),
    "thindielectric": (
        {"type": "thindielectric"},
        {"type": "thindielectric", "int_ior": 1.8},
    ),
}


def scene(name):
    d = base.cornell_box()
    small, large = SCENES[name]
    d["small-box"]["bsdf"] = small
    d["large-box"]["bsdf"] = large
    d["sensor"]["film"]["width"] = d["sensor"]["film"]["height"] = 32
    return d


def main():
    out = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "mitsuba")
    names = sys.argv[1:] or list(SCENES)
    for name in names:
        path = os.path.join(out, f"bsdfs-{name}.xml")
        with open(path, "w") as f:
            f.write(f"<!-- Mitsuba 3's mi.cornell_box() with {name} cubes, written by "
                    "scenes/tools/make_mitsuba_bsdfs.py -->\n")
            f.write(base.scene_xml(scene(name)))
        print(f"wrote {path}")
        refs.main([path])


if __name__ == "__main__":
    main()
