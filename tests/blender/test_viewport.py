"""The viewport's Rendered mode driven through view_update/view_draw with a stand-in context
(headless Blender has no 3D view): it renders progressively on a worker thread, draws each pass,
restarts on an edit and on a view change (cancelling the old render), and its camera, derived from
the region's matrices, gives the same image as the scene camera's F12 render."""

import math
import time

import bpy
import mathutils
import numpy as np
import pytest

from bxdf_lab import api, export, render_report, renderer, viewport


class RecordingDisplay:
    """Stands in for viewport.GPUDisplay: keeps what would be drawn."""

    def __init__(self):
        self.drawn = []

    def draw(self, engine, scene, job, region_size):
        if job.image is not None:
            self.drawn.append((job, job.version, job.image.shape, region_size))


class StandInEngine:
    def __init__(self):
        self.stats = ""

    def update_stats(self, _stats, info):
        self.stats = info


def _context(scene, width, height, view_matrix, window_matrix, perspective=True,
             view_perspective="PERSP", view_border=None):
    """`view_border`: the view's own Render Region (left, bottom, right, top), or None."""
    region = type("Region", (), {"width": width, "height": height})()
    region_data = type("RegionView3D", (), {"view_matrix": view_matrix, "window_matrix": window_matrix,
                                            "is_perspective": perspective,
                                            "view_perspective": view_perspective})()
    left, bottom, right, top = view_border or (0.0, 0.0, 1.0, 1.0)
    space = type("SpaceView3D", (), {"clip_start": 0.01, "clip_end": 1000.0,
                                     "use_render_border": view_border is not None,
                                     "render_border_min_x": left, "render_border_min_y": bottom,
                                     "render_border_max_x": right, "render_border_max_y": top,
                                     "use_local_camera": False, "camera": None})()
    return type("Context", (), {"region": region, "region_data": region_data, "space_data": space,
                                "scene": scene})()


def _camera_view(scene, camera, width, height):
    """The matrices of a 3D view looking through `camera`, as Blender computes them."""
    depsgraph = bpy.context.evaluated_depsgraph_get()
    window = camera.calc_matrix_camera(depsgraph, x=width, y=height)
    return camera.matrix_world.inverted(), window


@pytest.fixture
def scene(material):
    scene = bpy.context.scene
    api.assign(material, "oren_nayar", sigma=20.0)
    bpy.ops.mesh.primitive_uv_sphere_add(segments=24, ring_count=12)
    sphere = bpy.context.object
    sphere.data.materials.append(material)
    light = bpy.data.objects.new("lamp", bpy.data.lights.new("lamp", "POINT"))
    light.data.energy, light.data.shadow_soft_size = 800.0, 0.0
    light.location = (3, -3, 4)
    scene.collection.objects.link(light)
    camera = bpy.data.objects.new("cam", bpy.data.cameras.new("cam"))
    camera.location, camera.rotation_euler = (0, -6, 1.5), (math.radians(78), 0, 0)
    camera.data.shift_x, camera.data.shift_y = 0.08, -0.05
    scene.collection.objects.link(camera)
    scene.camera = camera
    scene.render.engine = "BXDF_LAB"
    s = scene.bxdf_lab_render
    s.viewport_samples, s.max_bounces, s.seed = 4, 2, 3
    scene.render.preview_pixel_size = "1"
    s.pixel_filter = "PIXEL_CENTER"
    return scene


def _wait(job, timeout=60.0):
    assert job.wait(timeout), "the viewport render did not finish"


def test_the_view_renders_progressively_and_restarts_on_an_edit_and_a_view_change(scene):
    display, engine = RecordingDisplay(), StandInEngine()
    session = viewport.ViewportSession(display=display, start_timer=False)
    view, window = _camera_view(scene, scene.camera, 48, 32)
    context = _context(scene, 48, 32, view, window)
    depsgraph = bpy.context.evaluated_depsgraph_get()
    session.update(context, depsgraph, [])
    session.draw(context, depsgraph, engine)
    first = session.job
    assert first is not None and session.restarts == 0
    _wait(first)
    session.draw(context, depsgraph, engine)
    # The first sample's pass, then passes sized by time as Cycles' viewport sizes them: a 48×32
    # view renders its other three samples within the first 0.1 s interval, in one pass.
    assert renderer.settings_dict(scene.bxdf_lab_render, "viewport")["progressive"]
    assert first.error == "" and 2 <= first.version <= 3
    assert display.drawn[-1][:3] == (first, first.version, (32, 48, 4))
    assert "4 samples per pixel" in engine.stats

    # Drawing again without a change keeps the render.
    session.draw(context, depsgraph, engine)
    assert session.job is first

    # A selection alone changes nothing; a moved object restarts and cancels the old render.
    session.update(context, depsgraph, [type("U", (), {
        "is_updated_geometry": False, "is_updated_transform": False, "is_updated_shading": False,
        "id": bpy.data.objects["Sphere"]})()])
    session.draw(context, depsgraph, engine)
    assert session.job is first
    bpy.data.objects["Sphere"].location.x += 0.5
    depsgraph = bpy.context.evaluated_depsgraph_get()
    moved = type("U", (), {"is_updated_geometry": False, "is_updated_transform": True,
                           "is_updated_shading": False, "id": bpy.data.objects["Sphere"]})()
    session.update(context, depsgraph, [moved])
    session.draw(context, depsgraph, engine)
    second = session.job
    assert second is not first and session.restarts == 1
    assert first.cancelled
    _wait(second)
    assert not np.array_equal(second.image, first.image)  # the sphere moved

    # A new view (the user orbits) restarts too.
    turned = mathutils.Matrix.Rotation(math.radians(5), 4, "Z") @ view
    session.draw(_context(scene, 48, 32, turned, window), depsgraph, engine)
    assert session.job is not second and second.cancelled and session.restarts == 2
    session.stop()
    assert render_report.last("viewport").scene == scene.name


