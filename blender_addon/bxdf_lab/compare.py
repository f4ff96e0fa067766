"""Render the scene with BXDF_LAB, CYCLES and POVRAY_RENDER and put the results side by side.

A stand-in for the comparison harness (compare/), which will replace these internals: each engine
renders to a linear EXR in a folder, with the fair settings of reference/renderers.md applied for
the duration and restored afterwards. Materials use their node tree for Cycles and their
material.pov settings (use_nodes off) for POV-Ray.
"""

import contextlib
import os

import addon_utils
import bpy
import numpy as np

from . import bake, engine

ENGINES = ("BXDF_LAB", "CYCLES", "POVRAY_RENDER")


@contextlib.contextmanager
def _temporarily(pairs):
    """Sets (owner, attribute, value) triples, restoring the old values on exit."""
    saved = []
    try:
        for owner, attr, value in pairs:
            if owner is not None and hasattr(owner, attr):
                saved.append((owner, attr, getattr(owner, attr)))
                setattr(owner, attr, value)
        yield
    finally:
        for owner, attr, value in reversed(saved):
            setattr(owner, attr, value)


def _engine_settings(scene, engine_id):
    r = scene.render
    pairs = [(r, "engine", engine_id), (r, "filepath", r.filepath),
             (r.image_settings, "file_format", "OPEN_EXR"), (r.image_settings, "color_depth", "32"),
             (scene.view_settings, "view_transform", "Standard"), (scene.view_settings, "look", "None"),
             (scene.view_settings, "exposure", 0.0), (scene.view_settings, "gamma", 1.0),
             (r, "film_transparent", False)]
    if engine_id == "CYCLES":
        c = scene.cycles
        pairs += [(c, "use_denoising", False), (c, "use_adaptive_sampling", False),
                  (c, "sample_clamp_direct", 0.0), (c, "sample_clamp_indirect", 0.0),
                  (c, "blur_glossy", 0.0), (c, "light_sampling_threshold", 0.0),
                  (c, "samples", scene.bxdf_lab_render.samples),
                  (c, "max_bounces", scene.bxdf_lab_render.max_bounces)]
    if engine_id == "POVRAY_RENDER":
        # 16-bit sRGB PNG: render_povray loads POV's PNG as sRGB into the linear render result
        # (a linear PNG, File_Gamma=1.0, would be decoded twice).
        pairs += [(scene.pov, "radio_enable", False),
                  (scene.pov, "command_line_switches", "+FN16")]
    use_nodes = engine_id == "CYCLES"
    pairs += [(m, "use_nodes", use_nodes) for m in bpy.data.materials
              if engine_id != "BXDF_LAB" and (m.node_tree is not None or not use_nodes)]
    return pairs


def render_engine(scene, engine_id, path):
    """Renders `scene` with one engine into `path` (EXR). Returns (ok, message)."""
    if engine_id == "POVRAY_RENDER" and not hasattr(bpy.types.Scene, "pov"):
        addon_utils.enable("render_povray", default_set=True)
    if engine_id not in {e.bl_idname for e in bpy.types.RenderEngine.__subclasses__()} | {"CYCLES"}:
        return False, f"{engine_id} is not available (is its add-on enabled?)"
    if os.path.exists(path):
        os.remove(path)
    with _temporarily(_engine_settings(scene, engine_id)):
        scene.render.filepath = path
        try:
            bpy.ops.render.render(write_still=True, scene=scene.name)
        except RuntimeError as exc:  # an engine's error report
            return False, str(exc)
    if engine_id == "BXDF_LAB" and engine.last_error:
        return False, engine.last_error
    if not os.path.exists(path):
        return False, f"{engine_id} wrote no image"
    return True, path


def side_by_side(paths, name="BxDF Lab comparison"):
    """One Blender image with the given EXR files next to each other (left to right)."""
    images = []
    for path in paths:
        image = bpy.data.images.load(path, check_existing=False)
        width, height = image.size
        pixels = np.empty(width * height * 4, dtype=np.float32)
        image.pixels.foreach_get(pixels)
        images.append(pixels.reshape(height, width, 4))
        bpy.data.images.remove(image)
    height = max(i.shape[0] for i in images)
    padded = [np.pad(i, ((0, height - i.shape[0]), (0, 0), (0, 0))) for i in images]
    return bake.to_image(name, np.concatenate(padded, axis=1))


def compare(scene, folder):
    """Renders with every engine into `folder`; returns ({engine: (ok, message)}, image or None)."""
    os.makedirs(folder, exist_ok=True)
    results = {e: render_engine(scene, e, os.path.join(folder, f"{e.lower()}.exr")) for e in ENGINES}
    written = [message for ok, message in results.values() if ok]
    return results, (side_by_side(written) if written else None)
