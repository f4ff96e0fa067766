"""The render engine BXDF_LAB ("BxDF Lab"): export, render with progress and cancel, pixels back.

Three kinds of render: F12 (render()), the Material tab's preview (render() with is_preview, on
Blender's preview scene, at the preview sample count) and the viewport's Rendered mode
(view_update/view_draw, handed to viewport.py). The Material Preview shading mode is EEVEE's
(bl_use_eevee_viewport), drawing the material's node tree as Blender's own engines do.

Blender swallows exceptions raised in render() (bpy.ops.render.render() still says FINISHED), so
every error is reported with self.report({'ERROR'}, ...) (which the operator's caller sees as a
RuntimeError) and recorded in `last_error` for scripts and tests; end_result() is always called, in a finally (a missing end_result followed by an EXR
write crashed Blender 3.4).
"""

import time

import bpy
import numpy as np

from . import export, render_report, renderer, viewport

# The last final render's error message ("" after a successful render) and whether it was
# cancelled (material previews leave both alone); its warnings are in render_report.
last_error = ""
last_cancelled = False

# The phases of a render that render_report.Report.timings holds (seconds): the Python-side
# export of the scene, the module's conversion of it into the renderer's scene (convert) and its
# BVH build (bvh), the samples (render), and the pixels' way back into Blender's result
# (hand_back); "total" is the whole of _render, "other" what none of the phases covers (settings,
# the call into the module, its threads starting, the image coming back from it).
PHASES = ("export", "convert", "bvh", "render", "hand_back", "other", "total")


# How often a render shows Blender its progress, in seconds of rendering. Each status and
# progress update has Blender redraw the window's header, and each partial result the Image
# Editor; without a GPU (software OpenGL, as under Xvfb) those redraws take the render's own
# cores. With the status every 50 ms and a partial result after each of the 8 passes, a
# 64-sample F12 render of cycles_glass_room at 256² took 6.2-7.0 s in a window against 2.4-3.0 s
# in `blender -b`; with these intervals, 3.2-3.5 s (Cycles: 4.4-5.2 s), as measured in
# docs/performance-history.md (twenty-first session).
STATUS_INTERVAL = 0.5
PARTIAL_RESULT_INTERVAL = 2.0  # the first one too, after as long


def update_due(last, now, interval):
    """Whether an update at `now` is shown, the last one (or the render's start) at `last`."""
    return now - last >= interval


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


def _phase_seconds(export_seconds, stats, hand_back_seconds, total_seconds):
    """Report.timings of a finished render (PHASES) from the engine's clocks and the module's
    stats (convert_seconds, bvh_seconds, seconds)."""
    timings = {"export": export_seconds,
               "convert": float(stats.get("convert_seconds", 0.0)),
               "bvh": float(stats.get("bvh_seconds", 0.0)),
               "render": float(stats.get("seconds", 0.0)),
               "hand_back": hand_back_seconds}
    timings["other"] = total_seconds - sum(timings.values())
    timings["total"] = total_seconds
    return timings


