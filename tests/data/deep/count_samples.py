"""Counts the samples of a deep scanline OpenEXR file (ZIPS or uncompressed) from its bytes alone,
independently of OpenEXR: the truth tests/test_deep_depth.cpp checks its reader against.

    python3 tests/data/deep/count_samples.py tests/data/deep/representativeDeepImage.exr
    -> 191482 227   (total samples, most in one pixel)
"""
import struct, zlib, sys
f = open(sys.argv[1], 'rb').read()
pos = 8
while True:
    end = f.index(b'\0', pos); name = f[pos:end]; pos = end + 1
    if not name: break
    end = f.index(b'\0', pos); pos = end + 1
    size = struct.unpack('<i', f[pos:pos + 4])[0]; pos += 4 + size
box = f.index(b"dataWindow\0box2i\0") + len(b"dataWindow\0box2i\0") + 4
x0, y0, x1, y1 = struct.unpack("<4i", f[box:box + 16])
w, h = x1 - x0 + 1, y1 - y0 + 1
offsets = struct.unpack('<%dQ' % h, f[pos:pos + 8 * h])
def unzip(b, n):
    if len(b) == n: return b
    t = bytearray(zlib.decompress(b))
    for i in range(1, len(t)): t[i] = (t[i - 1] + t[i] - 128) & 255
    half = (len(t) + 1) // 2
    out = bytearray(len(t)); out[0::2] = t[:half]; out[1::2] = t[half:]
    return bytes(out)
total = 0; most = 0
for o in offsets:
    y, tsize, dsize, usize = struct.unpack('<iQQQ', f[o:o + 28])
    table = struct.unpack('<%di' % w, unzip(f[o + 28:o + 28 + tsize], 4 * w))
    prev = 0
    for c in table: most = max(most, c - prev); prev = c
    total += table[-1]
print(total, most)
