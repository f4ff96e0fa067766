"""Node materials whose graphs have value nodes (textures, normal maps, texture-weighted mixes,
colour and math nodes, coordinates and mappings), rendered by BXDF_LAB and by Cycles: the images
agree within noise.

Texture lookups: a camera looking straight down sees a 2 × 2 plane whose UVs span [0, 1]² exactly, its
Emission colour read from an image through a Mapping node, so that pixel centres sample chosen
UVs (texel centres, texel edges and between) with no lighting at all: both renderers are
noise-free and must agree to float precision.
"""


import math

import bpy
import numpy as np
import pytest

from bxdf_lab import engine, nodes
from test_nodes import Tree
from test_render import _render as render_rgba
from test_render import _scene
TEXELS = 4


def _camera_scene(material, tmp_path):
    """test_render's scene (a plane under a sun, deterministic settings) at one sample per pixel
    (Cycles' first sample is the pixel centre), the sun turned 30° about Z, the plane shrunk to
    2 × 2 with UVs spanning [0, 1]² and the camera looking straight down at exactly it."""
    scene = _scene(material, tmp_path)
    scene.bxdf_lab_render.samples = scene.cycles.samples = 1
    bpy.data.objects["sun"].rotation_euler.z = math.radians(30.0)
    plane = bpy.data.objects["plane"]
    for vertex in plane.data.vertices:  # the mesh, not the object: an unscaled object
        vertex.co *= 0.1
    uv = plane.data.uv_layers.new(name="UVMap")
    for loop, coords in zip(uv.data, ((0, 0), (1, 0), (1, 1), (0, 1))):
        loop.uv = coords
    camera = scene.camera.data
    camera.lens, camera.sensor_width, camera.sensor_fit = 50.0, 36.0, "HORIZONTAL"
    scene.camera.location = (0, 0, 50.0 / 18.0)  # the view's half-width at the plane is 1
    return scene


def _render(scene, engine_id, path):
    return render_rgba(scene, engine_id, path)[..., :3]


def _texture_file(tmp_path, colorspace):
    """A 4 × 4 image of distinct colours written with OpenImageIO (top row first): float EXR
    (Linear) or 8-bit PNG (sRGB). Returns the loaded image and its pixels (bottom row first, as
    Blender's UVs and image.pixels run)."""
    import OpenImageIO as oiio
    rng = np.random.default_rng(11)
    pixels = rng.uniform(0.05, 0.95, (TEXELS, TEXELS, 3)).astype(np.float32)
    float_file = colorspace == "Linear"
    path = str(tmp_path / ("texture.exr" if float_file else "texture.png"))
    if not float_file:
        pixels = np.round(pixels * 255) / 255
    out = oiio.ImageOutput.create(path)
    out.open(path, oiio.ImageSpec(TEXELS, TEXELS, 3, "float" if float_file else "uint8"))
    out.write_image(np.ascontiguousarray(pixels[::-1]))
    out.close()
    image = bpy.data.images.load(path)
    image.colorspace_settings.name = colorspace
    return image


def _emission_of_image(tree, image, interpolation, extension, scale, offset):
    emission = tree.surface(tree.add("ShaderNodeEmission"))
    node = tree.add("ShaderNodeTexImage")
    node.image, node.interpolation, node.extension = image, interpolation, extension
    mapping = tree.add("ShaderNodeMapping")
    mapping.inputs["Location"].default_value = (offset, offset, 0.0)
    mapping.inputs["Scale"].default_value = (scale, scale, 1.0)
    coords = tree.add("ShaderNodeTexCoord")
    tree.link(coords.outputs["UV"], mapping.inputs["Vector"])
    tree.link(mapping.outputs[0], node.inputs["Vector"])
    tree.link(node.outputs["Color"], emission.inputs["Color"])


# u' = scale·u + offset at the pixel centres u = (i + ½)/16: with scale 1 and offset −1/32 they
# would fall on i/16 (texel edges at i = 0, 4, 8, 12; texel centres at i = 2, 6, 10, 14); with
# scale 2 and offset −½ − 1/16 they span [−0.5, 1.375], beyond the image on both sides. Both are
# moved by 1/256 (1/64 texel) so that no sample sits exactly on a texel edge, where Closest's
# choice would depend on the last bit of the hit point.
LOOKUPS = [(1.0, -1.0 / 32.0 + 1.0 / 256.0), (2.0, -0.5 - 1.0 / 16.0 + 1.0 / 256.0)]


