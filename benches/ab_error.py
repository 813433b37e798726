#!/usr/bin/env python3
"""Efficiency of two prism builds on one scene: error at equal samples, and time.

Renders SCENE with each build under seeds 0..SEEDS-1 (alternating builds), measures
each image's relative MSE against a converged render (the first build at 8192 spp, seed
999, made once into --out), and prints per build the mean relMSE, its spread over the
seeds, the median seconds and the efficiency 1 / (relMSE x seconds) relative to the
first build (the median relMSE too: where fireflies dominate, the mean is their
noise). For changes that alter images on purpose (sampling, estimators), where
`ab_render.py --same` cannot apply.

    pip install OpenEXR numpy
    python3 benches/ab_error.py OLD/prism NEW/prism --seeds 6 -- scenes/cornell-medium.gltf \
        --width 128 --height 128 --spp 64

A build may carry flags of its own ("target/release/prism --adaptive off" against
"target/release/prism": one build, two settings; more than two builds may be given),
and --reference names a converged image to measure against instead (a peer's, such as
Mitsuba's references of the scene kinds). --channels bands measures the spectral bands
(S0.*, with --spectral-bands) and --channels stokes the Stokes components S1 and S2 (with
--polarized) instead of RGB; their floor in the dark is relative, 0.01 times the
reference's mean squared, since their units are not the display's.
"""
import argparse, hashlib, json, os, shlex, subprocess, sys

import numpy as np
import OpenEXR


def read(path, kind="rgb"):
    channels = OpenEXR.File(path, separate_channels=True).channels()
    names = {
        "rgb": list("RGB"),
        "bands": sorted(c for c in channels if c.startswith("S0.") and c.endswith("nm")),
        "stokes": [f"S{k}.{c}" for k in (1, 2) for c in "RGB"],
    }[kind]
    if not names:
        sys.exit(f"ab_error: {path} has no {kind} channels")
    return np.stack([np.asarray(channels[c].pixels, dtype=np.float64) for c in names], -1)


def relmse(img, ref, kind="rgb"):
    """prism compare's relative MSE: noise relative to the reference, floored in the dark
    (for bands and Stokes components, relative to the reference's mean)."""
    floor = 0.01 if kind == "rgb" else 0.01 * float(np.mean(np.abs(ref))) ** 2
    return float(np.mean((img - ref) ** 2 / (ref ** 2 + floor)))


def main(argv):
    if "--" not in argv:
        sys.exit("ab_error: give the scene and render arguments after --")
    split = argv.index("--")
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("builds", nargs="+")
    ap.add_argument("--channels", choices=["rgb", "bands", "stokes"], default="rgb")
    ap.add_argument("--seeds", type=int, default=6)
    ap.add_argument("--out", default="ab-error")
    ap.add_argument("--reference", help="a converged image (EXR) to measure against")
    args = ap.parse_args(argv[:split])
    scene, *render_args = argv[split + 1:]
    os.makedirs(args.out, exist_ok=True)

    def render(build, path, *extra):
        exe, *flags = shlex.split(build)
        done = subprocess.run([exe, "render", scene, "-o", path, "-q", "--stats", *render_args, *flags, *extra],
                              check=True, capture_output=True, text=True)
        return json.loads((done.stdout.strip() or done.stderr.strip()).splitlines()[-1])

    stem = os.path.splitext(os.path.basename(scene))[0]
    key = hashlib.sha1(" ".join(render_args).encode()).hexdigest()[:8]
    reference = args.reference or os.path.join(args.out, f"reference-{stem}-{key}.exr")
    if not os.path.exists(reference):
        flags = list(render_args)
        if "--spp" in flags:
            del flags[flags.index("--spp"):flags.index("--spp") + 2]
        subprocess.run([*shlex.split(args.builds[0])[:1], "render", scene, "-o", reference, "-q", *flags,
                        "--spp", "8192", "--seed", "999"], check=True)
    if len(args.builds) < 2:
        sys.exit("ab_error: give at least two builds")
    ref = read(reference, args.channels)
    work = os.path.join(args.out, "render.exr")
    errors = {b: [] for b in args.builds}
    seconds = {b: [] for b in args.builds}
    for seed in range(args.seeds):
        for build in args.builds:
            stats = render(build, work, "--seed", str(seed))
            errors[build].append(relmse(read(work, args.channels), ref, args.channels))
            seconds[build].append(stats["seconds"])
    base = None
    for build in args.builds:
        e, t = np.mean(errors[build]), float(np.median(seconds[build]))
        efficiency = 1.0 / (e * t)
        base = base or efficiency
        spread = np.std(errors[build]) / np.sqrt(len(errors[build])) / e
        median = float(np.median(errors[build]))
        print(f"{build}: relMSE {e:.4e} (+-{100 * spread:.1f}%; median {median:.4e}), {t:.2f} s, "
              f"efficiency {efficiency / base:.3f}")


if __name__ == "__main__":
    main(sys.argv[1:])
