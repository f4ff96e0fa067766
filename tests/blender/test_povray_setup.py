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


def _povray_render(scene, tmp_path):
    """Renders `scene` 8×8 with POV-Ray; returns the linear RGB pixels, one row each."""
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
    return pixels.reshape(-1, 4)[:, :3]


def _plane(name, z, material):
    mesh = bpy.data.meshes.new(name)
    mesh.from_pydata([(-10, -10, z), (10, -10, z), (10, 10, z), (-10, 10, z)], [], [(0, 1, 2, 3)])
    mesh.materials.append(material)
    bpy.context.scene.collection.objects.link(bpy.data.objects.new(name, mesh))


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
    pixels = _povray_render(scene, tmp_path)
    wi = [0.0, -math.sin(math.radians(40)), math.cos(math.radians(40))]
    expected = np.asarray(bxdf.make("lambertian", reflectance=(0.7, 0.5, 0.3)).f([0, 0, 1], wi))[0] \
        * math.pi * wi[2]
    np.testing.assert_allclose(pixels, np.broadcast_to(expected, pixels.shape), rtol=5e-3, atol=2e-4)


@pytest.mark.parametrize("name, params, transparent, ior, back, mirror", [
    ("cycles_glass", {"color": (0.9, 0.8, 0.7), "ior": 1.6}, True, 1.6, 0.0, True),
    ("cycles_refraction", {"color": (0.9, 0.8, 0.7), "ior": 1.3}, True, 1.3, 0.0, False),
    ("cycles_transparent", {"color": (0.9, 0.8, 0.7)}, True, 1.0, 0.0, False),
    ("cycles_translucent", {"color": (0.9, 0.8, 0.7)}, False, None, 1.0, False),
])
def test_cycles_node_models_get_their_own_finish(material, name, params, transparent, ior, back,
                                                  mirror):
    api.assign(material, name, **params)
    _set_up(material)
    pov = material.pov
    assert material.bxdf_lab.pov_label == "approximate"
    assert tuple(material.diffuse_color)[:3] == pytest.approx(params["color"])
    assert pov.diffuse_intensity == 0.0 and pov.translucency == back
    assert pov.use_transparency is transparent
    if transparent:
        # render_povray writes pigment rgbft with filter = filter·(1 − alpha): all of it filtered.
        assert (pov.transparency_method, pov.alpha) == ("RAYTRACE", 0.0)
        assert material.pov_raytrace_transparency.filter == 1.0
        assert material.pov_raytrace_transparency.ior == pytest.approx(ior)
    assert material.pov_raytrace_mirror.use is mirror and pov.mirror_use_IOR is mirror
    assert name.split("_")[1] in material.bxdf_lab.pov_mapping.lower()


def test_velvet_finish_is_lambert_with_its_albedo(material, bxdf):
    api.assign(material, "cycles_velvet", color=(0.8, 0.5, 0.6), sigma=0.5)
    _set_up(material)
    albedo = np.asarray(bxdf.make("cycles_velvet", color=(0.8, 0.5, 0.6), sigma=0.5).rho_hh(4096))
    assert tuple(material.diffuse_color)[:3] == pytest.approx(tuple(albedo.reshape(3)), rel=0.05)
    assert material.pov.use_transparency is False
    assert "sheen" in material.bxdf_lab.pov_mapping


def test_principled_transmission_filters_the_base_colour_and_keeps_its_diffuse(material):
    api.assign(material, "cycles_principled", base_color=(0.6, 0.4, 0.2), transmission=0.5,
               metallic=0.2, ior=1.5)
    _set_up(material)
    pov, filtered = material.pov, 0.5 * (1.0 - 0.2)
    assert tuple(material.diffuse_color)[:3] == pytest.approx((0.6, 0.4, 0.2))
    assert (pov.use_transparency, pov.alpha) == (True, pytest.approx(1.0 - filtered))
    # POV's diffuse D·pigment·(1 − filter) is the model's (1 − metallic)(1 − transmission)·base.
    assert pov.diffuse_intensity * (1.0 - filtered) == pytest.approx(0.8 * 0.5)
    assert material.pov_raytrace_transparency.ior == pytest.approx(1.5)


def test_a_model_without_transparency_clears_an_earlier_one(material):
    api.assign(material, "cycles_glass", color=(1.0, 1.0, 1.0), ior=1.5)
    _set_up(material)
    api.assign(material, "lambertian")
    _set_up(material)
    assert material.pov.use_transparency is False and material.pov.mirror_use_IOR is False
    assert material.pov.translucency == 0.0 and material.pov_raytrace_mirror.use is False


def test_povray_renders_a_transparent_plane_as_a_colour_filter(material, tmp_path):
    """A Transparent plane over a Lambertian one, lit by a sun straight above: POV-Ray gives
    R·E/π·colour, the colour once (Cycles gives colour², the light being filtered on its way
    down too: the mapping text says so)."""
    api.assign(material, "lambertian", reflectance=(0.7, 0.5, 0.3))
    _plane("floor", 0.0, material)
    veil = bpy.data.materials.new("veil")
    api.assign(veil, "cycles_transparent", color=(0.5, 0.8, 1.0))
    _plane("veil", 1.0, veil)
    scene = bpy.context.scene
    _light("SUN", math.pi, (1.0, 1.0, 1.0))
    cam = bpy.data.objects.new("cam", bpy.data.cameras.new("cam"))
    cam.location = (0, 0, 5)
    scene.collection.objects.link(cam)
    scene.camera = cam
    _set_up(material)
    _set_up(veil)
    pixels = _povray_render(scene, tmp_path)
    expected = np.array([0.7, 0.5, 0.3]) * np.array([0.5, 0.8, 1.0])
    assert "colour²" in veil.bxdf_lab.pov_mapping
    np.testing.assert_allclose(pixels, np.broadcast_to(expected, pixels.shape), rtol=1e-2, atol=1e-3)