@pytest.mark.parametrize("interpolation", ["Closest", "Linear", "Cubic"])
@pytest.mark.parametrize("extension", ["REPEAT", "EXTEND", "CLIP"])
@pytest.mark.parametrize("scale, offset", LOOKUPS, ids=["texels", "beyond"])
def test_texture_lookups_match_cycles(interpolation, extension, scale, offset, tmp_path):
    tree = Tree("texture lookup")
    _emission_of_image(tree, _texture_file(tmp_path, "Linear"), interpolation, extension, scale,
                       offset)
    scene = _camera_scene(tree.material, tmp_path)
    ours = _render(scene, "BXDF_LAB", str(tmp_path / "bxdf_lab.exr"))
    assert engine.last_error == ""
    cycles = _render(scene, "CYCLES", str(tmp_path / "cycles.exr"))
    assert cycles.max() > 0.05
    np.testing.assert_allclose(ours, cycles, rtol=1e-4, atol=1e-5)


def test_an_srgb_image_is_linearised_like_cycles(tmp_path):
    tree = Tree("srgb")
    _emission_of_image(tree, _texture_file(tmp_path, "sRGB"), "Linear", "REPEAT", *LOOKUPS[0])
    scene = _camera_scene(tree.material, tmp_path)
    ours = _render(scene, "BXDF_LAB", str(tmp_path / "bxdf_lab.exr"))
    cycles = _render(scene, "CYCLES", str(tmp_path / "cycles.exr"))
    np.testing.assert_allclose(ours, cycles, rtol=2e-3, atol=1e-4)


def _environment_file(tmp_path):
    """A 7 × 5 float image of distinct colours for an Environment Texture: its middle row's
    centres lie on the horizon (v = ½), where an unlinked Vector (the position on the z = 0
    plane) looks, and with 7 columns no texel edge falls on the pixel grid's symmetry axes
    (at multiples of 45° of azimuth), where Closest's choice would turn on the last bit."""
    import OpenImageIO as oiio
    pixels = np.random.default_rng(12).uniform(0.05, 0.95, (5, 7, 3)).astype(np.float32)
    path = str(tmp_path / "environment.exr")
    out = oiio.ImageOutput.create(path)
    out.open(path, oiio.ImageSpec(7, 5, 3, "float"))
    out.write_image(pixels)
    out.close()
    image = bpy.data.images.load(path)
    image.colorspace_settings.name = "Linear"
    return image


# An Environment Texture inside a material (an Emission's colour), looked up by the world
# position (its unlinked Vector) or by a direction made from the UVs, (u − ½, v − ½, −0.3),
# which sweeps a cone of directions below the horizon across the image.
@pytest.mark.parametrize("interpolation", ["Closest", "Linear", "Cubic"])
@pytest.mark.parametrize("projection", ["EQUIRECTANGULAR", "MIRROR_BALL"])
@pytest.mark.parametrize("vector", ["position", "uv_direction"])
def test_an_environment_texture_in_a_material_matches_cycles(interpolation, projection, vector,
                                                             tmp_path):
    tree = Tree("environment in a material")
    emission = tree.surface(tree.add("ShaderNodeEmission"))
    node = tree.add("ShaderNodeTexEnvironment")
    node.image, node.interpolation, node.projection = (_environment_file(tmp_path),
                                                       interpolation, projection)
    if vector == "uv_direction":
        mapping = tree.add("ShaderNodeMapping")
        mapping.inputs["Location"].default_value = (-0.5, -0.5, -0.3)
        tree.link(tree.add("ShaderNodeTexCoord").outputs["UV"], mapping.inputs["Vector"])
        tree.link(mapping.outputs[0], node.inputs["Vector"])
    tree.link(node.outputs["Color"], emission.inputs["Color"])
    scene = _camera_scene(tree.material, tmp_path)
    ours = _render(scene, "BXDF_LAB", str(tmp_path / "bxdf_lab.exr"))
    assert engine.last_error == ""
    assert nodes.translate(tree.material, write_files=False).warnings == []
    cycles = _render(scene, "CYCLES", str(tmp_path / "cycles.exr"))
    assert np.ptp(cycles) > 0.05  # the lookup does vary over the image
    # The direction comes from the hit point, which the two renderers compute to a few ulps
    # apart; the mirror ball's mapping magnifies that to ~1e-4 (one pixel in 768).
    np.testing.assert_allclose(ours, cycles, rtol=5e-4, atol=5e-5)


