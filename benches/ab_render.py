"""Two or more prism builds timed on the same render, alternately, with medians: on a shared,
noisy VM a single run of each differs by 5-10% from the next, so a change of a few percent
shows only in alternating runs (the slowdowns of the host then hit every build alike).

  RUSTFLAGS=... cargo build --release -p prism-cli --target-dir /tmp/other
  python3 benches/ab_render.py target/release/prism /tmp/other/release/prism \
      --runs 7 -- render ../shared/scenes/cornell-box.gltf --width 128 --height 128 --spp 64

Prints each build's sorted wall times, its median, and the median's ratio to the first
build's. With --same it also checks that every build wrote a byte-identical image (the
render's `-o` is given by the script).
"""
import argparse, filecmp, os, statistics, subprocess, sys, tempfile, time


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("builds", nargs="+", help="prism binaries")
    ap.add_argument("--runs", type=int, default=7)
    ap.add_argument("--same", action="store_true", help="check the images are byte-identical")
    argv = sys.argv[1:]
    if "--" not in argv:
        sys.exit("ab_render: no prism arguments (give them after --)")
    split = argv.index("--")
    a = ap.parse_args(argv[:split])
    args = argv[split + 1:]
    if not args:
        sys.exit("ab_render: no prism arguments (give them after --)")
    out = tempfile.mkdtemp(prefix="prism-ab-")
    times = {b: [] for b in a.builds}
    for _ in range(a.runs):
        for i, build in enumerate(a.builds):
            image = os.path.join(out, f"{i}.exr")
            start = time.perf_counter()
            run = subprocess.run([build, *args, "-o", image], capture_output=True, text=True)
            elapsed = time.perf_counter() - start
            if run.returncode != 0:
                sys.exit(f"ab_render: {build} failed: {run.stderr.strip().splitlines()[-1:]}")
            times[build].append(elapsed)
    first = statistics.median(times[a.builds[0]])
    for build in a.builds:
        median = statistics.median(times[build])
        runs = " ".join(f"{t:.2f}" for t in sorted(times[build]))
        print(f"{build}: {runs}  median {median:.3f} s  ratio {median / first:.3f}")
    if a.same:
        images = [os.path.join(out, f"{i}.exr") for i in range(len(a.builds))]
        same = all(filecmp.cmp(images[0], other, shallow=False) for other in images[1:])
        print("images byte-identical" if same else "images DIFFER")
        sys.exit(0 if same else 1)


if __name__ == "__main__":
    main()
