"""Triangle meshes for the obstacle generators (make_primitives.py,
make_mannequin.py): writing a Wavefront OBJ and checking that a mesh is a
closed, manifold, outward-wound solid. Python 3 standard library only.

A mesh is (vertices, triangles): vertices a list of (x, y, z) in metres,
triangles a list of (a, b, c) vertex indices from 0, counter-clockwise seen
from outside (the face normal (b - a) x (c - a) points out of the solid).
"""

import math


def sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def norm(a):
    return math.sqrt(dot(a, a))


def write_obj(path, vertices, triangles, header_lines):
    """Writes the mesh, `header_lines` as comments first; 6 decimals (micrometres)."""
    with open(path, "w", encoding="ascii", newline="\n") as out:
        for line in header_lines:
            out.write("# " + line + "\n")
        for v in vertices:
            out.write("v %.6f %.6f %.6f\n" % tuple(0.0 if abs(c) < 5e-7 else c for c in v))
        for t in triangles:
            out.write("f %d %d %d\n" % (t[0] + 1, t[1] + 1, t[2] + 1))


def read_obj(path):
    """The vertices and triangles of an OBJ written by write_obj (v and f lines only)."""
    vertices, triangles = [], []
    with open(path, encoding="ascii") as f:
        for line in f:
            parts = line.split()
            if not parts or parts[0].startswith("#"):
                continue
            if parts[0] == "v":
                vertices.append(tuple(float(x) for x in parts[1:4]))
            elif parts[0] == "f":
                triangles.append(tuple(int(x.split("/")[0]) - 1 for x in parts[1:4]))
    return vertices, triangles


def check_solid(vertices, triangles, min_area=0.0):
    """What a solid obstacle must be, or raises ValueError saying what is not:
    every vertex used; every edge shared by exactly two triangles that traverse
    it in opposite directions (closed, consistently wound); every vertex's
    triangles one fan (manifold); one connected piece; no triangle of area <=
    min_area; a positive signed volume (outward). Returns a summary dict."""
    used = [False] * len(vertices)
    directed = {}
    for f, t in enumerate(triangles):
        if len(set(t)) != 3:
            raise ValueError("triangle %d repeats a vertex: %s" % (f, t))
        for k in range(3):
            a, b = t[k], t[(k + 1) % 3]
            used[a] = True
            if (a, b) in directed:
                raise ValueError("edge %d-%d is traversed twice the same way (triangles %d and %d)"
                                 % (a, b, directed[(a, b)], f))
            directed[(a, b)] = f
    if not all(used):
        raise ValueError("vertex %d belongs to no triangle" % used.index(False))
    for (a, b) in directed:
        if (b, a) not in directed:
            raise ValueError("edge %d-%d has one triangle: the mesh is open" % (a, b))
    # Manifold vertices: the triangles around a vertex form a single cycle.
    # Around vertex v, triangle (v, b, c) leads from b to c.
    around = {}
    for t in triangles:
        for k in range(3):
            v, b, c = t[k], t[(k + 1) % 3], t[(k + 2) % 3]
            around.setdefault(v, {})[b] = c
    for v, step in around.items():
        start = next(iter(step))
        n, x = 0, start
        while True:
            x = step[x]
            n += 1
            if x == start or n > len(step):
                break
        if n != len(step):
            raise ValueError("vertex %d is not manifold: its triangles form more than one fan" % v)
    # One connected piece.
    parent = list(range(len(vertices)))

    def find(i):
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    for t in triangles:
        for k in (1, 2):
            ra, rb = find(t[0]), find(t[k])
            if ra != rb:
                parent[ra] = rb
    pieces = len({find(i) for i in range(len(vertices))})
    if pieces != 1:
        raise ValueError("the mesh is %d separate pieces" % pieces)
    smallest, volume, area = float("inf"), 0.0, 0.0
    for t in triangles:
        a, b, c = (vertices[i] for i in t)
        n = cross(sub(b, a), sub(c, a))
        smallest = min(smallest, 0.5 * norm(n))
        area += 0.5 * norm(n)
        volume += dot(a, n) / 6.0
    if smallest <= min_area:
        raise ValueError("a triangle has area %.3g m^2 (at most %.3g)" % (smallest, min_area))
    if volume <= 0:
        raise ValueError("signed volume %.6g m^3: the triangles wind inward" % volume)
    euler = len(vertices) - len(directed) // 2 + len(triangles)
    lo = [min(v[d] for v in vertices) for d in range(3)]
    hi = [max(v[d] for v in vertices) for d in range(3)]
    return {"vertices": len(vertices), "triangles": len(triangles), "genus": (2 - euler) // 2,
            "volume": volume, "area": area, "smallest_area": smallest, "lo": lo, "hi": hi}


def summary_line(s):
    return ("%d vertices, %d triangles, closed and manifold, genus %d, outward "
            "(volume %.6f m^3, area %.4f m^2), bounds [%.4f, %.4f, %.4f] to [%.4f, %.4f, %.4f]"
            % (s["vertices"], s["triangles"], s["genus"], s["volume"], s["area"], *s["lo"],
               *s["hi"]))
