#!/usr/bin/env python3
"""Writes a large test scene: a displaced grid of about N triangles under one emitting quad.

Used by BENCHMARKS.md ("Loading big scenes") to measure how loading grows with the file: the same shape at 1 M, 4 M
and 16 M triangles. Its text is what scanned models look like (one `v` line per vertex, one `f` line per triangle,
six significant digits), so its load stages are those of a downloaded scene of that size. Deterministic.

    python3 scripts/make-big-scene.py OUT.obj [--triangles 4000000]
    build/lueur --headless OUT.obj --frames 1
"""
import argparse
import math
import os


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("out", help="the OBJ to write (its MTL is written beside it)")
    parser.add_argument("--triangles", type=int, default=4_000_000, help="about this many triangles (default 4 M)")
    args = parser.parse_args()
    if args.triangles < 2:
        parser.error("--triangles must be at least 2")
    # An n x n grid of quads, each two triangles.
    n = max(1, round(math.sqrt(args.triangles / 2)))
    mtl = os.path.splitext(args.out)[0] + ".mtl"
    with open(mtl, "w") as f:
        f.write("newmtl ground\nKd 0.6 0.55 0.5\nnewmtl light\nKd 0 0 0\nKe 20 20 20\n")
    with open(args.out, "w") as f:
        f.write(f"# {2 * n * n} triangles: a displaced {n} x {n} grid under one emitting quad\n")
        f.write(f"mtllib {os.path.basename(mtl)}\nusemtl ground\n")
        for j in range(n + 1):
            z = -1.0 + 2.0 * j / n
            rows = []
            for i in range(n + 1):
                x = -1.0 + 2.0 * i / n
                # Hills of a few wavelengths: every triangle a little tilted, none degenerate.
                y = 0.08 * math.sin(7.0 * x + 1.3) * math.cos(5.0 * z) + 0.03 * math.sin(23.0 * (x + z))
                rows.append(f"v {x:.6g} {y:.6g} {z:.6g}\n")
            f.write("".join(rows))
        for j in range(n):
            rows = []
            for i in range(n):
                a = j * (n + 1) + i + 1  # OBJ indices start at 1
                b, c, d = a + 1, a + n + 1, a + n + 2
                rows.append(f"f {a} {c} {b}\nf {b} {c} {d}\n")
            f.write("".join(rows))
        v = (n + 1) * (n + 1)
        f.write("usemtl light\nv -0.3 1.5 -0.3\nv 0.3 1.5 -0.3\nv 0.3 1.5 0.3\nv -0.3 1.5 0.3\n")
        f.write(f"f {v + 1} {v + 2} {v + 3}\nf {v + 1} {v + 3} {v + 4}\n")


if __name__ == "__main__":
    main()
