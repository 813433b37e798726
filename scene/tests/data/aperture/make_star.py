"""Writes star.png: a five-pointed star, white on black, 32 x 32 grey pixels, the aperture
image the scene format's tests load (scene/tests/lens_format.rs). Pure Python (zlib).
Run from this folder: python3 make_star.py
"""

import math
import struct
import zlib

SIDE = 32


def inside_star(x, y):
    # A point is inside the star if it lies inside the pentagram's outline: in polar
    # terms, its radius is below the outline's radius at its angle.
    r = math.hypot(x, y)
    a = math.atan2(y, x) - math.pi / 2
    sector = (a % (2 * math.pi / 5)) / (2 * math.pi / 5)
    outer, inner = 0.95, 0.38
    t = abs(sector - 0.5) * 2  # 1 at a point, 0 between two points
    return r <= inner + (outer - inner) * t


def main():
    rows = []
    for j in range(SIDE):
        row = bytearray([0])  # filter: none
        for i in range(SIDE):
            x = -1 + (i + 0.5) * 2 / SIDE
            y = 1 - (j + 0.5) * 2 / SIDE
            row.append(255 if inside_star(x, y) else 0)
        rows.append(bytes(row))

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))

    png = b"\x89PNG\r\n\x1a\n"
    png += chunk(b"IHDR", struct.pack(">IIBBBBB", SIDE, SIDE, 8, 0, 0, 0, 0))
    png += chunk(b"IDAT", zlib.compress(b"".join(rows), 9))
    png += chunk(b"IEND", b"")
    with open("star.png", "wb") as f:
        f.write(png)


if __name__ == "__main__":
    main()
