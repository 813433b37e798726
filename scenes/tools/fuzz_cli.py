"""Runs `prism render` on mutated copies of the repository's scenes and reports every run
that panics, hangs or writes a non-finite pixel. Bad input must end in one error line and
exit code 1 or 2; a good one in a finite image.

  cargo build --release -p prism-cli
  python3 scenes/tools/fuzz_cli.py gltf 2000 --seed 1   # JSON values and buffer words
  python3 scenes/tools/fuzz_cli.py assets 1000          # the same on scenes/assets (real-asset
      # features: alpha modes, quantized and coloured vertices, WebP, unlit, GLB), rendered
      # under their default light or an environment image
  python3 scenes/tools/fuzz_cli.py toml 600             # overlay material descriptions
  python3 scenes/tools/fuzz_cli.py glb 1500             # GLB headers, chunk lengths, bytes
  python3 scenes/tools/fuzz_cli.py args 400             # command-line options
  python3 scenes/tools/fuzz_cli.py specs 1000           # prism color and upsample inputs
  python3 scenes/tools/fuzz_cli.py xml 1000             # Mitsuba scenes (scenes/mitsuba):
      # truncated, values replaced (huge, negative, NaN, not numbers), tags retyped,
      # cyclic and missing includes, deep nesting, hostile serialized, OBJ and PLY meshes
      # (counts far beyond the data, cut short, bytes flipped, indices out of range)
  python3 scenes/tools/fuzz_cli.py files 1000           # the other files prism reads:
      # coefficient tables (table info), accumulation files (merge, render --resume),
      # images (compare), spectrum and camera-response CSVs (color, --camera-response)

Failing inputs are kept in the work directory (printed at the end). Checking pixels needs
numpy and mitsuba (to read EXR); without them only exit codes are checked. The same
mutations of the Cornell box run in the test suite (scene/tests/load_mutations.rs) without
the CLI; this script also covers rendering, overlays, GLB and the options.
"""
import argparse, copy, json, os, random, shutil, struct, subprocess, sys, tempfile
from collections import Counter

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SCENES = os.path.join(ROOT, "scenes")
PRISM = os.path.join(ROOT, "target", "release", "prism")
GLTF = ["cornell-box.gltf", "cornell-spectral.gltf", "cornell-bunny.gltf", "effects.gltf", "prism.gltf", "rainbow.gltf", "textured.gltf"]
NUMBERS = [0, -0.0, 1, -1, 2, 3, 7, 100, 65535, 4294967295, 2**53, 0.5, 1e-45, 1e-39, 1e6, 1e30, 3e38, -3e38, 1e300]
STRINGS = ["", "x", "data:", "blackbody:-5", "blackbody:1e30", "gaussian:550:0", "csv:missing.csv", "D65", "nan", "1e40"]
WORDS = [3e38, -3e38, 1e30, 1e-40, 0.0, float("inf"), float("nan")]


def paths(v, p=()):
    yield p
    if isinstance(v, dict):
        for k, x in v.items():
            yield from paths(x, p + (k,))
    elif isinstance(v, list):
        for i, x in enumerate(v):
            yield from paths(x, p + (i,))


def get(v, p):
    for k in p:
        v = v[k]
    return v


