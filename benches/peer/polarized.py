"""prism's polarized renders against Mitsuba 3's, Stokes component by component.

  pip install mitsuba numpy
  cargo build --release -p prism-cli
  python3 benches/peer/polarized.py --spp 1024 --width 128

The scene: Mitsuba's built-in Cornell box (the repository's scenes/cornell-box.gltf, its
walls made Lambertian like Mitsuba's) with its two boxes replaced by a smooth glass sphere (index 1.5) and a smooth metal sphere
(complex index 0.2 + 3i at every wavelength), both the same triangle mesh with vertex
normals in the two renderers (written here as glTF for prism and OBJ for Mitsuba). Mitsuba
renders it with `scalar_spectral_polarized` and its `stokes` integrator around `path`
(unbounded depth); prism with `--polarized` (no light paths: polarized prism leaves
caustics to camera paths, as Mitsuba's path tracer does). Both write S0..S3 as linear
sRGB images in the same frame: x = ray x camera up, the image's rows.

For each Stokes component and colour channel the image is cut into GRID x GRID regions
and their means compared (regions whose S0 has at least 2% of the brightest's): the
difference of the renderers' means divided by the region's S0, and divided by its
standard error, estimated from SEEDS independent renders per renderer (z). Agreement
within noise shows as a median |z| near 0.7 and a mean z^2 near 1 (somewhat above: the
errors are themselves estimated from few seeds), with no region far out. Prints one
JSON object; --keep DIR keeps the scene and the images (prism's EXR, Mitsuba's .npy).
"""
import argparse, base64, json, math, os, struct, subprocess, sys, tempfile, time

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
GLASS = ((-0.42, -0.6, -0.2), 0.4)
METAL = ((0.45, -0.62, 0.3), 0.38)
ETA_METAL, K_METAL = 0.2, 3.0
COMPONENTS = ["S0", "S1", "S2", "S3"]


def sphere(centre, radius, rings=64, segments=128):
    """Positions, normals and triangle indices of a UV sphere."""
    pos, nor, idx = [], [], []
    for i in range(rings + 1):
        theta = math.pi * i / rings
        for j in range(segments + 1):
            phi = 2 * math.pi * j / segments
            n = (math.sin(theta) * math.cos(phi), math.cos(theta), math.sin(theta) * math.sin(phi))
            nor.append(n)
            pos.append(tuple(c + radius * x for c, x in zip(centre, n)))
    for i in range(rings):
        for j in range(segments):
            a, b = i * (segments + 1) + j, (i + 1) * (segments + 1) + j
            # Counter-clockwise seen from outside.
            if i != 0:
                idx.append((a, a + 1, b))
            if i != rings - 1:
                idx.append((a + 1, b + 1, b))
    return pos, nor, idx


def write_obj(path, mesh):
    pos, nor, idx = mesh
    with open(path, "w") as f:
        for p in pos:
            f.write("v %.7f %.7f %.7f\n" % p)
        for n in nor:
            f.write("vn %.7f %.7f %.7f\n" % n)
        for t in idx:
            f.write("f " + " ".join("%d//%d" % (k + 1, k + 1) for k in t) + "\n")


