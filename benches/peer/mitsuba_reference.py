"""A converged Mitsuba 3 reference of a shared scene, for time to equal error against an
independent renderer (issue 30): the mean of PASSES renders of SPP samples each with seeds
1000, 1001, ... (one render of 8192 spp at 256 x 256 would hold 537 M lanes in memory in the
LLVM variant).

  DRJIT_LIBLLVM_PATH=/usr/lib/x86_64-linux-gnu/libLLVM-19.so \
    python3 benches/peer/mitsuba_reference.py box --width 256 --spp 8192 --out ref-box.exr

Uses the Mitsuba script peers.py names for the scene, so the reference is the same
Mitsuba scene the timed renders use. Depth as there (-1: unbounded).
"""
import argparse, os, subprocess, sys, tempfile

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from peers import SCENES, script as peer_script  # noqa: E402


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("scene", choices=SCENES)
    ap.add_argument("--width", type=int, default=256)
    ap.add_argument("--spp", type=int, default=8192)
    ap.add_argument("--pass-spp", type=int, default=256)
    ap.add_argument("--depth", type=int, default=-1)
    ap.add_argument("--variant", default="llvm_ad_spectral")
    ap.add_argument("--out", required=True)
    a = ap.parse_args()
    import mitsuba as mi
    mi.set_variant("scalar_rgb")
    passes = max(1, a.spp // a.pass_spp)
    total = None
    with tempfile.TemporaryDirectory() as tmp:
        for k in range(passes):
            exr = os.path.join(tmp, "pass.exr")
            subprocess.run([sys.executable, peer_script(a.scene), a.variant,
                            a.scene, str(a.pass_spp), "--depth", str(a.depth), "--width", str(a.width),
                            "--seed", str(1000 + k), "--out", exr], check=True, capture_output=True)
            img = np.array(mi.Bitmap(exr), dtype=np.float64)[..., :3]
            total = img if total is None else total + img
            print(f"pass {k + 1}/{passes}", file=sys.stderr)
    mean = (total / passes).astype(np.float32)
    tmp_out = a.out + ".partial.exr"
    mi.Bitmap(mean).write(tmp_out)
    os.replace(tmp_out, a.out)


if __name__ == "__main__":
    main()
