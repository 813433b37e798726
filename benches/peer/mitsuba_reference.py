"""A converged Mitsuba 3 reference of a shared scene, for time to equal error against an
independent renderer (issue 30): the mean of PASSES renders of SPP samples each with seeds
1000, 1001, ... (one render of 8192 spp at 256 x 256 would hold 537 M lanes in memory in the
LLVM variant).

  DRJIT_LIBLLVM_PATH=/usr/lib/x86_64-linux-gnu/libLLVM-19.so \
    python3 benches/peer/mitsuba_reference.py box --width 256 --spp 8192 --out ref-box.exr

Uses the Mitsuba script peers.py names for the scene, so the reference is the same
Mitsuba scene the timed renders use. Depth as there (-1: unbounded).

Beside OUT it writes the reference's own noise, the variance of the mean per pixel and
channel estimated from the passes (OUT with ".exr" replaced by ".variance.exr"):
compare.py subtracts what it adds to every renderer's error against the reference.
"""
import argparse, os, subprocess, sys, tempfile

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from peers import check_scene, is_xml, script as peer_script  # noqa: E402


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("scene", type=check_scene, help="a comparison scene, or a Mitsuba .xml file")
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
    total = squares = None
    with tempfile.TemporaryDirectory() as tmp:
        for k in range(passes):
            exr = os.path.join(tmp, "pass.exr")
            size = [] if is_xml(a.scene) else ["--width", str(a.width)]
            subprocess.run([sys.executable, peer_script(a.scene), a.variant,
                            a.scene, str(a.pass_spp), "--depth", str(a.depth), *size,
                            "--seed", str(1000 + k), "--out", exr], check=True, capture_output=True)
            img = np.array(mi.Bitmap(exr), dtype=np.float64)[..., :3]
            total = img if total is None else total + img
            squares = img ** 2 if squares is None else squares + img ** 2
            print(f"pass {k + 1}/{passes}", file=sys.stderr)
    mean = total / passes
    # The sample variance of one pass over the number of passes: the mean's variance.
    variance = np.maximum(squares / passes - mean ** 2, 0.0) * passes / max(passes - 1, 1) / passes
    for image, path in ((variance, variance_path(a.out)), (mean, a.out)):
        tmp_out = path + ".partial.exr"
        mi.Bitmap(image.astype(np.float32)).write(tmp_out)
        os.replace(tmp_out, path)


def variance_path(reference):
    """Where a reference's per-pixel variance of the mean is written beside it."""
    stem = reference[:-4] if reference.endswith(".exr") else reference
    return stem + ".variance.exr"


if __name__ == "__main__":
    main()
