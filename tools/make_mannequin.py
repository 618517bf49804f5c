#!/usr/bin/env python3
"""Writes a dressmaker's mannequin as a closed triangle mesh (Wavefront OBJ,
metres, Y up, facing +Z, counter-clockwise seen from outside): a torso with
hips, waist, chest, shoulders and arm stumps, a neck and a head, on a pole
and a round foot standing on the floor (y = 0). The obstacle of
assets/scenes/mannequin_drape.json.

How: the body is a signed-distance function (negative inside), a smooth union
of ellipsoids and capsules (Quilez's polynomial smooth minimum), sampled on a
grid and polygonised by marching tetrahedra (each grid cube cut into six
tetrahedra around its main diagonal, the same cut in every cube, so that
neighbouring cubes meet on the same face diagonals). A vertex is made once per
grid edge the surface crosses and shared by every triangle on that edge, so
the mesh is watertight; within a tetrahedron the sampled field is linear, so
each piece is flat and wound to face the outside samples. The vertices are
then relaxed a few times (moved towards their neighbours' mean, then back onto
the surface along the field's gradient), which evens out the marching
triangles without changing which vertex joins which.

The mesh is checked before it is written (closed, every edge shared by two
triangles traversing it in opposite directions, manifold vertices, one piece,
genus 0, no degenerate triangle, every face turned the way the field grows,
and, with --check-intersections, no two triangles crossing).

  python3 tools/make_mannequin.py --out assets/meshes/mannequin.obj

The default spacing (--cell) gives about 20,000 triangles. Python 3 standard
library only; about a minute.
"""

import argparse
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import obj_mesh  # noqa: E402
from obj_mesh import cross, dot, norm, sub  # noqa: E402

# --- The body's distance field ------------------------------------------------


def ellipsoid(c, r):
    """An ellipsoid of centre c and radii r (Quilez's distance bound)."""
    cx, cy, cz = c
    rx, ry, rz = r

    def f(x, y, z):
        px, py, pz = (x - cx) / rx, (y - cy) / ry, (z - cz) / rz
        k0 = math.sqrt(px * px + py * py + pz * pz)
        qx, qy, qz = px / rx, py / ry, pz / rz
        k1 = math.sqrt(qx * qx + qy * qy + qz * qz)
        if k1 < 1e-12:
            return -min(r)
        return k0 * (k0 - 1.0) / k1

    return f, (cx - rx, cy - ry, cz - rz), (cx + rx, cy + ry, cz + rz)


def capsule(a, b, ra, rb=None):
    """The points within a radius of segment a-b, the radius going from ra at a
    to rb at b (a tapered capsule; a distance bound when the taper is slight)."""
    rb = ra if rb is None else rb
    ab = sub(b, a)
    length2 = dot(ab, ab)

    def f(x, y, z):
        ap = (x - a[0], y - a[1], z - a[2])
        h = min(1.0, max(0.0, dot(ap, ab) / length2))
        d = (ap[0] - h * ab[0], ap[1] - h * ab[1], ap[2] - h * ab[2])
        return norm(d) - (ra + h * (rb - ra))

    r = max(ra, rb)
    lo = tuple(min(a[i], b[i]) - r for i in range(3))
    hi = tuple(max(a[i], b[i]) + r for i in range(3))
    return f, lo, hi


def rounded_disc(c, radius, half_height, rounding):
    """An upright cylinder about c with its rim rounded (an exact distance)."""
    cx, cy, cz = c

    def f(x, y, z):
        qx = math.hypot(x - cx, z - cz) - radius + rounding
        qy = abs(y - cy) - half_height + rounding
        outside = math.hypot(max(qx, 0.0), max(qy, 0.0))
        return outside + min(max(qx, qy), 0.0) - rounding

    return f, (cx - radius, cy - half_height, cz - radius), (cx + radius, cy + half_height,
                                                             cz + radius)


def smooth_min(a, b, k):
    """Quilez's polynomial smooth minimum: min(a, b) rounded over a width k."""
    h = max(k - abs(a - b), 0.0) / k
    return min(a, b) - h * h * k * 0.25


def mirrored(make, c, *rest):
    """make(c, ...) and make(c with x negated, ...)."""
    return [make(c, *rest), make((-c[0], c[1], c[2]), *rest)]


