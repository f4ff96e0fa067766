"""Builds a SceneSpec into the current bpy scene (runs inside Blender only).

Spheres are smooth-shaded UV spheres of 128 x 64 segments: the silhouette and the interpolated
normals are then within about 3e-4 of the true sphere (analytic.py turns that into a per-pixel
tolerance), and the few silhouette pixels where mesh and sphere disagree are masked out of the
diffs (metrics.edge_mask)."""
from __future__ import annotations

import math
import os

import bmesh
import bpy
from mathutils import Matrix, Vector

from . import gradient_world
from .scene_spec import (AreaLight, Box, EnvironmentMap, PointLight, Quad, SceneSpec, Sphere,
                         SpotLight, SunLight, ZGradientWorld)

SPHERE_SEGMENTS = 128
SPHERE_RINGS = 64


def clear_scene():
    for collection in (bpy.data.objects, bpy.data.meshes, bpy.data.materials, bpy.data.lights,
                       bpy.data.cameras):
        for block in list(collection):
            collection.remove(block)


def _link(name, data):
    obj = bpy.data.objects.new(name, data)
    bpy.context.scene.collection.objects.link(obj)
    return obj


def _mesh_from_bmesh(name, bm, smooth):
    mesh = bpy.data.meshes.new(name)
    for face in bm.faces:
        face.smooth = smooth
    bm.to_mesh(mesh)
    bm.free()
    return mesh


def _sphere_mesh(sphere: Sphere):
    bm = bmesh.new()
    bmesh.ops.create_uvsphere(bm, u_segments=SPHERE_SEGMENTS, v_segments=SPHERE_RINGS,
                              radius=sphere.radius)
    return _mesh_from_bmesh(sphere.name, bm, smooth=True)


def _quad_mesh(quad: Quad):
    """The quad with UVs (0, 0), (1, 0), (1, 1), (0, 1) at its corners (for textured materials)."""
    mesh = bpy.data.meshes.new(quad.name)
    mesh.from_pydata([tuple(map(float, c)) for c in quad.corners], [], [(0, 1, 2, 3)])
    uv_layer = mesh.uv_layers.new(name="UVMap")
    for loop, uv in zip(uv_layer.data, ((0, 0), (1, 0), (1, 1), (0, 1))):
        loop.uv = uv
    return mesh


def _box_mesh(box: Box):
    bm = bmesh.new()
    bmesh.ops.create_cube(bm, size=1.0)
    bmesh.ops.scale(bm, vec=Vector(box.size), verts=bm.verts)
    return _mesh_from_bmesh(box.name, bm, smooth=False)


def look_at_rotation(location, target):
    """Blender cameras look along local -Z with +Y up; world +Z is up."""
    direction = Vector(target) - Vector(location)
    return direction.to_track_quat("-Z", "Y")


def _aim(obj, direction):
    """Blender lights shine along their local -Z."""
    obj.rotation_mode = "QUATERNION"
    obj.rotation_quaternion = Vector(direction).to_track_quat("-Z", "Y")


def _build_light(i, light):
    if isinstance(light, (PointLight, SpotLight)):
        kind = "POINT" if isinstance(light, PointLight) else "SPOT"
        data = bpy.data.lights.new(f"{kind.lower()}_{i}", kind)
        data.energy = 4.0 * math.pi * light.intensity   # I = P / (4 pi)
        data.shadow_soft_size = light.radius
        obj = _link(data.name, data)
        obj.location = light.location
        if kind == "SPOT":
            data.spot_size = math.radians(light.spot_size_deg)
            data.spot_blend = light.blend
            _aim(obj, light.direction)
    elif isinstance(light, SunLight):
        data = bpy.data.lights.new(f"sun_{i}", "SUN")
        data.energy = light.irradiance
        data.angle = math.radians(light.angle_deg)
        # A sun shines away from `direction`.
        _aim(_link(f"sun_{i}", data), -Vector(light.direction))
    elif isinstance(light, AreaLight):
        data = bpy.data.lights.new(f"area_{i}_{light.shape.lower()}", "AREA")
        data.shape = light.shape
        data.size = light.size
        data.size_y = light.size_y if light.shape in ("RECTANGLE", "ELLIPSE") else light.size
        data.energy = light.power
        obj = _link(data.name, data)
        obj.location = light.center
        _aim(obj, light.direction)
    else:
        raise TypeError(f"unknown light {light!r}")
    data.color = light.color


