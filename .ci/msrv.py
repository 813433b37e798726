"""The workspace's rust-version holds for its dependencies too: no crate in the lock file
declares a newer one. (The machine has one toolchain and cannot fetch another, so the MSRV
build itself is not run here; clippy's incompatible_msrv lint, on in CI through
clippy::all, flags standard-library APIs newer than rust-version in prism's own code.)"""
import json
import subprocess
import sys

meta = json.loads(subprocess.check_output(
    ["cargo", "metadata", "--format-version", "1", "--locked"]))
members = set(meta["workspace_members"])
def version(text):
    return tuple(int(x) for x in text.split("."))[:3] + (0,) * (3 - len(text.split(".")))
ours = {p["rust_version"] for p in meta["packages"] if p["id"] in members}
if len(ours) != 1:
    sys.exit(f"workspace members disagree on rust-version: {sorted(ours)}")
msrv = version(ours.pop())
newer = [(p["name"], p["version"], p["rust_version"]) for p in meta["packages"]
         if p.get("rust_version") and version(p["rust_version"]) > msrv]
if newer:
    sys.exit(f"dependencies need a newer Rust than {msrv}: {newer}")
print(f"rust-version {'.'.join(map(str, msrv))}: no dependency declares a newer one")
