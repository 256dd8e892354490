#!/usr/bin/env python3
"""Issue 44's stack: 300 unit squares 0.01 apart (alpha 0.12), crossed by 50
long slivers, as binary little-endian PLY (float x y z, uchar RGBA per
vertex), the layout oitgen writes. Deterministic: same arguments, same bytes.

Usage: data_scripts/stack_slivers.py OUT.ply [SQUARES [SLIVERS]]

Square i spans [-0.5, 0.5]^2 in x, y at z = 0.01 i (alpha 31/255 = 0.12,
its colour cycling through six hues). Sliver j is a long thin triangle
pair (2 triangles, 0.004 wide) from below the stack to above it, leaning
across it at an angle of its own, so it crosses every layer; alpha 0.5.
300 squares and 50 slivers: 700 triangles, ~80 layers seen from 20 degrees
above (oitstream's default --elevation), as the issue's case."""
import math
import struct
import sys


def squares(n):
    hues = [(230, 80, 60), (60, 160, 230), (90, 200, 90), (230, 200, 60),
            (180, 90, 220), (60, 210, 200)]
    for i in range(n):
        z = 0.01 * i
        r, g, b = hues[i % len(hues)]
        c = (r, g, b, 31)
        a, bb, cc, d = (-0.5, -0.5, z), (0.5, -0.5, z), (0.5, 0.5, z), (-0.5, 0.5, z)
        yield (a, c), (bb, c), (cc, c)
        yield (a, c), (cc, c), (d, c)


def slivers(n, height):
    for j in range(n):
        t = (j + 0.5) / n
        x0 = -0.45 + 0.9 * t
        y0 = -0.45 + 0.9 * ((j * 37) % n) / n
        lean = 0.6 * math.sin(2.0 * math.pi * t * 3.0)
        bot = (x0 - lean / 2, y0, -0.2)
        top = (x0 + lean / 2, y0 + 0.1 * math.cos(7.0 * t), height + 0.2)
        w = 0.002
        c = (250, 250, 250, 128)
        p0 = (bot[0] - w, bot[1], bot[2])
        p1 = (bot[0] + w, bot[1], bot[2])
        p2 = (top[0] + w, top[1], top[2])
        p3 = (top[0] - w, top[1], top[2])
        yield (p0, c), (p1, c), (p2, c)
        yield (p0, c), (p2, c), (p3, c)


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    out = sys.argv[1]
    n_sq = int(sys.argv[2]) if len(sys.argv) > 2 else 300
    n_sl = int(sys.argv[3]) if len(sys.argv) > 3 else 50
    tris = list(squares(n_sq)) + list(slivers(n_sl, 0.01 * (n_sq - 1)))
    header = ("ply\nformat binary_little_endian 1.0\n"
              "element vertex %d\n"
              "property float x\nproperty float y\nproperty float z\n"
              "property uchar red\nproperty uchar green\nproperty uchar blue\n"
              "property uchar alpha\n"
              "element face %d\nproperty list uchar int vertex_indices\n"
              "end_header\n" % (3 * len(tris), len(tris)))
    with open(out, "wb") as f:
        f.write(header.encode("ascii"))
        for tri in tris:
            for (x, y, z), (r, g, b, a) in tri:
                f.write(struct.pack("<fffBBBB", x, y, z, r, g, b, a))
        for i in range(len(tris)):
            f.write(struct.pack("<Biii", 3, 3 * i, 3 * i + 1, 3 * i + 2))
    print("%d triangles" % len(tris))


if __name__ == "__main__":
    main()
