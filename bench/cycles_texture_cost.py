"""Cycles' own cost of texturing, on the scene of bench/render/bench_textured.cpp.

    blender -b --factory-startup --python-exit-code 1 --python bench/cycles_texture_cost.py

The same floor and two smooth UV spheres under a point light and a grey world, seen by the same
camera, with a Mix of Diffuse and Glossy (GGX): once with constants (colour 0.5, roughness 0.5,
factor 0.5), once with the benchmark's four 256² images (sRGB colour, Non-Color roughness, a
tangent-space normal map, the mix factor) on the UV map. Cycles renders both at 160², 64
samples, 4 bounces, 2 threads, alternately; the best of 4 of each is printed with the ratio, the
figure to set beside bxdf_bench_textured's (issue #11). Times include Cycles' scene sync, which
both variants pay alike.
"""
import math
import os
import tempfile
import time

import bpy
import numpy as np

SIZE = 256  # the benchmark's texture size


def scene_settings(scene):
    scene.render.engine = "CYCLES"
    scene.cycles.device = "CPU"
    scene.render.resolution_x = scene.render.resolution_y = 160
    scene.render.resolution_percentage = 100
    scene.cycles.samples = 64
    scene.cycles.use_adaptive_sampling = False
    scene.cycles.use_denoising = False
    scene.cycles.max_bounces = 4
    scene.render.threads_mode = "FIXED"
    scene.render.threads = 2


def build_geometry(scene):
    world = bpy.data.worlds.new("grey")
    scene.world = world
    world.use_nodes = True
    world.node_tree.nodes["Background"].inputs[0].default_value = (0.2, 0.2, 0.2, 1)
    bpy.ops.mesh.primitive_plane_add(size=8, location=(0, 0, -1))
    for radius, location in ((0.9, (-0.6, 0, 0)), (0.6, (1.2, 0.6, -0.4))):
        bpy.ops.mesh.primitive_uv_sphere_add(segments=64, ring_count=32, radius=radius,
                                             location=location)
        bpy.ops.object.shade_smooth()
    light = bpy.data.lights.new("point", "POINT")
    light.energy = 60.0 * 4.0 * math.pi  # the benchmark's intensity 60, as power
    light.shadow_soft_size = 0.0
    light_object = bpy.data.objects.new("point", light)
    light_object.location = (2, -3, 4)
    scene.collection.objects.link(light_object)
    camera = bpy.data.objects.new("camera", bpy.data.cameras.new("camera"))
    scene.collection.objects.link(camera)
    scene.camera = camera
    # look_at((0, -6, 2.5) → (0, 0, -0.3)): a tilt about X from looking straight down.
    camera.location = (0, -6, 2.5)
    camera.rotation_euler = (math.atan2(6.0, 2.8), 0, 0)


def write_image(folder, name, texel, colorspace):
    """A SIZE² 8-bit PNG from texel(x, y) -> RGB, row 0 at the bottom as the benchmark's."""
    pixels = np.ones((SIZE, SIZE, 4), np.float32)
    for y in range(SIZE):
        for x in range(SIZE):
            pixels[y, x, :3] = texel(x, y)
    image = bpy.data.images.new(name, SIZE, SIZE, alpha=False)
    image.pixels.foreach_set(np.round(pixels.ravel() * 255.0) / 255.0)
    image.filepath_raw = os.path.join(folder, name + ".png")
    image.file_format = "PNG"
    image.save()
    loaded = bpy.data.images.load(image.filepath_raw, check_existing=False)
    loaded.colorspace_settings.name = colorspace
    return loaded


def benchmark_images(folder):
    def normal(x, y):
        dx, dy = 0.3 * math.sin(x * 0.2), 0.3 * math.cos(y * 0.2)
        length = math.sqrt(dx * dx + dy * dy + 1.0)
        return [0.5 + 0.5 * dx / length, 0.5 + 0.5 * dy / length, 0.5 + 0.5 / length]

    return {
        "colour": write_image(folder, "colour", lambda x, y: [
            0.2 + 0.6 * float(((x // 32) + (y // 32) + c) % 2) for c in range(3)], "sRGB"),
        "rough": write_image(folder, "rough", lambda x, y: [0.2 + 0.6 * x / 255.0] * 3, "Non-Color"),
        "normal": write_image(folder, "normal", normal, "Non-Color"),
        "factor": write_image(folder, "factor", lambda x, y: [((x ^ y) & 255) / 255.0] * 3,
                              "Non-Color"),
    }


def material(name, images=None):
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    nodes, links = mat.node_tree.nodes, mat.node_tree.links
    nodes.clear()
    output = nodes.new("ShaderNodeOutputMaterial")
    mix = nodes.new("ShaderNodeMixShader")
    diffuse = nodes.new("ShaderNodeBsdfDiffuse")
    glossy = nodes.new("ShaderNodeBsdfGlossy")
    glossy.distribution = "GGX"
    links.new(diffuse.outputs[0], mix.inputs[1])
    links.new(glossy.outputs[0], mix.inputs[2])
    links.new(mix.outputs[0], output.inputs[0])
    if images is None:
        mix.inputs[0].default_value = 0.5
        for bsdf in (diffuse, glossy):
            bsdf.inputs["Color"].default_value = (0.5, 0.5, 0.5, 1)
            bsdf.inputs["Roughness"].default_value = 0.5
        return mat
    coordinates = nodes.new("ShaderNodeTexCoord")

    def texture(image):
        node = nodes.new("ShaderNodeTexImage")
        node.image = image
        node.interpolation = "Linear"
        links.new(coordinates.outputs["UV"], node.inputs[0])
        return node

    colour, rough, normal, factor = (texture(images[k]) for k in ("colour", "rough", "normal", "factor"))
    normal_map = nodes.new("ShaderNodeNormalMap")
    links.new(normal.outputs[0], normal_map.inputs["Color"])
    for bsdf in (diffuse, glossy):
        links.new(colour.outputs[0], bsdf.inputs["Color"])
        links.new(rough.outputs[0], bsdf.inputs["Roughness"])
        links.new(normal_map.outputs[0], bsdf.inputs["Normal"])
    links.new(factor.outputs[0], mix.inputs[0])
    return mat


def main():
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    scene_settings(scene)
    build_geometry(scene)
    with tempfile.TemporaryDirectory() as folder:
        materials = {"constant": material("constant"),
                     "textured": material("textured", benchmark_images(folder))}
        meshes = [o for o in scene.objects if o.type == "MESH"]
        scene.render.filepath = os.path.join(folder, "render.png")

        def render(variant):
            for o in meshes:
                o.data.materials.clear()
                o.data.materials.append(materials[variant])
            start = time.perf_counter()
            bpy.ops.render.render()
            return time.perf_counter() - start

        for variant in materials:  # warm-up: kernels, images
            render(variant)
        best = {variant: render(variant) for variant in materials}
        for _ in range(3):
            for variant in materials:
                best[variant] = min(best[variant], render(variant))
    print("cycles_texture_cost: 160x160, 64 spp, 4 bounces, 2 threads, best of 4:")
    print("  constant parameters   %.3f s" % best["constant"])
    print("  every parameter textured (colour, roughness, normal map, mix factor)  %.3f s"
          % best["textured"])
    print("  textured / constant   %.2fx" % (best["textured"] / best["constant"]))


main()
