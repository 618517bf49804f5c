#!/usr/bin/env python3
"""Writes simple closed obstacle meshes as Wavefront OBJ (metres, Y up),
counter-clockwise seen from outside, and checks each is a closed, manifold,
outward-wound solid before writing it.

  icosphere: an icosahedron subdivided N times (each triangle into four), its
             vertices pushed onto the sphere of radius r about the origin;
             20 * 4^N triangles.
  box:       an axis-aligned box about the origin as 12 triangles (8 vertices).

The shipped assets/meshes/icosphere.obj and box12.obj are the analytic
colliders of sphere_drop.json (radius 0.35) and table_drape.json (0.8 x 0.75 x
0.8) centred on the origin; their scenes' "mesh" modules translate them to
where those colliders stand:

  python3 tools/make_primitives.py icosphere --radius 0.35 --subdivisions 4 \\
      --out assets/meshes/icosphere.obj
  python3 tools/make_primitives.py box --size 0.8 0.75 0.8 --out assets/meshes/box12.obj

Python 3 standard library only.
"""

import argparse
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import obj_mesh  # noqa: E402


def icosphere(radius, subdivisions):
    t = (1.0 + math.sqrt(5.0)) / 2.0
    vertices = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t),
                (0, -1, -t), (0, 1, -t), (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    triangles = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4),
                 (11, 10, 2), (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8),
                 (3, 8, 9), (4, 9, 5), (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1)]

    def unit(p):
        n = obj_mesh.norm(p)
        return (p[0] / n, p[1] / n, p[2] / n)

    vertices = [unit(v) for v in vertices]
    for _ in range(subdivisions):
        middle = {}  # an edge's midpoint, shared by the two triangles on it

        def mid(a, b):
            key = (min(a, b), max(a, b))
            if key not in middle:
                pa, pb = vertices[a], vertices[b]
                vertices.append(unit(((pa[0] + pb[0]) / 2, (pa[1] + pb[1]) / 2,
                                      (pa[2] + pb[2]) / 2)))
                middle[key] = len(vertices) - 1
            return middle[key]

        finer = []
        for a, b, c in triangles:
            ab, bc, ca = mid(a, b), mid(b, c), mid(c, a)
            finer += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        triangles = finer
    return [(radius * x, radius * y, radius * z) for x, y, z in vertices], triangles


def box(size):
    hx, hy, hz = (s / 2.0 for s in size)
    vertices = [(sx * hx, sy * hy, sz * hz) for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)]

    def corner(sx, sy, sz):  # index of the vertex on sides sx, sy, sz (0 or 1 each)
        return 4 * sx + 2 * sy + sz

    triangles = []
    # Each face as two triangles, counter-clockwise seen from outside: for the
    # face on side s of axis d, corners in the order that makes u x v = +-e_d.
    for d in range(3):
        u, v = (d + 1) % 3, (d + 2) % 3
        for s in (0, 1):
            quad = []
            for a, b in ((0, 0), (1, 0), (1, 1), (0, 1)):
                side = [0, 0, 0]
                side[d], side[u], side[v] = s, a, b
                quad.append(corner(*side))
            if s == 0:
                quad.reverse()
            triangles += [(quad[0], quad[1], quad[2]), (quad[0], quad[2], quad[3])]
    return vertices, triangles


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    kinds = parser.add_subparsers(dest="kind", required=True)
    ico = kinds.add_parser("icosphere", help="a subdivided icosahedron on a sphere")
    ico.add_argument("--radius", type=float, default=1.0, help="m (default 1)")
    ico.add_argument("--subdivisions", type=int, default=3, help="0..7 (default 3)")
    ico.add_argument("--out", required=True)
    bx = kinds.add_parser("box", help="an axis-aligned box as 12 triangles")
    bx.add_argument("--size", type=float, nargs=3, default=[1, 1, 1], metavar=("X", "Y", "Z"),
                    help="m (default 1 1 1)")
    bx.add_argument("--out", required=True)
    args = parser.parse_args()

    if args.kind == "icosphere":
        if not (args.radius > 0 and 0 <= args.subdivisions <= 7):
            parser.error("--radius must be > 0 and --subdivisions in 0..7")
        vertices, triangles = icosphere(args.radius, args.subdivisions)
        # The largest gap between a flat triangle and the sphere (at a face's
        # centre): what the mesh's surface misses the sphere by.
        chord = max(args.radius - abs(obj_mesh.dot(
            tuple(sum(vertices[i][d] for i in t) / 3 for d in range(3)),
            obj_mesh.cross(obj_mesh.sub(vertices[t[1]], vertices[t[0]]),
                           obj_mesh.sub(vertices[t[2]], vertices[t[0]])))) /
            obj_mesh.norm(obj_mesh.cross(obj_mesh.sub(vertices[t[1]], vertices[t[0]]),
                                         obj_mesh.sub(vertices[t[2]], vertices[t[0]])))
            for t in triangles)
        header = ["An icosphere: radius %g m about the origin, %d subdivisions of an icosahedron"
                  % (args.radius, args.subdivisions),
                  "(%d triangles; its faces lie at most %.3g m inside the sphere)."
                  % (len(triangles), chord),
                  "Written by tools/make_primitives.py icosphere --radius %g --subdivisions %d"
                  % (args.radius, args.subdivisions)]
    else:
        if not all(s > 0 for s in args.size):
            parser.error("--size must be three numbers > 0")
        vertices, triangles = box(args.size)
        header = ["A box of %g x %g x %g m about the origin as 12 triangles." % tuple(args.size),
                  "Written by tools/make_primitives.py box --size %g %g %g" % tuple(args.size)]
    summary = obj_mesh.check_solid(vertices, triangles)
    obj_mesh.write_obj(args.out, vertices, triangles, header + ["Metres, Y up, counter-clockwise "
                                                                "seen from outside."])
    print("%s: %s" % (args.out, obj_mesh.summary_line(summary)))


if __name__ == "__main__":
    main()
