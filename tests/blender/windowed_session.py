"""Drives a windowed Blender (under Xvfb) through what only a window can do: the Material tab's
preview of every model (Blender renders previews in a job that needs the GPU: in background mode
it crashes), and the viewport's Rendered mode drawn through the gpu module, with an edit that
restarts it. Writes what it saw as JSON, and screenshots when asked.

    xvfb-run -a -s "-screen 0 1280x800x24" blender FILE.blend --python tests/blender/windowed_session.py \
        -- --out result.json [--screenshots DIR] [--models NAME ...]

Steps run from a timer (Blender's event loop must run for jobs and redraws); each step yields the
seconds to wait before the next.
"""

import argparse
import faulthandler
import json
import os
import sys
import time
import traceback

import bpy
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
for variable in ("BXDF_PYTHONPATH", "PYTHONPATH"):
    for entry in reversed(os.environ.get(variable, "").split(os.pathsep)):
        if entry and os.path.abspath(entry) not in sys.path:
            sys.path.insert(0, os.path.abspath(entry))
sys.path.insert(0, os.path.join(ROOT, "blender_addon"))

parser = argparse.ArgumentParser()
parser.add_argument("--out", required=True)
parser.add_argument("--screenshots", default="")
parser.add_argument("--models", nargs="*", default=None)
args = parser.parse_args(sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else [])

TIMEOUT = 120.0
# A whole session takes 85-105 s. Past HANG_SECONDS something is stuck: every Python thread's
# stack goes to OUT.stacks and Blender exits, so that the test reports where instead of timing out.
# Blender's own quit (jobs, windows, Python) gets QUIT_SECONDS, its stacks OUT.quit_stacks (the
# test takes the native stacks with gdb before then, after 45 s).
HANG_SECONDS = 420.0
QUIT_SECONDS = 150.0
stacks, quit_stacks = open(args.out + ".stacks", "w"), open(args.out + ".quit_stacks", "w")
JOB_KINDS = ("RENDER", "RENDER_PREVIEW", "OBJECT_BAKE", "COMPOSITE", "SHADER_COMPILATION")
result = {"previews": {}, "viewport": {}, "errors": []}
session_started = time.time()


def mark(step):
    """One line per step on stdout, so that a stuck session's output shows the last step reached."""
    print(f"[windowed_session {time.time() - session_started:6.1f} s] {step}", flush=True)


def area(kind):
    return next(a for a in bpy.context.window.screen.areas if a.type == kind)


def screenshot(kind, name):
    if not args.screenshots:
        return
    os.makedirs(args.screenshots, exist_ok=True)
    with bpy.context.temp_override(window=bpy.context.window, area=area(kind)):
        bpy.ops.screen.screenshot_area(filepath=os.path.join(args.screenshots, name))


def wait_for(condition, what):
    deadline = time.time() + TIMEOUT
    while not condition():
        if time.time() > deadline:
            raise TimeoutError(f"waited {TIMEOUT:.0f} s for {what}")
        yield 0.1


# Every preview render, with the image it produced: Blender starts one whenever the material
# changes (the Material tab's Preview panel and the material's icon), and cancels a running one
# when a newer one starts.
preview_renders = []


def record_previews():
    from bxdf_lab import engine, render_report
    last_image = {}
    pixels_for_blender, record = engine.pixels_for_blender, render_report.record

    def keep_pixels(image, width, height):
        last_image["image"] = np.array(image, dtype=np.float32)
        return pixels_for_blender(image, width, height)

    def keep_report(report):
        if report.kind == "preview":
            preview_renders.append((time.time(), report, last_image.pop("image", None)))
        record(report)

    engine.pixels_for_blender, render_report.record = keep_pixels, keep_report


def quiet(seconds=1.5):
    """Waits until no preview has finished for `seconds` (Blender may queue several)."""
    yield from wait_for(lambda: not preview_renders or time.time() - preview_renders[-1][0] > seconds,
                        "the previews to settle")


