"""The scene kinds in Mitsuba 3, rendered by its `path` integrator. `textured`
(scenes/textured-sky.gltf, written by scenes/tools/make_textured_sky.py) is read whole
from its file: meshes with texture coordinates, Lambertian materials with their sRGB
base colour textures, the gold conductor, the camera and scenes/sky.hdr (resampled four
times finer: `resampled_sky`). The Cornell box's
kinds (scenes/cornell-specular.gltf, -glossy, -caustic, -plastic, written by
scenes/tools/make_cornell_kinds.py) are
Mitsuba's built-in `cornell_box()` (whose walls, light and camera prism's glTF copies)
without its two boxes, plus the glTF file's spheres, read from the file itself: the mesh
(positions, smooth normals, triangles) as a PLY file, placed by the node's translation and
scale, and each material from its `PRISM_spectral` description (a dielectric's index, a
conductor's eta and k tables, a plastic's reflectance and index, GGX alpha = roughness^2
for rough ones). Times a render,
optionally writes it; prints one JSON line as ../../../shared/scenes/peer/mitsuba_peer.py
does.

  pip install mitsuba numpy
  python3 benches/peer/mitsuba_kinds.py scalar_spectral specular 64 --width 128 --out s.exr
"""
import argparse, base64, json, os, struct, tempfile, time

import numpy as np
import mitsuba as mi

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
KINDS = ("specular", "glossy", "caustic", "textured", "plastic")
SKY = os.path.join(ROOT, "scenes", "sky.hdr")
# How much finer than scenes/sky.hdr the sky Mitsuba is given is (`resampled_sky`).
SKY_FACTOR = 4
SHARED_NODES = {"light", "floor", "ceiling", "back", "green-wall", "red-wall", "camera"}


def accessor(doc, blobs, index, dtype, width):
    a = doc["accessors"][index]
    view = doc["bufferViews"][a["bufferView"]]
    blob = blobs[view["buffer"]]
    start = view.get("byteOffset", 0) + a.get("byteOffset", 0)
    count = a["count"] * width
    return np.frombuffer(blob, dtype=dtype, count=count, offset=start).reshape(-1, width) if width > 1 else \
        np.frombuffer(blob, dtype=dtype, count=count, offset=start)


def ply(path, positions, normals, indices, uvs=None):
    faces = indices.reshape(-1, 3)
    columns = [positions, normals] + ([uvs] if uvs is not None else [])
    with open(path, "wb") as f:
        f.write((f"ply\nformat binary_little_endian 1.0\nelement vertex {len(positions)}\n"
                 "property float x\nproperty float y\nproperty float z\n"
                 "property float nx\nproperty float ny\nproperty float nz\n" +
                 ("property float u\nproperty float v\n" if uvs is not None else "") +
                 f"element face {len(faces)}\nproperty list uchar int vertex_indices\nend_header\n").encode())
        f.write(np.hstack(columns).astype("<f4").tobytes())
        for a, b, c in faces:
            f.write(struct.pack("<B3i", 3, int(a), int(b), int(c)))


def spectrum(table):
    if isinstance(table, (int, float)):
        return float(table)
    return {"type": "spectrum", "value": [(float(nm), float(v)) for nm, v in table]}


def bsdf(desc):
    alpha = float(desc.get("roughness", 0.0)) ** 2
    if desc["type"] == "dielectric":
        ior = float(desc["ior"])
        if alpha:
            return {"type": "roughdielectric", "distribution": "ggx", "alpha": alpha, "int_ior": ior, "ext_ior": 1.0}
        return {"type": "dielectric", "int_ior": ior, "ext_ior": 1.0}
    if desc["type"] == "conductor":
        d = {"type": "roughconductor" if alpha else "conductor", "eta": spectrum(desc["eta"]), "k": spectrum(desc["k"])}
        if alpha:
            d.update(distribution="ggx", alpha=alpha)
        return d
    if desc["type"] == "plastic":
        d = {"type": "roughplastic" if alpha else "plastic", "diffuse_reflectance": spectrum(desc["reflectance"]),
             "int_ior": float(desc.get("ior", 1.49)), "ext_ior": 1.0, "nonlinear": bool(desc.get("nonlinear", False))}
        if alpha:
            d.update(distribution="ggx", alpha=alpha)
        return d
    raise SystemExit(f"no Mitsuba BSDF for {desc['type']}")