class BXDFLAB_RenderEngine(bpy.types.RenderEngine):
    bl_idname = "BXDF_LAB"
    bl_label = "BxDF Lab"
    bl_use_preview = True
    bl_use_eevee_viewport = True
    bl_use_postprocess = True

    def __init__(self):
        self.viewport = None  # a viewport.ViewportSession once the viewport renders

    def __del__(self):
        session = getattr(self, "viewport", None)
        if session is not None:
            session.stop()

    def view_update(self, context, depsgraph):
        if self.viewport is None:
            self.viewport = viewport.ViewportSession()
        self.viewport.update(context, depsgraph)

    def view_draw(self, context, depsgraph):
        if self.viewport is None:
            self.view_update(context, depsgraph)
        self.viewport.draw(context, depsgraph, self)

    def render(self, depsgraph):
        if self.is_preview:
            render_report.record(self._render(depsgraph, "preview"))
            return
        global last_error, last_cancelled
        report = self._render(depsgraph, "final")
        last_error, last_cancelled = report.errors[0] if report.errors else "", report.cancelled
        render_report.record(report)

    def _render(self, depsgraph, purpose):
        """Renders into the render result; returns the render_report.Report of this render (with
        `cancelled` set)."""
        scene = depsgraph.scene
        report = render_report.Report("preview" if purpose == "preview" else "render", scene.name)
        width, height = export.resolution(scene)
        # With a Render Region Blender's result holds only the region: only it is rendered.
        region = renderer.render_region(scene, width, height) if purpose == "final" else None
        if region is not None:
            width, height = region[2] - region[0], region[3] - region[1]
        result = self.begin_result(0, 0, width, height)
        cancelled = False
        try:
            started = time.perf_counter()
            self.update_stats("BxDF Lab", "Exporting scene")
            data = export.export_scene(depsgraph)
            for warning in data["warnings"]:
                self._warn(report, warning)
            if "warning" in data["camera"]:  # the viewport has its own camera: said only here
                self._warn(report, data["camera"]["warning"])
            n_triangles = sum(len(m["triangles"]) for m in data["meshes"])
            export_seconds = time.perf_counter() - started
            self.update_stats("BxDF Lab", f"Exported {n_triangles} triangles, "
                              f"{len(data['instance_mesh'])} instances in "
                              f"{export_seconds:.2f} s; rendering")
            combined = result.layers[0].passes["Combined"]
            status_shown = -STATUS_INTERVAL  # the first at once
            partial_shown = time.perf_counter()

            def on_progress(done, total, image=None):
                nonlocal cancelled, status_shown, partial_shown
                now = time.perf_counter()
                if update_due(status_shown, now, STATUS_INTERVAL):
                    status_shown = now
                    self.update_progress(done / max(total, 1))
                    self.update_stats("BxDF Lab", f"Rendering: {done} of {total} tiles "
                                      f"({100.0 * done / max(total, 1):.0f}%)")
                if image is not None and update_due(partial_shown, now, PARTIAL_RESULT_INTERVAL):
                    # A partial result: show it while rendering.
                    partial_shown = now
                    combined.rect.foreach_set(pixels_for_blender(image, width, height))
                    self.update_result(result)
                cancelled = cancel_requested(self)
                return not cancelled

            settings = renderer.settings_dict(scene.bxdf_lab_render, purpose,
                                              renderer.cycles_settings(scene, purpose))
            settings["region"] = region
            # Blender without a window (blender -b) shows no partial result: the passes' images
            # (a copy, a flip and foreach_set each, ~1 ms at 128², competing with the render
            # threads) would be made for nobody. Cycles updates none there either.
            image, stats = renderer.render(data, settings, on_progress,
                                           partial_images=not bpy.app.background)
            for warning in stats.get("warnings", []):
                self._warn(report, warning)
            if cancelled or stats.get("cancelled") or cancel_requested(self):
                cancelled = True
            else:
                hand_back_started = time.perf_counter()
                combined.rect.foreach_set(pixels_for_blender(image, width, height))
                self.update_progress(1.0)
                report.timings = _phase_seconds(export_seconds, stats,
                                                time.perf_counter() - hand_back_started,
                                                time.perf_counter() - started)
                samples = renderer.samples_text(stats, image.shape[0] * image.shape[1])
                report.summary = (f"{width}×{height} pixels, {samples}: export "
                                  f"{export_seconds:.2f} s, render {stats.get('seconds', 0.0):.2f} s")
                self.update_stats("BxDF Lab", report.summary)
        except Exception as exc:  # reported and recorded, never swallowed
            report.errors.append(f"{type(exc).__name__}: {exc}")
            self.report({"ERROR"}, f"BxDF Lab: {exc}")
            print(f"BxDF Lab render failed: {report.errors[-1]}")
            cancelled = True
        finally:
            if cancelled and not report.errors:
                # An error report is what stops Blender from writing the (empty) result of a
                # cancelled render to disk (render.render(write_still=True)); a warning does not.
                # A preview is cancelled whenever a newer one starts: nothing to tell.
                if not self.is_preview:
                    self.report({"ERROR"}, "BxDF Lab: render cancelled; nothing is written")
                report.summary = "Cancelled; nothing was written"
            report.cancelled = cancelled
            # cancel=True discards the result, so a cancelled or failed render writes no file.
            self.end_result(result, cancel=cancelled)
        return report

    def _warn(self, report, warning):
        if warning not in report.warnings:
            report.warnings.append(warning)
            if not self.is_preview:  # a preview's warnings would flood the status bar
                self.report({"WARNING"}, warning)


def register():
    bpy.utils.register_class(BXDFLAB_RenderEngine)


def unregister():
    bpy.utils.unregister_class(BXDFLAB_RenderEngine)
