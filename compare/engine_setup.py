"""Render settings for each engine, so that all three render the same thing (runs inside Blender).

Facts from reference/renderers.md: Cycles with radius-0 lights, no clamping, no denoising, no adaptive
sampling, pixel-centre sampling through GAUSSIAN width 0.01; POV-Ray with linear 16-bit PNG output
(+FN16 File_Gamma=1.0), radiosity only where the scene asks for global illumination, and point lights
recalibrated to a true inverse-square fall-off."""
from __future__ import annotations

import math
import os

import bpy

from .scene_spec import PointLight, SceneSpec, SunLight

# POV-Ray's exporter writes a light colour as `color srgb <%.3g ...>`: choose a colour that three
# digits represent exactly and put the rest of the calibration into the fade distance (%.6f).
POV_POINT_SRGB = 100.0


def srgb_to_linear(c: float) -> float:
    return c / 12.92 if c <= 0.04045 else ((c + 0.055) / 1.055) ** 2.4


def linear_to_srgb(c: float) -> float:
    return c * 12.92 if c <= 0.0031308 else 1.055 * c ** (1.0 / 2.4) - 0.055


def common_settings(spec: SceneSpec):
    scene = bpy.context.scene
    view = scene.view_settings
    view.view_transform = "Standard"
    view.look = "None"
    view.exposure = 0.0
    view.gamma = 1.0
    scene.display_settings.display_device = "sRGB"
    scene.render.film_transparent = False
    scene.render.use_compositing = False
    scene.render.use_sequencer = False
    image = scene.render.image_settings
    image.file_format = "OPEN_EXR"
    image.color_mode = "RGB"
    image.color_depth = "32"
    image.exr_codec = "ZIP"


def configure_cycles(spec: SceneSpec, spp: int, seed: int, threads: int) -> dict:
    scene = bpy.context.scene
    scene.render.engine = "CYCLES"
    cycles = scene.cycles
    cycles.device = "CPU"
    cycles.samples = spp
    cycles.seed = seed
    cycles.use_animated_seed = False
    cycles.use_denoising = False      # this build has no OpenImageDenoise
    cycles.use_adaptive_sampling = False
    cycles.sample_clamp_direct = 0.0
    cycles.sample_clamp_indirect = 0.0
    cycles.blur_glossy = 0.0
    cycles.caustics_reflective = True
    cycles.caustics_refractive = True
    cycles.light_sampling_threshold = 0.0
    cycles.max_bounces = spec.max_bounces
    for name in ("diffuse_bounces", "glossy_bounces", "transmission_bounces", "volume_bounces"):
        setattr(cycles, name, spec.max_bounces)
    cycles.transparent_max_bounces = max(spec.max_bounces, 1)
    cycles.pixel_filter_type = "GAUSSIAN"   # BOX ignores the width; 0.01 = pixel centre
    cycles.filter_width = 0.01
    _threads(scene, threads)
    return {"samples": spp, "seed": seed, "max_bounces": spec.max_bounces,
            "filter": "GAUSSIAN 0.01", "threads": threads}


def configure_bxdf_lab(spec: SceneSpec, spp: int, seed: int, threads: int) -> dict:
    scene = bpy.context.scene
    if not hasattr(scene, "bxdf_lab_render"):
        raise RuntimeError("the bxdf_lab add-on is not registered (scene.bxdf_lab_render missing)")
    scene.render.engine = "BXDF_LAB"
    settings = scene.bxdf_lab_render
    settings.samples = spp
    settings.seed = seed
    settings.max_bounces = spec.max_bounces
    settings.pixel_filter = "PIXEL_CENTER"
    settings.threads = threads
    return {"samples": spp, "seed": seed, "max_bounces": spec.max_bounces,
            "filter": "PIXEL_CENTER", "threads": threads}


def configure_povray(spec: SceneSpec, work_dir: str, basename: str, threads: int) -> dict:
    """POV-Ray is deterministic here (no anti-aliasing, one ray per pixel centre): one render."""
    scene = bpy.context.scene
    scene.render.engine = "POVRAY_RENDER"
    pov = scene.pov
    pov.tempfiles_enable = False       # keep .pov/.ini/.png in scene_path (read back the PNG)
    pov.deletefiles_enable = False
    pov_dir = os.path.join(work_dir, "povray_files")
    os.makedirs(pov_dir, exist_ok=True)
    pov.scene_path = pov_dir + os.sep
    pov.scene_name = basename
    pov.command_line_switches = f"+FN16 File_Gamma=1.0 +WT{max(threads, 1)}"  # never +FE
    pov.antialias_enable = False
    pov.radio_enable = spec.povray_radiosity
    pov.max_trace_level = max(5, 2 * spec.max_bounces + 2)
    scene.world.pov.horizon_color = spec.world_color
    calibration = _calibrate_povray_lights(spec)
    return {"radiosity": spec.povray_radiosity, "antialias": False,
            "max_trace_level": pov.max_trace_level, "switches": pov.command_line_switches,
            "lights": calibration}


def _calibrate_povray_lights(spec: SceneSpec) -> list:
    """POV-Ray ignores light energy and attenuates a point light by 2 / (1 + (d/D)^2) with
    D = sqrt(distance/2); for D << d that is 2 D^2 / d^2. Its diffuse term has no 1/pi, so a
    Lambertian match needs colour C with C * 2 D^2 = I / pi; a sun (parallel light, no fade) needs
    C = E / pi."""
    notes = []
    lights = [o for o in bpy.context.scene.objects if o.type == "LIGHT"]
    lights.sort(key=lambda o: int(o.name.rsplit("_", 1)[1]))
    for obj, light in zip(lights, spec.lights):
        data = obj.data
        if isinstance(light, PointLight):
            c_lin = srgb_to_linear(POV_POINT_SRGB)
            # distance = 2 D^2 = I_max / (pi C): the brightest channel gets exactly C.
            i_max = light.intensity * max(light.color)
            data.distance = i_max / (math.pi * c_lin)
            data.falloff_type = "INVERSE_SQUARE"
            data.color = tuple(linear_to_srgb(c_lin * ch / max(light.color)) for ch in light.color)
            fade = math.sqrt(data.distance / 2.0)
            notes.append({"light": obj.name, "srgb_color": list(data.color),
                          "fade_distance": fade, "fade_power": 2,
                          "relative_error_at_1m": fade * fade})
        elif isinstance(light, SunLight):
            data.color = tuple(linear_to_srgb(light.irradiance * ch / math.pi)
                               for ch in light.color)
            notes.append({"light": obj.name, "srgb_color": list(data.color), "parallel": True})
    return notes


def _threads(scene, threads):
    if threads > 0:
        scene.render.threads_mode = "FIXED"
        scene.render.threads = threads
    else:
        scene.render.threads_mode = "AUTO"
