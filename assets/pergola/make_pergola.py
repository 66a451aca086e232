#!/usr/bin/env python3
"""Writes Lueur's textured test scene 'pergola': a tiled floor and a brick wall (map_Kd colour maps, repeated by
texture coordinates beyond 1), a wooden crate, and a pergola roof whose lattice of slats and leaves is cut out of a
plane by an alpha mask (map_d), under an area light, so that the floor shows the lattice's shadow. Everything here
is generated: no downloaded asset. Run it from anywhere; it rewrites the files beside itself."""

import math
import os
import struct
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))


def png(path, width, height, texel):
    """An 8-bit RGBA PNG whose texel (x, y), rows from the top, is texel(x, y) = (r, g, b, a)."""
    rows = b"".join(b"\x00" + bytes(c for x in range(width) for c in texel(x, y)) for y in range(height))

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)

    header = struct.pack(">IIBBBBB", width, height, 8, 6, 0, 0, 0)
    with open(os.path.join(HERE, path), "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", zlib.compress(rows, 9)) +
                chunk(b"IEND", b""))


def noise(x, y, seed):
    """A cheap deterministic hash in [0, 1) for texel variation."""
    h = (x * 374761393 + y * 668265263 + seed * 2147483647) & 0xFFFFFFFF
    h = ((h ^ (h >> 13)) * 1274126177) & 0xFFFFFFFF
    return ((h ^ (h >> 16)) & 0xFFFF) / 65536.0


def tiles(x, y):
    """Terracotta tiles, 32 texels each with a 2-texel grout line; the image holds 2 x 2 tiles."""
    if x % 32 < 2 or y % 32 < 2:
        return (200, 196, 186, 255)
    shade = 0.85 + 0.15 * noise(x // 32, y // 32, 1) + 0.05 * noise(x, y, 2)
    return (int(190 * shade), int(100 * shade), int(70 * shade), 255)


def bricks(x, y):
    """Running-bond bricks 32 x 16 texels with mortar."""
    row = y // 16
    offset = 16 if row % 2 else 0
    if y % 16 < 2 or (x + offset) % 32 < 2:
        return (180, 176, 168, 255)
    shade = 0.8 + 0.2 * noise((x + offset) // 32, row, 3) + 0.06 * noise(x, y, 4)
    return (int(150 * shade), int(70 * shade), int(55 * shade), 255)


def crate(x, y):
    """Planks with a frame: a wooden crate face."""
    border = x < 6 or y < 6 or x >= 58 or y >= 58
    diagonal = abs(x - y) < 4
    grain = 0.85 + 0.15 * math.sin(0.9 * y + 3 * noise(x // 16, 0, 5))
    if border or diagonal:
        grain *= 0.75
    return (int(170 * grain), int(120 * grain), int(70 * grain), 255)


def lattice(x, y):
    """A square lattice of slats with leaves growing over it: alpha 255 on wood and leaves, 0 in the gaps."""
    slat = x % 32 < 6 or y % 32 < 6
    # Leaves: round blobs scattered by a hash, each about 10 texels across.
    leaf = False
    for cx in range(-1, 2):
        for cy in range(-1, 2):
            gx, gy = x // 24 + cx, y // 24 + cy
            if noise(gx, gy, 6) < 0.45:
                px = gx * 24 + 24 * noise(gx, gy, 7)
                py = gy * 24 + 24 * noise(gx, gy, 8)
                if (x - px) ** 2 + (y - py) ** 2 < 30:
                    leaf = True
    if leaf:
        g = 0.7 + 0.3 * noise(x, y, 9)
        return (int(60 * g), int(140 * g), int(50 * g), 255)
    if slat:
        return (150, 110, 70, 255)
    return (0, 0, 0, 0)


def main():
    png("tiles.png", 64, 64, tiles)
    png("bricks.png", 64, 64, bricks)
    png("crate.png", 64, 64, crate)
    png("lattice.png", 128, 128, lattice)

    v, vt, faces = [], [], []

    def quad(corners, uv_scale, material):
        """A quad a b c d, counter-clockwise seen from the side it faces, with texture coordinates 0..uv_scale."""
        base_v, base_t = len(v) + 1, len(vt) + 1
        v.extend(corners)
        su, sv = uv_scale
        vt.extend([(0, 0), (su, 0), (su, sv), (0, sv)])
        faces.append((material, [(base_v + k, base_t + k) for k in range(4)]))

    # Floor 6 x 6 facing up, tiles 3 times across; back wall facing +z, bricks 4 x 2.
    quad([(-3, 0, 3), (3, 0, 3), (3, 0, -3), (-3, 0, -3)], (3, 3), "tiles")
    quad([(-3, 0, -3), (3, 0, -3), (3, 3, -3), (-3, 3, -3)], (4, 2), "bricks")
    # A crate 0.8 on a side, its five visible faces.
    x0, x1, z0, z1, h = 0.6, 1.4, -1.4, -0.6, 0.8
    quad([(x0, h, z1), (x1, h, z1), (x1, h, z0), (x0, h, z0)], (1, 1), "crate")
    quad([(x0, 0, z1), (x1, 0, z1), (x1, h, z1), (x0, h, z1)], (1, 1), "crate")
    quad([(x1, 0, z1), (x1, 0, z0), (x1, h, z0), (x1, h, z1)], (1, 1), "crate")
    quad([(x0, 0, z0), (x0, 0, z1), (x0, h, z1), (x0, h, z0)], (1, 1), "crate")
    quad([(x1, 0, z0), (x0, 0, z0), (x0, h, z0), (x1, h, z0)], (1, 1), "crate")
    # The pergola roof at height 2.2, facing down, the lattice repeated twice; two posts.
    quad([(-2, 2.2, -2.5), (2, 2.2, -2.5), (2, 2.2, 1.5), (-2, 2.2, 1.5)], (2, 2), "lattice")
    for px in (-2, 1.9):
        quad([(px, 0, 1.5), (px + 0.1, 0, 1.5), (px + 0.1, 2.2, 1.5), (px, 2.2, 1.5)], (1, 1), "post")
    # The sun: a small bright area light high above and behind the roof, facing down.
    quad([(-0.15, 7, -0.65), (0.15, 7, -0.65), (0.15, 7, -0.35), (-0.15, 7, -0.35)], (1, 1), "sun")

    with open(os.path.join(HERE, "pergola.obj"), "w") as f:
        f.write("# Lueur scene 'pergola', written by make_pergola.py\nmtllib pergola.mtl\n")
        for p in v:
            f.write("v %g %g %g\n" % p)
        for t in vt:
            f.write("vt %g %g\n" % t)
        current = None
        for material, corners in faces:
            if material != current:
                f.write("usemtl %s\n" % material)
                current = material
            f.write("f " + " ".join("%d/%d" % c for c in corners) + "\n")

    with open(os.path.join(HERE, "pergola.mtl"), "w") as f:
        f.write("# Lueur scene 'pergola', written by make_pergola.py\n")
        for name, lines in [("tiles", "Kd 1 1 1\nmap_Kd tiles.png"), ("bricks", "Kd 1 1 1\nmap_Kd bricks.png"),
                            ("crate", "Kd 1 1 1\nmap_Kd crate.png"),
                            ("lattice", "Kd 1 1 1\nmap_Kd lattice.png\nmap_d lattice.png"),
                            ("post", "Kd 0.45 0.32 0.2"), ("sun", "Kd 0 0 0\nKe 1600 1480 1220")]:
            f.write("\nnewmtl %s\n%s\n" % (name, lines))

if __name__ == "__main__":
    main()
