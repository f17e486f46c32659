#!/usr/bin/env python3
"""An independent LDR-FLIP (Andersson et al., HPG 2020) in plain Python, to
pin voxrg's C implementation (core/tools/src/metrics.c) on a small image pair.

It follows the steps of the paper and of the official code's Python/PyTorch
versions rather than voxrg's C: the contrast sensitivity filters and the
feature detectors are built and applied as 2D kernels (the C filters
separably), over images padded by repeating the edge pixel. Only the colour
matrices are voxrg's (docs/compare.md): the official code writes the same
sRGB/XYZ matrices as fractions, which moves the score slightly (see
docs/compare.md).

Prints the mean FLIP of the pair; test_metrics flip_pinned compares it and
the C value with the recorded constant. Plain Python: CI needs no numpy.
"""
import math
import struct

W, H = 8, 6
PPD = 0.7 * (3840 / 0.7) * math.pi / 180

RGB_TO_XYZ = ((0.4124564, 0.3575761, 0.1804375),
              (0.2126729, 0.7151522, 0.0721750),
              (0.0193339, 0.1191920, 0.9503041))
XYZ_TO_RGB = ((3.2404542, -1.5371385, -0.4985314),
              (-0.9692660, 1.8760108, 0.0415560),
              (0.0556434, -0.2040259, 1.0572252))


def f32(v):
    """the value as the C test's float image holds it"""
    return struct.unpack("f", struct.pack("f", v))[0]


def image_pair():
    """(reference, test) as rows of (r, g, b) in [0, 1]; test_metrics.c
    builds the same pair (flip_pair): a colour gradient with one bright
    pixel; the test has that pixel moved by one and three pixels changed on
    the borders, one in a corner, so the padding decides part of the score."""
    def ref_px(x, y):
        if (x, y) == (3, 2):
            return (240, 240, 240)
        return (30 + 28 * x, 50 + 35 * y, 200 - 20 * x - 10 * y)
    ref = [[ref_px(x, y) for x in range(W)] for y in range(H)]
    test = [row[:] for row in ref]
    test[2][3], test[2][4] = ref[2][4], ref[2][3]
    test[0][0] = (255, 0, 0)
    test[3][7] = (ref[3][7][0], ref[3][7][1] + 40, ref[3][7][2])
    test[5][2] = (0, 0, 0)
    scale = lambda img: [[tuple(f32(c / 255.0) for c in px) for px in row] for row in img]
    return scale(ref), scale(test)


def mul(m, v):
    return tuple(sum(m[r][i] * v[i] for i in range(3)) for r in range(3))


WHITE = mul(RGB_TO_XYZ, (1.0, 1.0, 1.0))


def srgb_to_linear(c):
    return c / 12.92 if c <= 0.04045 else ((c + 0.055) / 1.055) ** 2.4


def srgb_to_ycxcz(px):
    x, y, z = (v / w for v, w in zip(mul(RGB_TO_XYZ, tuple(srgb_to_linear(c) for c in px)), WHITE))
    return (116 * y - 16, 500 * (x - y), 200 * (y - z))


def ycxcz_to_linear(c):
    y = (c[0] + 16) / 116
    xyz = ((y + c[1] / 500) * WHITE[0], y * WHITE[1], (y - c[2] / 200) * WHITE[2])
    return tuple(min(max(v, 0.0), 1.0) for v in mul(XYZ_TO_RGB, xyz))


def linear_to_lab(rgb):
    d = 6 / 29
    f = lambda t: t ** (1 / 3) if t > d ** 3 else t / (3 * d * d) + 4 / 29
    fx, fy, fz = (f(v / w) for v, w in zip(mul(RGB_TO_XYZ, rgb), WHITE))
    return (116 * fy - 16, 500 * (fx - fy), 200 * (fy - fz))


def hunt(lab):
    return (lab[0], 0.01 * lab[0] * lab[1], 0.01 * lab[0] * lab[2])


def hyab(a, b):
    return abs(a[0] - b[0]) + math.hypot(a[1] - b[1], a[2] - b[2])