def _normal_texture(tmp_path):
    """A tangent-space normal map of tilted facets (Non-Color)."""
    ys, xs = np.mgrid[0:TEXELS, 0:TEXELS]
    tilt = np.stack([np.sin(xs * 1.3) * 0.4, np.cos(ys * 0.9) * 0.4, np.ones_like(xs, float)], -1)
    tilt /= np.linalg.norm(tilt, axis=-1, keepdims=True)
    pixels = np.concatenate([tilt * 0.5 + 0.5, np.ones((TEXELS, TEXELS, 1))], -1)
    image = bpy.data.images.new("normals", TEXELS, TEXELS, float_buffer=True)
    image.colorspace_settings.name = "Non-Color"  # first: a change regenerates the pixels
    image.pixels.foreach_set(pixels.astype(np.float32).ravel())
    return image


def _scale_object(scene, scale):
    """Scales the plane object by `scale` and its mesh by the inverse: the same surface in
    world space, whose object-space tangents must go through the object matrix."""
    plane = bpy.data.objects["plane"]
    for vertex in plane.data.vertices:
        vertex.co = (vertex.co.x / scale[0], vertex.co.y / scale[1], vertex.co.z)
    plane.scale = scale


# On Diffuse, Cycles dims light at grazing angles to the perturbed normal by its bump
# shadowing term (kernel/closure/bsdf.h); on Glossy it does not; on Principled it dims the
# diffuse and sheen lobes (diffuse closures in Cycles) and not the specular one.
NORMAL_MAPPED = {
    "ShaderNodeBsdfGlossy": {"Color": (0.8, 0.6, 0.4, 1.0), "Roughness": 0.6},
    "ShaderNodeBsdfDiffuse": {"Color": (0.8, 0.6, 0.4, 1.0), "Roughness": 0.6},
    "ShaderNodeBsdfPrincipled": {"Base Color": (0.8, 0.6, 0.4, 1.0), "Roughness": 0.6,
                                 "Sheen": 1.0, "Specular": 0.5},
}


@pytest.mark.parametrize("bsdf", list(NORMAL_MAPPED))
@pytest.mark.parametrize("scale", [(1.0, 1.0, 1.0), (2.0, 0.5, 1.0)], ids=["unscaled", "scaled"])
def test_a_normal_map_matches_cycles(bsdf, scale, tmp_path):
    tree = Tree("normal mapped")
    closure = tree.surface(tree.add(bsdf))
    for name, value in NORMAL_MAPPED[bsdf].items():
        closure.inputs[name].default_value = value
    normal_map = tree.add("ShaderNodeNormalMap", Strength=0.8)
    image = tree.add("ShaderNodeTexImage")
    image.image, image.interpolation = _normal_texture(tmp_path), "Closest"
    tree.link(image.outputs["Color"], normal_map.inputs["Color"])
    tree.link(normal_map.outputs[0], closure.inputs["Normal"])
    scene = _camera_scene(tree.material, tmp_path)
    _scale_object(scene, scale)
    ours = _render(scene, "BXDF_LAB", str(tmp_path / "bxdf_lab.exr"))
    assert engine.last_error == ""
    cycles = _render(scene, "CYCLES", str(tmp_path / "cycles.exr"))
    assert np.ptp(cycles) > 0.05  # the normal map does vary the shading
    np.testing.assert_allclose(ours, cycles, rtol=5e-3, atol=1e-4)


def _math_node(tree, operation):
    node = tree.add("ShaderNodeMath")
    node.operation = operation
    return node


def _facets(tree, slope_u, slope_v):
    """A height of two planar facets meeting at u = ½: slope_u·|u − ½| + slope_v·v."""
    _, u, v = _uv(tree)
    centred = _math_node(tree, "SUBTRACT")
    tree.link(u, centred.inputs[0])
    centred.inputs[1].default_value = 0.5
    folded = _math_node(tree, "ABSOLUTE")
    tree.link(centred.outputs[0], folded.inputs[0])
    height = _math_node(tree, "MULTIPLY_ADD")
    tree.link(folded.outputs[0], height.inputs[0])
    height.inputs[1].default_value = slope_u
    slope = _math_node(tree, "MULTIPLY")
    tree.link(v, slope.inputs[0])
    slope.inputs[1].default_value = slope_v
    tree.link(slope.outputs[0], height.inputs[2])
    return height.outputs[0]


