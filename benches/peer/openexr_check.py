"""Checks prism's spectral EXR with the OpenEXR reference library (its Python bindings).

  pip install OpenEXR numpy
  cargo build --release -p prism-cli
  python3 benches/peer/openexr_check.py

Renders the Cornell box with --spectral-bands 8 --energy, opens the file with OpenEXR (the
Academy Software Foundation's library, not the Rust exr crate prism writes with) and checks
the spectral layout of Fichet, Pacanowski and Wilkie (JCGT 10(3), 2021): the
spectralLayoutVersion and emissiveUnits attributes, S0.<nm>nm channel names with a decimal
comma at the band centres, finite non-negative radiance, the RGB preview and the energy
channels. Prints one JSON line; exits non-zero on the first failed check.
"""
import json, os, re, subprocess, sys, tempfile

import numpy as np
import OpenEXR

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
PRISM = os.path.join(ROOT, "target", "release", "prism")


def check(condition, what):
    if not condition:
        print(json.dumps({"ok": False, "failed": what}))
        sys.exit(1)


def main():
    out = os.path.join(tempfile.mkdtemp(prefix="prism-openexr-"), "spectral.exr")
    subprocess.run([PRISM, "render", "--width", "32", "--height", "24", "--spp", "8", "--spectral-bands", "8",
                    "--spectral-range", "380:780", "--energy", "-o", out, "-q"], check=True)
    with OpenEXR.File(out) as f:
        header, channels = f.header(), f.channels()
        check(str(header.get("spectralLayoutVersion")) == "1.0", "spectralLayoutVersion = 1.0")
        check(str(header.get("emissiveUnits")) == "W.m^-2.sr^-1", "emissiveUnits = W.m^-2.sr^-1")
        names = sorted(k for k in channels if k.startswith("S0."))
        check(len(names) == 8, f"8 spectral channels, found {names}")
        pattern = re.compile(r"^S0\.(\d+),(\d+)nm$")
        centres = []
        for n in names:
            m = pattern.match(n)
            check(m is not None, f"channel name {n} follows S0.<integer>,<fraction>nm")
            centres.append(float(f"{m.group(1)}.{m.group(2)}"))
        check(np.allclose(sorted(centres), [380 + 25 + 50 * k for k in range(8)]), f"band centres {centres}")
        spectra = np.stack([channels[n].pixels for n in names])
        check(spectra.shape == (8, 24, 32), f"spectral shape {spectra.shape}")
        check(np.all(np.isfinite(spectra)) and np.all(spectra >= 0), "finite non-negative spectral radiance")
        check(spectra.mean() > 0, "some light")
        rgb = channels.get("RGB") or None
        check(rgb is not None and rgb.pixels.shape == (24, 32, 3), "an RGB preview")
        for n in ("energy.radiance", "energy.eV", "energy.photons"):
            check(n in channels, f"{n} channel")
    print(json.dumps({"ok": True, "file": out, "spectral_channels": names, "openexr": OpenEXR.__version__}))


if __name__ == "__main__":
    main()