def body_parts():
    """(field, lower corner, upper corner, blend width) of each part, in metres.
    A woman's dress form of about 1.7 m: hips 0.94 m round, waist 0.70, bust 0.90."""
    parts = []

    def add(shape, k):
        parts.append((shape[0], shape[1], shape[2], k))

    # Stand: a round foot on the floor and a pole up into the hips.
    add(rounded_disc((0, 0.035, 0), 0.17, 0.03, 0.02), 0.03)
    add(capsule((0, 0.04, 0), (0, 0.9, 0), 0.022), 0.04)
    # Torso, bottom to top.
    add(ellipsoid((0, 0.93, -0.005), (0.165, 0.1, 0.115)), 0.06)   # hips
    add(ellipsoid((0, 1.06, 0.0), (0.125, 0.1, 0.09)), 0.08)       # waist
    add(ellipsoid((0, 1.22, -0.005), (0.15, 0.13, 0.1)), 0.07)     # ribcage
    for s in mirrored(ellipsoid, (0.065, 1.255, 0.05), (0.07, 0.065, 0.065)):
        add(s, 0.05)                                               # bust
    add(ellipsoid((0, 1.34, -0.015), (0.165, 0.07, 0.09)), 0.06)   # upper chest and back
    # Shoulders: a rounded bar across, with short arm stumps turned down a little.
    add(capsule((-0.15, 1.385, -0.015), (0.15, 1.385, -0.015), 0.05), 0.05)
    add(capsule((-0.175, 1.37, -0.01), (-0.205, 1.28, -0.005), 0.055, 0.047), 0.04)
    add(capsule((0.175, 1.37, -0.01), (0.205, 1.28, -0.005), 0.055, 0.047), 0.04)
    # Neck and head.
    add(capsule((0, 1.4, -0.01), (0, 1.52, 0.005), 0.05, 0.045), 0.04)
    add(ellipsoid((0, 1.62, 0.01), (0.075, 0.1, 0.09)), 0.04)      # skull
    add(ellipsoid((0, 1.565, 0.04), (0.055, 0.05, 0.055)), 0.03)   # jaw and chin
    return parts


def body_field(parts):
    """f(x, y, z): the smooth union, evaluating only the parts whose box (grown
    by their blend width) holds the point: a part farther than its blend width
    does not change the smooth minimum. Outside every box, the distance to the
    nearest box: enough to tell outside."""
    grown = [(f, tuple(l - k for l in lo), tuple(h + k for h in hi), k) for f, lo, hi, k in parts]

    def field(x, y, z):
        d = None
        far = float("inf")
        for f, lo, hi, k in grown:
            if lo[0] <= x <= hi[0] and lo[1] <= y <= hi[1] and lo[2] <= z <= hi[2]:
                v = f(x, y, z)
                d = v if d is None else smooth_min(d, v, k)
            else:
                far = min(far, max(lo[0] - x, x - hi[0], lo[1] - y, y - hi[1], lo[2] - z,
                                   z - hi[2]))
        return far if d is None else d

    lo = tuple(min(p[1][i] for p in parts) for i in range(3))
    hi = tuple(max(p[2][i] for p in parts) for i in range(3))
    return field, lo, hi


def gradient(field, p, h=1e-4):
    x, y, z = p
    return ((field(x + h, y, z) - field(x - h, y, z)) / (2 * h),
            (field(x, y + h, z) - field(x, y - h, z)) / (2 * h),
            (field(x, y, z + h) - field(x, y, z - h)) / (2 * h))


# --- Marching tetrahedra ------------------------------------------------------

# The six tetrahedra of a cube around its diagonal from corner 0 to corner 7
# (corner index = x + 2 y + 4 z): one per order of the three axes.
_TETS = []
for order in ((0, 1, 2), (0, 2, 1), (1, 0, 2), (1, 2, 0), (2, 0, 1), (2, 1, 0)):
    corner, path = 0, [0]
    for axis in order:
        corner += 1 << axis
        path.append(corner)
    _TETS.append(tuple(path))


