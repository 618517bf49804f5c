"""A Blender cloth bake exported as users export one, run inside Blender (headless).

    blender -b --factory-startup --python blender_cloth_bake.py -- \
        N SECONDS FPS OUT_PREFIX [--mass-per-area KG] [--quality Q]
        [--spring K --damping C] [--shear K] [--bend B] [--bend-damping D] [--unpinned]

A cloth of N x N vertices, 0.6 m square, flat at 1 m, pinned at the two corners
of one edge (a "pin" vertex group; --unpinned leaves it free, to check the
fall), swinging down under gravity for SECONDS at FPS, QUALITY substeps a frame
(Blender's default 5). Air damping 0. Without --spring, Blender's own stiffness
and damping (its defaults assume 0.3 kg vertices; on these they are the
settings that do not fall: see "Why the defaults do not fall" below). Then it
exports what a user would hand over:

  OUT_PREFIX.pc2   the bake through Blender's own "Pointcache (.pc2)" exporter
                   (io_export_pc2, its defaults: Y-up, object space, modifiers
                   applied), every frame from 1;
  OUT_PREFIX.obj   the mesh the cache deforms (without the cloth modifier)
                   through Blender's OBJ exporter (Y up, -Z forward), no
                   normals, no UVs, no materials;
  OUT_PREFIX.json  the settings used (Blender's and ours), the conjugate
                   gradient's worst frame, and the fall of the cloth's mean
                   height, for the fit's report.

The grid's vertex order is Blender's from_pydata order, row i along -y, column
j along x: in neurocloth's frame (y up) row i runs along +z, so node i * N + j
is vertex i * N + j.

Units, read from Blender's source (blender/blender's 2.9-3.x files: .cc in
recent versions, .c or .cpp in older ones; file and function named) and
checked on 3.4.1 by the runs below:

* Time. clothModifier_do (blenkernel/intern/cloth.cc) sets
  sim_parms->timescale = (one frame, from BKE_ptcache_id_time) x time_scale;
  do_init_cloth sets sim_parms->dt = 1 / stepsPerFrame (the quality);
  SIM_cloth_solve (simulation/intern/SIM_mass_spring.cc) steps
  `while (step < tf)` with dt = sim_parms->dt x timescale: a frame advances the
  solver by time_scale units in QUALITY implicit-Euler substeps
  (SIM_mass_spring_solve_velocities, implicit_blender.cc: (M - dt dF/dv -
  dt^2 dF/dx) dv = dt (F + dt dF/dx v), then x += dt v_new).
* Gravity. cloth_calc_force (SIM_mass_spring.cc) takes the scene's gravity
  times 0.001 times the effector weights' gravity, as a force mass x g
  (SIM_mass_spring_force_gravity). So a unit of Blender's cloth time is
  tau = sqrt(0.001) s, and time_scale = 1 / (FPS tau) makes a frame 1/FPS s.
  Velocities are per unit (the cache stores them so; pinned vertices' are
  (xconst - xold) / time_scale).
* Mass. The vertex mass is in kg, every vertex alike (cloth_from_object:
  verts->mass = sim_parms->mass); only forces / mass matter, and a force of
  1 kg m / unit^2 is 1/tau^2 = 1000 N.
* Springs. cloth_calc_spring_force (SIM_mass_spring.cc): structural and shear
  springs get k = setting / avg_spring_len (the mean structural rest length,
  computed in cloth_build_springs), whatever their own length; damping is
  the setting as it is, along the spring on the relative velocity
  (SIM_mass_spring_force_spring_linear). So tension = compression = K tau^2 h
  and shear = K_shear tau^2 h give springs of K N/m, and damping = C tau gives
  C N s/m. Compression beyond the rest length follows Choi and Ko's buckling
  curve (fbstar: linear with the compression stiffness near the rest length,
  a plateau past ~1% shortening); shear springs pull only (new_compress is
  false for them and resist_compress is off under angular bending).
* Bending (angular model). k = bending x rest length x 0.1, the force at the
  hinge's faces per radian of fold (SIM_mass_spring_force_spring_angular);
  so bending = B tau^2 / (0.1 h) gives B N per radian. Its damping is
  bending_damping as it is, a force per m/unit of the faces' normal speed:
  bending_damping = D tau gives D N s/m. Neither enters the solver's
  Jacobians (the angular spring adds no dF/dx, dF/dv): both act explicitly.

Why the defaults do not fall. Blender's defaults (tension 15, damping 5,
bending 0.5, bending damping 0.5) assume its 0.3 kg vertex. On 0.2 kg/m^2 at
16 x 16 (0.28 g vertices) they are, in these units, springs of 375 kN/m and
158 N s/m and a hinge damping of 15.8 N s/m taken explicitly. Measured
(unpinned, quality 5, 30 fps, 0.6 s): the cloth crumples and its mean height
falls 0.20 m where free fall is 1.77 m; every substep's conjugate gradient
(cg_filtered, implicit_blender.cc) ends at its relative residual of 1%
(conjgrad_epsilon 0.01), 3 frames at its 100 iterations. The internal forces
sum to zero, so only that residual, 1% of forces far above the weight, can
slow the mean. Bending damping 0 alone brings the fall to 1.67 m (the stiff
springs still leave the solve 1% off); the 0.3 kg vertex with every other
default, or these units' 1 kN/m and 0.1 N s/m springs with bending damping 0,
fall 1.7854 m: implicit Euler's own discrete fall, 1/2 g dt^2 n (n + 1) at
n = 90 substeps of 1/150 s (1.1% beyond 1/2 g t^2; one conjugate gradient
iteration a substep). The time scale was right; the defaults were not. So the
bending damping here is 0 unless --bend-damping is given.

Quality. Blender's implicit Euler converges slowly in the substeps on this
swing (measured, 100 N/m and 0.05 N s/m springs, no bending, 1 s at 30 fps):
quality 5, 20, 40, 80 and 160 are 66, 23, 27, 14 and 4 mm (rms over nodes and
frames) from quality 320, and neurocloth's run of the same settings (1e-4 s
steps) is 68 mm from quality 5 and 7.4 mm from quality 320. A bake to fit
against is taken at --quality 320 (the same file twice, byte for byte).
"""
import json
import math
import sys

