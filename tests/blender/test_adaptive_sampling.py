"""Cycles' Adaptive Sampling settings (Render Properties > Sampling), which BXDF_LAB reads as it
reads Light Paths: F12 takes the Render ones, the viewport the Viewport ones, the material preview
none; an F12 render with them on stops pixels early, says how many samples it took, and takes as
many as Cycles' (its Debug Sample Count pass)."""

import bpy
import numpy as np

import pairing_scene
from bxdf_lab import engine, render_report, renderer


def test_each_render_reads_its_own_cycles_settings_with_cycles_defaults():
    scene = bpy.context.scene
    # A new scene's, as Cycles has them: on, 0.01 for F12 and 0.1 for the viewport, minimum automatic.
    final = renderer.cycles_adaptive_sampling(scene, "final")
    assert final["adaptive_sampling"] and final["adaptive_min_samples"] == 0
    assert abs(final["adaptive_threshold"] - 0.01) < 1e-6
    view = renderer.cycles_adaptive_sampling(scene, "viewport")
    assert view["adaptive_sampling"] and abs(view["adaptive_threshold"] - 0.1) < 1e-6
    assert renderer.cycles_adaptive_sampling(scene, "preview") == {}
    c = scene.cycles
    c.use_adaptive_sampling, c.adaptive_threshold, c.adaptive_min_samples = False, 0.05, 20
    c.preview_adaptive_threshold, c.preview_adaptive_min_samples = 0.2, 8
    s = scene.bxdf_lab_render
    final = renderer.settings_dict(s, "final", renderer.cycles_settings(scene, "final"))
    assert (final["adaptive_sampling"], final["adaptive_min_samples"]) == (False, 20)
    assert abs(final["adaptive_threshold"] - 0.05) < 1e-6
    view = renderer.settings_dict(s, "viewport", renderer.cycles_settings(scene, "viewport"))
    assert view["adaptive_sampling"] and view["adaptive_min_samples"] == 8
    assert abs(view["adaptive_threshold"] - 0.2) < 1e-6
    assert "adaptive_sampling" not in renderer.settings_dict(
        s, "preview", renderer.cycles_settings(scene, "preview"))
    # Without Cycles' settings, Cycles' defaults; settings_dict without them samples every pixel.
    assert renderer.cycles_settings(None, "final")["adaptive_sampling"]
    assert "adaptive_sampling" not in renderer.settings_dict(s, "final")


def test_samples_text_tells_a_stopped_render_from_a_full_one():
    assert renderer.samples_text({"samples_per_pixel": 64, "camera_samples": 64 * 100}, 100) == \
        "64 samples per pixel"
    assert renderer.samples_text({"samples_per_pixel": 256, "camera_samples": 9700}, 100) == \
        "up to 256 samples per pixel (mean 97)"


def test_f12_with_adaptive_sampling_stops_pixels_and_reports_the_mean(tmp_path):
    scene = bpy.context.scene
    pairing_scene.uniform_world(scene, (0.5, 0.5, 0.5))
    pairing_scene.exr_output(scene, 32, 24)
    pairing_scene.exact_pairing_settings(scene, 256, 2, seed=3)
    bpy.ops.mesh.primitive_uv_sphere_add(radius=0.8, location=(0.0, 0.0, 0.0))
    bpy.context.active_object.data.materials.append(pairing_scene.lambertian_material("white"))
    pairing_scene.add_camera(scene, (0.0, -4.0, 0.0))
    scene.bxdf_lab_render.pixel_filter = "BLACKMAN_HARRIS"
    plain = pairing_scene.render_rgba(scene, "BXDF_LAB", tmp_path / "plain.exr")
    plain_report = render_report.last("render")
    assert "256 samples per pixel" in plain_report.summary and "up to" not in plain_report.summary
    # 0.002: an automatic minimum of 104 samples, the first check after 112.
    scene.cycles.use_adaptive_sampling, scene.cycles.adaptive_threshold = True, 0.002
    adaptive = pairing_scene.render_rgba(scene, "BXDF_LAB", tmp_path / "adaptive.exr")
    assert engine.last_error == ""
    summary = render_report.last("render").summary
    assert "up to 256 samples per pixel (mean " in summary, summary
    mean = float(summary.split("(mean ")[1].split(")")[0])
    assert 112 <= mean < 256
    # The world's pixels stop at the first check; the image stays the plain render's, near enough.
    assert np.isfinite(adaptive).all()
    assert np.abs(adaptive[..., :3] - plain[..., :3]).mean() < 0.02 * plain[..., :3].mean()


