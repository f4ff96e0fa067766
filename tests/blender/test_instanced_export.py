"""Shared geometry leaves Blender once: linked duplicates, collection instances and geometry-nodes
instances export one mesh and a matrix each, and the renderer stores that mesh once (Embree
instances); objects with geometry of their own (modifiers, object-linked materials) do not share.
Linked duplicates, mirrored and non-uniformly scaled among them, render as Cycles renders them."""

import math

import bpy
import numpy as np

import pairing_scene
from bxdf_lab import export, renderer

SIZE = 32


_diffuse = pairing_scene.lambertian_material


def _ball(material, segments=32, rings=16):
    bpy.ops.mesh.primitive_uv_sphere_add(segments=segments, ring_count=rings, radius=0.5)
    bpy.ops.object.shade_smooth()
    obj = bpy.context.active_object
    obj.name = "ball"
    obj.data.materials.append(material)
    return obj


def _duplicate(obj, name, location, scale=(1, 1, 1), rotation=(0, 0, 0)):
    """A linked duplicate: a new object showing the same mesh datablock."""
    dup = bpy.data.objects.new(name, obj.data)
    dup.location, dup.scale, dup.rotation_euler = location, scale, rotation
    bpy.context.scene.collection.objects.link(dup)
    return dup


def _instance_on_points(owner, instanced):
    """Geometry nodes on `owner`: `instanced`'s geometry on each of owner's vertices."""
    tree = bpy.data.node_groups.new("scatter", "GeometryNodeTree")
    tree.inputs.new("NodeSocketGeometry", "Geometry")
    tree.outputs.new("NodeSocketGeometry", "Geometry")
    group_in, group_out = tree.nodes.new("NodeGroupInput"), tree.nodes.new("NodeGroupOutput")
    on_points = tree.nodes.new("GeometryNodeInstanceOnPoints")
    info = tree.nodes.new("GeometryNodeObjectInfo")
    info.inputs["Object"].default_value = instanced
    tree.links.new(group_in.outputs[0], on_points.inputs["Points"])
    tree.links.new(info.outputs["Geometry"], on_points.inputs["Instance"])
    tree.links.new(on_points.outputs[0], group_out.inputs[0])
    owner.modifiers.new("scatter", "NODES").node_group = tree


def test_shared_geometry_is_exported_once_and_stored_once(bxdf):
    white, red = _diffuse("white"), _diffuse("red")
    ball = _ball(white)
    n_triangles = sum(len(p.vertices) - 2 for p in ball.data.polygons)
    _duplicate(ball, "rotated", (1.5, 0, 0), rotation=(0.3, 0.2, 1.0))
    _duplicate(ball, "mirrored", (-1.5, 0, 0), scale=(-1, 1, 1))
    # Geometry of its own: a modifier, or a material linked to the object instead of the mesh.
    smooth = _duplicate(ball, "subdivided", (0, 1.5, 0))
    smooth.modifiers.new("subsurf", "SUBSURF")
    own_material = _duplicate(ball, "red_one", (0, -1.5, 0))
    own_material.material_slots[0].link = "OBJECT"
    own_material.material_slots[0].material = red
    # A collection instance of the ball, and geometry-nodes instances of it on a grid's 4 points.
    group = bpy.data.collections.new("balls")
    group.objects.link(ball)
    holder = bpy.data.objects.new("holder", None)
    holder.instance_type, holder.instance_collection = "COLLECTION", group
    holder.location = (0, 0, 2)
    bpy.context.scene.collection.objects.link(holder)
    bpy.ops.mesh.primitive_plane_add(size=2, location=(0, 0, -3))
    _instance_on_points(bpy.context.active_object, ball)
    bpy.context.scene.camera = bpy.data.objects.new("cam", bpy.data.cameras.new("cam"))
    bpy.context.scene.collection.objects.link(bpy.context.scene.camera)
    bpy.context.scene.camera.location = (0, -12, 4)

    data = export.export_scene(bpy.context.evaluated_depsgraph_get())
    counts = np.bincount(data["instance_mesh"], minlength=len(data["meshes"]))
    by_size = {}
    for mesh, count in zip(data["meshes"], counts):
        by_size.setdefault(len(mesh["triangles"]), []).append(int(count))
    # The ball's mesh: once for ball, rotated, mirrored and the collection instance (4 placements)
    # plus once for the red object; geometry-nodes instances share one copy of their own (Blender
    # evaluates the Object Info geometry into a datablock of its own), 4 placements.
    assert sorted(by_size[n_triangles]) == [1, 4, 4], by_size
    # ... and the subdivided object its own, larger mesh: 4 meshes for 10 placements in all.
    assert len(data["meshes"]) == 4 and len(data["instance_mesh"]) == 10
    assert [int(c) for m, c in zip(data["meshes"], counts) if len(m["triangles"]) > n_triangles] == [1]
    assert data["instance_matrix"].shape == (len(data["instance_mesh"]), 4, 4)

    settings = renderer.settings_dict(bpy.context.scene.bxdf_lab_render)
    settings.update(samples=1, threads=2)
    _, stats = renderer.render(data, settings, None)
    drawn = sum(len(data["meshes"][i]["triangles"]) for i in data["instance_mesh"])
    assert stats["triangles"] == drawn
    assert stats["instances"] == 8  # the two shared meshes' placements; the rest moved to world space
    assert stats["stored_triangles"] == drawn - 6 * n_triangles


