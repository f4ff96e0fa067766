"""A scene camera that is not a camera object, against Cycles: Blender lets any object be the
scene's camera, and Cycles renders through it (an empty with its default 50 mm camera, a light
with its spot size as the field of view). BXDF_LAB frames the same picture and names the object
in a warning; the export (which the viewport shares) does not fail."""

import math

import bpy
import numpy as np
import pytest
from mathutils import Vector

import pairing_scene
from bxdf_lab import export, render_report

SIZE = 32


def _scene_seen_by(camera_obj):
    scene = bpy.context.scene
    pairing_scene.uniform_world(scene, (1.0, 1.0, 1.0))
    pairing_scene.exr_output(scene, SIZE, SIZE * 3 // 4)  # wider than tall: automatic fit is horizontal
    pairing_scene.exact_pairing_settings(scene, 64, 0, seed=5)
    white = pairing_scene.lambertian_material("white")
    # Off-centre spheres on a floor: a wrong field of view or frame moves their edges.
    for location, radius in (((0.9, 0.0, 0.5), 0.5), ((-1.2, 1.0, 0.3), 0.3)):
        bpy.ops.mesh.primitive_uv_sphere_add(radius=radius, location=location)
        bpy.context.active_object.data.materials.append(white)
    bpy.ops.mesh.primitive_plane_add(size=40.0)
    bpy.context.active_object.data.materials.append(pairing_scene.lambertian_material("floor", 0.3))
    location, target = Vector((1.0, -5.0, 2.5)), Vector((0.0, 0.0, 0.4))
    camera_obj.location = location
    camera_obj.rotation_euler = (target - location).to_track_quat("-Z", "Y").to_euler()
    camera_obj.scale = (2.0, 0.5, 3.0)  # ignored by the view, as in Blender
    scene.collection.objects.link(camera_obj)
    scene.camera = camera_obj
    return scene


def _empty():
    return bpy.data.objects.new("viewpoint", None)


def _light(kind, spot_degrees=None):
    light = bpy.data.lights.new("viewpoint", kind)
    light.energy = 0.0  # it is only a viewpoint here
    if spot_degrees is not None:
        light.spot_size = math.radians(spot_degrees)
    return bpy.data.objects.new("viewpoint", light)


@pytest.mark.parametrize("make, lens", [
    (_empty, 50.0),
    (lambda: _light("SPOT", 70.0), 16.0 / math.tan(math.radians(35.0))),
    (lambda: _light("POINT"), 16.0 / math.tan(math.radians(22.5))),  # Blender's default spot size
], ids=["empty", "spot", "point"])
def test_a_non_camera_object_as_the_scene_camera_frames_as_cycles(make, lens, tmp_path):
    scene = _scene_seen_by(make())
    camera = export.export_scene(bpy.context.evaluated_depsgraph_get())["camera"]
    assert camera["lens"] == pytest.approx(lens, rel=1e-6)
    assert "'viewpoint'" in camera["warning"]

    ours = pairing_scene.render_rgba(scene, "BXDF_LAB", tmp_path / "ours.exr")[..., :3]
    warnings = render_report.last("render").warnings
    assert any("scene camera 'viewpoint'" in w and "not a camera" in w for w in warnings), warnings
    cycles = pairing_scene.render_rgba(scene, "CYCLES", tmp_path / "cycles.exr")[..., :3]
    # 4×4 tiles: the silhouettes sit where Cycles puts them (a 50 mm lens against the spot's
    # 23 mm moves every edge by several pixels).
    h, w = cycles.shape[:2]
    tiles = [img.reshape(h // 4, 4, w // 4, 4, 3).mean(axis=(1, 3)) for img in (ours, cycles)]
    worst = np.abs(tiles[0] - tiles[1]).max()
    assert worst < 0.05 * cycles.max(), worst
