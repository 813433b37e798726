#!/usr/bin/env python3
"""Mitsuba 3's own render test suite, rendered by prism and judged by Mitsuba's own test.

mitsuba-renderer/mitsuba-data holds the suite: 41 scenes under tests/scenes/<folder>/, each
with references rendered by Mitsuba (refs/<name>_ref_spectral.exr, the mean, and
_var.exr, the per-sample variance). Mitsuba's test (src/render/tests/test_renders.py of
mitsuba-renderer/mitsuba3) renders each scene with spp = 2e6 / pixels and seed 0, passing
`spp` and the scene's integrator (its file name's last word) as parameters, then z-tests
every pixel in XYZ, Sidak-corrected at 0.01, and passes a scene when 99.75% of the
pixels' channels pass. This script does the same with prism: `prism render scene.xml
-D spp=N -D integrator=NAME --spp N --seed 0`, then `prism compare --variance --spp`,
which is that test.

The data carries no licence file, so it is fetched, not committed:

  git clone --depth 1 --filter=blob:none --sparse https://github.com/mitsuba-renderer/mitsuba-data
  (cd mitsuba-data && git sparse-checkout set tests common docs/scenes/sdfgrid)
  cargo build --release -p prism-cli
  python3 benches/peer/mitsuba_suite.py mitsuba-data [--only NAME ...] [--polarized]
      [--markdown table.md] [--json results.json] [--keep DIR]

--polarized renders with prism's --polarized against the `spectral_polarized` references
where the suite has them. Prints a line per scene and a summary; --markdown writes the
table the guide shows (docs/guide/mitsuba-suite.md), --json every figure.
"""

import argparse
import glob
import json
import os
import platform
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.abspath(os.path.join(HERE, "..", ".."))
BUDGET = 2_000_000  # samples per image, as Mitsuba's suite spends


def prism_binary():
    return os.environ.get("PRISM_BIN", os.path.join(ROOT, "target", "release", "prism"))


def exr_size(path):
    """Width and height of an EXR from its header's dataWindow (box2i: xmin ymin xmax ymax)."""
    with open(path, "rb") as f:
        data = f.read(65536)
    key = b"dataWindow\x00box2i\x00"
    at = data.find(key)
    if at < 0:
        raise ValueError(f"{path}: no dataWindow in the EXR header")
    at += len(key) + 4  # the attribute's size
    xmin, ymin, xmax, ymax = (int.from_bytes(data[at + 4 * i:at + 4 * i + 4], "little", signed=True)
                              for i in range(4))
    return xmax - xmin + 1, ymax - ymin + 1


def cpu_model():
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown CPU"


def suite(data_dir):
    scenes = sorted(glob.glob(os.path.join(data_dir, "tests", "scenes", "*", "*.xml")))
    if not scenes:
        sys.exit(f"mitsuba_suite.py: no scenes under {data_dir}/tests/scenes/*/ (is it mitsuba-data?)")
    return scenes


def references(scene, mode):
    base = os.path.splitext(os.path.basename(scene))[0].rsplit("_", 1)[0]
    ref = os.path.join(os.path.dirname(scene), "refs", f"{base}_ref_{mode}.exr")
    return ref, ref.replace(".exr", "_var.exr")


def last_line(text):
    lines = [line for line in text.strip().splitlines() if line.strip()]
    return lines[-1] if lines else ""


def short(message, data_dir):
    """An error line without the program's prefix and with paths relative to the data."""
    message = message.removeprefix("prism: error: ")
    return message.replace(os.path.join(os.path.abspath(data_dir), ""), "").replace(
        os.path.join(data_dir, ""), "")