def load_gltf(name):
    """A glTF file under scenes/ and its buffers' bytes."""
    with open(os.path.join(ROOT, "scenes", name)) as f:
        doc = json.load(f)
    blobs = []
    for b in doc["buffers"]:
        uri = b["uri"]
        if uri.startswith("data:"):
            blobs.append(base64.b64decode(uri.split(",", 1)[1]))
        else:
            with open(os.path.join(ROOT, "scenes", uri), "rb") as f:
                blobs.append(f.read())
    return doc, blobs


def spheres(kind, tmp):
    """Mitsuba shapes for the glTF file's meshes that are not the box's."""
    doc, blobs = load_gltf(f"cornell-{kind}.gltf")
    shapes = {}
    for node in (doc["nodes"][i] for i in doc["scenes"][0]["nodes"]):
        if node["name"] in SHARED_NODES or "mesh" not in node:
            continue
        primitive = doc["meshes"][node["mesh"]]["primitives"][0]
        itype = {5123: "<u2", 5125: "<u4"}[doc["accessors"][primitive["indices"]]["componentType"]]
        path = os.path.join(tmp, node["name"] + ".ply")
        ply(path, accessor(doc, blobs, primitive["attributes"]["POSITION"], "<f4", 3),
            accessor(doc, blobs, primitive["attributes"]["NORMAL"], "<f4", 3),
            accessor(doc, blobs, primitive["indices"], itype, 1))
        to_world = mi.ScalarTransform4f().translate(node.get("translation", [0, 0, 0])).scale(node.get("scale", [1, 1, 1]))
        material = doc["materials"][primitive["material"]]["extensions"]["PRISM_spectral"]
        shapes[node["name"]] = {"type": "ply", "filename": path, "to_world": to_world, "bsdf": bsdf(material)}
    return shapes


def rotate(q, v):
    """The vector v turned by the unit quaternion q = (x, y, z, w)."""
    u, w = np.array(q[:3]), q[3]
    v = np.array(v, dtype=float)
    return 2 * np.dot(u, v) * u + (w * w - np.dot(u, u)) * v + 2 * w * np.cross(u, v)


def resampled_sky(tmp, factor=SKY_FACTOR):
    """scenes/sky.hdr resampled `factor` times finer, each new texel prism's radiance at
    its centre (bilinear in RGB between the texel centres (i + 0.5) / W, u wrapping, v
    clamped: `EnvironmentMap::rgb`). Mitsuba's spectral `envmap` blends the four texels'
    normalized spectra and their scales apart, which shifts the colour where brightness and
    colour change together between neighbouring texels (the horizon, the sun's rim); on
    texels that close together, it evaluates nearly the radiance prism does."""
    sky = np.array(mi.Bitmap(SKY), dtype=np.float64)[..., :3]
    h, w, _ = sky.shape
    x = (np.arange(w * factor) + 0.5) / factor - 0.5
    y = np.clip((np.arange(h * factor) + 0.5) / factor - 0.5, 0, h - 1)
    x0, y0 = np.floor(x).astype(int), np.minimum(np.floor(y).astype(int), h - 2)
    fx, fy = (x - x0)[None, :, None], (y - y0)[:, None, None]
    x0, x1 = x0 % w, (x0 + 1) % w
    rows = lambda r: sky[r][:, x0] * (1 - fx) + sky[r][:, x1] * fx
    fine = rows(y0) * (1 - fy) + rows(y0 + 1) * fy
    path = os.path.join(tmp, "sky.exr")
    mi.Bitmap(fine.astype(np.float32)).write(path)
    return path


