"""Writes scenes/smoke.vol: a plume of smoke on a 40^3 grid (Mitsuba's .vol format, one
float channel), for the media examples of docs/scene-format.md and the README's scenes.

The plume rises from a narrow source at the bottom centre of the unit box [0, 1]^3 (y up),
widening and thinning as it climbs, its edges torn by a few octaves of smooth
deterministic noise (sums of sines, no random numbers: the file is the same on every run),
fading out before the top. Densities are 0 to about 1: a medium's `scale` sets how thick
the smoke is. Most of the box is empty, which is what the coarse majorant grid is for.

Run from the repository root: python3 scenes/tools/make_smoke.py
"""

import math
import os
import struct

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
N = 40


def noise(x, y, z):
    value, amplitude, frequency = 0.0, 1.0, 5.0
    for octave in range(4):
        value += amplitude * math.sin(frequency * x + 1.7 * octave + 2.3 * math.sin(frequency * 0.7 * z + octave)) \
            * math.sin(frequency * 0.9 * z - 0.8 * octave + 1.9 * math.sin(frequency * 0.6 * y)) \
            * math.cos(frequency * 0.5 * y + 0.4 * octave)
        amplitude *= 0.5
        frequency *= 2.1
    return value


def density(x, y, z):
    # Centre line sways as it rises; radius grows from 0.05 to 0.35.
    cx = 0.5 + 0.08 * math.sin(5.0 * y)
    cz = 0.5 + 0.06 * math.cos(4.0 * y)
    radius = 0.05 + 0.3 * y
    r = math.hypot(x - cx, z - cz) / radius
    torn = r + 0.35 * noise(x, y, z)
    if torn >= 1.0:
        return 0.0
    fade = min(1.0, y / 0.05) * max(0.0, 1.0 - ((y - 0.1) / 0.85) ** 2)
    thinning = 0.25 + 0.75 / (1.0 + 6.0 * y)
    return max(0.0, (1.0 - torn) ** 1.5 * fade * thinning)


def main():
    values = []
    for k in range(N):
        for j in range(N):
            for i in range(N):
                values.append(density((i + 0.5) / N, (j + 0.5) / N, (k + 0.5) / N))
    out = bytearray(b"VOL")
    out.append(3)
    out += struct.pack("<5i", 1, N, N, N, 1)
    out += struct.pack("<6f", 0.0, 0.0, 0.0, 1.0, 1.0, 1.0)
    out += struct.pack(f"<{len(values)}f", *values)
    path = os.path.join(ROOT, "scenes", "smoke.vol")
    with open(path + ".partial", "wb") as f:
        f.write(out)
    os.replace(path + ".partial", path)
    filled = sum(v > 0 for v in values)
    print(f"{path}: {N}^3 voxels, {filled} non-empty ({100 * filled / len(values):.1f}%), max {max(values):.3f}")


if __name__ == "__main__":
    main()
