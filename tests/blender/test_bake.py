"""Lobe bakes into Blender images: sizes, orientation and values (a Lambertian is R/π·cos θi)."""

import math
import os

import bpy
import mathutils
import numpy as np
import pytest

from bxdf_lab import api

R = (0.2, 0.5, 0.8)


def _pixels(image):
    width, height = image.size
    out = np.empty(width * height * 4, dtype=np.float32)
    image.pixels.foreach_get(out)
    return out.reshape(height, width, 4)


def _bake(material, **kw):
    with bpy.context.temp_override(material=material):
        assert bpy.ops.bxdf_lab.bake_lobe_texture(**kw) == {"FINISHED"}


def test_lambertian_polar_lobe_is_r_over_pi_cos_theta(material):
    api.assign(material, "lambertian", reflectance=R)
    _bake(material, theta_in=30.0, size=64)
    image = bpy.data.images[f"{material.name} lobe 30deg"]
    assert tuple(image.size) == (64, 64)
    pixels = _pixels(image)
    centres = (np.arange(64) + 0.5) / 64 * 2 - 1
    x, y = np.meshgrid(centres, centres)
    r2 = x * x + y * y
    inside = r2 <= 1.0
    cos_theta = 1.0 - r2  # Lambert's equal-area projection: z = 1 − r²
    expected = np.asarray(R)[None, :] / math.pi * cos_theta[inside][:, None]
    np.testing.assert_allclose(pixels[inside][:, :3], expected, rtol=1e-4, atol=1e-6)
    assert np.all(pixels[inside][:, 3] == 1.0) and np.all(pixels[~inside] == 0.0)
    # the middle of the disc is the normal: R/π exactly
    assert pixels[31:33, 31:33, 0].max() == pytest.approx(R[0] / math.pi, rel=1e-3)


def test_lambertian_slice_is_r_over_pi_and_albedo_is_r(material):
    api.assign(material, "lambertian", reflectance=R)
    _bake(material, theta_in=0.0, size=32, albedo_samples=4096)
    slice_px = _pixels(bpy.data.images[f"{material.name} slice"])
    assert slice_px.shape == (32, 32, 4)
    # both directions above the horizon where θh + θd < 90°: f = R/π (bottom-left triangle)
    theta = (np.arange(32) + 0.5) / 32 * 90
    above = theta[:, None] + theta[None, :] < 89.0  # [row = θd, col = θh]
    np.testing.assert_allclose(slice_px[above][:, :3], np.broadcast_to(np.asarray(R) / math.pi,
                               (above.sum(), 3)), rtol=1e-5)
    albedo = _pixels(bpy.data.images[f"{material.name} albedo"])
    assert albedo.shape == (1, 32, 4)
    np.testing.assert_allclose(albedo[0, :, :3], np.broadcast_to(R, (32, 3)), rtol=1e-5)


def test_bake_saves_exr_and_reuses_images(material, tmp_path):
    api.assign(material, "lambertian", reflectance=R)
    _bake(material, theta_in=45.0, size=16, save_exr=True, directory=str(tmp_path))
    names = sorted(os.listdir(tmp_path))
    assert len(names) == 3 and all(n.endswith(".exr") for n in names)
    loaded = bpy.data.images.load(str(tmp_path / [n for n in names if "lobe" in n][0]))
    expected = _pixels(bpy.data.images[f"{material.name} lobe 45deg"])
    np.testing.assert_allclose(_pixels(loaded), expected, rtol=1e-6)
    count = len(bpy.data.images)
    _bake(material, theta_in=45.0, size=8)
    assert len(bpy.data.images) == count  # same names: replaced, not duplicated
    assert tuple(bpy.data.images[f"{material.name} slice"].size) == (8, 8)


def test_bake_of_a_broken_material_reports_an_error(material):
    material.bxdf_lab.lambertian.reflectance = (float("nan"), 0.5, 0.5)
    with bpy.context.temp_override(material=material):
        with pytest.raises(RuntimeError, match="reflectance"):
            bpy.ops.bxdf_lab.bake_lobe_texture(size=8)


