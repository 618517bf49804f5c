"""Blender's cloth on the table_drape scene, run inside Blender (headless).

    blender -b --factory-startup --python blender_cloth_drape.py -- \
        N QUALITY SECONDS FPS OUT.json [--spring K --shear K --bend B --damping C
                                        --bend_damping D --distance M
                                        --shift_x DX --shift_z DZ]

Builds the drape of assets/scenes/table_drape.json in an empty scene: an N x N
vertex grid 1.2 m wide, 25 cm above a 0.8 x 0.8 x 0.75 m box (a collider),
total mass 1.5 kg/m^2 x area spread evenly over the vertices (Blender's mass is
per vertex), air damping 0, QUALITY substeps per frame, frames stepped at FPS
for SECONDS. Writes OUT.json: the seconds spent stepping the frames (not
Blender's startup), the settings used and the final vertex positions of the
evaluated mesh, in neurocloth's frame (y up) and node order (row i along z,
column j along x: node i * N + j), so bench/peers/run measures both sides'
drapes with the same code. --shift_x/--shift_z move the cloth horizontally (m,
in neurocloth's frame) before it falls: an ensemble member (bench/peers/run
--ensemble).

Units. Blender's cloth integrates in "frames": one frame advances its solver
by time_scale units, and its gravity is the scene's times 0.001 (cloth_calc_force
in SIM_mass_spring.cc). A unit is therefore tau = 1/sqrt(1000) s of real time
for the fall to be right, and time_scale = 1 / (fps * tau) makes one frame
1/fps s. In those units a spring constant k (N/m) is k * tau^2 and a damping
c (N s/m) is c * tau; Blender divides tension, compression and shear by the
mean structural edge length (k_spring = tension / h), so tension = k tau^2 h
gives every spring exactly neurocloth's constant. Bending has no exact
counterpart (bench/peers/run and docs/tradeoff.md say which value is used and why).
Without --spring etc. the cloth keeps Blender's default stiffness and damping.

The mapping, with the Blender source it is read from, is in
blender_cloth_bake.py's docstring. The fall checked (2026-12-07, 0.2 s at
30 fps, quality 5, before the cloth reaches the table): with the scene's
material (--spring 201 --damping 0.367 and the --bend bench/peers/run gives,
bending damping 0) the mean height falls 0.2027 m at 32^2 and 0.2028 m at
128^2, implicit Euler's own 0.2027 m; with Blender's defaults (no --spring:
tension 15, damping 5, bending damping 0.5, which assume 0.3 kg vertices) only
0.088 and 0.050 m, a cloth held up by its conjugate gradient's 1% residual
(blender_cloth_bake.py, "Why the defaults do not fall").
"""
import json
import math
import sys
import time

import bpy

TAU = 1.0 / math.sqrt(1000.0)  # Blender cloth's time unit in seconds (gravity x 0.001)
WIDTH = 1.2
MASS_PER_AREA = 1.5
CLOTH_HEIGHT = 1.0  # y of the cloth at rest: 25 cm above the table's top
TABLE = (0.8, 0.75, 0.8)  # x, y (height), z sizes of the box, standing on y = 0
TABLE_THICKNESS = 0.005  # the box module's contact margin


def parse(argv):
    args = argv[argv.index("--") + 1:] if "--" in argv else []
    if len(args) < 5:
        raise SystemExit("usage: ... -- N QUALITY SECONDS FPS OUT.json [--spring K ...]")
    o = {"n": int(args[0]), "quality": int(args[1]), "seconds": float(args[2]),
         "fps": float(args[3]), "out": args[4]}
    rest = args[5:]
    for k in range(0, len(rest), 2):
        o[rest[k].lstrip("-")] = float(rest[k + 1])
    return o


