"""A Mitsuba 3 scene file rendered by Mitsuba 3 itself, for compare.py's XML scenes: the
file as it stands (its film's size, its integrator and depth), with the samples and seed
compare.py asks for. Times a render, optionally writes it; prints one JSON line as the
other peer scripts do.

  pip install mitsuba
  python3 benches/peer/mitsuba_xml.py scalar_spectral scene.xml 64 --out scene.exr

The file's `<default>` parameters `spp` and `integrator` are set as Mitsuba's own render
suite sets them (`integrator` from the file name's last word, `scene_path.xml` -> `path`,
when the file declares it). --depth and --width are accepted for compare.py's sake and must
be left at -1 and the film's own width: a Mitsuba file says its own.
"""
import argparse, json, os, re, time

import mitsuba as mi


def parameters(path, spp):
    """The suite's parameters the file declares as <default>s."""
    text = open(path).read()
    declared = set(re.findall(r'<default\s+name="([^"]+)"', text))
    out = {}
    if "spp" in declared:
        out["spp"] = str(spp)
    if "integrator" in declared:
        out["integrator"] = os.path.splitext(os.path.basename(path))[0].rsplit("_", 1)[-1]
    return out


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("variant"); ap.add_argument("scene"); ap.add_argument("spp", type=int)
    ap.add_argument("--depth", type=int, default=-1); ap.add_argument("--width", type=int)
    ap.add_argument("--out"); ap.add_argument("--seed", type=int, default=1)
    a = ap.parse_args()
    mi.set_variant(a.variant)
    import drjit as dr
    scene = mi.load_file(a.scene, **parameters(a.scene, a.spp))
    width, height = scene.sensors()[0].film().crop_size()
    if a.depth != -1 or (a.width is not None and a.width != width):
        raise SystemExit(f"{a.scene}: a Mitsuba file says its own depth and size")
    img = mi.render(scene, spp=1); dr.eval(img)  # warm-up (JIT compilation for the LLVM variant)
    t = time.time(); img = mi.render(scene, spp=a.spp, seed=a.seed); dr.eval(img); dr.sync_thread(); dt = time.time() - t
    if a.out:
        mi.util.write_bitmap(a.out, img)
    print(json.dumps({"variant": a.variant, "scene": a.scene, "spp": a.spp, "depth": a.depth, "width": int(width),
                      "height": int(height), "seconds": round(dt, 3), "paths_per_second": width * height * a.spp / dt}))


if __name__ == "__main__":
    main()