def correlate_replicate(plane, kernel):
    """2D correlation of plane (rows) with a square kernel, the image padded
    by repeating its edge pixels (PyTorch's mode='replicate')"""
    r = len(kernel) // 2
    out = []
    for y in range(H):
        row = []
        for x in range(W):
            s = 0.0
            for j in range(-r, r + 1):
                src = plane[min(max(y + j, 0), H - 1)]
                krow = kernel[j + r]
                for i in range(-r, r + 1):
                    s += krow[i + r] * src[min(max(x + i, 0), W - 1)]
            row.append(s)
        out.append(row)
    return out


# (a1, b1, a2, b2) of the achromatic, red-green and blue-yellow CSFs
CSF = ((1.0, 0.0047, 0.0, 1e-5), (1.0, 0.0053, 0.0, 1e-5), (34.1, 0.04, 13.5, 0.025))


def csf_kernel(channel):
    a1, b1, a2, b2 = CSF[channel]
    r = int(math.ceil(3 * math.sqrt(max(max(c[1], c[3]) for c in CSF) / (2 * math.pi ** 2)) * PPD))
    k = [[0.0] * (2 * r + 1) for _ in range(2 * r + 1)]
    for y in range(-r, r + 1):
        for x in range(-r, r + 1):
            z = (x * x + y * y) / (PPD * PPD)
            k[y + r][x + r] = (a1 * math.sqrt(math.pi / b1) * math.exp(-math.pi ** 2 * z / b1) +
                               a2 * math.sqrt(math.pi / b2) * math.exp(-math.pi ** 2 * z / b2))
    total = sum(map(sum, k))
    return [[v / total for v in row] for row in k]


def feature_kernel(point):
    """Gx of the paper: first (edge) or second (point) x-derivative of a
    Gaussian, sd = 0.5 w ppd with w = 0.082 degrees; positive weights
    normalised to sum 1, negative ones to -1"""
    sd = 0.5 * 0.082 * PPD
    r = int(math.ceil(3 * sd))
    k = []
    for y in range(-r, r + 1):
        row = []
        for x in range(-r, r + 1):
            g = math.exp(-(x * x + y * y) / (2 * sd * sd))
            row.append((x * x / (sd * sd) - 1) * g if point else -x * g)
        k.append(row)
    pos = sum(v for row in k for v in row if v > 0)
    neg = -sum(v for row in k for v in row if v < 0)
    return [[v / pos if v > 0 else v / neg for v in row] for row in k]


def transpose(k):
    return [list(col) for col in zip(*k)]


def features(y_plane, point):
    gx = feature_kernel(point)
    fx = correlate_replicate(y_plane, gx)
    fy = correlate_replicate(y_plane, transpose(gx))
    return [[math.hypot(fx[y][x], fy[y][x]) for x in range(W)] for y in range(H)]


def flip_map(ref, test):
    qc, qf, pc, pt = 0.7, 0.5, 0.4, 0.95
    cmax = hyab(hunt(linear_to_lab((0.0, 1.0, 0.0))), hunt(linear_to_lab((0.0, 0.0, 1.0)))) ** qc
    labs, edges, points = [], [], []
    for img in (ref, test):
        opp = [[srgb_to_ycxcz(px) for px in row] for row in img]
        planes = [[[px[c] for px in row] for row in opp] for c in range(3)]
        filt = [correlate_replicate(planes[c], csf_kernel(c)) for c in range(3)]
        labs.append([[hunt(linear_to_lab(ycxcz_to_linear((filt[0][y][x], filt[1][y][x], filt[2][y][x]))))
                      for x in range(W)] for y in range(H)])
        y_norm = [[(v + 16) / 116 for v in row] for row in planes[0]]
        edges.append(features(y_norm, False))
        points.append(features(y_norm, True))
    out = []
    for y in range(H):
        for x in range(W):
            e = hyab(labs[0][y][x], labs[1][y][x]) ** qc
            color = e * pt / (pc * cmax) if e < pc * cmax else pt + (e - pc * cmax) / (cmax - pc * cmax) * (1 - pt)
            feature = (max(abs(edges[0][y][x] - edges[1][y][x]), abs(points[0][y][x] - points[1][y][x])) / math.sqrt(2)) ** qf
            out.append(color ** (1 - feature))
    return out


if __name__ == "__main__":
    ref, test = image_pair()
    m = flip_map(ref, test)
    print("%.12f" % (sum(m) / len(m)))
