"""Writes scenes/sky.hdr: a small equirectangular HDR sky for the examples and tests.

A clear-sky gradient (a blue zenith brightening towards the horizon), a warm grey ground
below the horizon, and a sun 35 degrees above the horizon whose disk is a few texels
wide and bright enough to carry most of the light, as in a real daylight HDRI. Radiance
values are in emissive-colour units (linear sRGB; 1 is the radiance that lights a white
Lambertian plane to RGB 1 from a whole hemisphere). The mapping is prism's (and Blender's
and three.js's): +y up, the top row the zenith, the centre column towards +x, u = 3/4
towards +z. The sun is at azimuth u = 0.62, so it lights a model from the front right
of the default camera (which looks along -z).

Radiance RGBE with flat scanlines (no run-length encoding), written without an imaging
library. Run from the repository root:

    python3 scenes/tools/make_sky.py
"""

import math

WIDTH, HEIGHT = 256, 128
SUN_U, SUN_ELEVATION = 0.62, math.radians(35.0)
SUN_RADIUS = math.radians(2.5)
SUN = (420.0, 385.0, 330.0)


def direction(u, v):
    theta, phi = math.pi * v, 2.0 * math.pi * (u - 0.5)
    return (math.sin(theta) * math.cos(phi), math.cos(theta), math.sin(theta) * math.sin(phi))


SUN_DIR = direction(SUN_U, 0.5 - SUN_ELEVATION / math.pi)


def radiance(u, v):
    d = direction(u, v)
    cos_sun = sum(a * b for a, b in zip(d, SUN_DIR))
    if cos_sun > math.cos(SUN_RADIUS):
        return SUN
    if d[1] < 0.0:
        return (0.25, 0.22, 0.18)
    horizon = 1.0 - d[1]
    glow = 0.6 * max(cos_sun, 0.0) ** 8
    return (0.35 + 0.55 * horizon + glow, 0.5 + 0.45 * horizon + glow * 0.9, 0.9 + 0.2 * horizon + glow * 0.7)


def rgbe(c):
    m = max(c)
    if m < 1e-32:
        return bytes(4)
    mantissa, exponent = math.frexp(m)
    scale = mantissa * 256.0 / m
    return bytes([min(255, int(x * scale)) for x in c] + [exponent + 128])


def main():
    header = f"#?RADIANCE\n# prism scenes/tools/make_sky.py\nFORMAT=32-bit_rle_rgbe\n\n-Y {HEIGHT} +X {WIDTH}\n"
    body = b"".join(
        rgbe(radiance((x + 0.5) / WIDTH, (y + 0.5) / HEIGHT)) for y in range(HEIGHT) for x in range(WIDTH)
    )
    with open("scenes/sky.hdr", "wb") as f:
        f.write(header.encode() + body)


if __name__ == "__main__":
    main()
