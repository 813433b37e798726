"""Mitsuba 3's error-versus-time curve for a `prism trade` report, against the same reference.

  pip install mitsuba numpy
  prism trade scenes/cornell-box.gltf -o trade/box --spp 4,16,64,256 --width 128 --height 128
  python3 benches/peer/trade_peer.py box trade/box --spp 4,16,64,256 --width 128
  prism trade --report -o trade/box          # redraws plots and summary with the peer

Renders the scene with Mitsuba (../shared/scenes/peer/mitsuba_peer.py, the same Cornell box
and bunny box as the glTF files) at each sample count, computes the relative MSE of its
linear sRGB image against DIR/reference.exr exactly as prism trade does (mean over pixels
and channels of (x - ref)^2 / (ref^2 + 0.01)), and writes DIR/peer.csv. Times are
Mitsuba's own render time (scene loading and JIT excluded, as prism's exclude nothing but
process start-up); run it right after prism trade so both see the same machine load.
"""
import argparse, json, os, subprocess, sys, tempfile

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SHARED = os.environ.get("PRISM_SHARED", os.path.join(os.path.dirname(ROOT), "shared"))
NAMES = {"box": "cornell-box", "bunny": "cornell-bunny"}


def read_exr(path):
    import mitsuba as mi
    mi.set_variant("scalar_rgb")
    return np.array(mi.Bitmap(path), dtype=np.float64)[..., :3]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("scene", choices=NAMES)
    ap.add_argument("dir")
    ap.add_argument("--spp", default="4,16,64,256")
    ap.add_argument("--width", type=int, default=128)
    ap.add_argument("--variants", default="scalar_spectral")
    ap.add_argument("--repeat", type=int, default=1, help="renders per point (seeds 1..N); medians are kept")
    a = ap.parse_args()
    reference = read_exr(os.path.join(a.dir, "reference.exr"))
    rows = ["scene,sweep,setting,spp,seconds,setup_seconds,relmse,repeats"]
    out = tempfile.mkdtemp(prefix="prism-trade-peer-")
    for variant in a.variants.split(","):
        for spp in sorted(int(s) for s in a.spp.split(",")):
            times, errors = [], []
            for seed in range(1, a.repeat + 1):
                exr = os.path.join(out, f"{variant}-{spp}-{seed}.exr")
                run = subprocess.run([sys.executable, os.path.join(SHARED, "scenes", "peer", "mitsuba_peer.py"),
                                      variant, a.scene, str(spp), "--width", str(a.width), "--out", exr,
                                      "--seed", str(seed)],
                                     check=True, capture_output=True, text=True)
                times.append(json.loads(run.stdout.strip().splitlines()[-1])["seconds"])
                image = read_exr(exr)
                errors.append(float(np.mean((image - reference) ** 2 / (reference ** 2 + 1e-2))))
            rows.append(f"{NAMES[a.scene]},peer,mitsuba {variant},{spp},{np.median(times):.6f},0,"
                        f"{np.median(errors):.6e},{a.repeat}")
            print(rows[-1], file=sys.stderr)
    with open(os.path.join(a.dir, "peer.csv"), "w") as f:
        f.write("\n".join(rows) + "\n")


if __name__ == "__main__":
    main()