def grid_object(n, shift_x=0.0, shift_z=0.0):
    h = WIDTH / (n - 1)
    # neurocloth (x, y, z) with y up is Blender (x, -z, y) with z up.
    verts = [(-0.6 + j * h + shift_x, 0.6 - i * h - shift_z, CLOTH_HEIGHT)
             for i in range(n) for j in range(n)]
    faces = [(i * n + j, i * n + j + 1, (i + 1) * n + j + 1, (i + 1) * n + j)
             for i in range(n - 1) for j in range(n - 1)]
    mesh = bpy.data.meshes.new("cloth")
    mesh.from_pydata(verts, [], faces)
    mesh.update()
    ob = bpy.data.objects.new("cloth", mesh)
    bpy.context.scene.collection.objects.link(ob)
    return ob, h


def table_object():
    sx, sy, sz = TABLE[0] / 2, TABLE[2] / 2, TABLE[1]
    verts = [(x, y, z) for z in (0.0, sz) for y in (-sy, sy) for x in (-sx, sx)]
    # Wound so that the normals point out: Blender's cloth collides with the
    # outer side of a collider's faces only (collision.use_culling).
    faces = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
    mesh = bpy.data.meshes.new("table")
    mesh.from_pydata(verts, [], faces)
    mesh.update()
    ob = bpy.data.objects.new("table", mesh)
    bpy.context.scene.collection.objects.link(ob)
    ob.modifiers.new("collision", "COLLISION")
    ob.collision.thickness_outer = TABLE_THICKNESS
    return ob


def main():
    o = parse(sys.argv)
    n = o["n"]
    scene = bpy.context.scene
    scene.render.fps = int(round(o["fps"]))
    scene.render.fps_base = scene.render.fps / o["fps"]
    frames = int(round(o["seconds"] * o["fps"]))
    scene.frame_start = 1
    scene.frame_end = 1 + frames
    scene.gravity = (0.0, 0.0, -9.81)

    table_object()
    ob, h = grid_object(n, o.get("shift_x", 0.0), o.get("shift_z", 0.0))
    mod = ob.modifiers.new("cloth", "CLOTH")
    s = mod.settings
    s.quality = o["quality"]
    s.mass = MASS_PER_AREA * WIDTH * WIDTH / (n * n)
    s.air_damping = 0.0
    s.time_scale = 1.0 / (o["fps"] * TAU)
    s.bending_model = "ANGULAR"
    if "spring" in o:
        tension = o["spring"] * TAU * TAU * h
        s.tension_stiffness = tension
        s.compression_stiffness = tension
        s.shear_stiffness = o.get("shear", o["spring"]) * TAU * TAU * h
        s.bending_stiffness = o["bend"]
        damping = o["damping"] * TAU
        s.tension_damping = damping
        s.compression_damping = damping
        s.shear_damping = damping
        s.bending_damping = o.get("bend_damping", 0.0)
    c = mod.collision_settings
    c.use_collision = True
    c.use_self_collision = False
    # The cloth's own collision distance, added to the table's thickness.
    c.distance_min = o.get("distance", 0.015)  # Blender's default
    mod.point_cache.frame_start = 1
    mod.point_cache.frame_end = scene.frame_end

    scene.frame_set(1)
    start = time.perf_counter()
    for f in range(2, scene.frame_end + 1):
        scene.frame_set(f)
    seconds = time.perf_counter() - start

    depsgraph = bpy.context.evaluated_depsgraph_get()
    mesh = ob.evaluated_get(depsgraph).to_mesh()
    positions = [[v.co.x, v.co.z, -v.co.y] for v in mesh.vertices]
    result = {
        "n": n, "quality": o["quality"], "seconds": o["seconds"], "fps": o["fps"],
        "frames": frames, "step_seconds": seconds,
        "blender": bpy.app.version_string,
        "settings": {k: getattr(s, k) for k in (
            "mass", "time_scale", "tension_stiffness", "compression_stiffness",
            "shear_stiffness", "bending_stiffness", "tension_damping", "compression_damping",
            "shear_damping", "bending_damping", "air_damping")},
        "collision": {"cloth_distance_min": c.distance_min,
                      "table_thickness_outer": TABLE_THICKNESS,
                      "table_cloth_friction": bpy.data.objects["table"].collision.cloth_friction},
        "positions": positions,
    }
    with open(o["out"], "w") as f:
        json.dump(result, f)


main()