def _scene(samples):
    scene = bpy.context.scene
    pairing_scene.add_camera(scene, (0, -7, 4), (0, 0, 0.3))
    pairing_scene.uniform_world(scene, (0.05, 0.05, 0.05))
    pairing_scene.exr_output(scene, SIZE)
    pairing_scene.exact_pairing_settings(scene, samples, 2, seed=5)
    return scene


def _render(scene, engine_id, path):
    return pairing_scene.render_rgba(scene, engine_id, path)[..., :3]


def test_linked_duplicates_render_like_cycles(tmp_path):
    scene = _scene(256)
    ball = _ball(_diffuse("white"))
    ball.location = (0, 0, 0.5)
    _duplicate(ball, "stretched", (1.4, 0.3, 0.45), scale=(1.3, 0.7, 0.9), rotation=(0.4, 0, 0.9))
    _duplicate(ball, "mirrored", (-1.4, 0.2, 0.6), scale=(-1.2, 1.2, 1.2), rotation=(0, 0.5, 0.3))
    bpy.ops.mesh.primitive_plane_add(size=20)
    bpy.context.active_object.data.materials.append(_diffuse("floor", 0.5))
    sun = bpy.data.objects.new("sun", bpy.data.lights.new("sun", "SUN"))
    sun.data.energy, sun.data.angle = 3.0, math.radians(10.0)
    sun.rotation_euler = (math.radians(35), 0, math.radians(25))
    scene.collection.objects.link(sun)
    data = export.export_scene(bpy.context.evaluated_depsgraph_get())
    assert len(data["meshes"]) == 2 and len(data["instance_mesh"]) == 4  # ball once, floor once

    ours = _render(scene, "BXDF_LAB", tmp_path / "bxdf_lab.exr")
    cycles = _render(scene, "CYCLES", tmp_path / "cycles.exr")
    assert cycles.mean() > 0.05
    # Means over 8×8 tiles agree within 3% (noise averages out; a misplaced or mis-shaded
    # duplicate moves whole tiles), dark tiles against 2% of the image's mean.
    block = 8

    def tiles(img):
        return img.reshape(SIZE // block, block, SIZE // block, block, 3).mean(axis=(1, 3))
    a, b = tiles(ours), tiles(cycles)
    worst = np.abs(a - b) / np.maximum(b, 0.02 * cycles.mean())
    assert worst.max() < 0.03, f"worst tile differs by {worst.max():.3%}"
