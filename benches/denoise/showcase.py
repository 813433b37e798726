"""The README's showcase: the effects stage at its default 64 spp, denoised
(docs/images/effects.png), and a crop of the noisy render beside the same crop denoised
(docs/images/denoise-crop.png). Needs Open Image Denoise (pip install pyoidn; PRISM_OIDN or
the python3 on PATH finds it) and nothing else: PNGs are read and written here with zlib.

  python3 benches/denoise/showcase.py --prism target/release/prism
"""
import argparse, os, struct, subprocess, tempfile, zlib

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
IMAGES = os.path.join(ROOT, "docs", "images")
# The crop: the SF11 prism and the fluorescent sphere's booth, where 64 spp stays noisy.
CROP = (200, 170, 290, 170)  # x, y, width, height


def read_png(path):
    """An 8-bit RGB PNG whose scanlines all use filter 0 (prism's): (width, height, rows)."""
    data = open(path, "rb").read()
    pos, width, height, idat = 8, 0, 0, b""
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            width, height, depth, colour = struct.unpack(">IIBB", body[:10])
            assert (depth, colour) == (8, 2), "an 8-bit RGB PNG"
        elif kind == b"IDAT":
            idat += body
        pos += 12 + length
    raw = zlib.decompress(idat)
    stride = 3 * width + 1
    rows = []
    for y in range(height):
        line = raw[y * stride:(y + 1) * stride]
        assert line[0] == 0, "filter 0"
        rows.append(line[1:])
    return width, height, rows


def write_png(path, width, rows):
    chunk = lambda kind, body: struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body))
    raw = b"".join(b"\x00" + r for r in rows)
    png = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, len(rows), 8, 2, 0, 0, 0))
    png += chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b"")
    tmp = path + ".tmp"
    open(tmp, "wb").write(png)
    os.replace(tmp, path)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--prism", default=os.path.join(ROOT, "target", "release", "prism"))
    a = ap.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        noisy = os.path.join(tmp, "noisy.png")
        # --denoise renders without path reuse; the noisy image is the same render's.
        subprocess.run([a.prism, "render", "--denoise", "-q", "-o", os.path.join(IMAGES, "effects.png")], check=True)
        subprocess.run([a.prism, "render", "--reuse", "1", "-q", "-o", noisy], check=True)
        x, y, w, h = CROP
        crops = []
        for path in (noisy, os.path.join(IMAGES, "effects.png")):
            _, _, rows = read_png(path)
            crops.append([r[3 * x:3 * (x + w)] for r in rows[y:y + h]])
        gap = b"\xff" * (3 * 4)
        rows = [a_row + gap + b_row for a_row, b_row in zip(*crops)]
        write_png(os.path.join(IMAGES, "denoise-crop.png"), 2 * w + 4, rows)


if __name__ == "__main__":
    main()