import bpy

TAU = math.sqrt(0.001)  # Blender cloth's time unit in seconds: gravity x 0.001
WIDTH = 0.6
HEIGHT = 1.0
G = 9.81


def parse(argv):
    args = argv[argv.index("--") + 1:] if "--" in argv else []
    if len(args) < 4:
        raise SystemExit("usage: ... -- N SECONDS FPS OUT_PREFIX [--mass-per-area KG] "
                         "[--quality Q] [--spring K --damping C] [--shear K] [--bend B] "
                         "[--bend-damping D] [--unpinned]")
    o = {"n": int(args[0]), "seconds": float(args[1]), "fps": float(args[2]), "out": args[3],
         "mass_per_area": 0.2, "quality": 5, "bend": 0.0, "bend_damping": 0.0,
         "unpinned": False}
    rest = args[4:]
    k = 0
    while k < len(rest):
        name = rest[k].lstrip("-").replace("-", "_")
        if name == "unpinned":
            o[name] = True
            k += 1
            continue
        o[name] = float(rest[k + 1])
        k += 2
    if "spring" in o and "damping" not in o:
        raise SystemExit("--spring needs --damping")
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
    scene.gravity = (0.0, 0.0, -G)

    h = WIDTH / (n - 1)
    verts = [(-WIDTH / 2 + j * h, WIDTH / 2 - i * h, HEIGHT) for i in range(n) for j in range(n)]
    faces = [(i * n + j, i * n + j + 1, (i + 1) * n + j + 1, (i + 1) * n + j)
             for i in range(n - 1) for j in range(n - 1)]
    mesh = bpy.data.meshes.new("cloth")
    mesh.from_pydata(verts, [], faces)
    mesh.update()
    ob = bpy.data.objects.new("cloth", mesh)
    scene.collection.objects.link(ob)

    mod = ob.modifiers.new("cloth", "CLOTH")
    s = mod.settings
    if not o["unpinned"]:
        pin = ob.vertex_groups.new(name="pin")
        pin.add([0, n - 1], 1.0, "REPLACE")
        s.vertex_group_mass = "pin"
    s.quality = int(o["quality"])
    s.mass = o["mass_per_area"] * WIDTH * WIDTH / (n * n)
    s.time_scale = 1.0 / (o["fps"] * TAU)
    s.air_damping = 0.0
    s.bending_model = "ANGULAR"
    if "spring" in o:
        tension = o["spring"] * TAU * TAU * h
        s.tension_stiffness = s.compression_stiffness = tension
        s.shear_stiffness = o.get("shear", o["spring"]) * TAU * TAU * h
        s.tension_damping = s.compression_damping = s.shear_damping = o["damping"] * TAU
        s.bending_stiffness = o["bend"] * TAU * TAU / (0.1 * h)
        s.bending_damping = o["bend_damping"] * TAU
    mod.collision_settings.use_collision = False
    mod.collision_settings.use_self_collision = False
    mod.point_cache.frame_start = 1
    mod.point_cache.frame_end = scene.frame_end

    drop = []
    worst = {"max_iterations": 0, "max_error": 0.0, "no_convergence_frames": 0}
    for f in range(1, scene.frame_end + 1):
        scene.frame_set(f)
        evaluated = ob.evaluated_get(bpy.context.evaluated_depsgraph_get())
        z = [v.co.z for v in evaluated.data.vertices]
        drop.append(HEIGHT - sum(z) / len(z))
        r = evaluated.modifiers["cloth"].solver_result
        if f > 1 and r is not None:
            worst["max_iterations"] = max(worst["max_iterations"], r.max_iterations)
            worst["max_error"] = max(worst["max_error"], r.max_error)
            if "NO_CONVERGENCE" in r.status:
                worst["no_convergence_frames"] += 1
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
    # The same settings in neurocloth's units (the docstring's mapping).
    ours = {"node_mass": s.mass,
            "spring_constant": s.tension_stiffness / (TAU * TAU * h),
            "shear_constant": s.shear_stiffness / (TAU * TAU * h),
            "viscosity": s.tension_damping / TAU,
            "bend_n_per_rad": s.bending_stiffness * 0.1 * h / (TAU * TAU),
            "bend_damping": s.bending_damping / TAU,
            "substep_s": 1.0 / (o["fps"] * s.quality)}
    steps = frames * s.quality
    dt = 1.0 / (o["fps"] * s.quality)
    fall = {"seconds": frames / o["fps"], "mean_drop_m": drop[-1]}
    if o["unpinned"]:  # free fall: 1/2 g t^2, and implicit Euler's discrete one
        fall["half_g_t2_m"] = 0.5 * G * (frames / o["fps"]) ** 2
        fall["implicit_euler_m"] = 0.5 * G * dt * dt * steps * (steps + 1)
    info = {"n": n, "seconds": o["seconds"], "fps": o["fps"], "frames": frames + 1,
            "spacing": h, "mass_per_area": o["mass_per_area"], "pinned": not o["unpinned"],
            "blender": bpy.app.version_string, "settings": settings, "ours": ours,
            "solver": worst, "fall": fall}
    with open(o["out"] + ".json", "w") as f:
        json.dump(info, f, indent=1)
    free = (" (1/2 g t^2 %.4f m, implicit Euler %.4f m)"
            % (fall["half_g_t2_m"], fall["implicit_euler_m"]) if o["unpinned"] else "")
    print("bake: mean height fell %.4f m in %.3f s%s; conjugate gradient at most %d iterations, "
          "%d frames not converged" % (drop[-1], fall["seconds"], free, worst["max_iterations"],
                                       worst["no_convergence_frames"]))


main()
