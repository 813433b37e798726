"""scenes/cornell-medium.gltf in Mitsuba 3, rendered by `volpathmis` (the peers' spectral MIS
volumetric path tracer): the same Cornell box (Mitsuba's built-in `cornell_box()`, whose
geometry, colours, light and camera prism's glTF copies), its large box a null-BSDF shape
holding a homogeneous medium whose sigma_a and sigma_s are read from the glTF file, so both
renderers see the same spectra at the same nodes. Times a render, optionally writes it;
prints one JSON line as ../../../shared/scenes/peer/mitsuba_peer.py does.

  pip install mitsuba
  python3 benches/peer/mitsuba_media.py scalar_spectral media 64 --width 128 --out media.exr

(the same arguments as mitsuba_peer.py's, the scene always `media`).

Mitsuba's homogeneous medium takes sigma_t and the albedo sigma_s / sigma_t: both are given
per node, so between nodes Mitsuba interpolates the albedo where prism interpolates
sigma_s (10 nm nodes: the two differ by under 0.1%).
"""
import argparse, json, os, time

import mitsuba as mi

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def medium_spectra():
    with open(os.path.join(ROOT, "scenes", "cornell-medium.gltf")) as f:
        doc = json.load(f)
    for material in doc["materials"]:
        if material["name"] == "milky-dye":
            return material["extensions"]["PRISM_spectral"]["medium"]
    raise SystemExit("scenes/cornell-medium.gltf has no milky-dye material")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("variant"); ap.add_argument("scene", choices=["media"]); ap.add_argument("spp", type=int)
    ap.add_argument("--depth", type=int, default=-1); ap.add_argument("--width", type=int, default=256)
    ap.add_argument("--out"); ap.add_argument("--seed", type=int, default=1)
    a = ap.parse_args()
    mi.set_variant(a.variant)
    import drjit as dr
    medium = medium_spectra()
    sigma_a = dict((nm, v) for nm, v in medium["sigma_a"])
    sigma_s = dict((nm, v) for nm, v in medium["sigma_s"])
    nodes = sorted(sigma_a)
    sigma_t = [(nm, sigma_a[nm] + sigma_s[nm]) for nm in nodes]
    albedo = [(nm, sigma_s[nm] / (sigma_a[nm] + sigma_s[nm])) for nm in nodes]
    desc = mi.cornell_box()
    desc["integrator"] = {"type": "volpathmis", "max_depth": a.depth}
    desc["sensor"]["film"]["rfilter"] = {"type": "box"}
    desc["sensor"]["film"]["width"] = desc["sensor"]["film"]["height"] = a.width
    desc["large-box"]["bsdf"] = {"type": "null"}
    desc["large-box"]["interior"] = {
        "type": "homogeneous",
        "sigma_t": {"type": "spectrum", "value": sigma_t},
        "albedo": {"type": "spectrum", "value": albedo},
        "scale": 1.0,
        "phase": {"type": "hg", "g": float(medium["g"])},
    }
    scene = mi.load_dict(desc)
    img = mi.render(scene, spp=1); dr.eval(img)  # warm-up (JIT compilation for the LLVM variant)
    t = time.time(); img = mi.render(scene, spp=a.spp, seed=a.seed); dr.eval(img); dr.sync_thread(); dt = time.time() - t
    if a.out:
        mi.util.write_bitmap(a.out, img)
    print(json.dumps({"variant": a.variant, "scene": "media", "spp": a.spp, "depth": a.depth, "width": a.width,
                      "seconds": round(dt, 3), "paths_per_second": a.width * a.width * a.spp / dt}))


if __name__ == "__main__":
    main()