def test_a_new_render_cancels_the_running_one_quickly(scene):
    scene.bxdf_lab_render.viewport_samples = 4096  # would take minutes
    session = viewport.ViewportSession(display=RecordingDisplay(), start_timer=False)
    view, window = _camera_view(scene, scene.camera, 64, 64)
    context = _context(scene, 64, 64, view, window)
    depsgraph = bpy.context.evaluated_depsgraph_get()
    session.update(context, depsgraph, [])
    session.draw(context, depsgraph, StandInEngine())
    running = session.job
    time.sleep(0.2)
    started = time.perf_counter()
    session.stop()
    assert time.perf_counter() - started < 5.0
    assert running.done and running.cancelled and running.error == ""


def test_the_view_camera_matches_the_scene_camera(scene, tmp_path):
    """Looking through the camera, the viewport's derived lens and shift give F12's image."""
    width, height = 48, 32
    scene.render.resolution_x, scene.render.resolution_y = width, height
    scene.render.resolution_percentage = 100
    view, window = _camera_view(scene, scene.camera, width, height)
    region_data = type("R", (), {"view_matrix": view, "window_matrix": window,
                                 "is_perspective": True})()
    depsgraph = bpy.context.evaluated_depsgraph_get()
    data = export.export_scene(depsgraph)
    settings = renderer.settings_dict(scene.bxdf_lab_render, "viewport")
    expected = renderer.render(data, settings, None)[0]
    camera = viewport.view_camera(region_data, (0.01, 1000.0), width, height)
    got = renderer.render(dict(data, camera=camera, resolution=(width, height)), settings, None)[0]
    assert np.abs(got - expected).max() < 1e-4
    assert expected[..., :3].max() > 0.05  # the sphere is in view and lit


def _orthographic_window(left, right, bottom, top, near, far):
    """An OpenGL orthographic projection, as Blender's 3D view builds it."""
    return mathutils.Matrix((
        (2 / (right - left), 0, 0, -(right + left) / (right - left)),
        (0, 2 / (top - bottom), 0, -(top + bottom) / (top - bottom)),
        (0, 0, -2 / (far - near), -(far + near) / (far - near)),
        (0, 0, 0, 1)))


def test_an_orthographic_view_matches_the_orthographic_camera(scene):
    """Through an orthographic camera the view gives F12's image; a free orthographic view, whose
    depth range starts behind the eye (Blender clips it about the pivot), gives the same image."""
    width, height = 48, 32
    scene.render.resolution_x, scene.render.resolution_y = width, height
    scene.render.resolution_percentage = 100
    camera = scene.camera.data
    camera.type, camera.ortho_scale = "ORTHO", 3.5
    camera.clip_start, camera.clip_end = 0.1, 100.0
    view, window = _camera_view(scene, scene.camera, width, height)
    depsgraph = bpy.context.evaluated_depsgraph_get()
    data = export.export_scene(depsgraph)
    settings = renderer.settings_dict(scene.bxdf_lab_render, "viewport")
    expected = renderer.render(data, settings, None)[0]
    assert expected[..., :3].max() > 0.05  # the sphere is in view and lit
    region_data = type("R", (), {"view_matrix": view, "window_matrix": window, "is_perspective": False})()
    got = renderer.render(dict(data, camera=viewport.view_camera(region_data, (0.01, 1000.0), width, height),
                               resolution=(width, height)), settings, None)[0]
    assert np.abs(got - expected).max() < 1e-4

    # The same view from 5 units further ahead, near plane 4.9 behind the eye (the shift as offset).
    half_w, half_h = 3.5 / 2, 3.5 / 2 * height / width
    dx, dy = camera.shift_x * 3.5, camera.shift_y * 3.5
    ahead = mathutils.Matrix.Translation((0, 0, 5.0)) @ view  # view space moves +Z: the eye −Z
    free = _orthographic_window(dx - half_w, dx + half_w, dy - half_h, dy + half_h, 0.1 - 5.0, 100.0 - 5.0)
    region_data = type("R", (), {"view_matrix": ahead, "window_matrix": free, "is_perspective": False})()
    got = renderer.render(dict(data, camera=viewport.view_camera(region_data, (0.01, 1000.0), width, height),
                               resolution=(width, height)), settings, None)[0]
    assert np.abs(got - expected).max() < 1e-3


