#!/usr/bin/env python3
"""Renders Mitsuba 3's references for prism's per-pixel z-tests of Mitsuba scenes.

For each scene file scenes/mitsuba/<name>.xml given, Mitsuba 3 (pip, `scalar_spectral`)
renders the file as it stands with its integrator wrapped in Mitsuba's `moment`
integrator, as Mitsuba's own render suite makes its references (`render_ref_images` in
src/render/tests/test_renders.py of mitsuba-renderer/mitsuba3), and writes

    scenes/mitsuba/references/<name>-ref.exr   the mean, linear sRGB
    scenes/mitsuba/references/<name>-var.exr   the per-sample variance, the same way

cli/tests/mitsuba_ztests.rs and benches/peer/mitsuba_suite.py z-test prism's render of
the same file against them.

  /tmp/venv/bin/python scenes/tools/make_mitsuba_ztest_refs.py scenes/mitsuba/NAME.xml ... [--spp N]
"""

import argparse
import os

import mitsuba as mi
import numpy as np

mi.set_variant("scalar_spectral")


def xyz_to_rgb(array):
    bitmap = mi.Bitmap(np.ascontiguousarray(array, dtype=np.float32), mi.Bitmap.PixelFormat.XYZ)
    return bitmap.convert(mi.Bitmap.PixelFormat.RGB, mi.Struct.Type.Float32, False)


def render(path, spp, seed):
    scene = mi.load_file(path)
    moment = mi.load_dict({"type": "moment", "nested": scene.integrator()})
    moment.render(scene, seed=seed, spp=spp, develop=False)
    bitmap = scene.sensors()[0].film().bitmap(raw=False)
    # The moment integrator's AOVs beside the developed image (`<root>`): the nested
    # integrator's mean and its second moment (`m2_` + the same name), both in XYZ; the
    # per-sample variance is their difference.
    parts = {name: np.array(image, copy=True) for name, image in bitmap.split()}
    second = next(name for name in parts if name.startswith("m2_"))
    mean = parts[second[len("m2_"):]]
    return mean, parts[second] - mean * mean


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("scenes", nargs="+")
    parser.add_argument("--spp", type=int, default=32768)
    parser.add_argument("--seed", type=int, default=0)
    args = parser.parse_args(argv)
    for path in args.scenes:
        name = os.path.splitext(os.path.basename(path))[0]
        out = os.path.join(os.path.dirname(os.path.abspath(path)), "references")
        os.makedirs(out, exist_ok=True)
        mean, variance = render(path, args.spp, args.seed)
        for suffix, image in (("ref", mean), ("var", variance)):
            target = os.path.join(out, f"{name}-{suffix}.exr")
            xyz_to_rgb(image).write(target)
            print(f"wrote {target} (Mitsuba {mi.__version__} scalar_spectral, {args.spp} spp)")


if __name__ == "__main__":
    main()
