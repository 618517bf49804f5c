"""A Blender cloth bake exported as users export one, run inside Blender (headless).

    blender -b --factory-startup --python blender_cloth_bake.py -- \
        N SECONDS FPS OUT_PREFIX [--mass-per-area KG] [--spring K --damping C --bend B]

A cloth of N x N vertices, 0.6 m square, flat at 1 m, pinned at the two corners
of one edge (a "pin" vertex group), swinging down under gravity for SECONDS at
FPS, time-scaled so that one frame is 1/FPS s (the same units conversion as
blender_cloth_drape.py: Blender's cloth gravity is the scene's times 0.001, so
its time unit is 1/sqrt(1000) s). Air damping 0, as blender_cloth_drape.py
has it: Blender's air force does not scale with the vertex's mass, and its
default (1) holds a cloth of 0.4 g vertices nearly still (measured: the centre
fell 6 mm in 0.6 s). Otherwise Blender's defaults (quality 5, angular bending
0.5) except, when given, tension = compression = shear =
K (N/m per spring, converted), their damping C (N s/m, converted) and the
bending stiffness B (Blender's own unit: angular bending has no spring
counterpart). Then it exports what a user would hand over:

  OUT_PREFIX.pc2   the bake through Blender's own "Pointcache (.pc2)" exporter
                   (io_export_pc2, its defaults: Y-up, object space, modifiers
                   applied), every frame from 1;
  OUT_PREFIX.obj   the mesh the cache deforms (without the cloth modifier)
                   through Blender's OBJ exporter (Y up, -Z forward), no
                   normals, no UVs, no materials;
  OUT_PREFIX.json  the settings used, for the fit's report.

The grid's vertex order is Blender's from_pydata order, row i along -y, column
j along x: in neurocloth's frame (y up) row i runs along +z, so node i * N + j
is vertex i * N + j.
"""
import json
import math
import sys

import bpy

TAU = 1.0 / math.sqrt(1000.0)  # Blender cloth's time unit in seconds
WIDTH = 0.6
HEIGHT = 1.0


def parse(argv):
    args = argv[argv.index("--") + 1:] if "--" in argv else []
    if len(args) < 4:
        raise SystemExit("usage: ... -- N SECONDS FPS OUT_PREFIX [--mass-per-area KG]")
    o = {"n": int(args[0]), "seconds": float(args[1]), "fps": float(args[2]), "out": args[3],
         "mass_per_area": 0.2}
    rest = args[4:]
    for k in range(0, len(rest), 2):
        o[rest[k].lstrip("-").replace("-", "_")] = float(rest[k + 1])
    return o


def main():
    o = parse(sys.argv)
    n = o["n"]
    scene = bpy.context.scene
    scene.render.fps = int(round(o["fps"]))
    scene.render.fps_base = 1.0
    frames = int(round(o["seconds"] * o["fps"]))
    scene.frame_start = 1
    scene.frame_end = 1 + frames
    scene.gravity = (0.0, 0.0, -9.81)

    h = WIDTH / (n - 1)
    verts = [(-WIDTH / 2 + j * h, WIDTH / 2 - i * h, HEIGHT) for i in range(n) for j in range(n)]
    faces = [(i * n + j, i * n + j + 1, (i + 1) * n + j + 1, (i + 1) * n + j)
             for i in range(n - 1) for j in range(n - 1)]
    mesh = bpy.data.meshes.new("cloth")
    mesh.from_pydata(verts, [], faces)
    mesh.update()
    ob = bpy.data.objects.new("cloth", mesh)
    scene.collection.objects.link(ob)
    pin = ob.vertex_groups.new(name="pin")
    pin.add([0, n - 1], 1.0, "REPLACE")

    mod = ob.modifiers.new("cloth", "CLOTH")
    s = mod.settings
    s.mass = o["mass_per_area"] * WIDTH * WIDTH / (n * n)
    s.time_scale = 1.0 / (o["fps"] * TAU)
    s.vertex_group_mass = "pin"
    s.air_damping = 0.0
    if "spring" in o:
        tension = o["spring"] * TAU * TAU * h
        s.tension_stiffness = s.compression_stiffness = s.shear_stiffness = tension
        s.tension_damping = s.compression_damping = s.shear_damping = o["damping"] * TAU
        s.bending_stiffness = o["bend"]
    mod.collision_settings.use_collision = False
    mod.collision_settings.use_self_collision = False
    mod.point_cache.frame_start = 1
    mod.point_cache.frame_end = scene.frame_end

    for f in range(1, scene.frame_end + 1):
        scene.frame_set(f)
    scene.frame_set(1)
    bpy.ops.object.select_all(action="DESELECT")
    ob.select_set(True)
    bpy.context.view_layer.objects.active = ob

    bpy.ops.preferences.addon_enable(module="io_export_pc2")
    bpy.ops.export_shape.pc2(filepath=o["out"] + ".pc2", range_start=1, range_end=scene.frame_end)
    bpy.ops.wm.obj_export(filepath=o["out"] + ".obj", export_selected_objects=True,
                          apply_modifiers=False, export_uv=False, export_normals=False,
                          export_materials=False, forward_axis="NEGATIVE_Z", up_axis="Y")
    settings = {k: getattr(s, k) for k in (
        "quality", "mass", "time_scale", "tension_stiffness", "compression_stiffness",
        "shear_stiffness", "bending_stiffness", "tension_damping", "compression_damping",
        "shear_damping", "bending_damping", "air_damping", "bending_model")}
    # In neurocloth's units (N/m per spring, N s/m): Blender divides tension,
    # compression and shear by the mean structural edge length.
    settings["spring_constant_equivalent"] = s.tension_stiffness / (TAU * TAU * h)
    settings["damping_equivalent"] = s.tension_damping / TAU
    info = {"n": n, "seconds": o["seconds"], "fps": o["fps"], "frames": frames + 1,
            "spacing": h, "mass_per_area": o["mass_per_area"], "blender": bpy.app.version_string,
            "settings": settings}
    with open(o["out"] + ".json", "w") as f:
        json.dump(info, f, indent=1)


main()
