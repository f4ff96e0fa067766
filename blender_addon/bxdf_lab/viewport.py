"""The viewport's Rendered mode: a progressive render of the 3D view on a worker thread.

view_update (an edit in the scene) re-exports the scene on Blender's main thread; view_draw
compares the view (matrices, region size, pixel size) with the running render's and restarts the
render when the scene or the view changed. A restart cancels the old render (its on_progress
returns False, so the renderer stops within a tile) without waiting for it, so the UI never
blocks. The worker thread only calls the renderer (which releases the GIL) and keeps the newest
pass's image; a timer on the main thread asks the 3D views to redraw when a new pass arrived, and
view_draw uploads it to a GPU texture and draws it through Blender's display transform.

The viewport camera comes from the region's own matrices: the inverse view matrix is the
camera-to-world frame, and the perspective projection gives the lens (on a 36 mm horizontal
sensor) and the shift, so that the camera view's zoom and offset, and a free view, both match what
the region shows. An orthographic projection gives the view's width in scene units (the ortho
scale), its offset (the shift) and its depth range, which in a free orthographic view starts
behind the eye (Blender clips it symmetrically about the pivot): the camera then moves back to the
near plane.

A Render Region that applies to the view (its own, or the scene's through the camera) is rendered
alone, each pixel as the whole view's render has it, and drawn over its part of the view, as
Cycles' viewport does.
"""

import threading
import weakref

import bpy
import numpy as np

from . import export, render_report, renderer

_sessions = weakref.WeakSet()  # live sessions, for sessions()
SENSOR_WIDTH = 36.0  # mm; any width does, the lens is derived for it
REDRAW_INTERVAL = 0.1  # s between the timer's checks for a new pass


def view_camera(region_data, clip, width, height):
    """The renderer's camera dict for a 3D view of `width`×`height` pixels.

    `region_data` is a RegionView3D (view_matrix, window_matrix, is_perspective); `clip` the view's
    (clip start, clip end), used by perspective views (an orthographic projection holds its own)."""
    projection = np.array(region_data.window_matrix, dtype=np.float64)
    camera_to_world = np.array(region_data.view_matrix.inverted(), dtype=np.float32)
    for axis in range(3):  # the renderer wants an orthonormal frame
        camera_to_world[:3, axis] /= max(np.linalg.norm(camera_to_world[:3, axis]), 1e-30)
    if not region_data.is_perspective:
        return _orthographic_camera(projection, camera_to_world, width, height)
    # OpenGL frustum: P[0][0] = 2n/(r-l) = 2·lens/sensor, P[0][2] = (r+l)/(r-l) = 2·shift_x;
    # P[1][2] = (t+b)/(t-b), and the renderer's shift_y is in units of the (fitted) width.
    return {
        "matrix": camera_to_world,
        "type": "persp",
        "lens": float(projection[0, 0] * SENSOR_WIDTH / 2.0),
        "sensor_width": SENSOR_WIDTH,
        "sensor_height": SENSOR_WIDTH * height / width,
        "sensor_fit": "horizontal",
        "shift": (float(projection[0, 2] / 2.0), float(projection[1, 2] / 2.0 * height / width)),
        "clip": (float(clip[0]), float(clip[1])),
        "resolution": (width, height),
    }


def _orthographic_camera(projection, camera_to_world, width, height):
    """OpenGL orthographic projection: P[0][0] = 2/(r−l), P[0][3] = −(r+l)/(r−l), the same for y,
    P[2][2] = −2/(f−n), P[2][3] = −(f+n)/(f−n); near and far are depths along the view axis."""
    ortho_scale = 2.0 / projection[0, 0]  # the view's width in scene units
    centre = (-projection[0, 3] / projection[0, 0], -projection[1, 3] / projection[1, 1])
    near = (projection[2, 3] + 1.0) / projection[2, 2]
    far = (projection[2, 3] - 1.0) / projection[2, 2]
    camera_to_world = camera_to_world.copy()
    camera_to_world[:3, 3] -= camera_to_world[:3, 2] * near  # the eye onto the near plane (−Z looks ahead)
    return {
        "matrix": camera_to_world,
        "type": "ortho",
        "ortho_scale": float(ortho_scale),
        "sensor_fit": "horizontal",
        "shift": (float(centre[0] / ortho_scale), float(centre[1] / ortho_scale)),
        "clip": (0.0, float(far - near)),
        "resolution": (width, height),
    }


def view_render_border(space, region_data, scene):
    """The Render Region that applies to a 3D view, as (left, bottom, right, top) fractions of the
    view clamped to it, or None: as Cycles' blender_camera_border. A free view takes its own region
    (Ctrl+B in the viewport). Looking through the camera, the scene's region is a part of the
    camera frame, so it maps through the frame's place in the view; with no region but an opaque
    passepartout (alpha 1), the frame itself."""
    if region_data.view_perspective != "CAMERA":
        if not space.use_render_border:
            return None
        return _clamped((space.render_border_min_x, space.render_border_min_y,
                         space.render_border_max_x, space.render_border_max_y))
    camera = space.camera if space.use_local_camera else scene.camera
    if camera is None or camera.type != "CAMERA":  # any object can be the scene's camera
        return None
    r = scene.render
    if r.use_border:
        border = (r.border_min_x, r.border_min_y, r.border_max_x, r.border_max_y)
    elif camera.data.show_passepartout and camera.data.passepartout_alpha == 1.0:
        border = (0.0, 0.0, 1.0, 1.0)
    else:
        return None
    left, bottom, right, top = camera_frame_in_view(camera, scene, region_data)
    return _clamped((left + border[0] * (right - left), bottom + border[1] * (top - bottom),
                     left + border[2] * (right - left), bottom + border[3] * (top - bottom)))


