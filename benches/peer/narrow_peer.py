"""Mitsuba 3's timed render (../shared/scenes/peer/mitsuba_peer.py) as on a host without AVX-512,
run on one that has it: issue 30 asks for prism's lead on both kinds of host, and the
development VM may only be the wide kind.

  python3 benches/peer/narrow_peer.py VARIANT {box|bunny} SPP [mitsuba_peer.py's options]
  python3 benches/peer/compare.py box ... --narrow-peers     # the same, for every peer

What changes (PEER_TARGET_CPU, default znver3: AMD Zen 3, AVX2 and FMA, no AVX-512):
- Dr.Jit's LLVM backend compiles for that CPU, with every AVX-512 feature turned off, and
  8 lanes wide instead of 16 (jit_llvm_set_target, drjit-core's public API: "Width of
  vector registers, e.g. 8 for AVX"); its ray tracing calls then use Embree's 8-wide
  packets.
- Embree, which Mitsuba uses in every variant, is capped at AVX2 (`max_isa=avx2`, appended
  to Mitsuba's device configuration by narrow/embree_isa.c, built here with the C compiler
  and preloaded).
What does not: the host's caches, clocks and memory, and Mitsuba's own C++ code (built for
a generic x86-64, the same on both kinds of host). prism needs nothing: its release build is
x86-64-v2 everywhere (.cargo/config.toml), so its code is the same on both hosts.
So this is an imitation of the narrower host, not a measurement on one.
"""
import ctypes, os, runpy, subprocess, sys, tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
SHARED = os.environ.get("PRISM_SHARED", os.path.join(os.path.dirname(ROOT), "shared"))


def embree_library():
    import mitsuba
    return os.path.join(os.path.dirname(mitsuba.__file__), "libembree3.so")


def build_interposer():
    out = os.path.join(tempfile.gettempdir(), f"prism-embree-isa-{os.getuid()}.so")
    source = os.path.join(HERE, "narrow", "embree_isa.c")
    if not os.path.exists(out) or os.path.getmtime(out) < os.path.getmtime(source):
        subprocess.run([os.environ.get("CC", "cc"), "-shared", "-fPIC", "-O2", "-o", out, source, "-ldl"],
                       check=True)
    return out


def narrow_llvm(variant, target_cpu):
    """Initializes Dr.Jit's LLVM backend, then retargets it (before any kernel is compiled)."""
    import mitsuba as mi
    mi.set_variant(variant)
    import drjit as dr
    dr.eval(dr.llvm.Float([1.0]) + 1.0)  # the backend exists only once used
    core = ctypes.CDLL(os.path.join(os.path.dirname(dr.__file__), "libdrjit-core.so"))
    features_of = core._Z24jit_llvm_target_featuresv  # C++ names: drjit-core's jit_* API
    features_of.restype = ctypes.c_char_p
    width_of = core._Z21jit_llvm_vector_widthv
    width_of.restype = ctypes.c_uint32
    features = features_of().decode()
    narrow = ",".join("-" + f[1:] if f[1:].startswith(("avx512", "evex512", "avx10")) else f
                      for f in features.split(","))
    set_target = core._Z19jit_llvm_set_targetPKcS0_j
    set_target.argtypes = [ctypes.c_char_p, ctypes.c_char_p, ctypes.c_uint32]
    set_target(target_cpu.encode(), narrow.encode(), 8)
    if width_of() != 8:
        sys.exit("narrow_peer: Dr.Jit's LLVM backend did not take the narrower target")


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    if "EMBREE_EXTRA_CONFIG" not in os.environ:
        env = dict(os.environ, EMBREE_EXTRA_CONFIG="max_isa=avx2", EMBREE_LIBRARY=embree_library(),
                   LD_PRELOAD=build_interposer())
        os.execve(sys.executable, [sys.executable] + sys.argv, env)
    variant = sys.argv[1]
    if variant.startswith("llvm"):
        narrow_llvm(variant, os.environ.get("PEER_TARGET_CPU", "znver3"))
    peer = os.path.join(SHARED, "scenes", "peer", "mitsuba_peer.py")
    sys.argv = [peer] + sys.argv[1:]
    runpy.run_path(peer, run_name="__main__")


if __name__ == "__main__":
    main()
