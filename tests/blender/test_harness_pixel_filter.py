"""The comparison harness gives BXDF_LAB and Cycles the same pixel filter (compare/engine_setup.py).

Cycles' narrowest filter, Gaussian of width 0.01, still spreads camera rays by σ = 0.0025 px about
the pixel centre, so an edge that passes within a few thousandths of a pixel of a row of pixel
centres is partly covered in Cycles. BXDF_LAB's PIXEL_CENTER covers it all or not at all: at
96 × 96, area_light_room had one such pixel at z = 23 (issue #12). Here a lit plane ends
0.002 px beyond a row of pixel centres; the fraction of that row Cycles sees lit must be
BXDF_LAB's too."""

import math
import os
import sys

import bpy
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
if ROOT not in sys.path:
    sys.path.insert(0, ROOT)  # the harness package `compare` lives at the repository root

import pairing_scene  # noqa: E402
from bxdf_lab import engine  # noqa: E402
from compare import engine_setup  # noqa: E402
from compare.scene_spec import Camera, SceneSpec  # noqa: E402

SIZE = 8            # pixels; the orthographic camera sees one scene unit per pixel
EDGE_ROW = 3        # the image row (from the top) whose pixel centres the plane's edge passes by
EDGE_OFFSET = 0.002  # px beyond the row's centres: Cycles' rays land on the plane Φ(0.8) ≈ 79%
SAMPLES = 256


def _edge_scene():
    scene = bpy.context.scene
    material = pairing_scene.lambertian_material("white", 1.0)
    # Row r's centres are at y = SIZE/2 - (r + 0.5) (image rows run down, +y up the image).
    edge_y = SIZE / 2 - (EDGE_ROW + 0.5) + EDGE_OFFSET
    mesh = bpy.data.meshes.new("plane")
    mesh.from_pydata([(-20, -20, 0), (20, -20, 0), (20, edge_y, 0), (-20, edge_y, 0)], [],
                     [(0, 1, 2, 3)])
    mesh.materials.append(material)
    scene.collection.objects.link(bpy.data.objects.new("plane", mesh))
    sun = bpy.data.lights.new("sun", "SUN")
    sun.energy, sun.angle = math.pi, 0.0   # radiance 1 off a white Lambertian facing it
    scene.collection.objects.link(bpy.data.objects.new("sun", sun))
    # Looking down -z: image x = +x, image up = +y.
    pairing_scene.add_camera(scene, (0.0, 0.0, 10.0), ortho_scale=SIZE)
    pairing_scene.uniform_world(scene)
    scene.render.resolution_x = scene.render.resolution_y = SIZE
    scene.render.resolution_percentage = 100
    spec = SceneSpec(name="edge", description="a lit plane ending by a row of pixel centres",
                     camera=Camera((0.0, 0.0, 10.0), (0.0, 0.0, 0.0)), objects=(), lights=(),
                     max_bounces=0, spp=SAMPLES, resolution=(SIZE, SIZE))
    engine_setup.common_settings(spec)
    return scene, spec


def _render(scene, path):
    scene.render.filepath = str(path)
    bpy.ops.render.render(write_still=True)
    image = bpy.data.images.load(str(path))
    pixels = np.empty(SIZE * SIZE * 4, dtype=np.float32)
    image.pixels.foreach_get(pixels)
    bpy.data.images.remove(image)
    return pixels.reshape(SIZE, SIZE, 4)[::-1, :, 0]   # Blender's rows run up: flip to top-down


def test_harness_filters_put_an_edge_by_the_pixel_centres_in_the_same_place(tmp_path):
    scene, spec = _edge_scene()
    engine_setup.configure_cycles(spec, SAMPLES, seed=1, threads=1)
    cycles = _render(scene, tmp_path / "cycles.exr")
    engine_setup.configure_bxdf_lab(spec, SAMPLES, seed=1, threads=1)
    ours = _render(scene, tmp_path / "bxdf_lab.exr")
    assert engine.last_error == ""
    for image in (cycles, ours):   # the plane where it should be: lit below the row, dark above
        np.testing.assert_allclose(image[EDGE_ROW + 1:], 1.0, rtol=2e-3)
        np.testing.assert_array_equal(image[:EDGE_ROW], 0.0)
    lit_cycles, lit_ours = cycles[EDGE_ROW].mean(), ours[EDGE_ROW].mean()
    # Cycles' Gaussian filter table puts ~79% of the row's rays on the plane; the sampling noise of
    # 8 × 256 rays is below 0.01. PIXEL_CENTER gave 1.0 here.
    assert 0.6 < lit_cycles < 0.95, lit_cycles
    assert abs(lit_ours - lit_cycles) < 0.05, (lit_ours, lit_cycles)