def test_a_bump_matches_cycles(tmp_path):
    """Two chained Bump nodes (strength, distance, invert, Normal input) on a Diffuse: Cycles
    takes the height's differences over a pixel's footprint, we over a small fixed offset
    (docs/material-graph.md), so the heights are planar facets, on which both are exact; the
    pixels whose footprint reaches across the fold are left out."""
    tree = Tree("bumped")
    diffuse = tree.surface(tree.add("ShaderNodeBsdfDiffuse", Color=(0.8, 0.7, 0.6, 1.0)))
    first = tree.add("ShaderNodeBump", Strength=0.7, Distance=0.3)
    tree.link(_facets(tree, 1.2, 0.4), first.inputs["Height"])
    second = tree.add("ShaderNodeBump", Strength=1.0, Distance=0.2)
    second.invert = True
    tree.link(_facets(tree, -0.5, 0.9), second.inputs["Height"])
    tree.link(first.outputs[0], second.inputs["Normal"])
    tree.link(second.outputs[0], diffuse.inputs["Normal"])
    scene = _camera_scene(tree.material, tmp_path)
    ours = _render(scene, "BXDF_LAB", str(tmp_path / "bxdf_lab.exr"))
    assert engine.last_error == ""
    cycles = _render(scene, "CYCLES", str(tmp_path / "cycles.exr"))
    columns = (np.arange(cycles.shape[1]) + 0.5) / cycles.shape[1]  # u at the pixel centres
    away = np.abs(columns - 0.5) > 0.15
    left, right = cycles[:, columns < 0.35], cycles[:, columns > 0.65]
    assert abs(left.mean() - right.mean()) > 0.02  # the two facets do shade differently
    np.testing.assert_allclose(ours[:, away], cycles[:, away], rtol=5e-3, atol=1e-4)


def test_a_mix_shader_with_a_texture_factor_matches_cycles(tmp_path):
    tree = Tree("texture mix")
    mix = tree.surface(tree.add("ShaderNodeMixShader"))
    image = tree.add("ShaderNodeTexImage")
    image.image, image.interpolation = _texture_file(tmp_path, "Linear"), "Closest"
    tree.link(image.outputs["Color"], mix.inputs["Fac"])
    tree.link(tree.add("ShaderNodeBsdfDiffuse", Color=(0.9, 0.3, 0.1, 1.0)).outputs[0],
              mix.inputs[1])
    tree.link(tree.add("ShaderNodeBsdfGlossy", Color=(0.2, 0.5, 0.9, 1.0), Roughness=0.4).outputs[0],
              mix.inputs[2])
    scene = _camera_scene(tree.material, tmp_path)
    ours = _render(scene, "BXDF_LAB", str(tmp_path / "bxdf_lab.exr"))
    cycles = _render(scene, "CYCLES", str(tmp_path / "cycles.exr"))
    assert np.ptp(cycles) > 0.05
    np.testing.assert_allclose(ours, cycles, rtol=5e-3, atol=1e-4)


def test_a_holdout_mix_matches_cycles(tmp_path):
    """A Mix Shader of Holdout and Diffuse whose factor runs with u, on a transparent film: the
    alpha is 1 − the holdout weight and the colour the diffuse's share, as in Cycles."""
    tree = Tree("holdout")
    mix = tree.surface(tree.add("ShaderNodeMixShader"))
    _, u, _ = _uv(tree)
    tree.link(u, mix.inputs["Fac"])
    tree.link(tree.add("ShaderNodeHoldout").outputs[0], mix.inputs[1])
    tree.link(tree.add("ShaderNodeBsdfDiffuse", Color=(0.9, 0.5, 0.2, 1.0)).outputs[0], mix.inputs[2])
    scene = _camera_scene(tree.material, tmp_path)
    scene.render.film_transparent = True
    ours = render_rgba(scene, "BXDF_LAB", str(tmp_path / "bxdf_lab.exr"))
    assert engine.last_error == ""
    cycles = render_rgba(scene, "CYCLES", str(tmp_path / "cycles.exr"))
    assert np.ptp(cycles[..., 3]) > 0.5  # the alpha does run from opaque to transparent
    np.testing.assert_allclose(ours, cycles, rtol=5e-3, atol=1e-4)


