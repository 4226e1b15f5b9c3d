"""Minimal pure-Python OpenEXR reader for the sample checks.

Neither system Python nor Debian's Blender Python has numpy or an OpenEXR module here, so this
reads just what Blender writes for the samples and ssrcl for its pass: single-part scanline files,
HALF/FLOAT/UINT channels, compression NONE, RLE, ZIPS or ZIP. Pixels come back top row first (EXR y grows downwards),
as flat lists indexed [y * width + x].
"""
import struct
import zlib

_PIXEL_TYPES = {0: ("UINT", 4, "I"), 1: ("HALF", 2, "e"), 2: ("FLOAT", 4, "f")}
_COMPRESSION = {0: "NONE", 1: "RLE", 2: "ZIPS", 3: "ZIP", 4: "PIZ", 5: "PXR24", 6: "B44",
                7: "B44A", 8: "DWAA", 9: "DWAB"}
_LINES_PER_BLOCK = {"NONE": 1, "RLE": 1, "ZIPS": 1, "ZIP": 16}


class ExrFile:
    def __init__(self, path):
        with open(path, "rb") as f:
            data = f.read()
        self.path = path
        magic, version = struct.unpack_from("<ii", data, 0)
        if magic != 20000630:
            raise ValueError("%s: not an OpenEXR file" % path)
        if version & 0x1A00:  # tiled (0x200), deep (0x800) or multi-part (0x1000)
            raise ValueError("%s: only single-part scanline files are supported" % path)
        pos = 8
        self.attributes = {}
        while True:
            name, pos = _cstring(data, pos)
            if not name:
                break
            type_name, pos = _cstring(data, pos)
            size, = struct.unpack_from("<i", data, pos)
            pos += 4
            self.attributes[name] = (type_name, data[pos:pos + size])
            pos += size

        self.channels = _parse_chlist(self.attributes["channels"][1])  # [(name, type)] sorted
        self.compression = _COMPRESSION[self.attributes["compression"][1][0]]
        xmin, ymin, xmax, ymax = struct.unpack("<4i", self.attributes["dataWindow"][1])
        self.width, self.height = xmax - xmin + 1, ymax - ymin + 1
        self._ymin = ymin
        if self.compression not in _LINES_PER_BLOCK:
            raise ValueError("%s: compression %s not supported" % (path, self.compression))
        self._data = data
        self._table_pos = pos
        self._pixels = None

    def channel_types(self):
        return [(name, _PIXEL_TYPES[t][0]) for name, t in self.channels]

    def channel(self, name):
        if self._pixels is None:
            self._decode()
        if name not in self._pixels:
            raise KeyError("%s: no channel %r" % (self.path, name))
        return self._pixels[name]

    def _decode(self):
        lines = _LINES_PER_BLOCK[self.compression]
        chunks = (self.height + lines - 1) // lines
        offsets = struct.unpack_from("<%dQ" % chunks, self._data, self._table_pos)
        out = {name: [] for name, _ in self.channels}
        for offset in offsets:
            y, size = struct.unpack_from("<ii", self._data, offset)
            raw = self._data[offset + 8:offset + 8 + size]
            count = min(lines, self._ymin + self.height - y)
            expected = count * self.width * sum(_PIXEL_TYPES[t][1] for _, t in self.channels)
            if size < expected:  # a block is stored raw when compression would not shrink it
                raw = _unrle(raw) if self.compression == "RLE" else _unzip(raw)
            pos = 0
            # Within a block: for each scanline, every channel's row in chlist (name) order.
            for _ in range(count):
                for name, t in self.channels:
                    _, nbytes, code = _PIXEL_TYPES[t]
                    row = struct.unpack_from("<%d%s" % (self.width, code), raw, pos)
                    out[name].extend(row)
                    pos += nbytes * self.width
        self._pixels = out


def _cstring(data, pos):
    end = data.index(b"\0", pos)
    return data[pos:end].decode("latin-1"), end + 1


def _parse_chlist(blob):
    channels, pos = [], 0
    while blob[pos] != 0:
        name, pos = _cstring(blob, pos)
        pixel_type, = struct.unpack_from("<i", blob, pos)
        xs, ys = struct.unpack_from("<ii", blob, pos + 8)
        if (xs, ys) != (1, 1):
            raise ValueError("subsampled channel %s not supported" % name)
        channels.append((name, pixel_type))
        pos += 16
    return channels


def _unzip(raw):
    # OpenEXR ZIP: zlib, then undo the byte-delta predictor, then re-interleave the two halves.
    return _unpredict(bytearray(zlib.decompress(raw)))


def _unrle(raw):
    # OpenEXR RLE: runs, each a signed count byte n (n >= 0: the next byte n + 1 times; n < 0: the
    # next -n bytes as they are), then the same predictor and halves as ZIP.
    t, i = bytearray(), 0
    while i < len(raw):
        n = raw[i] - 256 if raw[i] > 127 else raw[i]
        if n < 0:
            t += raw[i + 1:i + 1 - n]
            i += 1 - n
        else:
            t += raw[i + 1:i + 2] * (n + 1)
            i += 2
    return _unpredict(t)


def _unpredict(t):
    acc = 0
    for i in range(len(t)):
        acc = (acc + t[i] - 128) & 0xFF if i else t[0]
        t[i] = acc
    half = (len(t) + 1) // 2
    out = bytearray(len(t))
    out[0::2] = t[:half]
    out[1::2] = t[half:]
    return bytes(out)
