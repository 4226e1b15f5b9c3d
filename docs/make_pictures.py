"""Pictures for docs/outputs.md: the bundled tinted_glossy sample, its reflection pass and a composite.

    /usr/bin/python3 docs/make_pictures.py SSRCL OUTDIR

Runs `SSRCL trace` on samples/blender/tinted_glossy (glossy-pass form, which the sample's base_color
and metallic AOVs allow) and writes OUTDIR/tinted_glossy.png: a 3x2 sheet of half-size tiles,

    beauty (Combined)              | pass RGB                     | pass A (confidence)
    beauty without its glossy light | Cycles' glossy light         | composite

the composite being  Combined - GlossCol (GlossDir + GlossInd) + GlossCol (refl.rgb + (GlossDir +
GlossInd) (1 - A)): the pass where it found the reflection, Cycles' own reflection where A says it
did not (outputs.md, "Where A is low"). Needs numpy (Debian's python3-numpy); EXRs are read with
samples/blender/minexr.py, the PNG written with zlib.
"""
import os
import struct
import subprocess
import sys
import tempfile
import zlib

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "samples", "blender"))
import minexr  # noqa: E402


def channels(exr, names):
    w, h = exr.width, exr.height
    return np.stack([np.array(exr.channel(n), dtype=np.float32).reshape(h, w) for n in names], axis=-1)


def to_srgb8(rgb):
    """Linear radiance -> 8-bit sRGB, clipped at 1 (no tone curve: the sample's values are small)."""
    c = np.clip(np.nan_to_num(rgb), 0.0, 1.0)
    s = np.where(c <= 0.0031308, 12.92 * c, 1.055 * np.power(c, 1 / 2.4) - 0.055)
    return (s * 255 + 0.5).astype(np.uint8)


def half_size(img):
    h, w = img.shape[0] // 2 * 2, img.shape[1] // 2 * 2
    return img[:h, :w].reshape(h // 2, 2, w // 2, 2, -1).mean(axis=(1, 3))


def write_png(path, rgb8):
    h, w, _ = rgb8.shape
    raw = b"".join(b"\x00" + rgb8[y].tobytes() for y in range(h))

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)

    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0))
                + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    ssrcl, outdir = sys.argv[1], sys.argv[2]
    os.makedirs(outdir, exist_ok=True)
    sample = os.path.join(ROOT, "samples", "blender", "tinted_glossy", "tinted_glossy.exr")
    with tempfile.TemporaryDirectory() as tmp:
        refl_path = os.path.join(tmp, "refl.exr")
        subprocess.run([ssrcl, "trace", sample, "-o", refl_path, "--output-form", "glossy-pass"], check=True)
        refl = minexr.ExrFile(refl_path)
        rgba = channels(refl, ["R", "G", "B", "A"])
    g = minexr.ExrFile(sample)
    layer = "ViewLayer."
    rgb = lambda p: channels(g, [layer + p + "." + c for c in "RGB"])  # noqa: E731
    combined, gloss_col = rgb("Combined"), rgb("GlossCol")
    glossy = rgb("GlossDir") + rgb("GlossInd")
    a = rgba[..., 3:4]
    no_glossy = combined - gloss_col * glossy
    composite = no_glossy + gloss_col * (rgba[..., :3] + glossy * (1 - a))
    tiles = [combined, rgba[..., :3], np.repeat(a, 3, axis=-1), no_glossy, gloss_col * glossy, composite]
    tiles = [to_srgb8(half_size(t)) for t in tiles]
    sheet = np.concatenate([np.concatenate(tiles[:3], axis=1), np.concatenate(tiles[3:], axis=1)], axis=0)
    out = os.path.join(outdir, "tinted_glossy.png")
    write_png(out, sheet)
    print("wrote", out)


if __name__ == "__main__":
    main()