def _environment_image(environment, work_dir):
    """The image file of the world: the map's own, or the z-gradient written into work_dir."""
    if isinstance(environment, EnvironmentMap):
        return bpy.data.images.load(environment.path, check_existing=True)
    from . import imageio  # noqa: PLC0415 - OpenImageIO is needed only for a generated world

    # Every engine's job of the scene writes the same file: each writes its own and renames it
    # into place, so that no job reads another's half-written image.
    path = os.path.join(work_dir, f"z_gradient_{environment.a:g}_{environment.b:g}.exr")
    partial = f"{path}.{os.getpid()}.exr"
    imageio.write_exr(partial, gradient_world.image(environment))
    os.replace(partial, path)
    image = bpy.data.images.load(path)
    image.colorspace_settings.name = "Linear"
    return image


def _build_world(spec, scene, work_dir):
    """Background colour, or an Environment Texture fed by Texture Coordinate > Mapping (the
    rotation about +Z), as a user builds an HDRI world."""
    world = scene.world or bpy.data.worlds.new("world")
    scene.world = world
    world.use_nodes = True
    world.color = spec.world_color
    tree = world.node_tree
    background = tree.nodes["Background"]
    background.inputs["Color"].default_value = (*spec.world_color, 1.0)
    background.inputs["Strength"].default_value = 1.0
    environment = spec.environment
    if environment is None:
        return
    if work_dir is None and isinstance(environment, ZGradientWorld):
        raise ValueError(f"scene '{spec.name}': a z-gradient world needs a work_dir to write "
                         "its image to")
    coords = tree.nodes.new("ShaderNodeTexCoord")
    mapping = tree.nodes.new("ShaderNodeMapping")
    texture = tree.nodes.new("ShaderNodeTexEnvironment")
    texture.image = _environment_image(environment, work_dir)
    rotation = getattr(environment, "rotation_z_deg", 0.0)
    mapping.inputs["Rotation"].default_value = (0.0, 0.0, math.radians(rotation))
    tree.links.new(coords.outputs["Generated"], mapping.inputs["Vector"])
    tree.links.new(mapping.outputs["Vector"], texture.inputs["Vector"])
    tree.links.new(texture.outputs["Color"], background.inputs["Color"])
    background.inputs["Strength"].default_value = getattr(environment, "strength", 1.0)
    if environment.map_resolution:
        world.cycles.sampling_method = "MANUAL"
        world.cycles.sample_map_resolution = environment.map_resolution


def build(spec: SceneSpec, materials: dict, work_dir: str = None) -> dict:
    """Builds camera, lights, world and objects; `materials` maps material name -> bpy material
    (made by the caller so that each engine's set-up can fill it); `work_dir` receives generated
    files (a z-gradient world's image). Returns {object name: bpy object}."""
    scene = bpy.context.scene
    scene.render.resolution_x, scene.render.resolution_y = spec.resolution
    scene.render.resolution_percentage = 100

    cam_data = bpy.data.cameras.new("camera")
    cam_data.lens = spec.camera.lens_mm
    cam_data.sensor_width = spec.camera.sensor_width_mm
    cam_data.sensor_fit = "HORIZONTAL"
    cam_data.clip_start = 0.01
    cam_data.clip_end = 1000.0
    camera = _link("camera", cam_data)
    camera.location = spec.camera.location
    camera.rotation_mode = "QUATERNION"
    camera.rotation_quaternion = look_at_rotation(spec.camera.location, spec.camera.look_at)
    scene.camera = camera

    for i, light in enumerate(spec.lights):
        _build_light(i, light)
    _build_world(spec, scene, work_dir)

    objects = {}
    for item in spec.objects:
        if isinstance(item, Sphere):
            obj = _link(item.name, _sphere_mesh(item))
            obj.location = item.center
        elif isinstance(item, Quad):
            obj = _link(item.name, _quad_mesh(item))
        elif isinstance(item, Box):
            obj = _link(item.name, _box_mesh(item))
            obj.matrix_world = (Matrix.Translation(item.center)
                                @ Matrix.Rotation(math.radians(item.rotation_z_deg), 4, "Z"))
        else:
            raise TypeError(f"unknown object {item!r}")
        obj.data.materials.append(materials[item.material.name])
        objects[item.name] = obj
    return objects