def _cycles_mean_samples(scene, path, samples):
    """Cycles' F12 with its Debug Sample Count pass (each pixel's samples over `samples`): the
    mean samples per pixel."""
    import OpenImageIO as oiio
    scene.view_layers[0].cycles.pass_debug_sample_count = True
    scene.render.image_settings.file_format = "OPEN_EXR_MULTILAYER"
    scene.render.engine = "CYCLES"
    scene.render.filepath = str(path)
    bpy.ops.render.render(write_still=True)
    image = oiio.ImageInput.open(str(path))
    names = list(image.spec().channelnames)
    pixels = image.read_image(format="float")
    image.close()
    channel = next(i for i, name in enumerate(names) if name.endswith("Debug Sample Count.X"))
    return float(pixels[..., channel].mean()) * samples


def test_f12_stops_pixels_as_cycles_does(tmp_path):
    # A sphere on a floor under a point light at 512 samples, both engines adaptive at Cycles'
    # default Noise Threshold: their mean samples per pixel agree (harness scenes at 512 read
    # 226.6 / 226, 86.7 / 86, 128.4 / 129: cornell, principled_showroom, the transmission sweep).
    # Not under a uniform world: there BXDF_LAB's image is far less noisy than Cycles' (the
    # harness's furnace: an MSE ratio of 0.01-0.1), so its pixels rightly stop sooner.
    scene = bpy.context.scene
    pairing_scene.uniform_world(scene, (0.0, 0.0, 0.0))
    light = bpy.data.objects.new("lamp", bpy.data.lights.new("lamp", "POINT"))
    light.data.energy, light.data.shadow_soft_size = 300.0, 0.0
    light.location = (1.5, -1.5, 2.5)
    scene.collection.objects.link(light)
    pairing_scene.exr_output(scene, 48, 36)
    pairing_scene.exact_pairing_settings(scene, 512, 3, seed=11)
    scene.bxdf_lab_render.pixel_filter = "BLACKMAN_HARRIS"
    scene.cycles.pixel_filter_type, scene.cycles.filter_width = "BLACKMAN_HARRIS", 1.5
    scene.cycles.use_adaptive_sampling, scene.cycles.adaptive_threshold = True, 0.01
    bpy.ops.mesh.primitive_uv_sphere_add(radius=0.7, location=(0.0, 0.0, 0.0))
    bpy.context.active_object.data.materials.append(pairing_scene.lambertian_material("white"))
    bpy.ops.mesh.primitive_plane_add(size=20.0, location=(0.0, 0.0, -0.7))
    bpy.context.active_object.data.materials.append(pairing_scene.lambertian_material("floor", 0.5))
    pairing_scene.add_camera(scene, (0.0, -3.5, 1.2))
    cycles_mean = _cycles_mean_samples(scene, tmp_path / "cycles.exr", 512)
    scene.render.image_settings.file_format = "OPEN_EXR"
    pairing_scene.render_rgba(scene, "BXDF_LAB", tmp_path / "ours.exr")
    summary = render_report.last("render").summary
    ours = float(summary.split("(mean ")[1].split(")")[0])
    assert 80 < cycles_mean < 400  # some pixels stopped at the first check, some went on
    assert abs(ours - cycles_mean) < 0.15 * cycles_mean, (ours, cycles_mean)
