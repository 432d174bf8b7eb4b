"""Reading the runner's linear EXR images (scan-line OpenEXR, NONE/ZIPS/ZIP compression, half or
float channels) into numpy arrays, for the viewer's linear pixel values and for telling identical
images apart whatever their headers' dates.

OpenEXR's ZIP: each block of scan lines (1 for ZIPS, 16 for ZIP) is deflated after a byte
predictor (each byte stored as the difference to the one before, plus 128) and a split of the even
and odd bytes into two halves; the lines hold the channels one after the other in name order."""
import struct
import zlib

import numpy as np

LINES_PER_BLOCK = {0: 1, 2: 1, 3: 16}  # NONE, ZIPS, ZIP
DTYPES = {1: np.dtype("<f2"), 2: np.dtype("<f4")}  # HALF, FLOAT


class ExrError(Exception):
    pass


def header(data):
    """({attribute: (type, bytes)}, offset after the header)."""
    if data[:4] != b"v/1\x01":
        raise ExrError("not an OpenEXR file")
    if data[5] & 0x1E:  # tiled, long names, deep or multi-part
        raise ExrError("only single-part scan-line files are read")
    attrs, i = {}, 8
    while data[i] != 0:
        n = data.index(b"\0", i)
        t = data.index(b"\0", n + 1)
        size = struct.unpack_from("<i", data, t + 1)[0]
        attrs[data[i:n].decode()] = (data[n + 1:t].decode(), data[t + 5:t + 5 + size])
        i = t + 5 + size
    return attrs, i + 1


def channels(chlist):
    out, i = [], 0
    while chlist[i] != 0:
        n = chlist.index(b"\0", i)
        out.append((chlist[i:n].decode(), struct.unpack_from("<i", chlist, n + 1)[0]))
        i = n + 1 + 16
    return out


def undo_zip(block):
    t = np.frombuffer(zlib.decompress(block), dtype=np.uint8).astype(np.int64)
    t[1:] -= 128
    t = (np.cumsum(t) & 0xFF).astype(np.uint8)
    half = (len(t) + 1) // 2
    out = np.empty_like(t)
    out[0::2], out[1::2] = t[:half], t[half:]
    return out.tobytes()


def read(path):
    """{channel name: float32 array (height, width)}."""
    with open(path, "rb") as f:
        data = f.read()
    attrs, at = header(data)
    compression = attrs["compression"][1][0]
    if compression not in LINES_PER_BLOCK:
        raise ExrError("%s: compression %d is not read (NONE, ZIPS and ZIP are)" % (path, compression))
    x0, y0, x1, y1 = struct.unpack("<4i", attrs["dataWindow"][1])
    width, height = x1 - x0 + 1, y1 - y0 + 1
    chans = sorted(channels(attrs["channels"][1]))
    if any(t not in DTYPES for _, t in chans):
        raise ExrError("%s: only half and float channels are read" % path)
    per_line = sum(DTYPES[t].itemsize for _, t in chans) * width
    lines = LINES_PER_BLOCK[compression]
    blocks = (height + lines - 1) // lines
    offsets = struct.unpack_from("<%dQ" % blocks, data, at)
    out = {name: np.empty((height, width), np.float32) for name, _ in chans}
    for offset in offsets:
        y, size = struct.unpack_from("<ii", data, offset)
        raw = data[offset + 8:offset + 8 + size]
        n = min(lines, y1 - y + 1)
        if size < per_line * n:
            raw = undo_zip(raw)
        pos = 0
        for row in range(y - y0, y - y0 + n):
            for name, t in chans:
                dt = DTYPES[t]
                out[name][row] = np.frombuffer(raw, dtype=dt, count=width, offset=pos)
                pos += dt.itemsize * width
    return out


def rgb(path):
    """The image's linear RGB as a float32 array (height, width, 3)."""
    c = read(path)
    return np.stack([c["R"], c["G"], c["B"]], axis=-1)
