#!/usr/bin/env python3
"""How much of path reuse's noise is shared within its tiles (the faint T x T blocks).

Renders SCENE under SEEDS seeds at each sample count, with reuse in tiles of T and
without, and splits each render's noise (its deviation from the mean over the seeds) into
what the pixels of a T x T tile share and what is each pixel's own: per tile and seed,
the tile's mean deviation is the shared part; the rest is per pixel. The mean pairwise
correlation of a tile's pixels follows from the two (`within`); the same statistic on
the grid shifted by T / 2, whose cells straddle tiles, is the correlation any neighbours
have (`across`). Prints, per sample count and mode, the shared part's standard
deviation and the per-pixel part's, both relative to the image's mean (luminance Y), and
the two correlations.

    pip install OpenEXR numpy
    python3 benches/tile_structure.py scenes/cornell-box.gltf --size 128 --spp 4,16,64,256 --seeds 8
"""
import argparse, os, subprocess, tempfile

import numpy as np
import OpenEXR

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def luminance(path):
    ch = OpenEXR.File(path, separate_channels=True).channels()
    r, g, b = (np.asarray(ch[c].pixels, dtype=np.float64) for c in "RGB")
    return 0.2126 * r + 0.7152 * g + 0.0722 * b


def split(images, t, offset):
    """(shared std, own std, mean pairwise correlation) of the deviations over cells of
    side t whose grid starts at `offset`."""
    dev = images - images.mean(axis=0)
    n, h, w = dev.shape
    rows, cols = (h - offset) // t, (w - offset) // t
    cells = dev[:, offset:offset + rows * t, offset:offset + cols * t].reshape(n, rows, t, cols, t)
    shared = cells.mean(axis=(2, 4), keepdims=True)
    own = cells - shared
    # n - 1 degrees of freedom in the seeds' deviations from their mean. For pixels of
    # variance s^2 and mean pairwise correlation rho, a cell's mean has variance
    # s^2 (1 + (t^2 - 1) rho) / t^2 and a pixel's deviation from it s^2 (1 - rho)
    # (t^2 - 1) / t^2: the shared part's variance is s^2 rho, the own part's s^2 (1 - rho).
    k = t * t
    var_mean = float((shared ** 2).sum() / ((n - 1) * rows * cols))
    var_within = float((own ** 2).sum() / ((n - 1) * rows * cols * k))
    common = var_mean - var_within / (k - 1)
    own_part = var_within * k / (k - 1)
    return np.sqrt(max(common, 0.0)), np.sqrt(own_part), common / (common + own_part)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("scene")
    ap.add_argument("--size", type=int, default=128)
    ap.add_argument("--spp", default="4,16,64,256")
    ap.add_argument("--seeds", type=int, default=8)
    ap.add_argument("--tile", type=int, default=4)
    ap.add_argument("--prism", default=os.path.join(ROOT, "target", "release", "prism"))
    a = ap.parse_args()
    t = a.tile
    print(f"{a.scene}, {a.size} x {a.size}, {a.seeds} seeds, tiles of {t}; standard deviations relative to the mean")
    print("| spp | reuse | shared in a tile | per pixel | correlation within tiles | across tiles |")
    print("|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "r.exr")
        for spp in [int(s) for s in a.spp.split(",")]:
            for reuse in (t, 1):
                images = []
                for seed in range(a.seeds):
                    subprocess.run([a.prism, "render", a.scene, "-o", out, "-q", "--width", str(a.size),
                                    "--height", str(a.size), "--spp", str(spp), "--seed", str(seed),
                                    "--splits", "1", "--reuse", str(reuse)], check=True)
                    images.append(luminance(out))
                images = np.array(images)
                mean = images.mean()
                c, own, rho = split(images, t, 0)
                _, _, rho_across = split(images, t, t // 2)
                print(f"| {spp} | {reuse} | {c / mean:.4f} | {own / mean:.4f} | {rho:.3f} | {rho_across:.3f} |")


if __name__ == "__main__":
    main()
