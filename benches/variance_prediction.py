#!/usr/bin/env python3
"""How well the variance AOV predicts a render's squared error, and what recording it costs.

For each sample count, renders SCENE under seeds 0..SEEDS-1 with `--aov variance` and
compares the mean of the variance layer with the mean squared error against prism's own
converged render (8192 spp, seed 999, made once into --out). With --cost it also renders
each seed without the buffer and reports the ratio of squared errors (the price of the
two independently scrambled halves the buffer needs).

    pip install OpenEXR numpy
    python3 benches/variance_prediction.py scenes/cornell-box.gltf --size 64 --spp 16,64 \
        --seeds 16 --cost
"""
import argparse, os, subprocess, sys

import numpy as np
import OpenEXR

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def read(path, layer=""):
    channels = OpenEXR.File(path, separate_channels=True).channels()
    prefix = layer + "." if layer else ""
    return np.stack([np.asarray(channels[prefix + c].pixels, dtype=np.float64) for c in "RGB"], -1)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("scene")
    ap.add_argument("--size", type=int, default=64)
    ap.add_argument("--spp", default="16,64")
    ap.add_argument("--seeds", type=int, default=16)
    ap.add_argument("--cost", action="store_true")
    ap.add_argument("--prism", default=os.path.join(ROOT, "target", "release", "prism"))
    ap.add_argument("--out", default="variance-prediction")
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)

    def render(path, spp, seed, *extra):
        size = str(args.size)
        subprocess.run([args.prism, "render", args.scene, "-o", path, "--width", size, "--height", size,
                        "--spp", str(spp), "--seed", str(seed), "-q", *extra], check=True)

    name = os.path.splitext(os.path.basename(args.scene))[0]
    reference = os.path.join(args.out, f"reference-{name}-{args.size}.exr")
    if not os.path.exists(reference):
        render(reference, 8192, 999)
    ref = read(reference)
    work = os.path.join(args.out, "render.exr")
    for spp in (int(s) for s in args.spp.split(",")):
        predicted, measured, plain = [], [], []
        for seed in range(args.seeds):
            render(work, spp, seed, "--aov", "variance")
            predicted.append(read(work, "variance").mean())
            measured.append(((read(work) - ref) ** 2).mean())
            if args.cost:
                render(work, spp, seed)
                plain.append(((read(work) - ref) ** 2).mean())
        predicted, measured = np.array(predicted), np.array(measured)
        line = (f"{name} {args.size}x{args.size} {spp} spp, {args.seeds} seeds: buffer / squared error "
                f"{predicted.sum() / measured.sum():.3f} (per seed {np.min(predicted / measured):.2f}"
                f"-{np.max(predicted / measured):.2f})")
        if plain:
            line += f"; squared error with the buffer / without {measured.sum() / sum(plain):.3f}"
        print(line, flush=True)


if __name__ == "__main__":
    sys.exit(main())