def camera_frame_in_view(camera, scene, region_data):
    """The camera frame's (left, bottom, right, top) as fractions of the view: its corners (the
    frame of the scene's render size, shift included) through the view's projection."""
    projection = region_data.window_matrix @ region_data.view_matrix
    xs, ys = [], []
    for corner in camera.data.view_frame(scene=scene):
        p = projection @ (camera.matrix_world @ corner).to_4d()
        xs.append((p.x / p.w + 1.0) / 2.0)
        ys.append((p.y / p.w + 1.0) / 2.0)
    return min(xs), min(ys), max(xs), max(ys)


def _clamped(border):
    return tuple(min(max(float(v), 0.0), 1.0) for v in border)


def relevant_update(updates):
    """Whether an edit (a depsgraph's `updates`) changes what the render shows (a selection alone
    does not)."""
    for update in updates:
        if update.is_updated_geometry or update.is_updated_transform or update.is_updated_shading:
            return True
        if isinstance(update.id, (bpy.types.Material, bpy.types.World, bpy.types.Light,
                                  bpy.types.Scene, bpy.types.Camera)):
            return True
    return False


class RenderJob:
    """One progressive render on a worker thread; `image` is the newest pass, `version` counts
    the passes received."""

    def __init__(self, data, settings):
        self.data, self.settings = data, settings
        self.image = None
        self.version = 0
        self.progress = 0.0
        self.stats = {}
        self.error = ""
        self.done = False
        self._cancel = False
        self._thread = threading.Thread(target=self._run, name="BxDF Lab viewport", daemon=True)
        self._thread.start()

    def _on_progress(self, done, total, image):
        self.progress = done / max(total, 1)
        if image is not None:
            self.image, self.version = image, self.version + 1
        return not self._cancel

    def _run(self):
        try:
            image, stats = renderer.render(self.data, self.settings, self._on_progress)
            if not stats.get("cancelled"):
                self.image, self.version = image, self.version + 1
            self.stats = stats
        except Exception as exc:  # shown in the viewport's status text and the Render tab
            self.error = f"{type(exc).__name__}: {exc}"
        finally:
            self.progress = 1.0 if not self._cancel else self.progress
            self.done = True

    @property
    def cancelled(self):
        return self._cancel

    def cancel(self):
        """Asks the render to stop; returns at once (the renderer stops within a tile)."""
        self._cancel = True

    def wait(self, timeout=None):
        self._thread.join(timeout)
        return not self._thread.is_alive()


class GPUDisplay:
    """Draws a render's image over the region through Blender's gpu module, in the scene's
    display transform (view transform, look, exposure), as Cycles' viewport does."""

    def __init__(self):
        self.texture = None
        self.version = None

    def draw(self, engine, scene, job, rect):
        """Draws the job's newest image over `rect` (x, y, width, height) of the region, in the
        region's pixels from its bottom-left corner."""
        import gpu
        from gpu_extras.presets import draw_texture_2d

        if job.image is None:
            return
        if self.version != (id(job), job.version):
            height, width = job.image.shape[:2]
            pixels = np.ascontiguousarray(job.image, dtype=np.float32).ravel()
            buffer = gpu.types.Buffer("FLOAT", pixels.size, pixels)
            self.texture = gpu.types.GPUTexture((width, height), format="RGBA16F", data=buffer)
            self.version = (id(job), job.version)
        gpu.state.blend_set("ALPHA_PREMULT")
        engine.bind_display_space_shader(scene)
        draw_texture_2d(self.texture, rect[:2], rect[2], rect[3])
        engine.unbind_display_space_shader()
        gpu.state.blend_set("NONE")


def preview_pixel_size(scene):
    """Viewport pixels per rendered pixel: Blender's own Viewport Pixel Size (Render Properties ›
    Performance in Cycles), read as Blender reads it for every engine (BKE_render_preview_pixel_size):
    Automatic is 2 on a high-DPI interface and 1 otherwise."""
    setting = scene.render.preview_pixel_size
    if setting == "AUTO":
        return 2 if bpy.context.preferences.system.pixel_size > 1.5 else 1
    return int(setting)


def _draw_rect(pixels, width, height, region):
    """Where an image of the view's `pixels` (renderer.border_pixels', or None for all of the
    `width`×`height` view) lies in the region: (x, y, width, height) in the region's pixels from
    its bottom-left, the render's pixels stretched over the region's (Viewport Pixel Size)."""
    if pixels is None:
        return (0, 0, region.width, region.height)
    sx, sy = region.width / width, region.height / height
    x0, top, x1, bottom = pixels
    left, right = round(x0 * sx), round(x1 * sx)
    low, high = round((height - bottom) * sy), round((height - top) * sy)
    return (left, low, right - left, high - low)