def textured_sky(tmp, width):
    """scenes/textured-sky.gltf as a whole Mitsuba scene: its meshes (with texture
    coordinates), Lambertian materials with their sRGB base colour textures, the gold
    conductor, the camera, and scenes/sky.hdr turned by the 90 degrees that separate
    Mitsuba's envmap mapping from prism's (benches/peer/environment.py)."""
    doc, blobs = load_gltf("textured-sky.gltf")

    def texture(index):
        view = doc["bufferViews"][doc["images"][doc["textures"][index]["source"]]["bufferView"]]
        path = os.path.join(tmp, f"texture-{index}.png")
        with open(path, "wb") as f:
            f.write(blobs[view["buffer"]][view.get("byteOffset", 0):view.get("byteOffset", 0) + view["byteLength"]])
        return {"type": "bitmap", "filename": path, "filter_type": "bilinear", "wrap_mode": "repeat"}

    def material(m):
        if "PRISM_spectral" in m.get("extensions", {}):
            return bsdf(m["extensions"]["PRISM_spectral"])
        pbr = m["pbrMetallicRoughness"]
        assert pbr.get("metallicFactor") == 0 and pbr.get("roughnessFactor", 1) == 1, m["name"]
        return {"type": "diffuse", "reflectance": texture(pbr["baseColorTexture"]["index"])}

    desc = {"type": "scene", "sky": {"type": "envmap", "filename": resampled_sky(tmp),
                                     "to_world": mi.ScalarTransform4f().rotate([0, 1, 0], 90)}}
    for node in (doc["nodes"][i] for i in doc["scenes"][0]["nodes"]):
        if "camera" in node:
            q, eye = node["rotation"], np.array(node["translation"], dtype=float)
            yfov = doc["cameras"][node["camera"]]["perspective"]["yfov"]
            desc["sensor"] = {
                "type": "perspective", "fov": float(np.degrees(yfov)), "fov_axis": "y",
                "to_world": mi.ScalarTransform4f().look_at(origin=eye.tolist(), target=(eye + rotate(q, [0, 0, -1])).tolist(),
                                                           up=rotate(q, [0, 1, 0]).tolist()),
                "film": {"type": "hdrfilm", "width": width, "height": width, "rfilter": {"type": "box"}},
                "sampler": {"type": "independent"}}
            continue
        primitive = doc["meshes"][node["mesh"]]["primitives"][0]
        attributes = primitive["attributes"]
        path = os.path.join(tmp, node["name"] + ".ply")
        positions = accessor(doc, blobs, attributes["POSITION"], "<f4", 3)
        indices = np.arange(len(positions))
        if "indices" in primitive:
            itype = {5123: "<u2", 5125: "<u4"}[doc["accessors"][primitive["indices"]]["componentType"]]
            indices = accessor(doc, blobs, primitive["indices"], itype, 1)
        ply(path, positions, accessor(doc, blobs, attributes["NORMAL"], "<f4", 3), indices,
            accessor(doc, blobs, attributes["TEXCOORD_0"], "<f4", 2) if "TEXCOORD_0" in attributes else None)
        desc[node["name"]] = {"type": "ply", "filename": path, "bsdf": material(doc["materials"][primitive["material"]])}
    return desc


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("variant"); ap.add_argument("scene", choices=KINDS); ap.add_argument("spp", type=int)
    ap.add_argument("--depth", type=int, default=-1); ap.add_argument("--width", type=int, default=256)
    ap.add_argument("--out"); ap.add_argument("--seed", type=int, default=1)
    a = ap.parse_args()
    mi.set_variant(a.variant)
    import drjit as dr
    with tempfile.TemporaryDirectory() as tmp:
        if a.scene == "textured":
            desc = textured_sky(tmp, a.width)
            desc["integrator"] = {"type": "path", "max_depth": a.depth}
        else:
            desc = mi.cornell_box()
            del desc["small-box"], desc["large-box"]
            desc["integrator"]["max_depth"] = a.depth
            desc["sensor"]["film"]["rfilter"] = {"type": "box"}
            desc["sensor"]["film"]["width"] = desc["sensor"]["film"]["height"] = a.width
            desc.update(spheres(a.scene, tmp))
        scene = mi.load_dict(desc)
    img = mi.render(scene, spp=1); dr.eval(img)  # warm-up (JIT compilation for the LLVM variant)
    t = time.time(); img = mi.render(scene, spp=a.spp, seed=a.seed); dr.eval(img); dr.sync_thread(); dt = time.time() - t
    if a.out:
        mi.util.write_bitmap(a.out, img)
    print(json.dumps({"variant": a.variant, "scene": a.scene, "spp": a.spp, "depth": a.depth, "width": a.width,
                      "seconds": round(dt, 3), "paths_per_second": a.width * a.width * a.spp / dt}))


if __name__ == "__main__":
    main()
