"""The render engine BXDF_LAB ("BxDF Lab"): export, render with progress and cancel, pixels back.

Blender swallows exceptions raised in render() (bpy.ops.render.render() still says FINISHED), so
every error is reported with self.report({'ERROR'}, ...) (which the operator's caller sees as a
RuntimeError) and recorded in `last_error` for scripts and tests; end_result() is always called, in a finally (a missing end_result followed by an EXR
write crashed Blender 3.4).
"""

import time

import bpy
import numpy as np

from . import export, renderer

# The last render's error message ("" after a successful render) and whether it was cancelled.
last_error = ""
last_cancelled = False


def cancel_requested(render_engine):
    """Whether the user asked to stop (Esc). One function, so that headless tests, which have no
    Esc key, can stand in for the user."""
    return render_engine.test_break()


def pixels_for_blender(image, width, height):
    """A (w·h, 4) C-contiguous float32 array, the only form rect.foreach_set takes quickly."""
    pixels = np.ascontiguousarray(image, dtype=np.float32)
    if pixels.shape != (height, width, 4):
        raise ValueError(f"renderer returned an image of shape {pixels.shape}, "
                         f"expected {(height, width, 4)}")
    return pixels.reshape(width * height, 4)


class BXDFLAB_RenderEngine(bpy.types.RenderEngine):
    bl_idname = "BXDF_LAB"
    bl_label = "BxDF Lab"
    bl_use_preview = False
    bl_use_postprocess = True

    def render(self, depsgraph):
        global last_error, last_cancelled
        last_error, last_cancelled = "", False
        scene = depsgraph.scene
        width, height = export.resolution(scene)
        result = self.begin_result(0, 0, width, height)
        cancelled = False
        try:
            started = time.perf_counter()
            self.update_stats("BxDF Lab", "Exporting scene")
            data = export.export_scene(depsgraph)
            for warning in data["warnings"]:
                self.report({"WARNING"}, warning)
            n_triangles = sum(len(m["triangles"]) for m in data["meshes"])
            self.update_stats("BxDF Lab", f"Exported {n_triangles} triangles, "
                              f"{len(data['instance_mesh'])} instances in "
                              f"{time.perf_counter() - started:.2f} s; rendering")
            combined = result.layers[0].passes["Combined"]

            def on_progress(done, total, image=None):
                nonlocal cancelled
                self.update_progress(done / max(total, 1))
                self.update_stats("BxDF Lab", f"Tile {done}/{total}")
                if image is not None:  # a partial result: show it while rendering
                    combined.rect.foreach_set(pixels_for_blender(image, width, height))
                    self.update_result(result)
                cancelled = cancel_requested(self)
                return not cancelled

            image, stats = renderer.render(data, scene.bxdf_lab_render, on_progress)
            for warning in stats.get("warnings", []):
                self.report({"WARNING"}, warning)
            if cancelled or stats.get("cancelled") or cancel_requested(self):
                cancelled = True
            else:
                combined.rect.foreach_set(pixels_for_blender(image, width, height))
                self.update_progress(1.0)
                self.update_stats("BxDF Lab", f"{stats.get('samples_per_pixel', 0)} samples per "
                                  f"pixel in {stats.get('seconds', 0.0):.2f} s")
        except Exception as exc:  # reported and recorded, never swallowed
            last_error = f"{type(exc).__name__}: {exc}"
            self.report({"ERROR"}, f"BxDF Lab: {exc}")
            print(f"BxDF Lab render failed: {last_error}")
            cancelled = True
        finally:
            if cancelled and not last_error:
                # An error report is what stops Blender from writing the (empty) result of a
                # cancelled render to disk (render.render(write_still=True)); a warning does not.
                self.report({"ERROR"}, "BxDF Lab: render cancelled; nothing is written")
            last_cancelled = cancelled
            # cancel=True discards the result, so a cancelled or failed render writes no file.
            self.end_result(result, cancel=cancelled)


def register():
    bpy.utils.register_class(BXDFLAB_RenderEngine)


def unregister():
    bpy.utils.unregister_class(BXDFLAB_RenderEngine)
