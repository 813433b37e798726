#!/usr/bin/env python3
"""Writes scenes/mitsuba/emitters.xml and the sky image it reads
(scenes/mitsuba/textures/emitters-sky.hdr).

The scene checks prism's reading of Mitsuba's emitters against Mitsuba's own render (its
references by make_mitsuba_ztest_refs.py): a floor and two spheres, diffuse, at 32 x 32
pixels, lit by

- an `envmap`: a 32 x 16 sky whose colours change with azimuth and height, with a small
  bright sun off to one side, turned by a `to_world` and scaled, so that the sky seen
  behind the spheres, the sun's shadows and the tint of the light show Mitsuba's
  direction mapping, texel grid and spectra;
- a `point` light placed by `position`, with a colour;
- a `spot` light placed and aimed by `to_world`, its edge between `beam_width` and
  `cutoff_angle` falling on the floor (Mitsuba's falloff is linear in angle);
- a `directional` light by `direction`, its irradiance a plain number (D65 times it).

The image is written here, byte for byte from this script (Radiance RGBE, flat
scanlines), so that the repository holds nothing it cannot regenerate.

  python3 scenes/tools/make_mitsuba_emitters.py
"""

import math
import os

HERE = os.path.dirname(os.path.abspath(__file__))
OUT = os.path.join(HERE, "..", "mitsuba")
WIDTH, HEIGHT = 32, 16
SUN = (20, 4)  # texel (column, row) of the sun's corner; the sun is 2 x 2 texels


def rgbe(rgb):
    m = max(rgb)
    if m < 1e-30:
        return bytes(4)
    mantissa, exponent = math.frexp(m)
    scale = mantissa * 256.0 / m
    return bytes([min(255, int(c * scale)) for c in rgb] + [exponent + 128])


def sky(x, y):
    """Linear sRGB radiance of texel (x, y): rows from the zenith down to the nadir."""
    if (x - SUN[0]) in (0, 1) and (y - SUN[1]) in (0, 1):
        return (30.0, 24.0, 16.0)
    u = (x + 0.5) / WIDTH
    theta = math.pi * y / (HEIGHT - 1)
    up = math.cos(theta)
    if up > 0:
        # Blue overhead, tinted towards the horizon by azimuth: warm on one side,
        # green on the other.
        hue = 0.5 + 0.5 * math.cos(2 * math.pi * u)
        horizon = 1 - up
        return (
            0.15 + 0.5 * horizon * hue,
            0.25 + 0.35 * horizon * (1 - hue),
            0.6 * up + 0.1,
        )
    return (0.12, 0.09, 0.06)  # ground


def write_sky():
    folder = os.path.join(OUT, "textures")
    os.makedirs(folder, exist_ok=True)
    data = bytearray(f"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y {HEIGHT} +X {WIDTH}\n".encode())
    for y in range(HEIGHT):
        for x in range(WIDTH):
            data += rgbe(sky(x, y))
    with open(os.path.join(folder, "emitters-sky.hdr"), "wb") as f:
        f.write(bytes(data))


SCENE = """<!-- Mitsuba's emitters on diffuse shapes, written by scenes/tools/make_mitsuba_emitters.py -->
<scene version="3.0.0">
    <integrator type="path">
        <integer name="max_depth" value="4"/>
    </integrator>
    <sensor type="perspective">
        <float name="fov" value="50"/>
        <transform name="to_world">
            <lookat origin="0, 1.2, -5" target="0, 0.6, 0" up="0, 1, 0"/>
        </transform>
        <sampler type="independent">
            <integer name="sample_count" value="64"/>
        </sampler>
        <film type="hdrfilm">
            <integer name="width" value="32"/>
            <integer name="height" value="32"/>
            <rfilter type="box"/>
        </film>
    </sensor>

    <emitter type="envmap">
        <string name="filename" value="textures/emitters-sky.hdr"/>
        <float name="scale" value="0.8"/>
        <transform name="to_world"><rotate y="1" angle="40"/></transform>
    </emitter>
    <emitter type="point">
        <point name="position" value="1.5, 2, -1"/>
        <rgb name="intensity" value="3, 2.5, 2"/>
    </emitter>
    <emitter type="spot">
        <rgb name="intensity" value="60, 70, 90"/>
        <float name="cutoff_angle" value="25"/>
        <float name="beam_width" value="15"/>
        <transform name="to_world">
            <lookat origin="0.3, 3, 0.5" target="0.6, 0, 0.8" up="0, 0, 1"/>
        </transform>
    </emitter>
    <emitter type="directional">
        <vector name="direction" value="-0.3, -1, 0.4"/>
        <float name="irradiance" value="0.5"/>
    </emitter>

    <shape type="rectangle">
        <transform name="to_world">
            <rotate x="1" angle="-90"/>
            <scale value="3"/>
        </transform>
        <bsdf type="diffuse"><rgb name="reflectance" value="0.6, 0.6, 0.6"/></bsdf>
    </shape>
    <shape type="sphere">
        <point name="center" value="-0.8, 0.5, 0"/>
        <float name="radius" value="0.5"/>
        <bsdf type="diffuse"><rgb name="reflectance" value="0.7, 0.25, 0.2"/></bsdf>
    </shape>
    <shape type="sphere">
        <point name="center" value="0.7, 0.4, -0.4"/>
        <float name="radius" value="0.4"/>
        <bsdf type="diffuse"><rgb name="reflectance" value="0.3, 0.5, 0.7"/></bsdf>
    </shape>
</scene>
"""


def main():
    write_sky()
    with open(os.path.join(OUT, "emitters.xml"), "w") as f:
        f.write(SCENE)


if __name__ == "__main__":
    main()
