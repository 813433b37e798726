"""What denoising does, measured: per scene, the relative MSE of the noisy and the denoised
render against a converged one, the largest shift of a region's mean, and for scenes whose
colours are spectral (the rainbow, the effects stage's dispersion and fluorescence) the
CIEDE2000 difference from the converged image where it is most saturated (the most
saturated tenth of the lit pixels).

  python3 -m venv /tmp/dn && /tmp/dn/bin/pip install pyoidn OpenEXR colour-science
  PRISM_OIDN=$(ls /tmp/dn/lib/python3*/site-packages/pyoidn/oidn/lib/libOpenImageDenoise.so.2) \\
      /tmp/dn/bin/python benches/denoise/measure.py --prism target/release/prism --spp 16 --seeds 2

Prints one JSON object; docs/trade-offs.md ("Denoising") quotes it. References are prism's
own renders at --reference-spp (unbiased against Mitsuba 3 on these scenes: the peer tests).
"""
import argparse, json, os, subprocess, tempfile

import numpy as np
import OpenEXR
import colour

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SCENES = {
    "cornell-box": ["scenes/cornell-box.gltf"],
    "effects": [],  # the embedded effects stage: dispersion, fluorescence, thin film
    "prism": ["scenes/prism.gltf"],  # a spectrum cast by a glass prism on a wall
    "rainbow": ["scenes/rainbow.gltf"],  # a water droplet's bows
}


def channels(path):
    ch = OpenEXR.File(path).channels()
    rgba = ch["RGBA"].pixels.astype(np.float64)
    noisy = ch["noisy"].pixels.astype(np.float64) if "noisy" in ch else None
    return rgba[..., :3], noisy


def render(prism, scene, size, spp, seed, out, extra):
    subprocess.run([prism, "render", *SCENES[scene], "--width", str(size), "--height", str(size), "--spp",
                    str(spp), "--seed", str(seed), "-q", "-o", out, *extra], check=True)


def relmse(a, ref):
    return float(np.mean((a - ref) ** 2 / (ref ** 2 + 0.01)))


def regions(a, grid=8):
    h, w, _ = a.shape
    return a[: h // grid * grid, : w // grid * grid].reshape(grid, h // grid, grid, w // grid, 3).mean(axis=(1, 3))


def delta_e(a, ref, mask):
    """Mean CIEDE2000 between linear sRGB images a and ref over mask (D65, Y scaled so the
    reference's brightest masked pixel has Y = 1)."""
    to_lab = lambda rgb: colour.XYZ_to_Lab(colour.RGB_to_XYZ(rgb, "sRGB", apply_cctf_decoding=False))
    scale = 1.0 / max(colour.RGB_to_XYZ(ref[mask], "sRGB", apply_cctf_decoding=False)[..., 1].max(), 1e-9)
    return float(np.mean(colour.delta_E(to_lab(a[mask] * scale), to_lab(ref[mask] * scale), method="CIE 2000")))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--prism", default=os.path.join(ROOT, "target/release/prism"))
    ap.add_argument("--size", type=int, default=128)
    ap.add_argument("--spp", type=int, default=16)
    ap.add_argument("--seeds", type=int, default=2)
    ap.add_argument("--reference-spp", type=int, default=2048)
    ap.add_argument("--scenes", default=",".join(SCENES))
    a = ap.parse_args()
    cpu = next((l.split(":", 1)[1].strip() for l in open("/proc/cpuinfo") if l.startswith("model name")), "unknown")
    result = {"cpu": cpu, "size": a.size, "spp": a.spp, "seeds": a.seeds, "scenes": {}}
    with tempfile.TemporaryDirectory() as tmp:
        for scene in a.scenes.split(","):
            ref_path = os.path.join(tmp, f"{scene}-ref.exr")
            render(a.prism, scene, a.size, a.reference_spp, 99, ref_path, [])
            ref, _ = channels(ref_path)
            # The most saturated tenth of the lit pixels: where spectral colours are.
            lum = ref @ np.array([0.2126, 0.7152, 0.0722])
            chroma = (ref.max(axis=-1) - ref.min(axis=-1)) / np.maximum(ref.max(axis=-1), 1e-9)
            lit = lum > 0.05 * lum.max()
            mask = lit & (chroma >= np.quantile(chroma[lit], 0.9))
            rows = []
            for seed in range(a.seeds):
                out = os.path.join(tmp, f"{scene}-{seed}.exr")
                render(a.prism, scene, a.size, a.spp, seed, out, ["--denoise"])
                den, noisy = channels(out)
                shift = np.abs(regions(den) - regions(noisy)) / np.maximum(regions(noisy), 1e-9)
                bright = regions(ref) > 0.05 * regions(ref).max()
                rows.append({
                    "relmse_noisy": relmse(noisy, ref), "relmse_denoised": relmse(den, ref),
                    "largest_region_shift": float(shift[bright].max()),
                    "delta_e2000_noisy": delta_e(noisy, ref, mask),
                    "delta_e2000_denoised": delta_e(den, ref, mask),
                })
            mean = {k: float(np.mean([r[k] for r in rows])) for k in rows[0]}
            mean["relmse_ratio"] = mean["relmse_noisy"] / mean["relmse_denoised"]
            result["scenes"][scene] = mean
    print(json.dumps(result, indent=1))


if __name__ == "__main__":
    main()