def mutate_json(doc, rng):
    """One edit: mostly a number replaced (keeping the file valid enough to reach the
    renderer), else a value deleted, retyped, emptied or duplicated."""
    ps = list(paths(doc))[1:]
    numeric = [p for p in ps if isinstance(get(doc, p), (int, float)) and not isinstance(get(doc, p), bool)]
    if numeric and rng.random() < 0.7:
        p = rng.choice(numeric)
        parent, cur = get(doc, p[:-1]), get(doc, p)
        if isinstance(cur, int) and rng.random() < 0.5:
            parent[p[-1]] = rng.choice([0, 1, 2, 3, cur + 1, max(0, cur - 1)])
        else:
            parent[p[-1]] = rng.choice(NUMBERS + [-cur, cur * 1e10])
        return
    p = rng.choice(ps)
    parent, cur = get(doc, p[:-1]), get(doc, p)
    if isinstance(parent, dict) and rng.random() < 0.2:
        del parent[p[-1]]
    elif isinstance(cur, str):
        parent[p[-1]] = rng.choice(STRINGS + [cur[: len(cur) // 2]])
    elif isinstance(cur, list):
        parent[p[-1]] = rng.choice([[], cur[:1], cur + [copy.deepcopy(cur[0])] if cur else [0]])
    else:
        parent[p[-1]] = rng.choice([0, "x", [], {}, None, True])


def mutate_buffer(work, doc, rng, i):
    """Overwrites a few 32-bit words of the file's .bin buffer with extreme values."""
    uri = doc.get("buffers", [{}])[0].get("uri") if isinstance(doc.get("buffers"), list) and doc["buffers"] and isinstance(doc["buffers"][0], dict) else None
    if not isinstance(uri, str) or not os.path.isfile(os.path.join(work, uri)):
        return
    b = bytearray(open(os.path.join(work, uri), "rb").read())
    for _ in range(rng.randint(1, 8)):
        k = rng.randrange(max(1, len(b) // 4)) * 4
        if k + 4 <= len(b):
            b[k:k + 4] = struct.pack("<f", rng.choice(WORDS)) if rng.random() < 0.8 else struct.pack("<I", rng.choice([0xFFFFFFFF, 1 << 31, 12345678]))
    name = f"buffer{i}.bin"
    open(os.path.join(work, name), "wb").write(b)
    doc["buffers"][0]["uri"] = name


def case_gltf(work, rng, i):
    doc = json.load(open(os.path.join(SCENES, rng.choice(GLTF))))
    for _ in range(rng.randint(1, 3)):
        mutate_json(doc, rng)
    if rng.random() < 0.4:
        mutate_buffer(work, doc, rng, i)
    path = os.path.join(work, f"case{i}.gltf")
    json.dump(doc, open(path, "w"))
    return [path]


def case_assets(work, rng, i):
    """A mutated copy of one of scenes/assets: its JSON, and (embedded buffers being data
    URIs) words of its buffer; GLBs as they are or with bytes overwritten."""
    import base64
    names = sorted(f for f in os.listdir(os.path.join(SCENES, "assets")) if f.endswith((".gltf", ".glb")))
    name = rng.choice(names)
    source = os.path.join(SCENES, "assets", name)
    extra = rng.choice([[], [], ["--environment", "grey-0.5.hdr", "--environment-rotation", str(rng.choice([0, 90, 1e30, -45]))], ["--transparent"]])
    if name.endswith(".glb"):
        b = bytearray(open(source, "rb").read())
        for _ in range(rng.randint(0, 8)):
            k = rng.randrange(len(b))
            b[k] = rng.randrange(256)
        path = os.path.join(work, f"case{i}.glb")
        open(path, "wb").write(bytes(b))
        return [path] + extra
    doc = json.load(open(source))
    for _ in range(rng.randint(1, 3)):
        mutate_json(doc, rng)
    buffers = doc.get("buffers")
    if rng.random() < 0.4 and isinstance(buffers, list) and buffers and isinstance(buffers[0], dict):
        uri = buffers[0].get("uri")
        if isinstance(uri, str) and ";base64," in uri:
            head, payload = uri.split(";base64,", 1)
            b = bytearray(base64.b64decode(payload))
            for _ in range(rng.randint(1, 8)):
                k = rng.randrange(max(1, len(b) // 4)) * 4
                if k + 4 <= len(b):
                    b[k:k + 4] = struct.pack("<f", rng.choice(WORDS)) if rng.random() < 0.8 else struct.pack("<I", rng.choice([0xFFFFFFFF, 1 << 31, 12345678]))
            buffers[0]["uri"] = head + ";base64," + base64.b64encode(bytes(b)).decode()
    path = os.path.join(work, f"case{i}.gltf")
    json.dump(doc, open(path, "w"))
    return [path] + extra


def case_toml(work, rng, i):
    import tomllib, tomli_w  # pip install tomli-w
    name = rng.choice(["cornell-blacklight.toml", "cornell-glass-bunny.toml"])
    doc = tomllib.load(open(os.path.join(SCENES, name), "rb"))
    spectra = [0.5, 0, -1, 1e30, 3e38, 1e-45, "blackbody:0", "blackbody:1e30", "illuminant:F13", "daylight:100",
               "gaussian:365:0", "gaussian:1e30:1e30", "constant:-1", "csv:nir-camera.csv", "csv:", [[400, 0.1]], [],
               [[700, 1], [400, 2]], {"rgb": [1e30, 0, 0]}, {"rgb": [0, 0]}, {"spectrum": 0.5, "scale": -1}, "x"]
    keys = ["emission", "reflectance", "absorption", "reemission", "quantum_yield", "type", "ior", "roughness", "metal", "eta", "k"]
    for _ in range(rng.randint(1, 3)):
        m = doc.setdefault("materials", {}).setdefault(rng.choice(list(doc.get("materials", {})) + ["white"]), {})
        if rng.random() < 0.15:
            m["type"] = rng.choice(["diffuse", "dielectric", "conductor", "fluorescent", "x"])
        elif m and rng.random() < 0.2:
            del m[rng.choice(list(m))]
        else:
            m[rng.choice(list(m) + keys)] = copy.deepcopy(rng.choice(spectra))
    path = os.path.join(work, f"case{i}.toml")
    open(path, "wb").write(tomli_w.dumps(doc).encode())
    return [path]


def glb_of(name):
    doc = json.load(open(os.path.join(SCENES, name)))
    b = open(os.path.join(SCENES, doc["buffers"][0].pop("uri")), "rb").read()
    j = json.dumps(doc).encode()
    j += b" " * (-len(j) % 4)
    b += b"\0" * (-len(b) % 4)
    body = struct.pack("<II", len(j), 0x4E4F534A) + j + struct.pack("<II", len(b), 0x004E4942) + b
    return bytes(struct.pack("<III", 0x46546C67, 2, 12 + len(body)) + body)


def case_glb(work, rng, i, bases={}):
    if not bases:
        bases.update({n: glb_of(n) for n in ["cornell-box.gltf", "cornell-spectral.gltf"]})
    g = bytearray(rng.choice(list(bases.values())))
    for _ in range(rng.randint(1, 6)):
        r = rng.random()
        if r < 0.3 and len(g) >= 16:
            k = rng.choice([4, 8, 12, 16, 20 + struct.unpack("<I", g[12:16])[0]])
            if k + 4 <= len(g):
                g[k:k + 4] = struct.pack("<I", rng.choice([0, 1, 3, 0xFFFFFFFF, len(g), 2 * len(g), rng.randrange(1 << 32)]))
        elif r < 0.5 and len(g) > 1:
            g = g[: rng.randrange(len(g))]
        elif g:
            g[rng.randrange(len(g))] = rng.randrange(256)
    path = os.path.join(work, f"case{i}.glb")
    open(path, "wb").write(g)
    return [path]


def case_args(work, rng, i):
    values = ["0", "1", "-1", "3", "16", "1e9", "1e300", "-1e300", "100000", "4294967296", "nan", "inf", "x", "", "1:1", "830:360", "100:20000", "0:1e300", "5..2", "0..0"]
    options = {o: values for o in ["--spp", "--width", "--height", "--seed", "--threads", "--max-depth", "--wavelengths",
                                   "--spectral-bands", "--spectral-range", "--wavelength-range", "--scene-index", "--clamp",
                                   "--exposure", "--time", "--checkpoint", "--environment", "--camera-polarizer"]}
    options.update({"--lambda-sampler": ["uniform", "visible", "response", "spd", "x"], "--filter": ["box", "gaussian", "x"],
                    "--camera-response": [os.path.join(SCENES, "nir-camera.csv"), "/nonexistent.csv", os.path.join(SCENES, "cornell-box.bin")],
                    "--white-balance": ["illuminant:A", "blackbody:0", "blackbody:1e30", "daylight:1", "x"],
                    "--space": ["srgb", "acescg", "x"], "--camera": ["camera", "x"], "--bvh": ["slow", "x"],
                    "--resume": ["/nonexistent.exr", os.path.join(SCENES, "cornell-box.bin")],
                    "--polarization-png": [os.path.join(work, "p.png"), "/nonexistent/dir/p.png"]})
    scene = rng.choice([os.path.join(SCENES, s) for s in ["cornell-box.gltf", "effects.gltf", "cornell-blacklight.toml", "window.gltf"]] + ["/nonexistent.gltf", os.path.join(SCENES, "cornell-box.bin")])
    args = [scene]
    for _ in range(rng.randint(1, 4)):
        o = rng.choice(list(options))
        args += [o, rng.choice(options[o])]
    return args + [f for f in ["--energy", "--no-light-paths", "--stats", "--polarized"] if rng.random() < 0.2]


def mutate_bytes(data, rng):
    """A few edits of a binary file: 32-bit words overwritten with extreme floats or
    integers, bytes flipped, the file cut short or a run repeated."""
    b = bytearray(data)
    for _ in range(rng.randint(1, 6)):
        r = rng.random()
        if r < 0.45 and len(b) >= 4:
            k = rng.randrange(len(b) - 3)
            if rng.random() < 0.6:
                b[k:k + 4] = struct.pack("<f", rng.choice(WORDS))
            else:
                b[k:k + 4] = struct.pack("<I", rng.choice([0, 1, 0xFFFFFFFF, 1 << 31, len(b), rng.randrange(1 << 32)]))
        elif r < 0.6 and len(b) > 1:
            b = b[: rng.randrange(len(b))]
        elif r < 0.7 and b:
            k = rng.randrange(len(b))
            b[k:k] = b[k:k + rng.randint(1, 64)]
        elif b:
            b[rng.randrange(len(b))] ^= 1 << rng.randrange(8)
    return bytes(b)


def mutate_csv(text, rng):
    """A few edits of a CSV: values replaced by extreme or broken ones, rows dropped,
    repeated or cut."""
    rows = text.splitlines()
    for _ in range(rng.randint(1, 4)):
        if not rows:
            break
        k = rng.randrange(len(rows))
        r = rng.random()
        cells = rows[k].split(",")
        if r < 0.6:
            cells[rng.randrange(len(cells))] = rng.choice(["nan", "inf", "-1", "0", "1e300", "-1e300", "1e-45", "", "x", "360", "830", "1e39"])
            rows[k] = ",".join(cells)
        elif r < 0.75:
            del rows[k]
        elif r < 0.9:
            rows.insert(k, rows[k])
        else:
            rows[k] = rows[k][: rng.randrange(len(rows[k]) + 1)]
    return "\n".join(rows) + ("\n" if rng.random() < 0.8 else "")


def file_bases(work):
    """Valid files to mutate, made once with prism itself."""
    def run(*args):
        subprocess.run([PRISM, *args], check=True, capture_output=True, cwd=work)
    run("table", "fit", "--res", "3", "-o", "table.bin")
    box = os.path.join(work, "cornell-box.gltf")
    run("render", box, "--width", "6", "--height", "4", "--sample-range", "0..2", "-o", "part0.exr", "-q")
    run("render", box, "--width", "6", "--height", "4", "--sample-range", "2..4", "-o", "part1.exr", "-q")
    run("render", box, "--width", "6", "--height", "4", "--spp", "2", "-o", "image.exr", "-o", "image.png", "-q")
    run("render", box, "--width", "6", "--height", "4", "--spp", "2", "--energy", "--spectral-bands", "4", "-o", "bands.exr", "-q")
    with open(os.path.join(work, "spectrum.csv"), "w") as f:
        f.write("nm,value\n" + "".join(f"{400 + 10 * k},{0.1 + 0.02 * k}\n" for k in range(31)))
    return {n: open(os.path.join(work, n), "rb").read() for n in
            ["table.bin", "part0.exr", "part1.exr", "image.exr", "image.png", "bands.exr", "nir-camera.csv", "spectrum.csv"]}


def case_files(work, rng, i, bases={}):
    """(arguments after `prism`, the output file to check or None)."""
    if not bases:
        bases.update(file_bases(work))
    kind = rng.choice(["table", "merge", "resume", "compare", "compare-png", "color", "response"])
    def write(base, data):
        path = os.path.join(work, f"case{i}{os.path.splitext(base)[1]}")
        open(path, "wb").write(data)
        return path
    out = os.path.join(work, "out.exr")
    small = ["--width", "6", "--height", "4", "--spp", "2", "-o", out, "-q"]
    box = os.path.join(work, "cornell-box.gltf")
    if kind == "table":
        return ["table", "info", write("t.bin", mutate_bytes(bases["table.bin"], rng))], None
    if kind == "merge":
        part = rng.choice(["part0.exr", "part1.exr"])
        other = "part1.exr" if part == "part0.exr" else "part0.exr"
        return ["merge", write(part, mutate_bytes(bases[part], rng)), os.path.join(work, other), "-o", out], out
    if kind == "resume":
        return ["render", box, "--resume", write("c.exr", mutate_bytes(bases["part0.exr"], rng))] + small, out
    if kind == "compare":
        name = rng.choice(["image.exr", "bands.exr"])
        return ["compare", write(name, mutate_bytes(bases[name], rng)), os.path.join(work, name), "--json"], None
    if kind == "compare-png":
        return ["compare", write("i.png", mutate_bytes(bases["image.png"], rng)), os.path.join(work, "image.png")], None
    if kind == "color":
        return ["color", write("s.csv", mutate_csv(bases["spectrum.csv"].decode(), rng).encode())], None
    return ["render", box, "--camera-response", write("r.csv", mutate_csv(bases["nir-camera.csv"].decode(), rng).encode())] + small, out


def case_specs(work, rng, i):
    """(arguments after `prism`, None): spectrum specifications for `color` and colours,
    spaces and options for `upsample`."""
    numbers = ["0", "1", "-1", "0.5", "1e-45", "1e-300", "1e300", "-1e300", "nan", "inf", "-inf", "", "x", "1e39", "3e38", "0x10"]
    def num():
        return rng.choice(numbers + [repr(rng.uniform(-2, 2))])
    if rng.random() < 0.5:
        kind = rng.choice(["blackbody", "illuminant", "daylight", "gaussian", "constant", "csv", "", "x"])
        spec = {"blackbody": lambda: f"blackbody:{num()}", "illuminant": lambda: f"illuminant:{rng.choice(['A', 'D65', 'F12', 'F13', '', 'x'])}",
                "daylight": lambda: f"daylight:{num()}", "gaussian": lambda: f"gaussian:{num()}:{num()}",
                "constant": lambda: f"constant:{num()}", "csv": lambda: rng.choice(["/nonexistent.csv", os.path.join(work, "cornell-box.bin"), os.path.join(work, "nir-camera.csv")]),
                "": lambda: "", "x": lambda: rng.choice([":", "::", "blackbody", "gaussian:1", "a:b:c:d"])}[kind]()
        args = ["color", spec]
        if rng.random() < 0.3:
            args += ["--observer", rng.choice(["cie1931", "cie1964", "x"])]
        if rng.random() < 0.3:
            args += ["--space", rng.choice(["srgb", "rec2020", "x", "0.7,0.3,0.2,0.75,0.12,0.05@illuminant:D50", "0,0,0,0,0,0", "1,1,1,1,1,1@x"])]
        return args + (["--json"] if rng.random() < 0.5 else []), None
    args = ["upsample"] + [num() for _ in range(rng.choice([0, 1, 2, 3, 3, 3, 6]))]
    if rng.random() < 0.3:
        args += ["--space", rng.choice(["srgb", "prophoto", "aces2065-1", "x", "0.7,0.3,0.2,0.75,0.12,0.05@illuminant:D50", "0,0,1,1,0.5,0.5", "nan,0,0,0,0,0"])]
    if rng.random() < 0.2:
        args += ["--table", rng.choice([os.path.join(work, "cornell-box.bin"), "/nonexistent.bin"])]
    return args + [f for f in ["--exact", "--refine", "--json"] if rng.random() < 0.2], None


XML_VALUES = ["", "abc", "nan", "inf", "-1", "0", "1e308", "-1e308", "99999999999999999999",
              "4294967296", "2147483648", "1e-320", "1, 2", "1 2 3 4 5", "$missing", "$$", "0x10"]
XML_TAGS = ["float", "integer", "boolean", "string", "rgb", "spectrum", "point", "vector",
            "shape", "bsdf", "emitter", "transform", "include", "ref", "default", "scene"]


def serialized_file(rng):
    """A `serialized` mesh file: valid, or with its counts, bytes or length broken."""
    import zlib
    plain = struct.pack("<I", 0x1000) + b"m\0" + struct.pack("<QQ", 3, 1)
    plain += struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0) + struct.pack("<3I", 0, 1, 2)
    kind = rng.randrange(4)
    if kind == 1:  # counts far beyond the data
        plain = plain[:6] + struct.pack("<QQ", rng.choice([2**31, 2**40, 2**64 - 1]), 1) + plain[22:]
    data = struct.pack("<HH", 0x041C, 4) + zlib.compress(plain)
    if kind == 2:
        data = data[: rng.randrange(len(data))]
    if kind == 3:
        data = mutate_bytes(data, rng)
    return data + struct.pack("<QI", 0, 1)


def obj_file(rng):
    """An OBJ mesh: valid, or with indices out of range, numbers broken or bytes cut."""
    text = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 1\nvn 0 0 1\nf 1/1/1 2/2/1 3/1/1 4/2/1\n"
    kind = rng.randrange(5)
    if kind == 1:  # an index far out of range, zero or too relative
        text += "f 1 2 " + rng.choice(["99999999999", "0", "-9", "5/1/1", "1/9/1", "1/1/9"]) + "\n"
    elif kind == 2:  # a number that is not one
        text = text.replace("1 1 0", rng.choice(["1 nan 0", "1 inf 0", "1 x 0", "1", "1e99999 0 0"]))
    elif kind == 3:
        text = text[: rng.randrange(len(text))]
    data = text.encode()
    return mutate_bytes(data, rng) if kind == 4 else data


def ply_file(rng):
    """A PLY mesh, ASCII or binary: valid, or declaring counts far beyond its data, cut
    short, with an index out of range or bytes flipped."""
    binary = rng.random() < 0.5
    counts = [4, 2]
    kind = rng.randrange(5)
    if kind == 1:  # counts far beyond the data
        counts[rng.randrange(2)] = rng.choice([2**31, 2**32 + 1, 2**40, 2**64 - 1])
    head = ("ply\nformat " + ("binary_little_endian" if binary else "ascii") + " 1.0\n"
            f"element vertex {counts[0]}\nproperty float x\nproperty float y\nproperty float z\n"
            "property uchar red\nproperty uchar green\nproperty uchar blue\n"
            f"element face {counts[1]}\nproperty list uchar int vertex_indices\n"
            "property float weight_0\nend_header\n").encode()
    corners = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0)]
    faces = [[0, 1, 2], [0, 2, rng.choice([3, 3, 4, 2**31 - 1])]]
    if binary:
        body = b"".join(struct.pack("<3f3B", *p, 200, 100, 50) for p in corners)
        body += b"".join(struct.pack("<B3if", 3, *f, 0.5) for f in faces)
    else:
        body = "".join(f"{x} {y} {z} 200 100 50\n" for x, y, z in corners).encode()
        body += "".join(f"3 {f[0]} {f[1]} {f[2]} 0.5\n" for f in faces).encode()
    data = head + body
    if kind == 2:
        data = data[: rng.randrange(len(data))]
    if kind == 3:
        data = mutate_bytes(data, rng)
    return data


def case_xml(work, rng, i):
    import re
    text = open(os.path.join(SCENES, "mitsuba", "cornell-box.xml")).read()
    kind = rng.randrange(10)
    if kind == 0:  # truncated
        text = text[: rng.randrange(len(text))]
    elif kind == 1:  # a value replaced
        values = list(re.finditer(r'value="([^"]*)"', text))
        m = rng.choice(values)
        text = text[: m.start(1)] + rng.choice(XML_VALUES) + text[m.end(1):]
    elif kind == 2:  # a tag retyped
        tags = list(re.finditer(r"<(/?)(\w+)", text))
        m = rng.choice(tags)
        text = text[: m.start(2)] + rng.choice(XML_TAGS) + text[m.end(2):]
    elif kind == 3:  # cyclic or missing includes
        other = os.path.join(work, f"inc{i}.xml")
        open(other, "w").write(f'<scene version="3.0.0"><include filename="case{i}.xml"/></scene>')
        name = rng.choice([f"inc{i}.xml", "missing.xml", "../../../../etc/passwd", ""])
        text = text.replace("</scene>", f'<include filename="{name}"/></scene>')
    elif kind == 4:  # deep nesting
        depth = rng.choice([50, 300, 5000])
        text = text.replace("</scene>", '<shape type="cube">' * depth + "</shape>" * depth + "</scene>")
    elif kind == 5:  # a serialized mesh, hostile or missing
        open(os.path.join(work, f"mesh{i}.serialized"), "wb").write(serialized_file(rng))
        name = rng.choice([f"mesh{i}.serialized", "missing.serialized"])
        index = rng.choice(["0", "1", "-1", "99999999999"])
        text = text.replace("</scene>", f'<shape type="serialized"><string name="filename" value="{name}"/>'
                            f'<integer name="shape_index" value="{index}"/></shape></scene>')
    elif kind in (8, 9):  # an OBJ or PLY mesh, hostile or missing, shown by vertex colour
        ext = "obj" if kind == 8 else "ply"
        open(os.path.join(work, f"mesh{i}.{ext}"), "wb").write((obj_file if kind == 8 else ply_file)(rng))
        name = rng.choice([f"mesh{i}.{ext}"] * 3 + [f"missing.{ext}"])
        bsdf = rng.choice(['', '<bsdf type="diffuse"><texture type="mesh_attribute" name="reflectance">'
                               f'<string name="name" value="{rng.choice(["vertex_color", "face_weight", "face_nothing"])}"/>'
                               '</texture></bsdf>'])
        text = text.replace("</scene>", f'<shape type="{ext}"><string name="filename" value="{name}"/>{bsdf}</shape></scene>')
    elif kind == 6:  # a reference to nothing, or a duplicate id
        text = text.replace('<ref name="bsdf" id="white"/>', rng.choice(['<ref id="nothing"/>', '<bsdf type="diffuse" id="white"/>']), 1)
    else:  # bytes flipped
        text = mutate_bytes(text.encode(), rng).decode("utf-8", "replace")
    path = os.path.join(work, f"case{i}.xml")
    open(path, "w").write(text)
    return [path]


def finite_exr(path):
    try:
        import numpy as np, mitsuba as mi
    except ImportError:
        return True
    mi.set_variant("scalar_rgb")
    return bool(np.isfinite(np.array(mi.Bitmap(path))).all())


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("kind", choices=["gltf", "assets", "toml", "glb", "args", "files", "specs", "xml"])
    ap.add_argument("cases", type=int)
    ap.add_argument("--seed", type=int, default=1)
    a = ap.parse_args()
    rng = random.Random(a.seed)
    work = tempfile.mkdtemp(prefix="prism-fuzz-")
    for f in os.listdir(SCENES):
        if os.path.isfile(os.path.join(SCENES, f)) and not f.endswith(".toml"):
            shutil.copy(os.path.join(SCENES, f), work)
    shutil.copy(os.path.join(SCENES, "assets", "grey-0.5.hdr"), work)
    make = {"gltf": case_gltf, "assets": case_assets, "toml": case_toml, "glb": case_glb, "args": case_args,
            "xml": case_xml}.get(a.kind)
    codes, bad = Counter(), 0
    for i in range(a.cases):
        out = os.path.join(work, "out.exr")
        if make:
            args = [PRISM, "render"] + make(work, rng, i) + ["--width", "8", "--height", "8", "--spp", "2", "-o", out, "-q"]
        else:
            rest, checked = (case_files if a.kind == "files" else case_specs)(work, rng, i)
            args = [PRISM] + rest
            out = checked or out
        try:
            r = subprocess.run(args, capture_output=True, text=True, timeout=120, cwd=work)
        except subprocess.TimeoutExpired:
            bad += 1
            print("hang:", " ".join(args[1:]))
            continue
        codes[r.returncode] += 1
        failed = r.returncode not in (0, 1, 2) or "panicked" in r.stderr
        # One error line (warnings about the file may precede it).
        errors = [l for l in r.stderr.strip().splitlines() if l.startswith("prism: error")]
        if r.returncode == 1 and (len(errors) != 1 or not r.stderr.strip().splitlines()[-1].startswith("prism: error")):
            failed = True
        if r.returncode == 0 and os.path.exists(out) and not finite_exr(out):
            failed = True
        if failed:
            bad += 1
            print(f"exit {r.returncode}:", " ".join(args[1:]), "|", r.stderr.strip()[-300:])
        if os.path.exists(out):
            os.remove(out)
    print(json.dumps({"cases": a.cases, "failed": bad, "exit_codes": dict(codes), "work": work}))
    sys.exit(1 if bad else 0)


if __name__ == "__main__":
    main()
