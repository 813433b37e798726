"""What Python costs over the command line, and prism.upsample on a million colours.

    pip install ./python && cargo build --release -p prism-cli
    python python/benches/overhead.py            # from the repository root
    cargo bench -p prism-benches --bench upsample -- "table lookup/trilinear many/64"

Medians of RUNS alternating runs, wall time, the CPU model printed first:
- the Cornell box at 64 x 64, 4 spp: `prism render` as a process, `python -c` importing
  prism, loading and rendering (start-up included, as the command line's), and
  `prism.render` alone in a running interpreter;
- `prism.upsample` of 10^6 random colours by the shipped table (method="table") and of
  10^4 by exact fits, per colour; compare the table's with the Rust batch lookup's
  (`lookup_many`) from the criterion bench above.
"""

import json
import os
import platform
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np

import prism

RUNS = 7
SCENE = "scenes/cornell-box.gltf"
CLI = os.environ.get("PRISM_BIN", "target/release/prism")


def cpu_model():
    try:
        for line in open("/proc/cpuinfo"):
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor()


def timed(run):
    start = time.perf_counter()
    run()
    return time.perf_counter() - start


def main():
    out = tempfile.mkdtemp()
    cli = [CLI, "render", SCENE, "--spp", "4", "--width", "64", "--height", "64", "-o", f"{out}/c.exr", "--quiet"]
    script = (
        "import prism; s = prism.load('%s'); prism.render(s, spp=4, width=64, height=64).save('%s/p.exr')"
        % (SCENE, out)
    )
    scene = prism.load(SCENE)
    times = {"cli process": [], "python process": [], "prism.render in process": []}
    for _ in range(RUNS):
        times["cli process"].append(timed(lambda: subprocess.run(cli, check=True)))
        times["python process"].append(timed(lambda: subprocess.run([sys.executable, "-c", script], check=True)))
        times["prism.render in process"].append(timed(lambda: prism.render(scene, spp=4, width=64, height=64)))
    rgb = np.random.default_rng(7).random((1_000_000, 3))
    table = statistics.median(timed(lambda: prism.upsample(rgb, method="table")) for _ in range(3)) / len(rgb)
    exact = statistics.median(timed(lambda: prism.upsample(rgb[:10_000])) for _ in range(3)) / 10_000
    result = {
        "cpu": cpu_model(),
        "threads": os.cpu_count(),
        "render_seconds": {k: statistics.median(v) for k, v in times.items()},
        "upsample_ns_per_colour": {"table": table * 1e9, "exact": exact * 1e9},
    }
    print(json.dumps(result, indent=1))


if __name__ == "__main__":
    main()