def previews(material):
    import bxdf
    from bxdf_lab import api
    for model in args.models or list(bxdf.models()):
        yield from quiet()
        first = len(preview_renders)
        mark(f"preview of {model}")
        api.assign(material, model)  # Blender re-renders the preview
        yield from wait_for(lambda: any(not r.cancelled for _, r, _ in preview_renders[first:]),
                            f"the preview of {model}")
        yield from quiet()
        report, image = [(r, i) for _, r, i in preview_renders[first:] if not r.cancelled][-1]
        h, w = image.shape[:2] if image is not None else (0, 0)
        centre = image[h // 3: 2 * h // 3, w // 3: 2 * w // 3, :3] if image is not None else None
        result["previews"][model] = {
            "scene": report.scene, "summary": report.summary, "errors": report.errors,
            "warnings": report.warnings, "size": [w, h],
            "finite": bool(np.isfinite(image).all()) if image is not None else False,
            "centre_mean": centre.mean(axis=(0, 1)).tolist() if image is not None else [],
            "std": float(image[..., :3].std()) if image is not None else 0.0,
        }


def showcase():
    """For the README's screenshots: a gold sphere beside the cube, on a floor."""
    from bxdf_lab import api
    bpy.ops.mesh.primitive_uv_sphere_add(radius=1.0, location=(2.6, 0.0, 0.0), segments=64, ring_count=32)
    sphere = bpy.context.object
    bpy.ops.object.shade_smooth()
    gold = bpy.data.materials.new("Gold")
    api.assign_preset(gold, "gold")
    sphere.data.materials.append(gold)
    bpy.ops.mesh.primitive_plane_add(size=20.0, location=(0.0, 0.0, -1.0))
    floor = bpy.data.materials.new("Floor")
    api.assign(floor, "oren_nayar", reflectance=(0.5, 0.5, 0.5), sigma=20.0)
    bpy.context.object.data.materials.append(floor)
    bpy.data.objects["Light"].data.energy = 1500.0
    world = bpy.context.scene.world
    world.node_tree.nodes["Background"].inputs["Color"].default_value = (0.25, 0.27, 0.3, 1.0)
    bpy.context.scene.bxdf_lab_render.viewport_samples = 64
    for material in (bpy.data.materials["Material"], gold, floor):  # labelled pairings in the report
        with bpy.context.temp_override(material=material):
            bpy.ops.bxdf_lab.set_up_cycles()
            bpy.ops.bxdf_lab.set_up_povray()
    for obj in bpy.context.selected_objects:
        obj.select_set(False)


def viewport_steps():
    from bxdf_lab import viewport
    if args.screenshots:
        showcase()
    view = area("VIEW_3D")
    mark("viewport: Rendered mode")
    with bpy.context.temp_override(window=bpy.context.window, area=view, scene=bpy.context.scene):
        view.spaces.active.shading.type = "RENDERED"
    yield from wait_for(lambda: viewport.sessions() and viewport.sessions()[0].job is not None,
                        "the viewport render to start")
    session = viewport.sessions()[0]
    first = session.job
    yield from wait_for(lambda: first.done and session.display.version == (id(first), first.version),
                        "the viewport render to finish and be drawn")
    result["viewport"]["first"] = {"version": first.version, "error": first.error,
                                   "shape": list(first.image.shape),
                                   "samples": first.stats.get("samples_per_pixel", 0)}
    screenshot("VIEW_3D", "viewport_rendered.png")
    mark("viewport: an edit")
    bpy.data.objects["Cube"].location.x += 0.5  # an edit: Blender calls view_update
    yield from wait_for(lambda: session.job is not first, "the viewport render to restart")
    second = session.job
    yield from wait_for(lambda: second.done and session.display.version == (id(second), second.version),
                        "the restarted render to finish and be drawn")
    result["viewport"]["second"] = {"version": second.version, "error": second.error,
                                    "first_cancelled_or_done": first.cancelled or first.done,
                                    "restarts": session.restarts,
                                    "changed": bool(np.abs(second.image - first.image).max() > 0.01)}


def compare_steps():
    """Compare Renders with a window: render jobs from the modal loop, the status bar, the figure
    in an Image Editor."""
    from bxdf_lab import compare
    import tempfile
    folder = tempfile.mkdtemp(prefix="bxdf_compare_")
    scene = bpy.context.scene
    before = (scene.render.engine, scene.render.resolution_percentage, scene.render.filepath)
    view = area("VIEW_3D")
    view.type = "IMAGE_EDITOR"  # somewhere to show the result
    with bpy.context.temp_override(window=bpy.context.window, area=area("IMAGE_EDITOR")):
        # The README's pictures at a readable size; the test at a quick one.
        size, samples = (320, 32) if args.screenshots else (48, 4)
        mark("Compare Renders")
        started = bpy.ops.bxdf_lab.compare_renders("EXEC_DEFAULT", directory=folder, size=size, samples=samples)
    result["compare"] = {"started": list(started), "folder": folder}

    def slow_handler(*_):
        time.sleep(1.0)
    # Another add-on's slow render_complete handler, after the operator's: each render job
    # outlives render_complete by a second, and a next render.render in that second is refused
    # (only one render job at a time). The operator must wait for the job itself to end.
    bpy.app.handlers.render_complete.append(slow_handler)
    try:
        yield from wait_for(lambda: compare.last_result.get("folder") == folder, "Compare Renders")
    finally:
        bpy.app.handlers.render_complete.remove(slow_handler)
    mark("Compare Renders finished")
    yield 0.5
    shown = area("IMAGE_EDITOR").spaces.active.image
    result["compare"].update(
        results=compare.last_result["results"],
        shown=shown.name if shown else "",
        report=os.path.exists(compare.last_result["report"]),
        windows=len(bpy.context.window_manager.windows),
        restored=(scene.render.engine, scene.render.resolution_percentage, scene.render.filepath) == before)
    screenshot("IMAGE_EDITOR", "compare_result.png")
    area("IMAGE_EDITOR").type = "VIEW_3D"


def steps():
    from bxdf_lab import api
    scene = bpy.context.scene
    scene.render.engine = "BXDF_LAB"
    material = bpy.data.materials["Material"]
    properties = area("PROPERTIES")
    properties.spaces.active.context = "MATERIAL"
    record_previews()
    yield 0.5
    yield from previews(material)
    first = len(preview_renders)
    api.assign(material, "microfacet", distribution="ggx", alpha_x=0.25, alpha_y=0.25,
               fresnel="conductor")
    yield from wait_for(lambda: any(not r.cancelled for _, r, _ in preview_renders[first:]),
                        "the panel's preview")
    yield from quiet()
    screenshot("PROPERTIES", "material_panel.png")
    yield from viewport_steps()
    view = area("VIEW_3D")
    with bpy.context.temp_override(window=bpy.context.window, area=view, scene=bpy.context.scene):
        view.spaces.active.shading.type = "SOLID"  # stops the viewport render before quitting
    yield 0.5
    yield from compare_steps()


def run():
    faulthandler.dump_traceback_later(HANG_SECONDS, exit=True, file=stacks)
    gen = steps()

    def tick():
        try:
            return next(gen)
        except StopIteration:
            pass
        except Exception:
            result["errors"].append(traceback.format_exc())
        bpy.app.timers.register(quit_when_idle, first_interval=0.2)
        return None

    refusals = 0

    def quit_when_idle():
        nonlocal refusals
        if refusals == 0:  # the first attempt: what is still running (the UI may have started
            # a material preview, as for a user who quits), then the result
            from bxdf_lab import viewport
            result["at_quit"] = {"jobs": [kind for kind in JOB_KINDS if bpy.app.is_job_running(kind)],
                                 "viewport_renders": sum(s.job is not None and not s.job.done
                                                         for s in viewport.sessions())}
            with open(args.out, "w") as f:
                json.dump(result, f, indent=1)
            mark(f"result written; quitting with {result['at_quit']} running")
            faulthandler.cancel_dump_traceback_later()
            faulthandler.dump_traceback_later(QUIT_SECONDS, exit=True, file=quit_stacks)
        try:
            bpy.ops.wm.quit_blender()
        except RuntimeError as exc:  # a preview job is still rendering: try again
            if refusals % 50 == 0:
                mark(f"quit refused ({exc}); trying every 0.2 s")
            refusals += 1
            return 0.2
        return None

    bpy.app.timers.register(tick, first_interval=1.0)


import addon_utils  # noqa: E402  (after sys.path holds the add-on and the module)

bpy.context.preferences.use_preferences_save = False  # never touch the user's preferences
addon_utils.enable("bxdf_lab", default_set=True, handle_error=None)
run()
