""""Compare Renders": each engine renders to EXR with fair settings, the images are put side by
side, and the scene's settings are restored afterwards."""

import math

import bpy
import numpy as np

from bxdf_lab import api, compare


def test_compare_renders_every_available_engine_side_by_side(material, bxdf, tmp_path):
    api.assign(material, "lambertian", reflectance=(0.6, 0.4, 0.2))
    scene = bpy.context.scene
    mesh = bpy.data.meshes.new("plane")
    mesh.from_pydata([(-10, -10, 0), (10, -10, 0), (10, 10, 0), (-10, 10, 0)], [], [(0, 1, 2, 3)])
    mesh.materials.append(material)
    scene.collection.objects.link(bpy.data.objects.new("plane", mesh))
    sun = bpy.data.lights.new("sun", "SUN")
    sun.energy, sun.angle = math.pi, 0.0
    scene.collection.objects.link(bpy.data.objects.new("sun", sun))
    cam = bpy.data.objects.new("cam", bpy.data.cameras.new("cam"))
    cam.location = (0, 0, 5)
    scene.collection.objects.link(cam)
    scene.camera = cam
    scene.render.resolution_x = scene.render.resolution_y = 8
    scene.render.resolution_percentage = 100
    scene.bxdf_lab_render.samples = 4
    with bpy.context.temp_override(material=material):
        assert bpy.ops.bxdf_lab.set_up_cycles() == {"FINISHED"}
        assert bpy.ops.bxdf_lab.set_up_povray() == {"FINISHED"}
    before = (scene.render.engine, scene.render.filepath, scene.cycles.samples, material.use_nodes)

    results, image = compare.compare(scene, str(tmp_path))

    assert results["CYCLES"][0] and results["POVRAY_RENDER"][0], results
    assert results["BXDF_LAB"][0] == hasattr(bxdf, "render"), results
    rendered = [e for e in compare.ENGINES if results[e][0]]
    assert tuple(image.size) == (8 * len(rendered), 8)
    pixels = np.empty(8 * 8 * len(rendered) * 4, dtype=np.float32)
    image.pixels.foreach_get(pixels)
    pixels = pixels.reshape(8, 8 * len(rendered), 4)[:, :, :3]
    # a Lambertian plane under a sun of irradiance π straight above: radiance = R
    np.testing.assert_allclose(pixels.reshape(-1, 3), np.broadcast_to((0.6, 0.4, 0.2), (pixels.size // 3, 3)),
                               rtol=5e-3, atol=5e-4)
    assert (scene.render.engine, scene.render.filepath, scene.cycles.samples, material.use_nodes) == before
