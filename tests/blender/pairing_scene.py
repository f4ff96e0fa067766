"""Set-up shared by the Blender tests that render one scene with BXDF_LAB and with Cycles and
compare the images: a camera, a uniform world, float EXR output, both engines' settings for an
exact pairing (pixel centres, no clamping, denoising or adaptive sampling), and the render read
back as an array."""

import bpy
import numpy as np
from mathutils import Vector

from bxdf_lab import api, engine


def lambertian_material(name, reflectance=0.8):
    """A Lambertian BxDF Lab material with its exact Cycles set-up (a Diffuse BSDF)."""
    material = bpy.data.materials.new(name)
    api.assign(material, "lambertian", reflectance=(reflectance,) * 3)
    with bpy.context.temp_override(material=material):
        assert bpy.ops.bxdf_lab.set_up_cycles() == {"FINISHED"}
    return material


def add_camera(scene, location, target=(0.0, 0.0, 0.0), lens=50.0, ortho_scale=None):
    """A camera at `location` looking at `target` (perspective, or orthographic of
    `ortho_scale` looking down -Z when given), made the scene's camera."""
    cam = bpy.data.objects.new("cam", bpy.data.cameras.new("cam"))
    cam.location = location
    if ortho_scale is None:
        cam.data.lens = lens
        cam.rotation_euler = Vector(np.subtract(target, location)).to_track_quat("-Z", "Y").to_euler()
    else:
        cam.data.type, cam.data.ortho_scale = "ORTHO", ortho_scale
    scene.collection.objects.link(cam)
    scene.camera = cam
    return cam


def uniform_world(scene, rgb=(0.0, 0.0, 0.0)):
    world = bpy.data.worlds.new("world")
    world.use_nodes = True
    world.node_tree.nodes["Background"].inputs["Color"].default_value = (*rgb, 1.0)
    scene.world = world
    return world


def exr_output(scene, width, height=None):
    r = scene.render
    r.resolution_x, r.resolution_y = width, height or width
    r.resolution_percentage = 100
    r.image_settings.file_format, r.image_settings.color_depth = "OPEN_EXR", "32"
    scene.view_settings.view_transform = "Standard"


def exact_pairing_settings(scene, samples, bounces, seed):
    """Both engines through pixel centres (Cycles: a Gaussian of width 0.01), at `samples` and
    `bounces`, with nothing that biases Cycles' image."""
    s = scene.bxdf_lab_render
    s.samples, s.max_bounces, s.pixel_filter, s.seed = samples, bounces, "PIXEL_CENTER", seed
    c = scene.cycles
    c.samples, c.max_bounces, c.use_denoising, c.use_adaptive_sampling = samples, bounces, False, False
    c.diffuse_bounces = c.glossy_bounces = c.transmission_bounces = bounces
    c.sample_clamp_direct = c.sample_clamp_indirect = 0.0
    c.light_sampling_threshold = 0.0
    c.pixel_filter_type, c.filter_width = "GAUSSIAN", 0.01


def render_rgba(scene, engine_id, path):
    """Renders with `engine_id` to `path` and returns the image as (height, width, 4) floats,
    bottom row first, as Blender stores it. A BXDF_LAB render must end without an error."""
    scene.render.engine = engine_id
    scene.render.filepath = str(path)
    bpy.ops.render.render(write_still=True)
    if engine_id == "BXDF_LAB":
        assert engine.last_error == ""
    image = bpy.data.images.load(str(path))
    width, height = image.size
    pixels = np.empty(width * height * 4, dtype=np.float32)
    image.pixels.foreach_get(pixels)
    bpy.data.images.remove(image)
    return pixels.reshape(height, width, 4)
