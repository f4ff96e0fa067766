"""The BXDF_LAB render engine: errors are reported and recorded, never swallowed or faked, and a
failed render writes no file."""

import os
import time

import bpy
import pytest

from bxdf_lab import api, engine, render_report, renderer


@pytest.fixture
def small_scene(material, tmp_path):
    scene = bpy.context.scene
    mesh = bpy.data.meshes.new("plane")
    mesh.from_pydata([(-1, -1, 0), (1, -1, 0), (1, 1, 0), (-1, 1, 0)], [], [(0, 1, 2, 3)])
    mesh.materials.append(material)
    scene.collection.objects.link(bpy.data.objects.new("plane", mesh))
    cam = bpy.data.objects.new("cam", bpy.data.cameras.new("cam"))
    cam.location = (0, 0, 5)
    scene.collection.objects.link(cam)
    scene.camera = cam
    scene.render.engine = "BXDF_LAB"
    scene.render.resolution_x = scene.render.resolution_y = 16
    scene.render.resolution_percentage = 100
    scene.render.filepath = str(tmp_path / "out.exr")
    scene.render.image_settings.file_format = "OPEN_EXR"
    return scene


def test_a_broken_setting_gives_a_reported_error_and_no_file(small_scene, material):
    api.assign(material, "lambertian")
    material.bxdf_lab.lambertian.reflectance = (0.5, float("nan"), 0.5)  # typed through Python
    # The engine's self.report({'ERROR'}) reaches the caller of the operator.
    with pytest.raises(RuntimeError, match="Test Material.*reflectance"):
        bpy.ops.render.render(write_still=True)
    assert "Test Material" in engine.last_error and "reflectance" in engine.last_error
    assert engine.last_cancelled
    assert not os.path.exists(small_scene.render.filepath)


def test_a_render_needs_the_renderer_and_never_fakes_one(small_scene, material, bxdf):
    api.assign(material, "lambertian")
    if hasattr(bxdf, "render"):
        bpy.ops.render.render(write_still=True)
        assert engine.last_error == ""
        assert os.path.exists(small_scene.render.filepath)
    else:
        with pytest.raises(RuntimeError, match="no renderer"):
            bpy.ops.render.render(write_still=True)
        assert "bxdf.render is missing" in engine.last_error
        assert not os.path.exists(small_scene.render.filepath)


def test_render_settings_live_on_the_scene(small_scene):
    settings = small_scene.bxdf_lab_render
    assert (settings.samples, settings.max_bounces, settings.pixel_filter, settings.threads,
            settings.seed) == (64, 8, "BLACKMAN_HARRIS", 0, 0)
    with pytest.raises(TypeError):
        settings.pixel_filter = "NO_SUCH_FILTER"


def test_a_finished_render_reports_where_its_time_went(small_scene, material, bxdf):
    assert hasattr(bxdf, "render"), "this build of bxdf has no renderer"
    api.assign(material, "lambertian")
    small_scene.bxdf_lab_render.samples = 2
    started = time.perf_counter()
    bpy.ops.render.render(write_still=False)
    operator_seconds = time.perf_counter() - started
    timings = render_report.last("render").timings
    assert tuple(timings) == engine.PHASES
    # Each phase is a part of the engine's render, and the parts add up to it.
    for phase in engine.PHASES:
        assert timings[phase] >= -1e-4, (phase, timings)
    assert min(timings["export"], timings["render"], timings["hand_back"]) > 0.0, timings
    assert timings["total"] == pytest.approx(sum(timings[p] for p in engine.PHASES[:-1]), abs=1e-9)
    assert timings["total"] <= operator_seconds


def test_partial_results_are_shown_at_their_interval(small_scene, material, monkeypatch):
    # Every redraw one causes takes a core from the render without a GPU: a render calling back
    # with an image every 0.1 s for 10 s shows a partial result every PARTIAL_RESULT_INTERVAL
    # (the first after as long), then the final image.
    api.assign(material, "lambertian")
    clock = [1000.0]
    monkeypatch.setattr(engine.time, "perf_counter", lambda: clock[0])
    shown = []
    real_pixels = engine.pixels_for_blender
    monkeypatch.setattr(engine, "pixels_for_blender",
                        lambda image, w, h: shown.append(clock[0]) or real_pixels(image, w, h))
    real_render = renderer.render

    def render(scene_data, settings, on_progress, partial_images=True):
        image, stats = real_render(scene_data, settings, None, False)
        for k in range(100):
            clock[0] += 0.1
            assert on_progress(k, 100, image) is True
        return image, stats

    monkeypatch.setattr(renderer, "render", render)
    bpy.ops.render.render(write_still=True)
    assert engine.last_error == ""
    partials = shown[:-1]  # the last is the final image
    assert len(partials) == int(10.0 / engine.PARTIAL_RESULT_INTERVAL + 1e-6)
    assert partials[0] - 1000.0 == pytest.approx(engine.PARTIAL_RESULT_INTERVAL, abs=0.11)
    assert all(b - a >= engine.PARTIAL_RESULT_INTERVAL - 1e-6 for a, b in zip(partials, partials[1:]))


def test_blender_without_a_window_asks_for_no_partial_images(small_scene, material, bxdf, monkeypatch):
    assert bpy.app.background  # the Blender tests run in blender -b
    api.assign(material, "lambertian")
    small_scene.bxdf_lab_render.samples = 16  # several passes
    asked = []
    real_render = renderer.render

    def render(scene_data, settings, on_progress, partial_images=True):
        asked.append(partial_images)
        return real_render(scene_data, settings, on_progress, partial_images)

    monkeypatch.setattr(renderer, "render", render)
    bpy.ops.render.render(write_still=True)
    assert asked == [False] and engine.last_error == ""
    assert os.path.exists(small_scene.render.filepath)
