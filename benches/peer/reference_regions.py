"""Region means of a converged Mitsuba 3 render, stored as a fixture for prism's
reference test (integrator/tests/reference.rs).

  pip install mitsuba numpy
  python3 ../shared/scenes/peer/mitsuba_peer.py scalar_spectral box 2048 --width 256 --out /tmp/box.exr
  python3 benches/peer/reference_regions.py /tmp/box.exr --spp 2048 \
      --out integrator/tests/data/cornell-box-mitsuba-regions.json
  python3 ../shared/scenes/peer/mitsuba_peer.py scalar_spectral bunny 2048 --width 256 --out /tmp/bunny.exr
  python3 benches/peer/reference_regions.py /tmp/bunny.exr --spp 2048 --scene bunny \
      --out integrator/tests/data/cornell-bunny-mitsuba-regions.json
  python3 benches/peer/mitsuba_media.py scalar_spectral media 2048 --width 128 --out /tmp/media.exr
  python3 benches/peer/reference_regions.py /tmp/media.exr --spp 2048 --scene media \
      --out integrator/tests/data/cornell-medium-mitsuba-regions.json
  python3 benches/peer/mitsuba_reference.py specular --width 128 --spp 8192 --out /tmp/specular.exr
  python3 benches/peer/reference_regions.py /tmp/specular.exr --spp 8192 --scene specular \
      --variant llvm_ad_spectral --out integrator/tests/data/cornell-specular-mitsuba-regions.json
  (and glossy, caustic, textured alike)

With a box pixel filter the mean of a region of the film is the integral of radiance over
that part of the film, whatever the resolution, so prism can be compared at a lower one.
"""
import argparse, json, sys

import numpy as np


# How each scene was made, after its name in the provenance.
SOURCES = {
    "box": "; rendered by ../shared/scenes/peer/mitsuba_peer.py",
    "bunny": "; boxes replaced by ../shared/scenes/peer/cornell-bunny.obj, diffuse rgb (0.8, 0.55, 0.2)"
             "; rendered by ../shared/scenes/peer/mitsuba_peer.py",
    "media": "; the large box a null BSDF holding scenes/cornell-medium.gltf's homogeneous medium"
             ", integrator volpathmis; rendered by benches/peer/mitsuba_media.py",
}
for kind in ("specular", "glossy", "caustic"):
    SOURCES[kind] = (f"; boxes replaced by the spheres of scenes/cornell-{kind}.gltf (mesh and materials read "
                     "from it); rendered by benches/peer/mitsuba_kinds.py")
# Scenes that are not Mitsuba's Cornell box: the whole description.
WHOLE = {
    "textured": "scenes/textured-sky.gltf read whole (meshes, sRGB textures, the gold conductor, the camera, "
                "scenes/sky.hdr resampled four times finer and turned by 90 degrees) by benches/peer/mitsuba_kinds.py",
}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("exr")
    ap.add_argument("--grid", type=int, default=8)
    ap.add_argument("--spp", type=int, required=True)
    ap.add_argument("--scene", default="box")
    ap.add_argument("--variant", default="scalar_spectral", help="the Mitsuba variant that rendered it")
    ap.add_argument("--out", required=True)
    a = ap.parse_args()
    import mitsuba as mi
    mi.set_variant("scalar_rgb")
    img = np.array(mi.Bitmap(a.exr), dtype=np.float64)[..., :3]
    h, w, _ = img.shape
    g = a.grid
    means = [[img[i * h // g:(i + 1) * h // g, j * w // g:(j + 1) * w // g].mean(axis=(0, 1)).tolist()
              for j in range(g)] for i in range(g)]
    scene = WHOLE.get(a.scene) or f"mitsuba.cornell_box() ({a.scene}{SOURCES.get(a.scene, SOURCES['box'])})"
    doc = {
        "provenance": f"Mitsuba {mi.__version__} {a.variant}, {scene}, "
                      f"{w}x{h}, {a.spp} spp, unbounded depth, box filter; linear sRGB region means "
                      f"(rows top to bottom), made by benches/peer/reference_regions.py",
        "grid": g, "width": w, "height": h, "spp": a.spp,
        "regions": means,
    }
    with open(a.out, "w") as f:
        json.dump(doc, f, indent=1)
        f.write("\n")


if __name__ == "__main__":
    main()
