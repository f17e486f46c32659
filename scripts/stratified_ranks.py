#!/usr/bin/env python3
"""How random.glsl's stratified_point() got its rank table and frame stride.

Point k of the R2 sequence is fract(k * alpha). A pixel's rank (its place in
a 4x4 tile) picks point frame * stride + rank. This script
  1. searches the 16! placements of the ranks (hill climbing from random
     starts, seeded) for the one whose every 2x2 and 3x3 window (the tile
     repeats) holds points far apart on the torus, and
  2. scores strides 16..40 with that placement: the RMS error of the mean of
     the points of a window (1, 2, 2x2, 3x3 pixels) over 1, 2, 4, 8 frames,
     integrating random half-plane indicators (a visibility edge), each
     window's error scaled by sqrt(samples) so that random numbers score
     about the same everywhere; Bayer and random numbers alongside. One ray
     per pixel, and one random shift per window (the shader has one per 4x4
     tile, so windows that cross a tile edge are modelled loosely).
Pure Python, about a minute: python3 scripts/stratified_ranks.py
"""
import math
import random

ALPHA = (0.7548776662466927, 0.5698402909980532)  # R2: 1/g, 1/g^2, g^3 = g + 1
POINTS = [((k * ALPHA[0]) % 1.0, (k * ALPHA[1]) % 1.0) for k in range(16)]
BAYER = [0, 8, 2, 10, 12, 4, 14, 6, 3, 11, 1, 9, 15, 7, 13, 5]


def torus_distance(a, b):
    dx, dy = abs(a[0] - b[0]), abs(a[1] - b[1])
    return math.hypot(min(dx, 1 - dx), min(dy, 1 - dy))


def spread(ranks):
    """Sum over every 2x2 (weight 2) and 3x3 window of the least distance between two of its points."""
    total = 0.0
    for w, weight in ((2, 2), (3, 1)):
        for oy in range(4):
            for ox in range(4):
                pts = [POINTS[ranks[((oy + y) % 4) * 4 + (ox + x) % 4]] for y in range(w) for x in range(w)]
                total += weight * min(torus_distance(pts[i], pts[j]) for i in range(len(pts)) for j in range(i))
    return total


def search(rng):
    best = None
    for _ in range(30):
        ranks = list(range(16))
        rng.shuffle(ranks)
        score = spread(ranks)
        for _ in range(3000):
            i, j = rng.sample(range(16), 2)
            ranks[i], ranks[j] = ranks[j], ranks[i]
            new = spread(ranks)
            if new >= score:
                score = new
            else:
                ranks[i], ranks[j] = ranks[j], ranks[i]
        if best is None or score > best[0]:
            best = (score, ranks[:])
    return best[1]


WINDOWS = [[(0, 0)], [(0, 0), (1, 0)], [(x, y) for y in range(2) for x in range(2)], [(x, y) for y in range(3) for x in range(3)]]


def error(point_of, edges, truths):
    """sum over windows and frame counts of RMS error * sqrt(samples)"""
    total = 0.0
    for window in WINDOWS:
        for frames in (1, 2, 4, 8):
            rng = random.Random(7)
            err, n = 0.0, 0
            for _ in range(30):
                shift = (rng.random(), rng.random())
                ox, oy, f0 = rng.randrange(4), rng.randrange(4), rng.randrange(1000)
                pts = [point_of(ox + x, oy + y, f0 + f, shift, rng) for f in range(frames) for x, y in window]
                for (a, b), t in zip(edges, truths):
                    m = sum(1.0 for u in pts if u[0] < a + b * u[1]) / len(pts)
                    err += (m - t) ** 2
                    n += 1
            total += math.sqrt(err / n) * math.sqrt(len(window) * frames)
    return total


def main():
    ranks = search(random.Random(3))
    print("ranks (row by row):", ranks, " spread", round(spread(ranks), 3), " Bayer's", round(spread(BAYER), 3))
    rng = random.Random(1)
    edges = [(rng.uniform(-0.5, 1.5), rng.uniform(-1, 1)) for _ in range(30)]
    truths = [sum(1.0 for i in range(100) for j in range(100) if (i + 0.5) / 100 < a + b * (j + 0.5) / 100) / 1e4 for a, b in edges]

    def kronecker(table, stride):
        def point_of(x, y, frame, shift, _rng):
            k = frame * stride + table[(y % 4) * 4 + x % 4]
            return ((k * ALPHA[0] + shift[0]) % 1.0, (k * ALPHA[1] + shift[1]) % 1.0)
        return point_of

    print("random numbers:", round(error(lambda x, y, f, s, r: (r.random(), r.random()), edges, truths), 3))
    print("Bayer, stride 17:", round(error(kronecker(BAYER, 17), edges, truths), 3))
    for stride in range(16, 41):
        print("stride", stride, round(error(kronecker(ranks, stride), edges, truths), 3))


if __name__ == "__main__":
    main()
