"""Render settings for each engine, so that all three render the same thing (runs inside Blender).

Facts from reference/renderers.md: Cycles with radius-0 lights, no clamping, no denoising, no
adaptive sampling, (nearly) pixel-centre sampling through GAUSSIAN width 0.01, and BXDF_LAB with
the same Gaussian (not PIXEL_CENTER: Cycles' sigma = 0.0025 px shows at edges by pixel centres);
POV-Ray with linear 16-bit PNG output (+FN16 File_Gamma=1.0), no anti-aliasing, radiosity only
where the scene asks for global illumination. (POV-Ray's light calibration belongs to the
material set-up: see material_setup.)"""
from __future__ import annotations

import math
import os

import bpy

from .scene_spec import SceneSpec


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


# Cycles' narrowest filter (its minimum width): camera rays within about 0.01 px of pixel centres.
CYCLES_FILTER_WIDTH = 0.01


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
    cycles.pixel_filter_type = "GAUSSIAN"   # BOX ignores the width; 0.01 = nearly the pixel centre
    cycles.filter_width = CYCLES_FILTER_WIDTH
    _threads(scene, threads)
    return {"samples": spp, "seed": seed, "max_bounces": spec.max_bounces,
            "filter": f"GAUSSIAN {CYCLES_FILTER_WIDTH}", "threads": threads}


def configure_bxdf_lab(spec: SceneSpec, spp: int, seed: int, threads: int) -> dict:
    scene = bpy.context.scene
    if not hasattr(scene, "bxdf_lab_render"):
        raise RuntimeError("the bxdf_lab add-on is not registered (scene.bxdf_lab_render missing)")
    scene.render.engine = "BXDF_LAB"
    settings = scene.bxdf_lab_render
    settings.samples = spp
    settings.seed = seed
    settings.max_bounces = spec.max_bounces
    # Cycles' filter as configure_cycles sets it, not PIXEL_CENTER: Gaussian width 0.01 still
    # spreads Cycles' camera rays by sigma = 0.0025 px, so an edge within ~0.01 px of a pixel
    # centre is partly covered in Cycles and all-or-nothing at the exact centre (z 23 at 96 px).
    settings.pixel_filter = "GAUSSIAN"
    settings.filter_width = CYCLES_FILTER_WIDTH
    settings.threads = threads
    # Cycles' Adaptive Sampling, which BXDF_LAB reads too (renderer.cycles_adaptive_sampling):
    # off, as for Cycles, whichever engine the scene was set up for last.
    if hasattr(scene, "cycles"):
        scene.cycles.use_adaptive_sampling = False
    return {"samples": spp, "seed": seed, "max_bounces": spec.max_bounces,
            "filter": f"GAUSSIAN {CYCLES_FILTER_WIDTH}", "threads": threads}


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
    if _has_povray_transmission(spec):
        # A POV-Ray glass finish traces both its Fresnel mirror and its refraction at every hit,
        # and the mirror's weight (rgb 1 before Fresnel) never trips adc_bailout: 2^level rays per
        # pixel. At level 18 cycles_glass_room ran past the 900 s job timeout; 8 bounds the tree.
        pov.max_trace_level = min(pov.max_trace_level, POVRAY_TRANSMISSION_TRACE_LEVEL)
    scene.world.pov.horizon_color = spec.world_color
    return {"radiosity": spec.povray_radiosity, "antialias": False,
            "max_trace_level": pov.max_trace_level, "switches": pov.command_line_switches,
            "lights": povray_lights_as_exported()}


POVRAY_TRANSMISSION_TRACE_LEVEL = 8


def _has_povray_transmission(spec: SceneSpec) -> bool:
    """Whether a material gets a transmitting POV-Ray finish (povray_setup: glass, refraction,
    transparent, Principled with transmission)."""
    for material in spec.materials():
        if material.model in ("cycles_glass", "cycles_refraction", "cycles_transparent"):
            return True
        if material.model == "cycles_principled" and material.params.get("transmission", 0.0) > 0:
            return True
    return False


def povray_lights_as_exported() -> list:
    """What render_povray will write for each light (after the calibration)."""
    out = []
    for obj in bpy.context.scene.objects:
        if obj.type == "LIGHT":
            data = obj.data
            entry = {"light": obj.name, "type": data.type, "srgb_color": list(data.color)}
            if data.type != "SUN":
                entry["fade_distance"] = math.sqrt(data.distance / 2.0)
                entry["falloff"] = data.falloff_type
            out.append(entry)
    return out


def _threads(scene, threads):
    if threads > 0:
        scene.render.threads_mode = "FIXED"
        scene.render.threads = threads
    else:
        scene.render.threads_mode = "AUTO"