# Cycles honours a holdout while the path keeps PATH_RAY_TRANSPARENT_BACKGROUND: camera rays and
# their continuations through a Transparent BSDF (integrator/shade_surface.h, path_state.h), the
# pixel turning transparent by the holdout weight times the path's throughput. Through any
# other bounce (here a sharp Refraction BSDF of IOR 1, which passes rays just as straight) the
# holdout is not honoured: a pure Holdout then shades black and the pixel stays opaque. The same
# flag makes the background seen through a Transparent BSDF transparency on a transparent film
# (shade_background.h), while seen through the refraction it is the world's light.
@pytest.mark.parametrize("behind", ["holdout", "nothing"])
@pytest.mark.parametrize("cover", ["ShaderNodeBsdfTransparent", "ShaderNodeBsdfRefraction"])
def test_a_holdout_behind_a_transparent_surface_matches_cycles(cover, behind, tmp_path):
    tree = Tree("holdout behind")
    tree.surface(tree.add("ShaderNodeHoldout"))
    scene = _camera_scene(tree.material, tmp_path)
    scene.render.film_transparent = True
    scene.bxdf_lab_render.max_bounces = scene.cycles.max_bounces = 2
    front = Tree("cover")
    node = front.surface(front.add(cover, Color=(0.5, 0.7, 0.9, 1.0)))
    if cover == "ShaderNodeBsdfRefraction":
        node.distribution, node.inputs["IOR"].default_value = "SHARP", 1.0
    plane = bpy.data.objects["plane"]
    cover_object = bpy.data.objects.new("cover", plane.data.copy())
    cover_object.data.materials[0] = front.material
    cover_object.location.z = 0.5
    scene.collection.objects.link(cover_object)
    plane.hide_render = behind == "nothing"
    ours = render_rgba(scene, "BXDF_LAB", str(tmp_path / "bxdf_lab.exr"))
    assert engine.last_error == ""
    cycles = render_rgba(scene, "CYCLES", str(tmp_path / "cycles.exr"))
    expected_alpha = 1.0 - (0.5 + 0.7 + 0.9) / 3.0 if cover == "ShaderNodeBsdfTransparent" else 1.0
    np.testing.assert_allclose(cycles[..., 3], expected_alpha, rtol=1e-4)
    np.testing.assert_allclose(ours, cycles, rtol=1e-4, atol=1e-5)


# ---- value nodes: an Emission colour computed from the UVs, seen at pixel centres --------------

def _uv(tree):
    coords = tree.add("ShaderNodeTexCoord")
    separate = tree.add("ShaderNodeSeparateXYZ")
    tree.link(coords.outputs["UV"], separate.inputs[0])
    return coords.outputs["UV"], separate.outputs["X"], separate.outputs["Y"]


def _math(tree):
    _, u, _ = _uv(tree)
    node = tree.add("ShaderNodeMath")
    node.operation, node.use_clamp = "POWER", True
    node.inputs[1].default_value = 2.2
    tree.link(u, node.inputs[0])
    return node.outputs[0]


def _mix_rgb(blend):
    def build(tree):
        uv, u, _ = _uv(tree)
        node = tree.add("ShaderNodeMixRGB")
        node.blend_type = blend
        node.inputs["Color1"].default_value = (0.2, 0.6, 0.4, 1.0)
        tree.link(u, node.inputs["Fac"])
        tree.link(uv, node.inputs["Color2"])
        return node.outputs[0]
    return build


MIX_BLENDS = ["OVERLAY", "DARKEN", "LIGHTEN", "DIFFERENCE", "DIVIDE", "DODGE", "BURN", "HUE",
              "SATURATION", "VALUE", "COLOR", "SOFT_LIGHT", "LINEAR_LIGHT"]


def _colour_op(bl_idname, **inputs):
    def build(tree):
        uv, _, _ = _uv(tree)
        node = tree.add(bl_idname, **inputs)
        tree.link(uv, node.inputs["Color"])
        return node.outputs[0]
    return build


def _swizzle(tree):
    _, u, v = _uv(tree)
    combine = tree.add("ShaderNodeCombineXYZ", Z=0.3)
    tree.link(v, combine.inputs["X"])
    tree.link(u, combine.inputs["Y"])
    return combine.outputs[0]


def _ramp(interpolation, color_mode="RGB", hue="NEAR"):
    def build(tree):
        _, u, _ = _uv(tree)
        node = tree.add("ShaderNodeValToRGB")
        ramp = node.color_ramp
        ramp.interpolation, ramp.color_mode, ramp.hue_interpolation = interpolation, color_mode, hue
        ramp.elements[0].color = (0.9, 0.1, 0.1, 1.0)
        middle = ramp.elements.new(0.4)
        middle.color = (0.1, 0.8, 0.2, 1.0)
        ramp.elements[-1].color = (0.2, 0.3, 0.9, 1.0)
        tree.link(u, node.inputs["Fac"])
        return node.outputs[0]
    return build


