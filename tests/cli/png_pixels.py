"""Reads an 8-bit RGB or RGBA PNG (as the project writes them) for the shell
tests: load(path) -> (width, height, pixel(x, y) -> (r, g, b))."""
import struct
import zlib


def load(path):
    data = open(path, "rb").read()
    assert data[:8] == b"\x89PNG\r\n\x1a\n", path
    w, h, depth, ctype = struct.unpack(">IIBB", data[16:26])
    assert depth == 8 and ctype in (2, 6), (depth, ctype)
    idat, i = b"", 8
    while i < len(data):
        n = struct.unpack(">I", data[i:i + 4])[0]
        if data[i + 4:i + 8] == b"IDAT":
            idat += data[i + 8:i + 8 + n]
        i += 12 + n
    raw, bpp = zlib.decompress(idat), 3 if ctype == 2 else 4
    rows, prev = [], bytearray(w * bpp)
    for y in range(h):
        start = y * (w * bpp + 1)
        f, line = raw[start], bytearray(raw[start + 1:start + 1 + w * bpp])
        for x in range(w * bpp):
            a = line[x - bpp] if x >= bpp else 0
            b, c = prev[x], prev[x - bpp] if x >= bpp else 0
            p = a + b - c
            paeth = a if abs(p - a) <= abs(p - b) and abs(p - a) <= abs(p - c) else b if abs(p - b) <= abs(p - c) else c
            line[x] = (line[x] + [0, a, b, (a + b) // 2, paeth][f]) & 255
        rows.append(line)
        prev = line
    return w, h, lambda x, y: tuple(rows[y][x * bpp:x * bpp + 3])
