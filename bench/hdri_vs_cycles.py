"""make bench: an HDRI-lit scene, BXDF_LAB's time to equal error against Cycles'.

Run inside Blender (tools/run-bench.sh does it):
    blender -b --factory-startup --python bench/hdri_vs_cycles.py
A 3×3 grid of white diffuse spheres on a grey floor under Blender's city.exr (rotated by a
Mapping node), direct and one indirect bounce. A Cycles render at REFERENCE_SPP samples is the
reference; then each engine renders at SPP samples, 2 threads each, in the same run, and the
figure of merit is MSE × wall-clock time (lower is better): the ratio BXDF_LAB / Cycles is the
time BXDF_LAB needs to reach Cycles' error, as a fraction of Cycles' time. Wall-clock times
include each engine's scene set-up (Cycles builds its world importance map then) and are noisy
while other work shares the machine.
"""

import math
import os
import sys
import tempfile
import time

import bpy
import numpy as np
from mathutils import Vector

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "blender_addon"))
import addon_utils  # noqa: E402

HDRI = "/usr/share/blender/datafiles/studiolights/world/city.exr"
SIZE = 96
REFERENCE_SPP = 1024
SPP = (16, 64)


def build():
    bpy.ops.wm.read_homefile(use_empty=True)
    from bxdf_lab import api
    scene = bpy.context.scene
    white = bpy.data.materials.new("white")
    api.assign(white, "lambertian", reflectance=(0.8, 0.8, 0.8))
    floor = bpy.data.materials.new("floor")
    api.assign(floor, "lambertian", reflectance=(0.4, 0.4, 0.4))
    for material in (white, floor):
        with bpy.context.temp_override(material=material):
            bpy.ops.bxdf_lab.set_up_cycles()
    for x in (-1.2, 0.0, 1.2):
        for y in (-1.2, 0.0, 1.2):
            bpy.ops.mesh.primitive_uv_sphere_add(segments=48, ring_count=24, radius=0.45, location=(x, y, 0.45))
            bpy.ops.object.shade_smooth()
            bpy.context.active_object.data.materials.append(white)
    bpy.ops.mesh.primitive_plane_add(size=30)
    bpy.context.active_object.data.materials.append(floor)
    cam = bpy.data.objects.new("cam", bpy.data.cameras.new("cam"))
    cam.location = (0, -6, 4)
    cam.rotation_euler = (Vector((0, 0, 0.3)) - cam.location).to_track_quat("-Z", "Y").to_euler()
    scene.collection.objects.link(cam)
    scene.camera = cam
    world = bpy.data.worlds.new("world")
    world.use_nodes = True
    nodes, links = world.node_tree.nodes, world.node_tree.links
    coords, mapping, env = (nodes.new("ShaderNodeTexCoord"), nodes.new("ShaderNodeMapping"),
                            nodes.new("ShaderNodeTexEnvironment"))
    mapping.inputs["Rotation"].default_value = (0, 0, math.radians(60))
    env.image = bpy.data.images.load(HDRI)
    links.new(coords.outputs["Generated"], mapping.inputs["Vector"])
    links.new(mapping.outputs["Vector"], env.inputs["Vector"])
    links.new(env.outputs["Color"], nodes["Background"].inputs["Color"])
    scene.world = world
    r = scene.render
    r.resolution_x = r.resolution_y = SIZE
    r.resolution_percentage = 100
    r.threads_mode, r.threads = "FIXED", 2
    r.image_settings.file_format, r.image_settings.color_depth = "OPEN_EXR", "32"
    scene.view_settings.view_transform = "Standard"
    c = scene.cycles
    c.use_denoising = c.use_adaptive_sampling = False
    c.max_bounces = c.diffuse_bounces = 1
    c.sample_clamp_direct = c.sample_clamp_indirect = 0.0
    c.pixel_filter_type, c.filter_width = "GAUSSIAN", 1.5
    b = scene.bxdf_lab_render
    b.max_bounces, b.threads, b.pixel_filter, b.filter_width = 1, 2, "GAUSSIAN", 1.5
    return scene


def render(scene, engine, spp, path):
    scene.render.engine = engine
    scene.cycles.samples = scene.bxdf_lab_render.samples = spp
    scene.render.filepath = path
    started = time.perf_counter()
    bpy.ops.render.render(write_still=True)
    seconds = time.perf_counter() - started
    image = bpy.data.images.load(path)
    pixels = np.empty(SIZE * SIZE * 4, dtype=np.float32)
    image.pixels.foreach_get(pixels)
    bpy.data.images.remove(image)
    return pixels.reshape(SIZE, SIZE, 4)[..., :3], seconds


def main():
    addon_utils.enable("bxdf_lab", default_set=True)
    scene = build()
    folder = tempfile.mkdtemp(prefix="bxdf_bench_hdri_")
    scene.cycles.seed = 12345  # independent of the measured renders (seed 0), or they share samples
    reference, ref_seconds = render(scene, "CYCLES", REFERENCE_SPP, os.path.join(folder, "reference.exr"))
    scene.cycles.seed = 0
    print(f"\nHDRI scene {SIZE}x{SIZE}, reference: Cycles {REFERENCE_SPP} spp in {ref_seconds:.1f} s")
    print(f"{'spp':>5s} {'engine':>9s} {'seconds':>8s} {'MSE':>10s} {'MSE x s':>10s}")
    worst = 0.0
    for spp in SPP:
        merit = {}
        for engine in ("BXDF_LAB", "CYCLES"):
            image, seconds = render(scene, engine, spp, os.path.join(folder, f"{engine}_{spp}.exr"))
            mse = float(np.mean((image - reference) ** 2))
            merit[engine] = mse * seconds
            print(f"{spp:5d} {engine:>9s} {seconds:8.2f} {mse:10.3e} {merit[engine]:10.3e}")
        ratio = merit["BXDF_LAB"] / merit["CYCLES"]
        worst = max(worst, ratio)
        print(f"{spp:5d} time to equal error, BXDF_LAB / Cycles: {ratio:.2f}x (goal <= 1.0x)")
    print(f"worst ratio {worst:.2f}x: {'PASS' if worst <= 1.0 else 'FAIL'}")


main()
