"""F12 with BXDF_LAB: the image Blender writes is the renderer's (bxdf.render called directly),
matches Cycles where the materials are exact, and a cancelled render writes no file."""

import math
import os

import bpy
import numpy as np
import pytest

from bxdf_lab import api, engine, export

SIZE = 16


def _scene(material, tmp_path):
    """A large plane under a sun at 40°, seen from above by a perspective camera."""
    scene = bpy.context.scene
    mesh = bpy.data.meshes.new("plane")
    mesh.from_pydata([(-10, -10, 0), (10, -10, 0), (10, 10, 0), (-10, 10, 0)], [], [(0, 1, 2, 3)])
    mesh.materials.append(material)
    scene.collection.objects.link(bpy.data.objects.new("plane", mesh))
    sun = bpy.data.lights.new("sun", "SUN")
    sun.energy, sun.angle = math.pi, 0.0
    sun_obj = bpy.data.objects.new("sun", sun)
    sun_obj.rotation_euler = (math.radians(40.0), 0, 0)
    scene.collection.objects.link(sun_obj)
    cam = bpy.data.objects.new("cam", bpy.data.cameras.new("cam"))
    cam.location = (0, 0, 4)
    scene.collection.objects.link(cam)
    scene.camera = cam
    r = scene.render
    r.resolution_x = r.resolution_y = SIZE
    r.resolution_percentage = 100
    r.image_settings.file_format, r.image_settings.color_depth = "OPEN_EXR", "32"
    settings = scene.bxdf_lab_render
    settings.samples, settings.max_bounces, settings.pixel_filter, settings.seed = 4, 0, "PIXEL_CENTER", 7
    c = scene.cycles
    c.samples, c.max_bounces, c.use_denoising, c.use_adaptive_sampling = 4, 0, False, False
    c.sample_clamp_direct = c.sample_clamp_indirect = 0.0
    c.pixel_filter_type, c.filter_width = "GAUSSIAN", 0.01  # pixel centres, as PIXEL_CENTER
    return scene


def _render(scene, engine_id, path):
    scene.render.engine = engine_id
    scene.render.filepath = path
    bpy.ops.render.render(write_still=True)
    image = bpy.data.images.load(path)
    pixels = np.empty(SIZE * SIZE * 4, dtype=np.float32)
    image.pixels.foreach_get(pixels)
    return pixels.reshape(SIZE, SIZE, 4)


@pytest.fixture
def bxdf_render(bxdf):
    assert hasattr(bxdf, "render"), "this bxdf build has no renderer binding"
    return bxdf.render


def test_f12_writes_the_image_of_the_renderer_called_directly(material, bxdf_render, tmp_path):
    api.assign(material, "lambertian", reflectance=(0.7, 0.5, 0.3))
    scene = _scene(material, tmp_path)
    written = _render(scene, "BXDF_LAB", str(tmp_path / "f12.exr"))
    assert engine.last_error == ""
    direct = bxdf_render(export.export_scene(bpy.context.evaluated_depsgraph_get()),
                         {"samples": 4, "max_bounces": 0, "pixel_filter": "pixel_center", "seed": 7},
                         bottom_up=True)
    np.testing.assert_allclose(written, direct, rtol=1e-6, atol=1e-7)
    # and it is the Lambertian's radiance R·E·cos θ/π with E = π
    expected = np.array([0.7, 0.5, 0.3]) * math.cos(math.radians(40.0))
    np.testing.assert_allclose(written[..., :3].reshape(-1, 3), np.broadcast_to(expected, (SIZE * SIZE, 3)),
                               rtol=2e-3)


@pytest.mark.parametrize("model_name, params", [
    ("lambertian", {"reflectance": (0.7, 0.5, 0.3)}),
    ("cycles_oren_nayar", {"color": (0.7, 0.5, 0.3), "roughness": 0.8}),
    ("cycles_glossy", {"color": (0.7, 0.5, 0.3), "roughness": 0.5, "distribution": "ggx"}),
])
def test_exact_cycles_set_up_renders_like_bxdf_lab(model_name, params, material, bxdf_render, tmp_path):
    api.assign(material, model_name, **params)
    with bpy.context.temp_override(material=material):
        assert bpy.ops.bxdf_lab.set_up_cycles() == {"FINISHED"}
    assert material.bxdf_lab.cycles_label == "exact"
    scene = _scene(material, tmp_path)
    ours = _render(scene, "BXDF_LAB", str(tmp_path / "bxdf_lab.exr"))
    cycles = _render(scene, "CYCLES", str(tmp_path / "cycles.exr"))
    assert ours[..., :3].max() > 0.05
    # delta sun, direct light only, pixel centres: both are noise-free
    np.testing.assert_allclose(ours[..., :3], cycles[..., :3], rtol=5e-3, atol=1e-4)


def test_a_cancelled_render_writes_no_file(material, bxdf_render, tmp_path, monkeypatch):
    api.assign(material, "lambertian")
    scene = _scene(material, tmp_path)
    scene.bxdf_lab_render.samples = 64
    # Headless Blender has no Esc key: the user "presses" it at the first progress report.
    calls = []

    def press_escape(_render_engine):  # keep no reference: Blender frees the engine
        calls.append(True)
        return True

    monkeypatch.setattr(engine, "cancel_requested", press_escape)
    path = str(tmp_path / "cancelled.exr")
    scene.render.engine = "BXDF_LAB"
    scene.render.filepath = path
    with pytest.raises(RuntimeError, match="cancelled"):  # scripts learn it did not finish
        bpy.ops.render.render(write_still=True)
    assert calls, "the engine never asked whether to stop"
    assert engine.last_cancelled and engine.last_error == ""
    assert not os.path.exists(path)
