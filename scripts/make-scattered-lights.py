#!/usr/bin/env python3
"""Writes a many-light test scene: a grey floor under N small emitting triangles scattered at random.

Used by BENCHMARKS.md to measure `--lights importance` where its clusters hold thousands of emitters (the scenes
shipped in ../shared have a handful). Deterministic for a given --seed.

    python3 scripts/make-scattered-lights.py OUT.obj [--count 20000] [--seed 1]
    build/lueur --headless OUT.obj --camera "0 8 12 0 0 0 50" --passes l1 --l1-rays 1 ...
"""
import argparse
import os
import random


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("out", help="the OBJ to write (its MTL is written beside it)")
    parser.add_argument("--count", type=int, default=20000, help="emitting triangles (default 20000)")
    parser.add_argument("--seed", type=int, default=1, help="random seed (default 1)")
    args = parser.parse_args()
    if args.count < 1:
        parser.error("--count must be at least 1")
    rng = random.Random(args.seed)
    mtl = os.path.splitext(args.out)[0] + ".mtl"
    with open(mtl, "w") as f:
        f.write("newmtl grey\nKd 0.5 0.5 0.5\nnewmtl light\nKd 0 0 0\nKe 10 10 10\n")
    with open(args.out, "w") as f:
        f.write(f"mtllib {os.path.basename(mtl)}\nusemtl grey\n")
        f.write("v -10 0 -10\nv 10 0 -10\nv 10 0 10\nv -10 0 10\nf 1 3 2\nf 1 4 3\nusemtl light\n")
        vertex = 5
        for _ in range(args.count):
            x, y, z = rng.uniform(-5, 5), rng.uniform(0.5, 5), rng.uniform(-5, 5)
            # A right triangle of side 0.05 in the plane y = const, wound to face down (normal -y).
            f.write(f"v {x:.5f} {y:.5f} {z:.5f}\nv {x + 0.05:.5f} {y:.5f} {z:.5f}\nv {x:.5f} {y:.5f} {z + 0.05:.5f}\n")
            f.write(f"f {vertex} {vertex + 1} {vertex + 2}\n")
            vertex += 3


if __name__ == "__main__":
    main()