def test_add_lobe_mesh_of_a_lambertian_is_a_cosine_lobe(material):
    api.assign(material, "lambertian", reflectance=R)
    with bpy.context.temp_override(material=material):
        assert bpy.ops.bxdf_lab.add_lobe_mesh(theta_in=60.0, size=2.0) == {"FINISHED"}
    obj = bpy.data.objects[f"{material.name} lobe"]
    co = np.array([v.co for v in obj.data.vertices])
    radius = np.linalg.norm(co, axis=1)
    assert radius.max() == pytest.approx(2.0, rel=1e-5)
    # Lambertian: radius ∝ cos θi, so every vertex lies on the sphere of diameter 2 touching
    # the origin: |p − (0, 0, 1)| = 1 (scaled by size/2).
    np.testing.assert_allclose(np.linalg.norm(co - [0, 0, 1.0], axis=1), 1.0, atol=1e-4)
    assert len(obj.data.polygons) > 0 and obj.data.validate() is False


def test_transmission_lobes_are_baked_below_the_surface(material):
    api.assign(material, "lambertian_transmission", transmittance=R)
    _bake(material, theta_in=0.0, size=32)
    pixels = _pixels(bpy.data.images[f"{material.name} lobe 0deg"])
    centres = (np.arange(32) + 0.5) / 32 * 2 - 1
    x, y = np.meshgrid(centres, centres)
    inside = x * x + y * y <= 1.0
    expected = np.asarray(R)[None, :] / math.pi * (1.0 - (x * x + y * y))[inside][:, None]
    np.testing.assert_allclose(pixels[inside][:, :3], expected, rtol=1e-4, atol=1e-6)
    with bpy.context.temp_override(material=material):
        assert bpy.ops.bxdf_lab.add_lobe_mesh(theta_in=0.0) == {"FINISHED"}
    z = np.array([v.co.z for v in bpy.data.objects[f"{material.name} lobe"].data.vertices])
    assert z.max() <= 1e-6 and z.min() < -0.5


def test_the_lobe_mesh_sits_beside_the_active_object_selected_with_its_incident_arrow(material):
    api.assign(material, "microfacet")
    bpy.ops.mesh.primitive_cube_add(size=2.0, location=(0, 0, 0))  # the default cube
    cube = bpy.context.object
    cube.data.materials.append(material)
    with bpy.context.temp_override(material=material):
        assert bpy.ops.bxdf_lab.add_lobe_mesh(theta_in=30.0, size=1.0) == {"FINISHED"}
    lobe = bpy.data.objects[f"{material.name} lobe"]
    assert lobe.location.x >= 1.0 + 1.0  # clear of the cube (which ends at x = 1)
    assert lobe.select_get() and bpy.context.view_layer.objects.active == lobe
    assert not cube.select_get()
    arrow = bpy.data.objects[f"{lobe.name} incident"]
    assert arrow.parent == lobe and arrow.empty_display_type == "SINGLE_ARROW"
    direction = arrow.matrix_basis.to_3x3() @ mathutils.Vector((0, 0, 1))
    np.testing.assert_allclose(direction, (math.sin(math.radians(30)), 0, math.cos(math.radians(30))),
                               atol=1e-6)


def test_the_bake_shows_its_images_with_colour_scales_that_do_not_clip(material):
    from bxdf_lab import bake_figure
    api.assign(material, "microfacet", distribution="ggx", alpha_x=0.05, alpha_y=0.05)
    _bake(material, theta_in=30.0, size=32)
    figure = bpy.data.images[f"{material.name} lobes"]
    assert figure.size[0] > 0 and figure.packed_file is not None
    luminance = bake_figure._luminance(_pixels(bpy.data.images[f"{material.name} lobe 30deg"]))
    scale = bake_figure._norm(luminance)
    assert scale.vmax == pytest.approx(float(luminance.max()))  # the peak is the top of the scale
    assert type(scale).__name__ == "LogNorm"  # a sharp GGX peak: logarithmic, the rest visible
