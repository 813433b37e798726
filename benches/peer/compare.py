"""prism against Mitsuba 3 in one run: speed (paths per second, as a ratio) and agreement
(region means of the two images, and of each against a converged reference).

  pip install mitsuba numpy
  cargo build --release -p prism-cli
  python3 benches/peer/compare.py box --spp 64 --width 256
  python3 benches/peer/compare.py box --reference ref.exr   # also compare against a reference
  python3 benches/peer/compare.py box --width 128 --reference-spp 4096   # render one first
  python3 benches/peer/compare.py box --peer-reference ref-box-256.exr   # Mitsuba's, 8192 spp
  python3 benches/peer/compare.py box --peer-reference ref-box-256.exr --repeats 3   # median times
  python3 benches/peer/compare.py box --peer-reference ref-box-256.exr --narrow-peers  # peers as without AVX-512
  python3 benches/peer/compare.py box bunny specular glossy caustic media textured --width 128 \
      --variants llvm_ad_spectral,scalar_spectral --peer-reference-dir refs --seeds 4   # the scene kinds
  python3 benches/peer/compare.py scenes/mitsuba/bsdfs-plastic.xml --peer-reference-dir refs  # a Mitsuba file

A SCENE is a comparison scene's name or a Mitsuba scene file (.xml), which both renderers
read as it stands (benches/peer/mitsuba_xml.py on Mitsuba's side): its film's size and its
integrator's depth, --spp samples; --width and --depth do not apply to it.

Several scenes print one JSON object each and then a Markdown table of the time-to-equal-error
ratios and paths/s per scene, with the CPU model (on stderr).

Issue 30's measure is the last form: the reference is a converged render of the independent
renderer (Mitsuba 3's llvm_ad_spectral at 8192 spp, benches/peer/mitsuba_reference.py), made
once per scene and size and reused (the file is rendered when it does not exist yet).

A reference is a converged render of the same scene and size, e.g. prism's own with another
seed: `prism render scenes/cornell-box.gltf --width 256 --height 256 --spp 4096 --seed 999
-o ref.exr`, which `--reference-spp 4096` renders first (prism and Mitsuba agree within 1%
per region, so at 64 spp the error is noise either way; same depth as the comparison).
With one, each renderer's relative MSE is reported (prism compare's: the mean of
(a - b)^2 / (b^2 + 0.01)), and for each peer the error ratio (prism / peer, at equal spp:
<= 1 is "equal or lower error") and the efficiency ratio, time times error of the peer over
prism's: how much sooner prism reaches the same error.

The Mitsuba side is ../shared/scenes/peer/mitsuba_peer.py (the same Cornell box and bunny box
as the glTF files), for `specular`, `glossy` and `caustic` (the box with glass and metal
spheres, scenes/tools/make_cornell_kinds.py) and `textured` (scenes/textured-sky.gltf,
a textured asset under an HDR sky) benches/peer/mitsuba_kinds.py, and for `media` (scenes/cornell-medium.gltf, the box's large block a
chromatic scattering medium) benches/peer/mitsuba_media.py with Mitsuba's `volpathmis`. Prints one JSON object. Region agreement: the image is cut into a
GRID x GRID grid; for each region and channel the relative difference of the means
is reported (max and mean over regions with enough signal).
"""
import argparse, json, os, subprocess, sys, tempfile

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from peers import SCENES, check_scene, is_xml, scene_name, scene_path, script as peer_script  # noqa: E402
from mitsuba_reference import variance_path  # noqa: E402


def read_exr(path):
    import mitsuba as mi
    mi.set_variant("scalar_rgb")
    return np.array(mi.Bitmap(path), dtype=np.float64)[..., :3]