def _view_factor(bl_idname, output, **inputs):
    def build(tree):
        return tree.add(bl_idname, **inputs).outputs[output]
    return build


def _mapped_generated(tree):
    coords = tree.add("ShaderNodeTexCoord")
    mapping = tree.add("ShaderNodeMapping")
    mapping.inputs["Rotation"].default_value = (0.0, 0.0, 0.5)
    mapping.inputs["Scale"].default_value = (1.5, 0.7, 1.0)
    mapping.inputs["Location"].default_value = (0.6, 0.2, 0.0)  # keeps the colour positive
    tree.link(coords.outputs["Generated"], mapping.inputs["Vector"])
    return mapping.outputs[0]


def _object_coordinates(tree):
    mapping = tree.add("ShaderNodeMapping")
    mapping.vector_type = "TEXTURE"
    mapping.inputs["Location"].default_value = (-1.0, -1.0, -1.0)
    mapping.inputs["Scale"].default_value = (2.0, 2.0, 2.0)
    tree.link(tree.add("ShaderNodeTexCoord").outputs["Object"], mapping.inputs["Vector"])
    return mapping.outputs[0]


def _named_uv_map(tree):
    node = tree.add("ShaderNodeUVMap")
    node.uv_map = "UVMap"
    return node.outputs[0]


def _unified_mix(tree):
    uv, u, _ = _uv(tree)
    node = tree.add("ShaderNodeMix")
    node.data_type, node.blend_type = "RGBA", "MULTIPLY"
    tree.link(u, node.inputs["Factor"])
    node.inputs[6].default_value = (0.9, 0.5, 0.2, 1.0)  # A (colour)
    tree.link(uv, node.inputs[7])                         # B (colour)
    return node.outputs[2]


VALUE_CASES = {
    "math_power": _math,
    **{f"mix_rgb_{blend.lower()}": _mix_rgb(blend) for blend in MIX_BLENDS},
    "invert": _colour_op("ShaderNodeInvert", Fac=0.7),
    "gamma": _colour_op("ShaderNodeGamma", Gamma=2.2),
    "bright_contrast": _colour_op("ShaderNodeBrightContrast", Bright=0.1, Contrast=0.3),
    "hue_saturation": _colour_op("ShaderNodeHueSaturation", Hue=0.3, Saturation=0.8, Value=1.1),
    "separate_combine_xyz": _swizzle,
    "color_ramp_linear": _ramp("LINEAR"),
    "color_ramp_constant": _ramp("CONSTANT"),
    "color_ramp_ease": _ramp("EASE"),
    "color_ramp_cardinal": _ramp("CARDINAL"),
    "color_ramp_b_spline": _ramp("B_SPLINE"),
    "color_ramp_hsv_far": _ramp("LINEAR", "HSV", "FAR"),
    "color_ramp_hsv_ccw": _ramp("LINEAR", "HSV", "CCW"),
    "color_ramp_hsl_near": _ramp("EASE", "HSL", "NEAR"),
    "color_ramp_hsl_cw": _ramp("CONSTANT", "HSL", "CW"),
    "fresnel": _view_factor("ShaderNodeFresnel", 0, IOR=1.5),
    "layer_weight_facing": _view_factor("ShaderNodeLayerWeight", "Facing", Blend=0.3),
    "generated_mapping": _mapped_generated,
    "object_texture_mapping": _object_coordinates,
    "uv_map": _named_uv_map,
    "mix_multiply": _unified_mix,
}


@pytest.mark.parametrize("case", VALUE_CASES)
def test_value_nodes_match_cycles(case, tmp_path):
    tree = Tree(case)
    emission = tree.surface(tree.add("ShaderNodeEmission"))
    tree.link(VALUE_CASES[case](tree), emission.inputs["Color"])
    scene = _camera_scene(tree.material, tmp_path)
    ours = _render(scene, "BXDF_LAB", str(tmp_path / "bxdf_lab.exr"))
    assert engine.last_error == ""
    cycles = _render(scene, "CYCLES", str(tmp_path / "cycles.exr"))
    assert np.ptp(cycles) > 5e-4  # the value does vary over the image (Fresnel the least)
    np.testing.assert_allclose(ours, cycles, rtol=1e-4, atol=1e-5)