def prism_scene(path, glass, metal):
    """scenes/cornell-box.gltf without its boxes, with the two spheres added."""
    with open(os.path.join(ROOT, "scenes", "cornell-box.gltf")) as f:
        doc = json.load(f)
    with open(os.path.join(ROOT, "scenes", doc["buffers"][0]["uri"]), "rb") as f:
        data = bytearray(f.read())
    doc["buffers"][0]["uri"] = os.path.basename(path) + ".bin"
    keep = [i for i, n in enumerate(doc["nodes"]) if n.get("name") not in ("small-box", "large-box")]
    doc["nodes"] = [doc["nodes"][i] for i in keep]
    doc["scenes"][0]["nodes"] = list(range(len(doc["nodes"])))
    # The walls as Mitsuba has them, Lambertian (glTF's metallic-roughness has a glossy
    # coating, which polarizes a little in prism; Mitsuba's diffuse does not).
    for m in doc["materials"]:
        if "emitter" not in m["name"]:
            rgb = m["pbrMetallicRoughness"]["baseColorFactor"][:3]
            m.setdefault("extensions", {})["PRISM_spectral"] = {"type": "diffuse", "reflectance": {"rgb": rgb}}
    doc["materials"] += [
        {"name": "glass", "extensions": {"PRISM_spectral": {"type": "dielectric", "ior": 1.5}}},
        {"name": "metal", "extensions": {"PRISM_spectral": {"type": "conductor", "eta": ETA_METAL, "k": K_METAL}}},
    ]
    doc.setdefault("extensionsUsed", []).append("PRISM_spectral")
    for name, mesh, material in (("glass", glass, len(doc["materials"]) - 2), ("metal", metal, len(doc["materials"]) - 1)):
        pos, nor, idx = mesh
        accessors = []
        for kind, values, fmt, count_type, target in (
            ("pos", pos, "<3f", "VEC3", 34962),
            ("nor", nor, "<3f", "VEC3", 34962),
            ("idx", [k for t in idx for k in t], "<I", "SCALAR", 34963),
        ):
            while len(data) % 4:
                data.append(0)
            offset = len(data)
            for v in values:
                data += struct.pack(fmt, *(v if isinstance(v, tuple) else (v,)))
            doc["bufferViews"].append({"buffer": 0, "byteOffset": offset, "byteLength": len(data) - offset, "target": target})
            accessor = {"bufferView": len(doc["bufferViews"]) - 1, "componentType": 5126 if kind != "idx" else 5125,
                        "count": len(values), "type": count_type}
            if kind == "pos":
                accessor["min"] = [min(p[k] for p in pos) for k in range(3)]
                accessor["max"] = [max(p[k] for p in pos) for k in range(3)]
            doc["accessors"].append(accessor)
            accessors.append(len(doc["accessors"]) - 1)
        doc["meshes"].append({"name": name, "primitives": [{"attributes": {"POSITION": accessors[0], "NORMAL": accessors[1]},
                                                            "indices": accessors[2], "material": material}]})
        doc["nodes"].append({"name": name, "mesh": len(doc["meshes"]) - 1})
        doc["scenes"][0]["nodes"].append(len(doc["nodes"]) - 1)
    doc["buffers"][0]["byteLength"] = len(data)
    with open(path + ".bin", "wb") as f:
        f.write(data)
    with open(path, "w") as f:
        json.dump(doc, f)


def mitsuba_render(objs, spp, width, seed):
    import mitsuba as mi
    mi.set_variant("scalar_spectral_polarized")
    desc = mi.cornell_box()
    del desc["small-box"], desc["large-box"]
    desc["glass"] = {"type": "obj", "filename": objs[0], "face_normals": False,
                     "bsdf": {"type": "dielectric", "int_ior": 1.5, "ext_ior": 1.0}}
    desc["metal"] = {"type": "obj", "filename": objs[1], "face_normals": False,
                     "bsdf": {"type": "conductor", "eta": ETA_METAL, "k": K_METAL}}
    desc["integrator"] = {"type": "stokes", "nested": {"type": "path", "max_depth": -1}}
    desc["sensor"]["film"]["rfilter"] = {"type": "box"}
    desc["sensor"]["film"]["width"] = desc["sensor"]["film"]["height"] = width
    scene = mi.load_dict(desc)
    t = time.time()
    img = np.array(mi.render(scene, spp=spp, seed=seed), dtype=np.float64)
    seconds = time.time() - t
    names = scene.integrator().aov_names()
    # The film's channels: R, G, B, (A), then the AOVs in order.
    first = img.shape[2] - len(names)
    stokes = {}
    for c, name in enumerate(names):
        stokes[name] = img[..., first + c]
    return np.stack([np.stack([stokes[f"{s}.{ch}"] for ch in "RGB"], axis=-1) for s in COMPONENTS]), seconds


