"""Rebuilds the float32 EXR conversions of the Radiance HDR environment maps, byte for byte.

The data folder's envmaps/*.exr were made for this project from the Poly Haven .hdr originals
(RGBE decoded as m * 2^(e - 136), as stb_image decodes it, stored as float32 B, G, R with ZIP
compression at zlib level 9 and a comment naming the source). No upstream repository holds
them, so `./lab data` makes them again from the downloaded .hdr files with this module and
checks the result against the manifest's SHA-256 like any download. No Debian package converts
RGBE to EXR (Debian has no OpenEXR binding for Python, and the `openexr` tools do not read
RGBE), and a library writer would not promise these exact bytes, hence the ~60 lines here.
"""
import array
import struct
import zlib


def read_rgbe(data):
    """(width, height, rows) of a Radiance HDR file; each row is its r, g, b, e byte planes."""
    i = 0
    while True:  # header lines, up to the blank line
        j = data.index(b"\n", i)
        line, i = data[i:j], j + 1
        if line == b"":
            break
    j = data.index(b"\n", i)
    res, i = data[i:j].split(), j + 1
    if len(res) != 4 or res[0] != b"-Y" or res[2] != b"+X":
        raise ValueError(f"unsupported HDR orientation {res!r}")
    height, width = int(res[1]), int(res[3])
    rows = []
    for _ in range(height):
        if data[i] == 2 and data[i + 1] == 2 and (data[i + 2] << 8 | data[i + 3]) == width:
            i += 4  # run-length encoded: four planes, each as runs and literals
            planes = []
            for _ in range(4):
                plane = bytearray()
                while len(plane) < width:
                    n = data[i]
                    i += 1
                    if n > 128:
                        plane += bytes([data[i]]) * (n - 128)
                        i += 1
                    else:
                        plane += data[i:i + n]
                        i += n
                planes.append(plane)
        else:  # flat: r, g, b, e per pixel
            flat = data[i:i + 4 * width]
            i += 4 * width
            planes = [flat[c::4] for c in range(4)]
        rows.append(planes)
    return width, height, rows


def _scanline(planes, width):
    r, g, b, e = planes
    out = [array.array("f", bytes(4 * width)) for _ in range(3)]
    for x in range(width):
        if e[x]:
            f = 2.0 ** (e[x] - 136)
            out[0][x], out[1][x], out[2][x] = b[x] * f, g[x] * f, r[x] * f
    return b"".join(a.tobytes() for a in out)  # channels in name order: B, G, R


def _zip_chunk(raw):
    # OpenEXR's ZIP: bytes split into even and odd halves, a delta predictor, then zlib.
    half = (len(raw) + 1) // 2
    t = bytearray(len(raw))
    t[:half], t[half:] = raw[0::2], raw[1::2]
    out, p = bytearray(t), t[0]
    for k in range(1, len(t)):
        out[k], p = (t[k] - p + 384) & 255, t[k]
    packed = zlib.compress(bytes(out), 9)
    return packed if len(packed) < len(raw) else raw


def _attribute(name, kind, value):
    return name.encode() + b"\0" + kind.encode() + b"\0" + struct.pack("<i", len(value)) + value


def hdr_to_exr(hdr, source_name):
    """The EXR bytes of Radiance HDR bytes `hdr`; `source_name` goes into the comment."""
    width, height, rows = read_rgbe(hdr)
    channel = struct.pack("<iB3xii", 2, 0, 1, 1)  # FLOAT, not linear, sampling 1 x 1
    window = struct.pack("<4i", 0, 0, width - 1, height - 1)
    header = b"\x76\x2f\x31\x01" + struct.pack("<i", 2) + b"".join([
        _attribute("channels", "chlist", b"B\0" + channel + b"G\0" + channel + b"R\0" + channel
                   + b"\0"),
        _attribute("comments", "string", (f"Converted losslessly from Poly Haven {source_name} "
                                          "(RGBE) to float32 EXR; CC0").encode()),
        _attribute("compression", "compression", b"\x03"),  # ZIP, 16 scanlines a chunk
        _attribute("dataWindow", "box2i", window),
        _attribute("displayWindow", "box2i", window),
        _attribute("lineOrder", "lineOrder", b"\x00"),
        _attribute("pixelAspectRatio", "float", struct.pack("<f", 1.0)),
        _attribute("screenWindowCenter", "v2f", struct.pack("<2f", 0.0, 0.0)),
        _attribute("screenWindowWidth", "float", struct.pack("<f", 1.0)),
    ]) + b"\0"
    lines = [_scanline(planes, width) for planes in rows]
    chunks = []
    for y in range(0, height, 16):
        packed = _zip_chunk(b"".join(lines[y:y + 16]))
        chunks.append(struct.pack("<ii", y, len(packed)) + packed)
    offset, table = len(header) + 8 * len(chunks), []
    for c in chunks:
        table.append(offset)
        offset += len(c)
    return header + struct.pack(f"<{len(chunks)}Q", *table) + b"".join(chunks)