def test_an_orthographic_view_renders_in_the_session(scene):
    engine, display = StandInEngine(), RecordingDisplay()
    session = viewport.ViewportSession(display=display, start_timer=False)
    view = mathutils.Matrix.Translation((0, 0, -6.0)) @ mathutils.Matrix.Rotation(math.radians(-90), 4, "X")
    context = _context(scene, 24, 16, view, _orthographic_window(-3, 3, -2, 2, -50, 50), perspective=False)
    depsgraph = bpy.context.evaluated_depsgraph_get()
    session.update(context, depsgraph, [])
    session.draw(context, depsgraph, engine)
    _wait(session.job)
    session.draw(context, depsgraph, engine)
    assert session.job.error == "" and "4 samples per pixel" in engine.stats
    image = display.drawn[-1][0].image
    assert image.shape == (16, 24, 4) and image[..., :3].max() > 0.05
    session.stop()


def _session_image(context):
    """The finished viewport render of `context` and the rectangle it was drawn over."""
    display = RecordingDisplay()
    session = viewport.ViewportSession(display=display, start_timer=False)
    depsgraph = bpy.context.evaluated_depsgraph_get()
    session.update(context, depsgraph, [])
    session.draw(context, depsgraph, StandInEngine())
    _wait(session.job)
    session.draw(context, depsgraph, StandInEngine())
    assert session.job.error == ""
    image, rect = session.job.image, display.drawn[-1][3]
    session.stop()
    return image, rect


def _zoomed_out_camera_view(scene, size):
    """A camera view of `size`² pixels showing twice the camera's field: the frame fills the
    middle half of the view, [0.25, 0.75]² (the shift scales with it)."""
    view, window = _camera_view(scene, scene.camera, size, size)
    return view, mathutils.Matrix.Diagonal((0.5, 0.5, 1.0, 1.0)) @ window


def _crop(image, region):
    """bxdf.render's `region` (rows from the top) out of a bottom-up image."""
    x0, top, x1, bottom = region
    height = image.shape[0]
    return image[height - bottom:height - top, x0:x1]


@pytest.mark.parametrize("case", ["view_border", "scene_border", "passepartout"])
def test_the_viewport_renders_only_the_render_region(scene, case):
    """As Cycles' viewport: a free view renders its own region; through the camera, the scene's
    region inside the camera frame, or the frame alone behind an opaque passepartout. The pixels
    are the whole view's and the image is drawn over its own part of the region."""
    size = 50
    scene.render.resolution_x = scene.render.resolution_y = size
    scene.render.resolution_percentage = 100
    view, window = _zoomed_out_camera_view(scene, size)
    if case == "view_border":
        context = _context(scene, size, size, view, window, view_border=(0.31, 0.11, 0.69, 0.53))
        expected_region = (15, 24, 34, 45)  # x 15.5 -> 15, 34.5 -> 34; y 5.5 -> 5, 26.5 -> 26
    elif case == "scene_border":
        scene.render.use_border = True
        scene.render.border_min_x, scene.render.border_max_x = 0.2, 0.6
        scene.render.border_min_y, scene.render.border_max_y = 0.12, 0.52
        context = _context(scene, size, size, view, window, view_perspective="CAMERA")
        expected_region = (17, 25, 27, 35)  # the frame's 0.35..0.55 x 0.31..0.51 of the view
    else:
        scene.camera.data.show_passepartout, scene.camera.data.passepartout_alpha = True, 1.0
        context = _context(scene, size, size, view, window, view_perspective="CAMERA")
        expected_region = (12, 13, 37, 38)  # the frame: 0.25..0.75 of the view
    image, rect = _session_image(context)
    whole, whole_rect = _session_image(_context(scene, size, size, view, window))
    x0, top, x1, bottom = expected_region
    assert image.shape == (bottom - top, x1 - x0, 4)
    assert np.array_equal(image, _crop(whole, expected_region))
    assert rect == (x0, size - bottom, x1 - x0, bottom - top) and whole_rect == (0, 0, size, size)
    assert whole[..., :3].max() > 0.05 and not render_report.last("viewport").warnings