def polygonise(field, lo, hi, cell):
    """Marching tetrahedra over a grid of spacing `cell` padded around lo..hi."""
    pad = 2 * cell
    origin = tuple(l - pad for l in lo)
    n = tuple(int(math.ceil((hi[i] + pad - origin[i]) / cell)) for i in range(3))
    nx, ny, nz = n
    sx, sy = nx + 1, (nx + 1) * (ny + 1)

    def point(i):
        return (origin[0] + cell * (i % sx), origin[1] + cell * (i // sx % (ny + 1)),
                origin[2] + cell * (i // sy))

    values = []
    for k in range(nz + 1):
        z = origin[2] + cell * k
        for j in range(ny + 1):
            y = origin[1] + cell * j
            for i in range(nx + 1):
                v = field(origin[0] + cell * i, y, z)
                values.append(v if v != 0.0 else 1e-12)  # a sample never on the surface
    vertices, triangles, on_edge = [], [], {}

    def edge_vertex(a, b):
        key = (a, b) if a < b else (b, a)
        index = on_edge.get(key)
        if index is None:
            va, vb = values[a], values[b]
            # Kept off the samples themselves, so no edge of the mesh has zero length.
            t = min(0.98, max(0.02, va / (va - vb)))
            pa, pb = point(a), point(b)
            vertices.append(tuple(pa[d] + t * (pb[d] - pa[d]) for d in range(3)))
            index = on_edge[key] = len(vertices) - 1
        return index

    def emit(tri, inside, outside):
        # Turned to face the outside samples: within a tetrahedron the surface is
        # the plane of the linear field, with every outside sample on its far side.
        p = [vertices[i] for i in tri]
        normal = cross(sub(p[1], p[0]), sub(p[2], p[0]))
        pin = [sum(point(i)[d] for i in inside) / len(inside) for d in range(3)]
        pout = [sum(point(i)[d] for i in outside) / len(outside) for d in range(3)]
        if dot(normal, sub(pout, pin)) < 0:
            tri = (tri[0], tri[2], tri[1])
        triangles.append(tri)

    offsets = [dx + sx * dy + sy * dz for dz in (0, 1) for dy in (0, 1) for dx in (0, 1)]
    for k in range(nz):
        for j in range(ny):
            base_row = sx * j + sy * k
            for i in range(nx):
                base = base_row + i
                corners = [base + o for o in offsets]
                signs = [values[c] < 0 for c in corners]
                if all(signs) or not any(signs):
                    continue
                for tet in _TETS:
                    ids = [corners[c] for c in tet]
                    inside = [g for g in ids if values[g] < 0]
                    outside = [g for g in ids if values[g] >= 0]
                    if not inside or not outside:
                        continue
                    if len(inside) == 1 or len(outside) == 1:
                        lone, rest = (inside[0], outside) if len(inside) == 1 else (outside[0],
                                                                                   inside)
                        emit(tuple(edge_vertex(lone, r) for r in rest), inside, outside)
                    else:
                        a, b = inside
                        c, d = outside
                        ac, ad, bd, bc = (edge_vertex(a, c), edge_vertex(a, d),
                                          edge_vertex(b, d), edge_vertex(b, c))
                        emit((ac, ad, bd), inside, outside)
                        emit((ac, bd, bc), inside, outside)
    return vertices, triangles


# --- Relaxation ---------------------------------------------------------------


def neighbours(count, triangles):
    ring = [set() for _ in range(count)]
    for a, b, c in triangles:
        ring[a].update((b, c))
        ring[b].update((a, c))
        ring[c].update((a, b))
    return [sorted(r) for r in ring]


def project(field, p, steps=3):
    """p moved onto the zero set along the field's gradient (Newton steps)."""
    for _ in range(steps):
        v = field(*p)
        if abs(v) < 1e-7:
            break
        g = gradient(field, p)
        g2 = dot(g, g)
        if g2 < 1e-12:
            break
        p = tuple(p[d] - v * g[d] / g2 for d in range(3))
    return p


def relax(field, vertices, triangles, iterations, weight=0.5):
    ring = neighbours(len(vertices), triangles)
    for _ in range(iterations):
        moved = []
        for i, p in enumerate(vertices):
            r = ring[i]
            mean = [sum(vertices[j][d] for j in r) / len(r) for d in range(3)]
            q = tuple(p[d] + weight * (mean[d] - p[d]) for d in range(3))
            moved.append(project(field, q))
        vertices = moved
    return vertices


# --- Checks -------------------------------------------------------------------


def check_faces_outward(field, vertices, triangles):
    """Every face turned the way the field grows (out of the body)."""
    for f, t in enumerate(triangles):
        p = [vertices[i] for i in t]
        n = cross(sub(p[1], p[0]), sub(p[2], p[0]))
        centre = tuple(sum(q[d] for q in p) / 3 for d in range(3))
        if dot(n, gradient(field, centre)) <= 0:
            raise ValueError("triangle %d faces into the body" % f)


def segment_crosses_triangle(p, q, a, b, c):
    """Whether segment p-q passes through the inside of triangle a-b-c."""
    e1, e2 = sub(b, a), sub(c, a)
    d = sub(q, p)
    h = cross(d, e2)
    det = dot(e1, h)
    if abs(det) < 1e-18:
        return False
    s = sub(p, a)
    u = dot(s, h) / det
    if u < 0 or u > 1:
        return False
    w = cross(s, e1)
    v = dot(d, w) / det
    if v < 0 or u + v > 1:
        return False
    t = dot(e2, w) / det
    return 0 < t < 1


def check_no_crossings(vertices, triangles, cell):
    """No two triangles without a shared vertex cross (an edge of one through the other)."""
    buckets = {}
    boxes = []
    for f, t in enumerate(triangles):
        p = [vertices[i] for i in t]
        lo = [int(math.floor(min(q[d] for q in p) / cell)) for d in range(3)]
        hi = [int(math.floor(max(q[d] for q in p) / cell)) for d in range(3)]
        boxes.append((lo, hi))
        for x in range(lo[0], hi[0] + 1):
            for y in range(lo[1], hi[1] + 1):
                for z in range(lo[2], hi[2] + 1):
                    buckets.setdefault((x, y, z), []).append(f)
    for f, t in enumerate(triangles):
        lo, hi = boxes[f]
        near = set()
        for x in range(lo[0], hi[0] + 1):
            for y in range(lo[1], hi[1] + 1):
                for z in range(lo[2], hi[2] + 1):
                    near.update(buckets[(x, y, z)])
        pf = [vertices[i] for i in t]
        for g in near:
            if g <= f or set(triangles[g]) & set(t):
                continue
            pg = [vertices[i] for i in triangles[g]]
            for one, other in ((pf, pg), (pg, pf)):
                for k in range(3):
                    if segment_crosses_triangle(one[k], one[(k + 1) % 3], *other):
                        raise ValueError("triangles %d and %d cross" % (f, g))


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--out", required=True, help="the OBJ to write")
    parser.add_argument("--cell", type=float, default=0.0215,
                        help="grid spacing, m (default 0.0215: about 20,000 triangles)")
    parser.add_argument("--relax", type=int, default=4, help="relaxation passes (default 4)")
    parser.add_argument("--check-intersections", action="store_true",
                        help="also check that no two triangles cross (slow)")
    args = parser.parse_args()
    if not 0.002 <= args.cell <= 0.1:
        parser.error("--cell must be in [0.002, 0.1] m")

    field, lo, hi = body_field(body_parts())
    vertices, triangles = polygonise(field, lo, hi, args.cell)
    vertices = relax(field, vertices, triangles, args.relax)
    summary = obj_mesh.check_solid(vertices, triangles, min_area=1e-4 * args.cell ** 2)
    if summary["genus"] != 0:
        raise ValueError("genus %d: the body should be a sphere's shape" % summary["genus"])
    check_faces_outward(field, vertices, triangles)
    if args.check_intersections:
        check_no_crossings(vertices, triangles, 2 * args.cell)
    header = ["A dressmaker's mannequin on a stand, about 1.7 m tall, standing on y = 0, facing +Z.",
              "Metres, Y up, counter-clockwise seen from outside; closed, manifold, genus 0.",
              "A smooth union of ellipsoids and capsules polygonised by marching tetrahedra",
              "(grid %g m, %d relaxation passes): %d vertices, %d triangles."
              % (args.cell, args.relax, len(vertices), len(triangles)),
              "Written by tools/make_mannequin.py --cell %g --relax %d" % (args.cell, args.relax)]
    obj_mesh.write_obj(args.out, vertices, triangles, header)
    # What was written is what was checked: read it back at the file's precision.
    v2, t2 = obj_mesh.read_obj(args.out)
    summary = obj_mesh.check_solid(v2, t2, min_area=1e-4 * args.cell ** 2)
    print("%s: %s" % (args.out, obj_mesh.summary_line(summary)))
    if args.check_intersections:
        print("  no two triangles cross")


if __name__ == "__main__":
    main()