def prism_render(gltf, spp, width, seed, out):
    exe = os.path.join(ROOT, "target", "release", "prism")
    cmd = [exe, "render", gltf, "--width", str(width), "--height", str(width), "--spp", str(spp), "--seed", str(seed),
           "--polarized", "-o", out, "--quiet", "--stats"]
    t = time.time()
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
    seconds = time.time() - t
    import mitsuba as mi
    mi.set_variant("scalar_rgb")
    bitmap = mi.Bitmap(out)
    channels = dict(bitmap.split())
    def plane(name):
        return np.array(channels[name], dtype=np.float64)
    stokes = []
    for s in COMPONENTS:
        layer = np.array(channels[s], dtype=np.float64) if s in channels else None
        stokes.append(layer[..., :3])
    return np.stack(stokes), seconds


def regions(img, grid):
    h, w = img.shape[:2]
    return np.array([[img[i * h // grid:(i + 1) * h // grid, j * w // grid:(j + 1) * w // grid].mean(axis=(0, 1))
                      for j in range(grid)] for i in range(grid)])


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--spp", type=int, default=1024)
    ap.add_argument("--width", type=int, default=128)
    ap.add_argument("--grid", type=int, default=8)
    ap.add_argument("--seeds", type=int, default=4)
    ap.add_argument("--keep", help="directory to keep the scene and images in")
    a = ap.parse_args()
    work = a.keep or tempfile.mkdtemp(prefix="prism-polarized-")
    os.makedirs(work, exist_ok=True)
    glass, metal = sphere(*GLASS), sphere(*METAL)
    objs = [os.path.join(work, "glass.obj"), os.path.join(work, "metal.obj")]
    write_obj(objs[0], glass)
    write_obj(objs[1], metal)
    gltf = os.path.join(work, "cornell-polarized.gltf")
    prism_scene(gltf, glass, metal)
    runs = {"prism": [], "mitsuba": []}
    seconds = {"prism": 0.0, "mitsuba": 0.0}
    seeds = list(range(1, a.seeds + 1))
    for seed in seeds:
        img, t = prism_render(gltf, a.spp, a.width, seed, os.path.join(work, f"prism-{seed}.exr"))
        runs["prism"].append(img); seconds["prism"] += t
        img, t = mitsuba_render(objs, a.spp, a.width, seed)
        runs["mitsuba"].append(img); seconds["mitsuba"] += t
        np.save(os.path.join(work, f"mitsuba-{seed}.npy"), img)
        print(f"seed {seed} done", file=sys.stderr)
    g = a.grid
    # [renderer] -> (seeds, 4, g, g, 3) region means.
    reg = {k: np.stack([np.stack([regions(c, g) for c in run]) for run in v]) for k, v in runs.items()}
    mean = {k: v.mean(axis=0) for k, v in reg.items()}
    # The variance of each renderer's mean over its seeds.
    var = {k: v.var(axis=0, ddof=1) / len(seeds) for k, v in reg.items()}
    diff = mean["prism"] - mean["mitsuba"]
    err = np.sqrt(var["prism"] + var["mitsuba"])
    s0 = mean["mitsuba"][0]
    signal = s0 > 0.02 * s0.max()
    result = {"spp_per_seed": a.spp, "seeds": len(seeds), "width": a.width, "grid": g, "seconds": seconds,
              "work": work}
    for k, name in enumerate(COMPONENTS):
        scaled = np.abs(diff[k])[signal] / s0[signal]
        # Regions where neither renderer sees any of this component (S1..S3 of walls
        # lit only by diffuse light) have no error to divide by and no difference.
        live = err[k][signal] > 1e-6 * s0[signal]
        z = np.abs(diff[k])[signal][live] / err[k][signal][live]
        entry = {"max_diff_over_s0": float(scaled.max()), "mean_diff_over_s0": float(scaled.mean()),
                 "regions": int(live.sum()), "median_abs_z": float(np.median(z)), "mean_z2": float((z ** 2).mean()),
                 "max_z": float(z.max()), "share_above_3": float((z > 3).mean()),
                 "prism_mean_over_s0": float((mean["prism"][k][signal] / s0[signal]).mean()),
                 "mitsuba_mean_over_s0": float((mean["mitsuba"][k][signal] / s0[signal]).mean()),
                 "max_abs_over_s0": float((np.abs(mean["mitsuba"][k])[signal] / s0[signal]).max())}
        result[name] = entry
    print(json.dumps(result, indent=1))


if __name__ == "__main__":
    main()