@pytest.mark.parametrize("view_perspective, view_border, scene_border", [
    ("PERSP", None, True),                    # the scene's region is not the free view's
    ("CAMERA", (0.2, 0.2, 0.4, 0.4), False),  # nor the view's own region the camera view's
    ("CAMERA", None, False),                  # a translucent passepartout (the default 0.5)
])
def test_a_render_region_of_another_kind_of_view_is_not_applied(scene, view_perspective, view_border,
                                                                  scene_border):
    scene.render.use_border = scene_border
    view, window = _zoomed_out_camera_view(scene, 16)
    image, rect = _session_image(_context(scene, 16, 16, view, window, view_perspective=view_perspective,
                                          view_border=view_border))
    assert image.shape == (16, 16, 4) and rect == (0, 0, 16, 16)


def test_a_border_covers_at_least_one_pixel_inside_the_view():
    assert renderer.border_pixels((0.0, 0.0, 1.0, 1.0), 40, 20) == (0, 0, 40, 20)
    assert renderer.border_pixels((0.5, 0.5, 0.5, 0.5), 40, 20) == (20, 9, 21, 10)
    assert renderer.border_pixels((1.0, 1.0, 1.0, 1.0), 40, 20) == (39, 0, 40, 1)


def test_the_view_renders_with_f12s_bounces_in_passes_that_size_themselves(scene):
    # As Cycles' viewport: the Light Paths of F12 (glass seen through the view is F12's glass);
    # only the material preview's small scene is cut to fewer bounces.
    s = scene.bxdf_lab_render
    s.max_bounces = 12
    final = renderer.settings_dict(s, "final")
    view = renderer.settings_dict(s, "viewport")
    assert view["max_bounces"] == final["max_bounces"] == 12
    assert view["samples"] == s.viewport_samples and view["progressive"]
    assert renderer.settings_dict(s, "preview")["max_bounces"] == renderer.PREVIEW_MAX_BOUNCES < 12
    assert "progressive" not in final  # F12's passes are for its partial results (engine.py)


def test_the_pixel_size_is_blenders_viewport_pixel_size_as_cycles_reads_it():
    scene = bpy.context.scene
    assert scene.render.preview_pixel_size == "AUTO"  # Blender's default, as for Cycles
    assert bpy.context.preferences.system.pixel_size < 1.5 and viewport.preview_pixel_size(scene) == 1
    for setting, size in (("1", 1), ("2", 2), ("4", 4), ("8", 8)):
        scene.render.preview_pixel_size = setting
        assert viewport.preview_pixel_size(scene) == size


def test_the_drawn_rectangle_stretches_with_the_pixel_size():
    region = type("Region", (), {"width": 101, "height": 60})()
    assert viewport._draw_rect(None, 50, 30, region) == (0, 0, 101, 60)
    # Columns 10..20 of 50 over 101 pixels; rows 5..15 from the top of 30 are 15..25 from the bottom.
    assert viewport._draw_rect((10, 5, 20, 15), 50, 30, region) == (20, 30, 20, 20)


def test_a_broken_material_is_reported_in_the_viewport(scene, material):
    material.bxdf_lab.oren_nayar.sigma = float("nan")
    engine = StandInEngine()
    session = viewport.ViewportSession(display=RecordingDisplay(), start_timer=False)
    view, window = _camera_view(scene, scene.camera, 16, 16)
    context = _context(scene, 16, 16, view, window)
    depsgraph = bpy.context.evaluated_depsgraph_get()
    session.update(context, depsgraph, [])
    session.draw(context, depsgraph, engine)
    assert session.job is None and "sigma" in engine.stats
    report = render_report.last("viewport")
    assert report.naming(material.name) and "sigma" in report.errors[0]


def test_a_free_view_renders_when_the_scene_camera_is_not_a_camera_object(scene):
    # Blender lets any object be the scene camera; the viewport has its own camera, so it renders
    # and says nothing of the scene camera (an F12 render names it: test_camera_cycles.py).
    empty = bpy.data.objects.new("viewpoint", None)
    scene.collection.objects.link(empty)
    view, window = _camera_view(scene, scene.camera, 16, 16)  # a view that happens to sit there
    scene.camera = empty
    engine = StandInEngine()
    session = viewport.ViewportSession(display=RecordingDisplay(), start_timer=False)
    context = _context(scene, 16, 16, view, window)
    depsgraph = bpy.context.evaluated_depsgraph_get()
    session.update(context, depsgraph, [])
    session.draw(context, depsgraph, engine)
    assert session.job is not None
    _wait(session.job)
    assert session.job.error == "" and session.job.image.mean() > 0.0
    report = render_report.last("viewport")
    assert report.errors == [] and report.warnings == []
    session.stop()
