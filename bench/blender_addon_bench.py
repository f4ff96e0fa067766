"""Timings of the Blender add-on, inside Blender:

    BXDF_BUILD=build blender -b --factory-startup --python bench/blender_addon_bench.py

- export of a 1-million-triangle mesh (depsgraph → numpy arrays; goal < 1 s)
- bake of a 256² polar lobe texture into a Blender image (goal < 50 ms)
Prints one line per measurement: name, median seconds over the runs, goal.
"""

import os
import statistics
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(os.path.dirname(HERE), "blender_addon"))
if os.environ.get("BXDF_BUILD"):
    sys.path.insert(0, os.path.join(os.path.abspath(os.environ["BXDF_BUILD"]), "python"))

import addon_utils  # noqa: E402
import bpy  # noqa: E402

assert addon_utils.enable("bxdf_lab", default_set=True, handle_error=None) is not None
from bxdf_lab import api, bake, export  # noqa: E402


def median_time(fn, runs):
    """(median wall time, best wall time, median CPU time of this process); the CPU time is
    what the code costs when other processes share the cores."""
    wall, cpu = [], []
    for _ in range(runs):
        start, start_cpu = time.perf_counter(), time.process_time()
        fn()
        wall.append(time.perf_counter() - start)
        cpu.append(time.process_time() - start_cpu)
    return statistics.median(wall), min(wall), statistics.median(cpu)


def report(name, seconds, goal):
    median, best, cpu = seconds
    verdict = "ok" if median < goal else "SLOWER THAN GOAL"
    print(f"bench {name}: median {median * 1e3:.1f} ms (best {best * 1e3:.1f} ms, CPU {cpu * 1e3:.1f} ms), "
          f"goal < {goal * 1e3:.0f} ms: {verdict} (load average {os.getloadavg()[0]:.1f})")


bpy.ops.wm.read_homefile(use_empty=True)
material = bpy.data.materials.new("bench")
api.assign(material, "lambertian", reflectance=(0.5, 0.5, 0.5))

# 708 × 708 vertices → 707² quads → 999,698 triangles, smooth-shaded with a UV map.
bpy.ops.mesh.primitive_grid_add(x_subdivisions=707, y_subdivisions=707, size=10.0,
                                calc_uvs=True)
grid = bpy.context.object
grid.data.materials.append(material)
grid.data.polygons.foreach_set("use_smooth", [True] * len(grid.data.polygons))
depsgraph = bpy.context.evaluated_depsgraph_get()
data = export.export_scene(depsgraph)
n_triangles = sum(len(m["triangles"]) for m in data["meshes"])
print(f"bench mesh: {n_triangles} triangles, {len(grid.data.vertices)} vertices")
report("export_1M_triangles", median_time(lambda: export.export_scene(depsgraph), 5), 1.0)

model = api.make(material)
report("bake_lobe_polar_256", median_time(lambda: bake.to_image("bench lobe", bake.lobe_polar(model, 45.0, 256)), 20), 0.05)
report("bake_slice_256", median_time(lambda: bake.to_image("bench slice", bake.slice_half_diff(model, 256)), 20), 0.05)
