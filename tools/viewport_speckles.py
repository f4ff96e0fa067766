"""The README's Rendered-viewport scene (tests/blender/windowed_session.py's showcase: a GGX gold
sphere beside the cube on an Oren–Nayar floor, a 10 cm point light) seen from the default 3D view,
rendered with BxDF Lab and with Cycles at equal samples and bounces, Cycles both without and with
its defaults that tame caustics (Filter Glossy 1.0, Clamp Indirect 10). Counts speckles (pixels
brighter than 1.5× their 5×5 median + 0.02) and writes a figure of the renders around the sphere.

    blender -b --factory-startup --python tools/viewport_speckles.py -- OUT_DIR [BUILD_PYTHON_DIR]
"""

import os
import sys

import bpy
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
args = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
out = os.path.abspath(args[0] if args else "speckles")
sys.path[:0] = [os.path.abspath(args[1] if len(args) > 1 else os.path.join(ROOT, "build", "python")),
                os.path.join(ROOT, "blender_addon")]
os.makedirs(out, exist_ok=True)

import addon_utils  # noqa: E402

addon_utils.enable("bxdf_lab", default_set=True, handle_error=None)
from bxdf_lab import api, compare  # noqa: E402

SAMPLES, BOUNCES = 64, 4  # the viewport's samples in the README picture and its bounce limit

scene = bpy.context.scene
bpy.ops.mesh.primitive_uv_sphere_add(radius=1.0, location=(2.6, 0.0, 0.0), segments=64, ring_count=32)
bpy.ops.object.shade_smooth()
gold = bpy.data.materials.new("Gold")
api.assign_preset(gold, "gold")
bpy.context.object.data.materials.append(gold)
bpy.ops.mesh.primitive_plane_add(size=20.0, location=(0.0, 0.0, -1.0))
floor = bpy.data.materials.new("Floor")
api.assign(floor, "oren_nayar", reflectance=(0.5, 0.5, 0.5), sigma=20.0)
bpy.context.object.data.materials.append(floor)
bpy.data.objects["Light"].data.energy = 1500.0
scene.world.node_tree.nodes["Background"].inputs["Color"].default_value = (0.25, 0.27, 0.3, 1.0)
for material in (gold, floor):
    with bpy.context.temp_override(material=material):
        bpy.ops.bxdf_lab.set_up_cycles()

# The default 3D view as the camera (a free view is a 72 mm sensor at the view's lens).
space = next(a.spaces.active for a in bpy.data.screens["Layout"].areas if a.type == "VIEW_3D")
camera = bpy.data.objects["Camera"]
camera.matrix_world = space.region_3d.view_matrix.inverted()
camera.data.lens, camera.data.sensor_width, camera.data.sensor_fit = space.lens, 72.0, "AUTO"
scene.render.resolution_x, scene.render.resolution_y, scene.render.resolution_percentage = 793, 463, 100
scene.view_settings.view_transform = "Standard"
scene.render.image_settings.file_format, scene.render.image_settings.color_depth = "OPEN_EXR", "32"


def render(engine, name, **cycles):
    scene.render.engine = engine
    scene.render.filepath = os.path.join(out, f"{name}.exr")
    for material in (gold, floor):
        material.use_nodes = engine == "CYCLES"
    scene.bxdf_lab_render.samples, scene.bxdf_lab_render.max_bounces = SAMPLES, BOUNCES
    c = scene.cycles
    c.samples, c.max_bounces, c.use_denoising, c.use_adaptive_sampling = SAMPLES, BOUNCES, False, False
    for key, value in cycles.items():
        setattr(c, key, value)
    bpy.ops.render.render(write_still=True)
    return compare.load_exr(scene.render.filepath)


def speckles(image):
    from numpy.lib.stride_tricks import sliding_window_view
    y = image[..., :3].mean(axis=2)
    median = np.median(sliding_window_view(np.pad(y, 2, mode="edge"), (5, 5)), axis=(2, 3))
    return int((y > 1.5 * median + 0.02).sum())


images = {
    "BxDF Lab": render("BXDF_LAB", "bxdf_lab"),
    "Cycles, no clamp, Filter Glossy 0": render("CYCLES", "cycles_fair", sample_clamp_direct=0.0,
                                                sample_clamp_indirect=0.0, blur_glossy=0.0),
    "Cycles defaults (Filter Glossy 1, Clamp Indirect 10)": render(
        "CYCLES", "cycles_defaults", sample_clamp_direct=0.0, sample_clamp_indirect=10.0, blur_glossy=1.0),
    "Cycles, Filter Glossy 1 only": render("CYCLES", "cycles_filter_glossy", sample_clamp_direct=0.0,
                                           sample_clamp_indirect=0.0, blur_glossy=1.0),
    "Cycles, Clamp Indirect 10 only": render("CYCLES", "cycles_clamp", sample_clamp_direct=0.0,
                                             sample_clamp_indirect=10.0, blur_glossy=0.0),
}
AROUND_SPHERE = (slice(150, 420), slice(250, 650))  # rows, columns of the 793×463 image
import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

scale = compare.display_scale(images)
figure, axes = plt.subplots(1, len(images), figsize=(4 * len(images), 3.2))
for ax, (name, image) in zip(axes, images.items()):
    count = speckles(image)
    print(f"{name}: {count} speckles, mean RGB {np.round(image[..., :3].mean(axis=(0, 1)), 4).tolist()}")
    ax.imshow(compare._display(image[AROUND_SPHERE], scale))
    ax.set_title(f"{name}\n{count} speckles", fontsize=9)
    ax.axis("off")
figure.tight_layout(rect=(0, 0, 1, 0.9))
figure.savefig(os.path.join(out, "speckles.png"), dpi=110)
