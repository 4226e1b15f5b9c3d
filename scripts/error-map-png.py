#!/usr/bin/env python3
"""Side-by-side PNG of panels from ssrcl_score_corpus --dump pictures (docs/images/).

Each dump (<scene>.<config>.ppm) holds five panels: ours, Cycles, |ours - Cycles|, our A and the
input colour, each divided by the peak. This takes one panel of each given dump, optionally a
crop of it, and writes them left to right, 4 pixels apart, as an 8-bit RGB PNG (zlib, no imaging
library needed):

    python3 scripts/error-map-png.py --panel 2 --crop 120,140,360,270 --scale 2 -o docs/images/x.png a.ppm b.ppm
"""
import argparse
import struct
import zlib

PANELS = 5


def read_ppm(path):
    with open(path, "rb") as f:
        data = f.read()
    fields, pos = [], 0
    while len(fields) < 4:  # P6, width, height, maxval, whitespace-separated
        while data[pos:pos + 1].isspace():
            pos += 1
        start = pos
        while not data[pos:pos + 1].isspace():
            pos += 1
        fields.append(data[start:pos])
    if fields[0] != b"P6" or int(fields[3]) != 255:
        raise SystemExit(f"{path}: not an 8-bit binary PPM (P6)")
    w, h = int(fields[1]), int(fields[2])
    pixels = data[pos + 1:pos + 1 + 3 * w * h]
    return w, h, [pixels[3 * w * y:3 * w * (y + 1)] for y in range(h)]


def write_png(path, width, rows):
    def chunk(kind, body):
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body) & 0xFFFFFFFF)

    raw = b"".join(b"\0" + r for r in rows)  # filter type 0 per row
    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n")
        f.write(chunk(b"IHDR", struct.pack(">IIBBBBB", width, len(rows), 8, 2, 0, 0, 0)))
        f.write(chunk(b"IDAT", zlib.compress(raw, 9)))
        f.write(chunk(b"IEND", b""))


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("dumps", nargs="+")
    ap.add_argument("--panel", type=int, default=2, help="0 ours, 1 Cycles, 2 |difference|, 3 A, 4 input")
    ap.add_argument("--crop", help="x0,y0,x1,y1 within the panel (default: all of it)")
    ap.add_argument("--scale", type=int, default=1, help="enlarge each pixel to NxN")
    ap.add_argument("-o", "--output", required=True)
    a = ap.parse_args()
    gap = 4
    pieces = []
    for path in a.dumps:
        w, h, rows = read_ppm(path)
        pw = w // PANELS
        x0, y0, x1, y1 = map(int, a.crop.split(",")) if a.crop else (0, 0, pw, h)
        if not (0 <= x0 < x1 <= pw and 0 <= y0 < y1 <= h):
            raise SystemExit(f"{path}: crop {a.crop} outside the {pw}x{h} panel")
        left = a.panel * pw
        crop = [r[3 * (left + x0):3 * (left + x1)] for r in rows[y0:y1]]
        pieces.append([b"".join(r[3 * x:3 * x + 3] * a.scale for x in range(len(r) // 3))
                       for r in crop for _ in range(a.scale)])
    height = len(pieces[0])
    if any(len(p) != height for p in pieces):
        raise SystemExit("the dumps differ in size")
    white = b"\xff" * (3 * gap)
    out = [white.join(p[y] for p in pieces) for y in range(height)]
    write_png(a.output, len(out[0]) // 3, out)


if __name__ == "__main__":
    main()
