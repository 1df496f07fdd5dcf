#!/usr/bin/env python3
"""Writes examples/hood.off: a car bonnet as a convex, doubly curved open patch (metres).

1.5 m wide (x), 1.2 m long (y), crown at (0, 0.6, 0.95) falling 6 cm to the sides and 5 cm to the
front and back edges; 81 x 61 vertices, triangulated with alternating diagonals so the mesh has no
preferred direction (--diagonals uniform splits every square the same way, for measuring how much the
curvature-sign counts depend on the tessellation: interior vertices here meet 4 or 8 triangles, there 6).
It is the bonnet of `scripts/demo-hood` (the paper's Fig. 12a/13 case: its front edge pulled 10 cm forward).
"""
import argparse
import pathlib

W, L = 1.5, 1.2


def height(x, y):
    return 0.95 - 0.06 * (x / (W / 2)) ** 2 - 0.05 * ((y - L / 2) / (L / 2)) ** 2


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--nx", type=int, default=81, help="vertices across (default 81)")
    parser.add_argument("--ny", type=int, default=61, help="vertices along (default 61)")
    parser.add_argument("--diagonals", choices=["alternating", "uniform"], default="alternating",
                        help="how each grid square is split (default alternating, as examples/hood.off)")
    parser.add_argument("--out", help="output .off (default examples/hood.off)")
    args = parser.parse_args()
    NX, NY = args.nx, args.ny
    verts, faces = [], []
    for j in range(NY):
        for i in range(NX):
            x = -W / 2 + W * i / (NX - 1)
            y = L * j / (NY - 1)
            verts.append((x, y, height(x, y)))
    for j in range(NY - 1):
        for i in range(NX - 1):
            a, b = j * NX + i, j * NX + i + 1
            c, d = a + NX, b + NX
            if args.diagonals == "uniform" or (i + j) % 2 == 0:
                faces += [(a, b, d), (a, d, c)]
            else:
                faces += [(a, b, c), (b, d, c)]
    out = pathlib.Path(args.out) if args.out else pathlib.Path(__file__).resolve().parent.parent / "examples" / "hood.off"
    with open(out, "w") as f:
        f.write("OFF\n# pushpull example: convex car bonnet, metres (scripts/make-example-hood.py)\n")
        f.write(f"{len(verts)} {len(faces)} 0\n")
        for v in verts:
            f.write(f"{v[0]:.6f} {v[1]:.6f} {v[2]:.6f}\n")
        for t in faces:
            f.write(f"3 {t[0]} {t[1]} {t[2]}\n")


if __name__ == "__main__":
    main()
