#!/usr/bin/env python3
"""Writes graphs/models/lanterns.vox, the shipped model of a scene lit by its
own emitting voxels: a walled stone courtyard with four wooden posts, each
carrying a lantern, and a glowing pool in the middle. Lanterns and pool are
MATL `_type = _emit` materials (docs/world.md, "Emission"), so at night the
courtyard is lit by them. Deterministic: the same bytes on every run.
usage: make_lanterns_vox.py [OUT.vox]"""
import os
import struct
import sys

W, D, H = 32, 32, 10  # MagicaVoxel's x, y (depth) and z (up)
STONE, BRICK, WOOD, LANTERN, POOL = 1, 2, 3, 4, 5
COLOURS = {STONE: (150, 150, 145), BRICK: (140, 70, 55), WOOD: (110, 80, 45), LANTERN: (255, 200, 120), POOL: (120, 190, 255)}
EMIT = {LANTERN: ("2", "1"), POOL: ("1", "0")}  # _emit, _flux: e = 4 * _emit * (1 + _flux)


def voxels():
    v = {}
    for x in range(W):
        for y in range(D):
            v[(x, y, 0)] = STONE
            if x in (0, W - 1) or y in (0, D - 1):  # the wall, with a gate in the middle of each side
                if not (abs(x - W // 2) < 2 or abs(y - D // 2) < 2):
                    for z in range(1, 5):
                        v[(x, y, z)] = BRICK
    for px, py in ((8, 8), (23, 8), (8, 23), (23, 23)):
        for z in range(1, 6):
            v[(px, py, z)] = WOOD
        v[(px, py, 6)] = LANTERN
    for x in range(14, 18):
        for y in range(14, 18):
            v[(x, y, 0)] = POOL
    return sorted(v.items())


def chunk(tag, content, children=b""):
    return tag + struct.pack("<ii", len(content), len(children)) + content + children


def string(s):
    b = s.encode()
    return struct.pack("<i", len(b)) + b


def matl(index, emit, flux):
    pairs = (("_type", "_emit"), ("_emit", emit), ("_flux", flux))
    return chunk(b"MATL", struct.pack("<ii", index, len(pairs)) + b"".join(string(k) + string(v) for k, v in pairs))


def model():
    vs = voxels()
    xyzi = struct.pack("<i", len(vs)) + b"".join(struct.pack("<4B", x, y, z, c) for (x, y, z), c in vs)
    rgba = b"".join(struct.pack("<4B", *COLOURS.get(i, (0, 0, 0)), 255) for i in range(1, 257))  # entry i-1 is colour i
    children = chunk(b"SIZE", struct.pack("<3i", W, D, H)) + chunk(b"XYZI", xyzi) + chunk(b"RGBA", rgba)
    children += b"".join(matl(i, *EMIT[i]) for i in sorted(EMIT))
    return b"VOX " + struct.pack("<i", 150) + chunk(b"MAIN", b"", children)


if __name__ == "__main__":
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(root, "graphs", "models", "lanterns.vox")
    with open(out + ".tmp", "wb") as f:
        f.write(model())
    os.replace(out + ".tmp", out)
    print("wrote", out)
