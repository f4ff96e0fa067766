"""F12 with BXDF_LAB: the image Blender writes is the renderer's (bxdf.render called directly),
matches Cycles where the materials are exact, and a cancelled render writes no file."""

import math
import os

import bpy
import numpy as np
import pytest

from bxdf_lab import api, engine, export

SIZE = 16
# bxdf.render's settings for what _scene sets on the Render tab.
DIRECT = {"samples": 4, "max_bounces": 0, "pixel_filter": "pixel_center", "seed": 7}


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
    width, height = image.size
    pixels = np.empty(width * height * 4, dtype=np.float32)
    image.pixels.foreach_get(pixels)
    return pixels.reshape(height, width, 4)  # rows bottom-up


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
                         DIRECT,
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


@pytest.mark.parametrize("crop", [True, False], ids=["cropped", "in-frame"])
def test_a_render_region_renders_only_its_pixels_as_cycles_does(crop, material, bxdf_render, tmp_path):
    # Render Region (Ctrl+B): BXDF_LAB renders only those pixels, and Blender writes them as it
    # writes Cycles' (cropped, or in place in an empty frame). With a render region Blender's
    # result holds only the region: the whole image handed back failed the render.
    api.assign(material, "lambertian", reflectance=(0.7, 0.5, 0.3))
    with bpy.context.temp_override(material=material):
        assert bpy.ops.bxdf_lab.set_up_cycles() == {"FINISHED"}
    scene = _scene(material, tmp_path)
    bpy.data.objects.remove(bpy.data.objects["sun"])
    lamp = bpy.data.lights.new("lamp", "POINT")  # every pixel differs: a misplaced region shows
    lamp.energy, lamp.shadow_soft_size = 300.0, 0.0
    lamp_obj = bpy.data.objects.new("lamp", lamp)
    lamp_obj.location = (3.0, 1.5, 2.0)
    scene.collection.objects.link(lamp_obj)
    r = scene.render
    r.use_border, r.use_crop_to_border = True, crop
    r.border_min_x, r.border_max_x, r.border_min_y, r.border_max_y = 0.3, 0.8, 0.55, 0.95
    ours = _render(scene, "BXDF_LAB", str(tmp_path / "bxdf_lab.exr"))
    assert engine.last_error == ""
    cycles = _render(scene, "CYCLES", str(tmp_path / "cycles.exr"))
    # Columns 4..11 and rows 8..14 from the bottom (Blender truncates 0.3·16 = 4.8 to 4, ...).
    columns, rows = slice(4, 12), slice(8, 15)
    assert ours.shape == ((7, 8, 4) if crop else (SIZE, SIZE, 4)) == cycles.shape
    np.testing.assert_allclose(ours[..., :3], cycles[..., :3], rtol=5e-3, atol=1e-4)
    r.use_border = False
    whole = bxdf_render(export.export_scene(bpy.context.evaluated_depsgraph_get()),
                        DIRECT,
                        bottom_up=True)
    region = ours if crop else ours[rows, columns]
    np.testing.assert_allclose(region, whole[rows, columns], rtol=1e-6, atol=1e-7)
    assert region[..., :3].max() > 0.05 and not np.allclose(region[0], region[-1])
    if not crop:
        outside = np.ones((SIZE, SIZE), dtype=bool)
        outside[rows, columns] = False
        assert not ours[outside].any()


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
