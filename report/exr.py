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


def load_header(path):
    """The file's bytes and its parsed header; ExrError naming the file where it is not a readable
    EXR (missing, not OpenEXR, or a kind not read here)."""
    try:
        with open(path, "rb") as f:
            data = f.read()
        attrs, at = header(data)
        for key in ("compression", "dataWindow", "channels"):
            if key not in attrs:
                raise ExrError("no '%s' attribute" % key)
    except (OSError, IndexError, struct.error, ExrError) as e:
        raise ExrError("%s: not a readable scan-line OpenEXR image (%s)" % (path, e)) from e
    if attrs["compression"][1][0] not in LINES_PER_BLOCK:
        raise ExrError("%s: compression %d is not read (NONE, ZIPS and ZIP are)" % (path, attrs["compression"][1][0]))
    return data, attrs, at


def read(path):
    """{channel name: float32 array (height, width)}."""
    data, attrs, at = load_header(path)
    compression = attrs["compression"][1][0]
    x0, y0, x1, y1 = struct.unpack("<4i", attrs["dataWindow"][1])
    width, height = x1 - x0 + 1, y1 - y0 + 1
    chans = sorted(channels(attrs["channels"][1]))
    if any(t not in DTYPES for _, t in chans):
        raise ExrError("%s: only half and float channels are read" % path)
    per_line = sum(DTYPES[t].itemsize for _, t in chans) * width
    lines = LINES_PER_BLOCK[compression]
    blocks = (height + lines - 1) // lines
    out = {name: np.empty((height, width), np.float32) for name, _ in chans}
    try:
        offsets = struct.unpack_from("<%dQ" % blocks, data, at)
        read_blocks(data, offsets, chans, width, per_line, lines, y0, y1, out)
    except (struct.error, zlib.error, ValueError, IndexError) as e:
        raise ExrError("%s: damaged pixel data (%s)" % (path, e)) from e
    return out


def read_blocks(data, offsets, chans, width, per_line, lines, y0, y1, out):
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


def rgb(path):
    """The image's linear RGB as a float32 array (height, width, 3)."""
    c = read(path)
    return np.stack([c["R"], c["G"], c["B"]], axis=-1)