def run_scene(scene, mode, polarized, out_dir, data_dir):
    folder = os.path.basename(os.path.dirname(scene))
    name = os.path.splitext(os.path.basename(scene))[0]
    integrator = name.rsplit("_", 1)[-1]
    row = {"folder": folder, "scene": name, "integrator": integrator}
    ref, var = references(scene, mode)
    if not (os.path.exists(ref) and os.path.exists(var)):
        row.update(status="no reference", reason=f"no {os.path.basename(ref)} in the suite")
        return row
    width, height = exr_size(ref)
    spp = max(1, BUDGET // (width * height))
    row.update(width=width, height=height, spp=spp)
    out = os.path.join(out_dir, f"{folder}-{name}.exr")
    command = [prism_binary(), "render", scene, "-D", f"spp={spp}", "-D",
               f"integrator={integrator}", "--spp", str(spp), "--seed", "0", "-q", "-o", out]
    if polarized:
        command.append("--polarized")
    start = time.perf_counter()
    render = subprocess.run(command, capture_output=True, text=True)
    row["seconds"] = round(time.perf_counter() - start, 2)
    warnings = [line for line in render.stderr.splitlines() if "warning" in line]
    row["warnings"] = warnings
    if render.returncode != 0:
        row.update(status="not loaded", reason=short(last_line(render.stderr), data_dir))
        return row
    compare = subprocess.run([prism_binary(), "compare", out, ref, "--variance", var, "--spp",
                              str(spp), "--json"], capture_output=True, text=True)
    try:
        result = json.loads(compare.stdout)
    except json.JSONDecodeError:
        row.update(status="error", reason=last_line(compare.stderr))
        return row
    z = result["ztest"]
    row.update(ztest=z, relmse=result["relmse"])
    row["status"] = "pass" if z["accepted"] else "fail"
    if not z["accepted"]:
        ratios = ", ".join("-" if r is None else f"{r:.4f}" for r in z["mean_ratio_xyz"])
        row["reason"] = (f"{z['passed']} of {3 * z['pixels']} pixel channels pass; "
                         f"XYZ mean ratio {ratios}")
    return row


def markdown(rows, mode, cpu):
    passed = sum(r["status"] == "pass" for r in rows)
    lines = [
        f"{passed} of {len(rows)} scenes pass ({mode} references; {cpu}).",
        "",
        "| folder | scene | result | pixel channels passing | XYZ mean ratio | seconds | why |",
        "|---|---|---|---|---|---|---|",
    ]
    for r in rows:
        z = r.get("ztest")
        share = f"{z['passed']} / {3 * z['pixels']}" if z else "-"
        ratio = (", ".join("-" if x is None else f"{x:.3f}" for x in z["mean_ratio_xyz"])
                 if z else "-")
        why = r.get("reason", "").replace("|", "\\|")
        lines.append(f"| {r['folder']} | {r['scene']} | {r['status']} | {share} | {ratio} | "
                     f"{r.get('seconds', '-')} | {why} |")
    return "\n".join(lines) + "\n"


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("data_dir", help="a mitsuba-data checkout (with tests/scenes and common)")
    parser.add_argument("--only", nargs="*", default=[], help="scene names (or folders) to run")
    parser.add_argument("--polarized", action="store_true",
                        help="render --polarized against the spectral_polarized references")
    parser.add_argument("--markdown", help="write the table here")
    parser.add_argument("--json", help="write every figure here")
    parser.add_argument("--keep", help="keep prism's renders in this directory")
    args = parser.parse_args()
    if not os.path.exists(prism_binary()):
        sys.exit(f"mitsuba_suite.py: no prism binary at {prism_binary()} "
                 "(cargo build --release -p prism-cli, or set PRISM_BIN)")
    mode = "spectral_polarized" if args.polarized else "spectral"
    scenes = [s for s in suite(args.data_dir)
              if not args.only or any(o in s for o in args.only)]
    out_dir = args.keep or tempfile.mkdtemp(prefix="prism-mitsuba-suite-")
    os.makedirs(out_dir, exist_ok=True)
    cpu = cpu_model()
    rows = []
    for scene in scenes:
        row = run_scene(scene, mode, args.polarized, out_dir, args.data_dir)
        rows.append(row)
        print(f"{row['status']:<12} {row['folder']}/{row['scene']}"
              + (f" ({row['seconds']} s)" if "seconds" in row else "")
              + (f": {row['reason']}" if "reason" in row else ""), flush=True)
    passed = sum(r["status"] == "pass" for r in rows)
    print(f"{passed} of {len(rows)} scenes pass ({mode}; {cpu})")
    if args.markdown:
        with open(args.markdown, "w") as f:
            f.write(markdown(rows, mode, cpu))
    if args.json:
        with open(args.json, "w") as f:
            json.dump({"cpu": cpu, "mode": mode, "rows": rows}, f, indent=1)
    sys.exit(0 if passed == len(rows) else 1)


if __name__ == "__main__":
    main()
