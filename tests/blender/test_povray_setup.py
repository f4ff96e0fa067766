""""Set Up POV-Ray Material": material.pov finish, use_nodes off, lights calibrated so that
POV-Ray's falloff and colour match Cycles' and BxDF Lab's light."""

import math

import addon_utils
import bpy
import numpy as np
import pytest

from bxdf_lab import api, povray_setup


@pytest.fixture(autouse=True)
def povray_addon():
    assert addon_utils.enable("render_povray", default_set=True) is not None
    yield


def _set_up(material):
    with bpy.context.temp_override(material=material):
        assert bpy.ops.bxdf_lab.set_up_povray() == {"FINISHED"}


def _light(kind, energy, color):
    light = bpy.data.lights.new(kind.lower(), kind)
    light.energy, light.color = energy, color
    obj = bpy.data.objects.new(kind.lower(), light)
    bpy.context.scene.collection.objects.link(obj)
    return obj


def test_lambertian_finish_and_use_nodes_off(material):
    api.assign(material, "lambertian", reflectance=(0.2, 0.4, 0.6))
    material.use_nodes = True
    _set_up(material)
    assert material.use_nodes is False
    assert tuple(material.diffuse_color) == pytest.approx((0.2, 0.4, 0.6, 1.0))
    pov = material.pov
    assert (pov.ambient, pov.diffuse_intensity, pov.diffuse_shader, pov.specular_intensity) == \
        (0.0, 1.0, "LAMBERT", 0.0)
    assert material.bxdf_lab.pov_label == "exact"
    assert bpy.context.scene.pov.radio_enable is False


def _as_povray_reads(light):
    """(linear colour, fade distance D) as render_povray writes them: colour srgb "%.3g",
    fade_distance "%.6f" of √(distance/2)."""
    color = np.array([povray_setup.srgb_decode(float(f"{c:.3g}")) for c in light.color])
    return color, float(f"{math.sqrt(light.distance / 2.0):.6f}")


@pytest.mark.parametrize("energy", [1.0, 75.0, 1000.0])
def test_point_light_is_calibrated_to_the_inverse_square_intensity(material, energy):
    api.assign(material, "lambertian")
    light = _light("POINT", energy, (1.0, 1.0, 1.0)).data
    _set_up(material)
    assert light.falloff_type == "INVERSE_SQUARE"
    color, fade = _as_povray_reads(light)
    intensity = energy / (4 * math.pi)  # W/sr, what Cycles and BxDF Lab use
    np.testing.assert_allclose(color * 2 * fade ** 2, intensity / math.pi, rtol=2e-4)
    np.testing.assert_allclose(np.array(light.color) * light.energy, energy, rtol=1e-6)
    assert fade < 0.05  # 2/(1 + (d/D)²) is inverse-square to (D/d)² at scene distances


def test_povray_renders_the_lambertian_set_up_like_the_model(material, bxdf, tmp_path):
    """A plane under a sun at 40°, seen from above: POV gives R·C·cos θ with C = E/π."""
    api.assign(material, "lambertian", reflectance=(0.7, 0.5, 0.3))
    scene = bpy.context.scene
    mesh = bpy.data.meshes.new("plane")
    mesh.from_pydata([(-10, -10, 0), (10, -10, 0), (10, 10, 0), (-10, 10, 0)], [], [(0, 1, 2, 3)])
    mesh.materials.append(material)
    scene.collection.objects.link(bpy.data.objects.new("plane", mesh))
    sun = _light("SUN", math.pi, (1.0, 1.0, 1.0))
    sun.rotation_euler = (math.radians(40.0), 0, 0)
    cam = bpy.data.objects.new("cam", bpy.data.cameras.new("cam"))
    cam.location = (0, 0, 5)
    scene.collection.objects.link(cam)
    scene.camera = cam
    _set_up(material)
    r = scene.render
    r.engine = "POVRAY_RENDER"
    r.resolution_x = r.resolution_y = 8
    r.resolution_percentage = 100
    r.filepath = str(tmp_path / "pov.exr")
    r.image_settings.file_format, r.image_settings.color_depth = "OPEN_EXR", "32"
    # 16-bit sRGB PNG: render_povray loads it as sRGB into the (linear) render result; a linear
    # PNG (File_Gamma=1.0) would be decoded twice.
    scene.pov.command_line_switches = "+FN16"
    scene.world = None
    bpy.ops.render.render(write_still=True)
    image = bpy.data.images.load(r.filepath)
    pixels = np.empty(8 * 8 * 4, dtype=np.float32)
    image.pixels.foreach_get(pixels)
    pixels = pixels.reshape(-1, 4)[:, :3]
    wi = [0.0, -math.sin(math.radians(40)), math.cos(math.radians(40))]
    expected = np.asarray(bxdf.make("lambertian", reflectance=(0.7, 0.5, 0.3)).f([0, 0, 1], wi))[0] \
        * math.pi * wi[2]
    np.testing.assert_allclose(pixels, np.broadcast_to(expected, pixels.shape), rtol=5e-3, atol=2e-4)
