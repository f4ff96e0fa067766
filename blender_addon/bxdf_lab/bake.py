"""Lobe textures: the bindings' bakes (bxdf.bake_*) turned into Blender images.

- polar lobe: f(ωo, ωi)·|cos θi| over the hemisphere of ωi seen from above (the lower one for
  transmission-only models), in Lambert's
  equal-area projection (every pixel the same solid angle; bxdf.bake_lobe_polar); alpha 1 inside
  the unit disc, 0 outside. A Lambertian gives R/π·cos θi.
- θh×θd slice: f at Rusinkiewicz's half/difference angles with φd = 90° (bxdf.bake_slice_half_diff),
  θh along x, θd up the image.
- albedo curve: a width×1 image of the directional albedo ρ(θo), θo over (0°, 90°)
  (bxdf.bake_albedo_curve).
Blender stores image rows bottom-up; the bakes are flipped where their row 0 is the top.
"""

import bpy
import numpy as np

from . import dependency


def _rgba(rgb, alpha):
    out = np.empty(rgb.shape[:-1] + (4,), dtype=np.float32)
    out[..., :3] = rgb
    out[..., 3] = alpha
    return out


def disc_mask(size):
    """1 for pixel centres inside the unit disc of the polar image, else 0."""
    centres = (np.arange(size) + 0.5) / size * 2.0 - 1.0
    x, y = np.meshgrid(centres, centres)
    return (x * x + y * y <= 1.0).astype(np.float32)


def hemisphere(model):
    """Where the lobe lives: "lower" for transmission-only models, else "upper"."""
    flags = set(model.flags)
    return "lower" if "transmission" in flags and "reflection" not in flags else "upper"


def lobe_polar(model, theta_in_deg, size):
    """(size, size, 4), rows bottom-up, +y up: the polar lobe for ωo at θo = theta_in_deg, φo = 0,
    over the lower hemisphere for a transmission-only model."""
    bxdf = dependency.require()
    rgb = bxdf.bake_lobe_polar(model, resolution=size, theta_o=float(theta_in_deg),
                               hemisphere=hemisphere(model))
    return _rgba(np.flipud(rgb), disc_mask(size))  # bake's row 0 is the top (+y)


def slice_half_diff(model, size):
    """(size, size, 4): f over θh (x) × θd (y, 0 at the bottom), φd = 90°."""
    rgb = dependency.require().bake_slice_half_diff(model, phi_d=90.0, resolution=size)
    return _rgba(rgb, 1.0)  # the bake's row 0 is θd ≈ 0, which Blender shows at the bottom


def albedo_curve(model, width, n_samples=4096):
    """(1, width, 4): directional albedo at θo = 90°·(k + 0.5)/width."""
    _, albedo = dependency.require().bake_albedo_curve(model, n_theta=width, n_samples=n_samples)
    return _rgba(np.asarray(albedo).reshape(1, width, 3), 1.0)


def to_image(name, pixels, save_path=""):
    """A float Blender image named `name` holding `pixels` (h, w, 4); replaced if it exists with
    another size. Saved as OpenEXR when `save_path` is given."""
    height, width = pixels.shape[:2]
    image = bpy.data.images.get(name)
    if image is not None and tuple(image.size) != (width, height):
        bpy.data.images.remove(image)
        image = None
    if image is None:
        image = bpy.data.images.new(name, width, height, alpha=True, float_buffer=True)
    # Non-Color: the values are data, and Blender 3.4 writes a generated "Linear" float image to
    # EXR sRGB-encoded (checked: 0.0075 came back as 0.082); Non-Color round-trips exactly.
    image.colorspace_settings.name = "Non-Color"
    image.pixels.foreach_set(np.ascontiguousarray(pixels, dtype=np.float32).ravel())
    image.update()
    if save_path:
        image.filepath_raw = bpy.path.abspath(save_path)
        image.file_format = "OPEN_EXR"
        image.save()
    return image
