"""What prism's error against a Mitsuba reference is made of: prism's own noise, the
reference's noise, and the two renderers' difference (what neither more samples of prism
nor of Mitsuba would remove). Time to equal error (compare.py) counts all three as prism's
error; where the third is a sizeable share, the two models differ there, and this says
where, region by region.

  pip install mitsuba numpy
  cargo build --release -p prism-cli
  python3 benches/peer/difference.py textured refs/ref-textured-128.exr --spp 1024

Renders the scene twice with prism (seeds 0 and 1, the reference's size): the two images'
difference measures prism's noise, the variance beside the reference (mitsuba_reference.py
writes it) the reference's, and what is left of the error is the difference of the
converged images. Prints one JSON object: the three parts of the relative MSE (compare.py's
measure) of one render, the share of the difference in each region of a GRID x GRID grid
(rows top to bottom), and the region means' ratios prism / reference per channel.
"""
import argparse, json, os, subprocess, sys, tempfile

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from compare import read_exr, reference_noise, relmse  # noqa: E402
from mitsuba_reference import variance_path  # noqa: E402
from peers import SCENES  # noqa: E402


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("scene", choices=SCENES)
    ap.add_argument("reference", help="a converged Mitsuba render of the scene (mitsuba_reference.py)")
    ap.add_argument("--spp", type=int, default=1024)
    ap.add_argument("--grid", type=int, default=8)
    ap.add_argument("--prism-args", default="", help="more arguments for prism render")
    a = ap.parse_args()
    ref = read_exr(a.reference)
    height, width = ref.shape[:2]
    if height % a.grid or width % a.grid:
        ap.error(f"--grid {a.grid} does not divide the reference's {width} x {height} pixels")
    prism = os.path.join(ROOT, "target", "release", "prism")
    images = []
    with tempfile.TemporaryDirectory() as tmp:
        for seed in (0, 1):
            out = os.path.join(tmp, f"prism-{seed}.exr")
            subprocess.run([prism, "render", os.path.join(ROOT, "scenes", SCENES[a.scene]), "--width", str(width),
                            "--height", str(height), "--spp", str(a.spp), "--seed", str(seed), "-o", out, "-q"]
                           + a.prism_args.split(), check=True, capture_output=True)
            images.append(read_exr(out))
    total = (relmse(images[0], ref) + relmse(images[1], ref)) / 2
    # Two independent renders differ by twice one render's variance.
    noise = relmse(images[0], images[1]) / 2
    ref_noise = reference_noise(a.reference, ref) or 0.0
    mean = (images[0] + images[1]) / 2
    # Per pixel: the mean image's squared difference, less what both noises add to it.
    floor = ref ** 2 + 0.01
    variance = (images[0] - images[1]) ** 2 / 4  # the mean's variance, per pixel
    if os.path.exists(variance_path(a.reference)):
        variance = variance + read_exr(variance_path(a.reference))
    part = ((mean - ref) ** 2 - variance) / floor
    g = a.grid
    shares = part.sum(axis=2).reshape(g, height // g, g, width // g).sum(axis=(1, 3))
    shares = shares / max(part.sum(), 1e-30)
    means = lambda img: img.reshape(g, height // g, g, width // g, 3).mean(axis=(1, 3))
    ratio = means(mean) / np.maximum(means(ref), 1e-12)
    print(json.dumps({
        "scene": a.scene, "spp": a.spp, "width": width, "height": height,
        "relmse": total, "prism_noise": noise, "reference_noise": ref_noise,
        "difference": total - noise - ref_noise,
        "difference_share_per_region": [[round(float(x), 4) for x in row] for row in shares],
        "region_ratio_rgb": [[[round(float(c), 4) for c in cell] for cell in row] for row in ratio],
        "image_mean_ratio": [float(x) for x in mean.mean(axis=(0, 1)) / ref.mean(axis=(0, 1))],
    }))


if __name__ == "__main__":
    main()