def regions(img, grid):
    h, w, _ = img.shape
    return np.array([[img[i * h // grid:(i + 1) * h // grid, j * w // grid:(j + 1) * w // grid].mean(axis=(0, 1))
                      for j in range(grid)] for i in range(grid)])


def agreement(a, b, grid):
    ra, rb = regions(a, grid), regions(b, grid)
    signal = rb > 0.02 * rb.max()
    rel = np.abs(ra - rb)[signal] / rb[signal]
    return {"max_rel": float(rel.max()), "mean_rel": float(rel.mean()), "regions": int(signal.sum()),
            "mean_ratio": [float(x) for x in ra.mean(axis=(0, 1)) / rb.mean(axis=(0, 1))]}


def relmse(img, ref):
    """prism compare's relative MSE: noise relative to the reference, floored in the dark."""
    return float(np.mean((img - ref) ** 2 / (ref ** 2 + 0.01)))


def reference_noise(reference, ref):
    """What a reference's own noise adds to any renderer's relative MSE against it (its
    variance of the mean, written beside it by mitsuba_reference.py), or None without it.
    An image independent of the reference has E[relmse] = its error against the converged
    image + this; subtracting it leaves the renderers' own error."""
    path = variance_path(reference)
    if not os.path.exists(path):
        print(f"note: no {os.path.basename(path)} beside the reference: its noise counts as every "
              "renderer's error (render it again with mitsuba_reference.py to measure it)", file=sys.stderr)
        return None
    variance = read_exr(path)
    return float(np.mean(variance / (ref ** 2 + 0.01)))


def cpu():
    """The host's CPU model and widest vector extension: figures are quoted with them."""
    model, flags = "unknown", set()
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                key, _, value = line.partition(":")
                if key.strip() == "model name" and model == "unknown":
                    model = value.strip()
                elif key.strip() == "flags" and not flags:
                    flags = set(value.split())
    except OSError:
        pass
    widest = next((f for f in ("avx512f", "avx2", "avx", "sse4_2") if f in flags), "")
    return f"{model} ({widest}, {os.cpu_count()} threads)"


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("scenes", nargs="+", type=check_scene, metavar="SCENE",
                    help=f"one or more of {', '.join(SCENES)}, or Mitsuba scene files (.xml)")
    ap.add_argument("--spp", type=int, default=64)
    ap.add_argument("--width", type=int, default=256)
    ap.add_argument("--depth", type=int, default=-1,
                    help="Mitsuba's max_depth (path segments, camera ray included; -1 unbounded): "
                         "prism renders D - 1 bounces, the same paths")
    ap.add_argument("--variants", default="scalar_spectral")
    ap.add_argument("--reference", help="a converged EXR of the same scene and size")
    ap.add_argument("--reference-spp", type=int,
                    help="without --reference: render one with prism at this many spp (seed 999)")
    ap.add_argument("--peer-reference",
                    help="a Mitsuba 3 reference EXR, rendered first by mitsuba_reference.py if missing (one scene)")
    ap.add_argument("--peer-reference-dir",
                    help="a folder of Mitsuba 3 references, ref-SCENE-WIDTH.exr, each rendered first if missing")
    ap.add_argument("--peer-reference-spp", type=int, default=8192)
    ap.add_argument("--prism-reference-dir",
                    help="measure prism's error against its own converged render, DIR/prism-ref-SCENE-WIDTH.exr "
                         "(rendered first at --peer-reference-spp, seed 999, if missing), the peers' against "
                         "theirs: for materials the two renderers define differently (Mitsuba's roughplastic "
                         "loses energy, prism's plastic does not); the two references' agreement is reported")
    ap.add_argument("--grid", type=int, default=8)
    ap.add_argument("--prism-args", default="", help="extra arguments for prism render")
    ap.add_argument("--repeats", type=int, default=1,
                    help="time every renderer this many times, in turns, and report the median (a shared "
                         "host's speed drifts by 20-30%% within minutes; images and errors are the first run's, "
                         "every run's being the same)")
    ap.add_argument("--seeds", type=int, default=1,
                    help="render every renderer with this many seeds (in turns, as --repeats) and report the "
                         "mean relative MSE: one seed's error is a poor estimate where fireflies are")
    ap.add_argument("--table", action="store_true", help="also print the Markdown table for one scene")
    ap.add_argument("--narrow-peers", action="store_true",
                    help="run Mitsuba as on a host without AVX-512 (narrow_peer.py: Dr.Jit 8 lanes wide for "
                         "Zen 3, Embree capped at AVX2); an imitation of such a host, not a measurement on one")
    a = ap.parse_args()
    if a.peer_reference and len(a.scenes) > 1:
        ap.error("--peer-reference names one scene's reference: use --peer-reference-dir for several")
    if a.depth == 0 or a.depth < -1:
        ap.error("--depth is -1 (unbounded) or at least 1")
    if a.repeats < 1 or a.seeds < 1:
        ap.error("--repeats and --seeds are at least 1")
    results = []
    for scene in a.scenes:
        reference = a.peer_reference
        if a.peer_reference_dir:
            size = "file" if is_xml(scene) else a.width
            reference = os.path.join(a.peer_reference_dir, f"ref-{scene_name(scene)}-{size}.exr")
        results.append(compare(scene, a, reference))
        print(json.dumps(results[-1]), flush=True)
    if len(results) > 1 or a.table:
        print(table(results), file=sys.stderr)


def table(results):
    """The results as a Markdown table: time to equal error against each peer, and paths/s."""
    variants = [k for k in results[0] if isinstance(results[0][k], dict) and "prism_speed_ratio" in results[0][k]]
    head = "| scene | " + " | ".join(f"vs {v}" for v in variants) + " | prism paths/s | " + \
        " | ".join(f"{v} paths/s" for v in variants) + " |"
    rows = [f"{results[0]['cpu']}, {results[0]['width']}x{results[0]['height']}, {results[0]['spp']} spp", "",
            head, "|" + "---|" * (2 + 2 * len(variants))]
    for r in results:
        ratio = lambda v: f"{r[v]['prism_efficiency_ratio']:.2f}x" if "prism_efficiency_ratio" in r[v] else \
            f"{r[v]['prism_speed_ratio']:.2f}x (speed)"
        rows.append(f"| {r['scene']} | " + " | ".join(ratio(v) for v in variants) +
                    f" | {r['prism']['paths_per_second'] / 1e6:.2f} M | " +
                    " | ".join(f"{r[v]['paths_per_second'] / 1e6:.2f} M" for v in variants) + " |")
    return "\n".join(rows)


def compare(scene, a, peer_reference):
    """One scene: prism and each peer timed in turns, their images against the reference."""
    out = tempfile.mkdtemp(prefix="prism-peer-")
    prism = os.path.join(ROOT, "target", "release", "prism")
    prism_exr = os.path.join(out, "prism.exr")
    size = [] if is_xml(scene) else ["--width", str(a.width), "--height", str(a.width)]
    cmd = [prism, "render", scene_path(scene), "--spp", str(a.spp), *size,
           "-o", prism_exr, "--stats"] + a.prism_args.split()
    if a.depth >= 1 and is_xml(scene):
        sys.exit(f"{scene}: a Mitsuba file says its own depth (--depth does not apply)")
    if a.depth >= 1:
        # Mitsuba's max_depth counts segments (1: emitters seen directly); prism's
        # --max-depth counts bounces (0: the same). Equal numbers would give prism one
        # bounce more: measured 5.9% region differences at depth 8 on the box, 0.96% with
        # this (within noise at 256 spp).
        cmd += ["--max-depth", str(a.depth - 1)]
    variants = a.variants.split(",")

    def run_peer(variant, exr, seed):
        peer = subprocess.run([sys.executable, peer_script(scene, a.narrow_peers), variant,
                               scene, str(a.spp), "--depth", str(a.depth), *size[:2], "--out", exr,
                               "--seed", str(seed + 1)],
                              check=True, capture_output=True, text=True)
        return json.loads(peer.stdout.strip().splitlines()[-1])

    # Every renderer once per turn, so that a drift of the host's speed reaches all alike.
    # Turn t renders seed t % seeds; the first `seeds` turns' images are kept.
    prism_runs, peer_runs = [], {v: [] for v in variants}
    image_of = lambda name, turn: os.path.join(out, f"{name}-{turn}.exr")
    for turn in range(max(a.repeats, a.seeds)):
        seed = turn % a.seeds
        run = [image_of("prism", turn) if c == prism_exr else c for c in cmd] + ["--seed", str(seed)]
        prism_runs.append(json.loads(subprocess.run(run, check=True, capture_output=True, text=True).stdout))
        for variant in variants:
            peer_runs[variant].append(run_peer(variant, image_of(variant, turn), seed))
    median = lambda runs: float(np.median([r["seconds"] for r in runs]))
    prism_stats = dict(prism_runs[0])
    prism_stats["seconds"] = median(prism_runs)
    pixels = prism_stats["width"] * prism_stats["height"]
    prism_stats["paths_per_second"] = pixels * a.spp / prism_stats["seconds"]
    result = {"scene": scene_name(scene), "spp": a.spp, "width": prism_stats["width"],
              "height": prism_stats["height"], "depth": a.depth, "cpu": cpu(),
              "peers": "imitating a host without AVX-512" if a.narrow_peers else "native",
              "prism": {k: prism_stats[k] for k in ("seconds", "paths_per_second", "peak_memory_bytes", "splits", "reuse")}}
    if a.repeats > 1:
        result["prism"]["seconds_each"] = [r["seconds"] for r in prism_runs]
    seeded = {name: [read_exr(image_of(name, t)) for t in range(a.seeds)] for name in ["prism"] + variants}
    images = {name: runs[0] for name, runs in seeded.items()}
    for variant in variants:
        seconds = median(peer_runs[variant])
        pps = pixels * a.spp / seconds
        result[variant] = {"seconds": seconds, "paths_per_second": pps,
                           "prism_speed_ratio": prism_stats["paths_per_second"] / pps}
        if a.repeats > 1:
            result[variant]["seconds_each"] = [r["seconds"] for r in peer_runs[variant]]
        result[variant]["prism_vs_peer"] = agreement(images["prism"], images[variant], a.grid)
    reference = a.reference
    if reference is None and peer_reference:
        reference = peer_reference
        if not os.path.exists(reference):
            subprocess.run([sys.executable, os.path.join(ROOT, "benches", "peer", "mitsuba_reference.py"), scene,
                            *size[:2], "--spp", str(a.peer_reference_spp), "--depth", str(a.depth),
                            "--out", reference], check=True, capture_output=True)
    if reference is None and a.reference_spp:
        reference = os.path.join(out, "reference.exr")
        ref_cmd = [c for c in cmd if c != "--stats"]
        ref_cmd[ref_cmd.index("--spp") + 1] = str(a.reference_spp)
        ref_cmd[ref_cmd.index(prism_exr)] = reference
        if "--seed" in ref_cmd:
            ref_cmd[ref_cmd.index("--seed") + 1] = "999"
        else:
            ref_cmd += ["--seed", "999"]
        subprocess.run(ref_cmd + ["-q"], check=True, capture_output=True)
    if reference:
        ref = read_exr(reference)
        result["against_reference"] = {name: agreement(img, ref, a.grid) for name, img in images.items()}
        # Fireflies make one seed's error a poor estimate: the mean over the seeds.
        errors = {name: float(np.mean([relmse(img, ref) for img in runs])) for name, runs in seeded.items()}
        noise = reference_noise(reference, ref)
        if noise is not None:
            result["reference_noise"] = noise
            result["relmse_with_reference_noise"] = dict(errors)
            errors = {name: e - noise for name, e in errors.items()}
            if min(errors.values()) <= 0.0:
                sys.exit(f"{scene}: the reference's noise ({noise:.3g}) is not below every renderer's error "
                         "against it: render it with more samples (--peer-reference-spp)")
        if a.prism_reference_dir:
            own = os.path.join(a.prism_reference_dir, f"prism-ref-{scene_name(scene)}-{result['width']}.exr")
            if not os.path.exists(own):
                own_cmd = [c for c in cmd if c != "--stats"]
                own_cmd[own_cmd.index("--spp") + 1] = str(a.peer_reference_spp)
                own_cmd[own_cmd.index(prism_exr)] = own
                subprocess.run(own_cmd + ["--seed", "999", "-q"], check=True, capture_output=True)
            own_ref = read_exr(own)
            result["prism_reference"] = own
            result["references_agree"] = agreement(own_ref, ref, a.grid)
            result["against_reference"]["prism"] = agreement(images["prism"], own_ref, a.grid)
            # Kept beside the own-reference error: the two renderers' models' difference
            # counts as prism's error in this one.
            result["prism_relmse_against_peer_reference"] = errors["prism"]
            errors["prism"] = float(np.mean([relmse(img, own_ref) for img in seeded["prism"]]))
        if a.seeds > 1:
            result["seeds"] = a.seeds
        result["prism"]["relmse"] = errors["prism"]
        for variant in variants:
            peer = result[variant]
            peer["relmse"] = errors[variant]
            peer["prism_error_ratio"] = errors["prism"] / errors[variant]
            peer["prism_efficiency_ratio"] = (peer["seconds"] * errors[variant]) / (
                result["prism"]["seconds"] * errors["prism"])
    return result


if __name__ == "__main__":
    main()