def sessions():
    """The viewports rendering now (Blender's engine instances are not reachable from Python;
    scripts and the windowed tests look here)."""
    return list(_sessions)


def _tag_3d_views():
    for window in bpy.context.window_manager.windows:
        for area in window.screen.areas:
            if area.type == "VIEW_3D":
                area.tag_redraw()


class ViewportSession:
    """The Rendered mode of one viewport: the exported scene, the view it was rendered for and the
    running RenderJob. `display` draws a job's image (GPUDisplay; tests pass a stand-in)."""

    def __init__(self, display=None, start_timer=True):
        self.display = display if display is not None else GPUDisplay()
        self.start_timer = start_timer
        self.data = None
        self.export_error = ""
        self.scene_version = 0
        self.job = None
        self.job_key = None
        self.restarts = 0
        self._drawn_version = None
        _sessions.add(self)

    # ---- main thread: Blender's view_update and view_draw --------------------------------

    def update(self, context, depsgraph, updates=None):
        """view_update: re-export when the edit matters (or on the first call). `updates` defaults
        to the depsgraph's, which Blender fills only while it calls view_update."""
        updates = depsgraph.updates if updates is None else updates
        if self.data is not None and not relevant_update(updates):
            return
        scene = depsgraph.scene
        try:
            self.data = export.export_scene(depsgraph)
            self.export_error = ""
        except Exception as exc:  # a bad material: the viewport says so instead of drawing
            self.data, self.export_error = None, f"{type(exc).__name__}: {exc}"
            if self.job is not None:
                self.job.cancel()
            self._record(scene.name, [])
        self.scene_version += 1

    def draw(self, context, depsgraph, engine):
        """view_draw: (re)start the render for this view if needed, draw its newest image."""
        scene = depsgraph.scene
        region = context.region
        if self.export_error:
            engine.update_stats("", f"BxDF Lab: {self.export_error}")
            return
        if self.data is None:
            return
        settings = scene.bxdf_lab_render
        pixel_size = preview_pixel_size(scene)
        width, height = max(1, region.width // pixel_size), max(1, region.height // pixel_size)
        region_data = context.region_data
        render_settings = renderer.settings_dict(settings, "viewport",
                                                 renderer.cycles_settings(scene, "viewport"))
        border = view_render_border(context.space_data, region_data, scene)
        pixels = renderer.border_pixels(border, width, height) if border is not None else None
        render_settings["region"] = pixels
        key = (self.scene_version, width, height, tuple(map(tuple, region_data.view_matrix)),
               tuple(map(tuple, region_data.window_matrix)), tuple(sorted(render_settings.items())))
        if key != self.job_key:
            camera = view_camera(region_data, (context.space_data.clip_start,
                                               context.space_data.clip_end), width, height)
            self._restart(scene.name, camera, render_settings, key)
        job = self.job
        if job is None:
            return
        engine.update_stats("", self._status(job))
        self.display.draw(engine, scene, job, _draw_rect(pixels, width, height, region))
        self._drawn_version = job.version

    def _restart(self, scene_name, camera, settings, key):
        if self.job is not None:
            self.job.cancel()  # stops within a tile; not waited for
            self.restarts += 1
        data = dict(self.data, camera=camera, resolution=camera["resolution"])
        self.job = RenderJob(data, settings)
        self.job_key = key
        self._record(scene_name, data["warnings"])
        if self.start_timer:
            bpy.app.timers.register(self._redraw_when_new(self.job), first_interval=REDRAW_INTERVAL)

    def _redraw_when_new(self, job):
        def check():
            if self.job is not job:
                return None
            if job.version != self._drawn_version or job.done:
                _tag_3d_views()
            if job.done:
                if job.error:
                    self._record_error(job.error)
                return None
            return REDRAW_INTERVAL
        return check

    def _record(self, scene_name, warnings):
        report = render_report.Report("viewport", scene_name, warnings=list(warnings))
        if self.export_error:
            report.errors.append(self.export_error)
        render_report.record(report)

    def _record_error(self, error):
        report = render_report.last("viewport")
        if report is not None and error not in report.errors:
            report.errors.append(error)

    @staticmethod
    def _status(job):
        if job.error:
            return f"BxDF Lab: {job.error}"
        if job.done:
            pixels = job.image.shape[0] * job.image.shape[1] if job.image is not None else 0
            return (f"BxDF Lab: {renderer.samples_text(job.stats, pixels)} "
                    f"in {job.stats.get('seconds', 0.0):.1f} s")
        return f"BxDF Lab: rendering {100.0 * job.progress:.0f}%"

    def stop(self, wait=True):
        """Cancels the running render (and waits for it to stop when `wait`)."""
        job, self.job = self.job, None
        if job is not None:
            job.cancel()
            if wait:
                job.wait()
