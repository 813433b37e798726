#!/usr/bin/env python3
"""Writes scenes/mitsuba/textures.xml and the tiny images it reads (scenes/mitsuba/textures/).

The scene checks prism's reading of Mitsuba's textures against Mitsuba's own render (its
references by make_mitsuba_ztest_refs.py): three rectangles under a white sky, seen at
32 x 32 pixels,

- a colour bitmap (6 x 5 texels of saturated colours, so that blending spectra rather
  than colours shows) on a diffuse surface, bilinear, repeated by a to_uv that scales and
  shifts it;
- a checkerboard whose second colour is a grey bitmap read nearest and mirrored;
- a mask whose opacity is a grey bitmap over a diffuse surface, the sky seen through it.

The images are written here, byte for byte from this script (PNG by zlib, no imaging
library), so that the repository holds nothing it cannot regenerate.

  python3 scenes/tools/make_mitsuba_textures.py
"""

import os
import struct
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))
OUT = os.path.join(HERE, "..", "mitsuba")


def png(path, width, height, channels, pixels):
    """An 8-bit PNG of `channels` (1: grey, 3: RGB) from rows of byte values."""
    colour = {1: 0, 3: 2}[channels]
    raw = b"".join(b"\x00" + bytes(row) for row in pixels)

    def chunk(kind, data):
        body = kind + data
        return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body) & 0xFFFFFFFF)

    header = struct.pack(">IIBBBBB", width, height, 8, colour, 0, 0, 0)
    data = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b"")
    with open(path, "wb") as f:
        f.write(data)


def images():
    folder = os.path.join(OUT, "textures")
    os.makedirs(folder, exist_ok=True)
    palette = [(230, 40, 30), (30, 200, 60), (40, 60, 220), (240, 220, 40), (250, 250, 250), (10, 10, 10)]
    colour = [[c for x in range(6) for c in palette[(x + 2 * y) % len(palette)]] for y in range(5)]
    png(os.path.join(folder, "colours.png"), 6, 5, 3, colour)
    ramp = [[(40 * x + 70 * y) % 256 for x in range(4)] for y in range(4)]
    png(os.path.join(folder, "ramp.png"), 4, 4, 1, ramp)
    disc = [[255 if (x - 3.5) ** 2 + (y - 3.5) ** 2 < 10 else 0 for x in range(8)] for y in range(8)]
    png(os.path.join(folder, "disc.png"), 8, 8, 1, disc)


SCENE = """<!-- Mitsuba textures (bitmap, checkerboard, mask), written by scenes/tools/make_mitsuba_textures.py -->
<scene version="3.0.0">
    <integrator type="path">
        <integer name="max_depth" value="3"/>
    </integrator>
    <sensor type="perspective">
        <float name="fov" value="40"/>
        <transform name="to_world">
            <lookat origin="0, 0, 6" target="0, 0, 0" up="0, 1, 0"/>
        </transform>
        <sampler type="independent">
            <integer name="sample_count" value="64"/>
        </sampler>
        <film type="hdrfilm">
            <integer name="width" value="32"/>
            <integer name="height" value="32"/>
            <rfilter type="box"/>
            <string name="pixel_format" value="rgb"/>
        </film>
    </sensor>
    <emitter type="constant">
        <rgb name="radiance" value="1"/>
    </emitter>
    <shape type="rectangle">
        <transform name="to_world">
            <scale x="1" y="1.9"/>
            <translate x="-1.05"/>
        </transform>
        <bsdf type="diffuse">
            <texture type="bitmap" name="reflectance">
                <string name="filename" value="textures/colours.png"/>
                <transform name="to_uv">
                    <scale x="1.5" y="1.2"/>
                    <translate x="-0.2" y="0.1"/>
                </transform>
            </texture>
        </bsdf>
    </shape>
    <shape type="rectangle">
        <transform name="to_world">
            <scale value="0.9"/>
            <translate x="1.05" y="0.95"/>
        </transform>
        <bsdf type="diffuse">
            <texture type="checkerboard" name="reflectance">
                <rgb name="color0" value="0.8, 0.3, 0.1"/>
                <texture type="bitmap" name="color1">
                    <string name="filename" value="textures/ramp.png"/>
                    <string name="filter_type" value="nearest"/>
                    <string name="wrap_mode" value="mirror"/>
                    <transform name="to_uv">
                        <scale value="1.7"/>
                    </transform>
                </texture>
                <transform name="to_uv">
                    <scale value="3"/>
                </transform>
            </texture>
        </bsdf>
    </shape>
    <shape type="rectangle">
        <transform name="to_world">
            <scale value="0.9"/>
            <translate x="1.05" y="-0.95"/>
        </transform>
        <bsdf type="mask">
            <texture type="bitmap" name="opacity">
                <string name="filename" value="textures/disc.png"/>
                <string name="wrap_mode" value="clamp"/>
            </texture>
            <bsdf type="diffuse">
                <rgb name="reflectance" value="0.1, 0.2, 0.7"/>
            </bsdf>
        </bsdf>
    </shape>
</scene>
"""


def main():
    images()
    with open(os.path.join(OUT, "textures.xml"), "w") as f:
        f.write(SCENE)
    print("wrote scenes/mitsuba/textures.xml and scenes/mitsuba/textures/*.png")


if __name__ == "__main__":
    main()
