"""Node-tree translation (bxdf_lab.nodes): each translator's graph, warnings and coverage."""

import math
import os

import bpy
import mathutils
import numpy as np
import pytest

from bxdf_lab import nodes
from bxdf_lab.nodes import mapping

PRINCIPLED_PARAMS = {"base_color", "subsurface", "subsurface_color", "metallic", "specular",
                     "specular_tint", "roughness", "anisotropic", "anisotropic_rotation", "sheen",
                     "sheen_tint", "clearcoat", "clearcoat_roughness", "ior", "transmission",
                     "transmission_roughness", "distribution"}


class Tree:
    """A material whose node tree holds only a Material Output; helpers to add and link."""

    def __init__(self, name="Tree"):
        self.material = bpy.data.materials.new(name)
        self.material.use_nodes = True
        self.nodes = self.material.node_tree.nodes
        self.nodes.clear()
        self.output = self.nodes.new("ShaderNodeOutputMaterial")

    def add(self, bl_idname, **inputs):
        node = self.nodes.new(bl_idname)
        for name, value in inputs.items():
            node.inputs[name.replace("_", " ")].default_value = value
        return node

    def link(self, from_socket, to_socket):
        return self.material.node_tree.links.new(from_socket, to_socket)

    def surface(self, node):
        self.link(node.outputs[0], self.output.inputs["Surface"])
        return node

    def translate(self):
        t = nodes.translate(self.material)
        return t, t.graph.as_dict()


@pytest.fixture
def tree():
    return Tree()


def approx(values):
    return pytest.approx(values, abs=1e-6)


# ---- shaders --------------------------------------------------------------------------------

def test_principled_parameters_are_the_registry_names(tree):
    tree.surface(tree.add("ShaderNodeBsdfPrincipled", Base_Color=(0.9, 0.5, 0.1, 1.0),
                          Metallic=1.0, Roughness=0.3))
    t, graph = tree.translate()
    assert t.warnings == []
    (closure,) = graph["closures"]
    assert closure["model"] == "cycles_principled" and closure["weight"] == 1.0
    assert set(closure["params"]) == PRINCIPLED_PARAMS
    assert closure["params"]["base_color"] == approx([0.9, 0.5, 0.1])
    assert closure["params"]["metallic"] == 1.0
    assert closure["params"]["roughness"] == approx(0.3)
    assert closure["params"]["distribution"] == "ggx"
    assert "normal" not in closure and graph["nodes"] == [] and graph["emission"] == [0, 0, 0]
    assert nodes.material_coverage(tree.material) == [
        {"node": "Principled BSDF", "type": "ShaderNodeBsdfPrincipled", "status": "exact", "why": ""}]


def test_principled_alpha_and_emission_become_transparent_and_emission(tree):
    tree.surface(tree.add("ShaderNodeBsdfPrincipled", Alpha=0.25,
                          Emission=(1.0, 0.5, 0.0, 1.0), Emission_Strength=2.0))
    _, graph = tree.translate()
    transparent, principled = graph["closures"]
    assert transparent["model"] == "cycles_transparent"
    assert transparent["weight"] == approx(0.75) and principled["weight"] == approx(0.25)
    # Cycles adds the emission to the BSDF, then mixes both with the transparent closure.
    assert graph["emission"] == approx([0.5, 0.25, 0.0])


@pytest.mark.parametrize("bl_idname, model, params", [
    ("ShaderNodeBsdfDiffuse", "cycles_oren_nayar", {"color", "roughness"}),
    ("ShaderNodeBsdfGlossy", "cycles_glossy", {"color", "roughness", "distribution", "anisotropy"}),
    ("ShaderNodeBsdfAnisotropic", "cycles_glossy",
     {"color", "roughness", "distribution", "anisotropy"}),
    ("ShaderNodeBsdfGlass", "cycles_glass", {"color", "roughness", "ior", "distribution"}),
    ("ShaderNodeBsdfRefraction", "cycles_refraction", {"color", "roughness", "ior", "distribution"}),
    ("ShaderNodeBsdfTranslucent", "cycles_translucent", {"color"}),
    ("ShaderNodeBsdfTransparent", "cycles_transparent", {"color"}),
    ("ShaderNodeBsdfVelvet", "cycles_velvet", {"color", "sigma"}),
])
def test_each_bsdf_node_becomes_its_model(tree, bl_idname, model, params):
    node = tree.surface(tree.add(bl_idname, Color=(0.2, 0.4, 0.6, 1.0)))
    t, graph = tree.translate()
    (closure,) = graph["closures"]
    assert closure["model"] == model and closure["weight"] == 1.0
    assert set(closure["params"]) == params
    assert closure["params"]["color"] == approx([0.2, 0.4, 0.6])
    if "distribution" in params:
        assert closure["params"]["distribution"] == node.distribution.lower()
    assert [w for w in t.warnings if "outside" not in w] == []


def test_anisotropic_rotation_and_glossy_distribution(tree):
    node = tree.surface(tree.add("ShaderNodeBsdfAnisotropic", Rotation=0.25, Anisotropy=0.5))
    node.distribution = "BECKMANN"
    _, graph = tree.translate()
    (closure,) = graph["closures"]
    assert closure["rotation"] == 0.25 and closure["params"]["anisotropy"] == 0.5
    assert closure["params"]["distribution"] == "beckmann"


def test_mix_shader_folds_its_factor_into_the_weights(tree):
    outer = tree.surface(tree.add("ShaderNodeMixShader", Fac=0.25))
    inner = tree.add("ShaderNodeMixShader", Fac=0.4)
    tree.link(tree.add("ShaderNodeBsdfDiffuse").outputs[0], outer.inputs[1])
    tree.link(inner.outputs[0], outer.inputs[2])
    tree.link(tree.add("ShaderNodeBsdfGlossy").outputs[0], inner.inputs[1])
    tree.link(tree.add("ShaderNodeBsdfTranslucent").outputs[0], inner.inputs[2])
    _, graph = tree.translate()
    weights = {c["model"]: c["weight"] for c in graph["closures"]}
    assert weights == approx({"cycles_oren_nayar": 0.75, "cycles_glossy": 0.25 * 0.6,
                              "cycles_translucent": 0.25 * 0.4})
    assert [c["model"] for c in graph["closures"]] == [
        "cycles_oren_nayar", "cycles_glossy", "cycles_translucent"]  # Cycles' order


def test_mix_shader_factor_out_of_range_is_clamped_and_zero_weight_dropped(tree):
    mix = tree.surface(tree.add("ShaderNodeMixShader", Fac=1.5))
    tree.link(tree.add("ShaderNodeBsdfDiffuse").outputs[0], mix.inputs[1])
    tree.link(tree.add("ShaderNodeBsdfGlossy").outputs[0], mix.inputs[2])
    _, graph = tree.translate()
    assert [(c["model"], c["weight"]) for c in graph["closures"]] == [("cycles_glossy", 1.0)]


def test_mix_shader_with_a_texture_factor_weights_by_reference(tree):
    mix = tree.surface(tree.add("ShaderNodeMixShader"))
    image = tree.add("ShaderNodeTexImage")
    tree.link(image.outputs["Color"], mix.inputs["Fac"])
    tree.link(tree.add("ShaderNodeBsdfDiffuse").outputs[0], mix.inputs[1])
    tree.link(tree.add("ShaderNodeBsdfGlossy").outputs[0], mix.inputs[2])
    _, graph = tree.translate()
    ops = [n["op"] for n in graph["nodes"]]
    assert ops == ["uv", "image", "math", "math"]
    saturate, one_minus = graph["nodes"][2], graph["nodes"][3]
    assert (saturate["operation"], saturate["clamp"], saturate["a"]) == (
        "multiply", True, {"node": 1, "out": "color"})
    assert (one_minus["operation"], one_minus["a"], one_minus["b"]) == (
        "subtract", 1.0, {"node": 2, "out": "value"})
    assert [c["weight"] for c in graph["closures"]] == [{"node": 3, "out": "value"},
                                                        {"node": 2, "out": "value"}]


def test_add_shader_emission_and_holdout(tree):
    add = tree.surface(tree.add("ShaderNodeAddShader"))
    tree.link(tree.add("ShaderNodeEmission", Color=(1.0, 0.5, 0.25, 1.0), Strength=4.0).outputs[0],
              add.inputs[0])
    tree.link(tree.add("ShaderNodeHoldout").outputs[0], add.inputs[1])
    _, graph = tree.translate()
    assert graph["emission"] == approx([4.0, 2.0, 1.0])
    assert graph["closures"] == [{"model": "holdout", "weight": 1.0, "params": {}}]


def test_an_emission_of_zero_strength_is_no_closure_at_all(tree):
    tree.surface(tree.add("ShaderNodeEmission", Strength=0.0))
    t, graph = tree.translate()
    assert graph["emission"] == [0.0, 0.0, 0.0] and t.closure_counts == {}


def test_a_value_linked_into_a_shader_input_emits_it_as_cycles_does(tree):
    add = tree.surface(tree.add("ShaderNodeAddShader"))
    rgb = tree.add("ShaderNodeRGB")
    rgb.outputs[0].default_value = (0.5, 0.25, 0.125, 1.0)
    value = tree.add("ShaderNodeValue")
    value.outputs[0].default_value = 2.0
    tree.link(rgb.outputs[0], add.inputs[0])
    tree.link(value.outputs[0], add.inputs[1])
    t, graph = tree.translate()
    assert graph["emission"] == approx([2.5, 2.25, 2.125]) and graph["closures"] == []
    assert t.warnings == []


def test_material_without_nodes_is_cycles_diffuse_of_its_viewport_colour():
    material = bpy.data.materials.new("plain")
    material.diffuse_color = (0.3, 0.2, 0.1, 1.0)
    graph = nodes.translate(material).graph.as_dict()
    assert graph["closures"] == [{"model": "cycles_oren_nayar", "weight": 1.0,
                                  "params": {"color": approx([0.3, 0.2, 0.1]), "roughness": 0.0}}]


def test_the_active_cycles_output_is_the_target(tree):
    eevee = tree.nodes.new("ShaderNodeOutputMaterial")
    eevee.target = "EEVEE"
    tree.output.target = "CYCLES"
    tree.surface(tree.add("ShaderNodeBsdfDiffuse"))
    tree.link(tree.add("ShaderNodeBsdfGlossy").outputs[0], eevee.inputs["Surface"])
    eevee.is_active_output = True
    _, graph = tree.translate()
    assert [c["model"] for c in graph["closures"]] == ["cycles_oren_nayar"]


# ---- values -----------------------------------------------------------------------------------

def _diffuse_colour_from(tree, node, output=0):
    diffuse = tree.surface(tree.add("ShaderNodeBsdfDiffuse"))
    tree.link(node.outputs[output], diffuse.inputs["Color"])
    t, graph = tree.translate()
    return t, graph, graph["closures"][0]["params"]["color"]


def test_rgb_and_value_are_constants_converted_like_cycles_sockets(tree):
    rgb = tree.add("ShaderNodeRGB")
    rgb.outputs[0].default_value = (0.1, 0.2, 0.3, 1.0)
    value = tree.add("ShaderNodeValue")
    value.outputs[0].default_value = 0.7
    diffuse = tree.surface(tree.add("ShaderNodeBsdfDiffuse"))
    tree.link(rgb.outputs[0], diffuse.inputs["Roughness"])  # colour → float: Rec.709 luminance
    tree.link(value.outputs[0], diffuse.inputs["Color"])    # float → colour: grey
    _, graph = tree.translate()
    params = graph["closures"][0]["params"]
    assert params["roughness"] == approx(0.2126729 * 0.1 + 0.7151522 * 0.2 + 0.0721750 * 0.3)
    assert params["color"] == approx([0.7, 0.7, 0.7])
    assert graph["nodes"] == []


@pytest.mark.parametrize("bl_idname, settings, op, fields", [
    ("ShaderNodeMixRGB", {"blend_type": "MULTIPLY", "use_clamp": True}, "mix_rgb",
     {"blend": "multiply", "clamp": True, "fac": 0.5, "a": (0.5, 0.5, 0.5), "b": (0.5, 0.5, 0.5)}),
    ("ShaderNodeInvert", {}, "invert", {"fac": 1.0, "color": (0.0, 0.0, 0.0)}),
    ("ShaderNodeGamma", {}, "gamma", {"color": (1.0, 1.0, 1.0), "gamma": 1.0}),
    ("ShaderNodeBrightContrast", {}, "bright_contrast",
     {"color": (1.0, 1.0, 1.0), "bright": 0.0, "contrast": 0.0}),
    ("ShaderNodeHueSaturation", {}, "hsv", {"hue": 0.5, "saturation": 1.0, "value": 1.0,
                                             "fac": 1.0, "color": (0.8, 0.8, 0.8)}),
    ("ShaderNodeCombineRGB", {}, "combine", {"x": 0.0, "y": 0.0, "z": 0.0}),
    ("ShaderNodeCombineXYZ", {}, "combine", {"x": 0.0, "y": 0.0, "z": 0.0}),
])
def test_colour_nodes_become_their_ops(tree, bl_idname, settings, op, fields):
    node = tree.add(bl_idname)
    for name, value in settings.items():
        setattr(node, name, value)
    t, graph, colour = _diffuse_colour_from(tree, node)
    (emitted,) = graph["nodes"]
    assert emitted["op"] == op
    assert {k: emitted[k] for k in fields} == {k: approx(v) if not isinstance(v, (str, bool))
                                               else v for k, v in fields.items()}
    assert colour == {"node": 0, "out": "color" if op != "combine" or "RGB" in bl_idname
                      else "vector"}
    assert t.warnings == []


def test_math_separate_and_the_unified_mix_node(tree):
    math_node = tree.add("ShaderNodeMath")
    math_node.operation, math_node.use_clamp = "POWER", True
    separate = tree.add("ShaderNodeSeparateXYZ")
    tree.link(separate.outputs["Y"], math_node.inputs[0])
    mix = tree.add("ShaderNodeMix")
    mix.data_type = "FLOAT"
    mix.inputs[2].default_value, mix.inputs[3].default_value = 0.25, 0.75  # A, B (floats)
    tree.link(math_node.outputs[0], mix.inputs["Factor"])
    diffuse = tree.surface(tree.add("ShaderNodeBsdfDiffuse"))
    tree.link(mix.outputs["Result"], diffuse.inputs["Roughness"])
    _, graph = tree.translate()
    ops = graph["nodes"]
    ref = lambda node, out: {"node": ops.index(node), "out": out}
    by_operation = {n.get("operation", n["op"]): n for n in ops}
    assert sorted(by_operation) == ["multiply", "multiply_add", "power", "separate", "subtract"]
    power, separate = by_operation["power"], by_operation["separate"]
    assert power["clamp"] is True and power["a"] == ref(separate, "y")
    # a + fac·(b − a), the factor clamped to [0, 1] as Blender's Clamp Factor does
    saturate, lerp = by_operation["multiply"], by_operation["multiply_add"]
    assert saturate["clamp"] is True and saturate["a"] == ref(power, "value")
    assert lerp["a"] == ref(saturate, "value") and lerp["b"] == ref(by_operation["subtract"], "value")
    assert lerp["c"] == 0.25 and (by_operation["subtract"]["a"], by_operation["subtract"]["b"]) == (
        0.75, 0.25)
    assert graph["closures"][0]["params"]["roughness"] == ref(lerp, "value")
    assert all(r["node"] < i for i, n in enumerate(ops) for r in n.values() if isinstance(r, dict))


def test_color_ramp_stops_and_alpha(tree):
    ramp = tree.add("ShaderNodeValToRGB")
    ramp.color_ramp.interpolation = "CONSTANT"
    ramp.color_ramp.elements[1].color = (1.0, 0.0, 0.0, 0.5)
    _, graph, colour = _diffuse_colour_from(tree, ramp)
    (node,) = graph["nodes"]
    assert node["op"] == "color_ramp" and node["interpolation"] == "constant"
    assert np.array(node["stops"]) == approx(np.array([[0, 0, 0, 0, 1], [1, 1, 0, 0, 0.5]]))
    assert colour == {"node": 0, "out": "color"}


def test_fresnel_and_layer_weight_as_mix_factors(tree):
    mix = tree.surface(tree.add("ShaderNodeMixShader"))
    layer = tree.add("ShaderNodeLayerWeight", Blend=0.3)
    tree.link(layer.outputs["Facing"], mix.inputs["Fac"])
    fresnel = tree.add("ShaderNodeFresnel", IOR=1.6)
    inner = tree.add("ShaderNodeMixShader")
    tree.link(fresnel.outputs[0], inner.inputs["Fac"])
    tree.link(inner.outputs[0], mix.inputs[1])
    tree.link(tree.add("ShaderNodeBsdfDiffuse").outputs[0], inner.inputs[1])
    tree.link(tree.add("ShaderNodeBsdfGlossy").outputs[0], inner.inputs[2])
    tree.link(tree.add("ShaderNodeBsdfGlossy").outputs[0], mix.inputs[2])
    _, graph = tree.translate()
    ops = {n["op"]: n for n in graph["nodes"]}
    assert ops["layer_weight"]["blend"] == approx(0.3) and "normal" not in ops["layer_weight"]
    assert ops["fresnel"]["ior"] == approx(1.6)
    assert len(graph["closures"]) == 3
    assert all(isinstance(c["weight"], dict) for c in graph["closures"])


def test_texture_coordinates_uv_map_and_mapping(tree):
    coords = tree.add("ShaderNodeTexCoord")
    uv_map = tree.add("ShaderNodeUVMap")
    uv_map.uv_map = "Detail"
    map_node = tree.add("ShaderNodeMapping")
    map_node.vector_type = "TEXTURE"
    map_node.inputs["Location"].default_value = (0.5, 0.0, 0.0)
    map_node.inputs["Rotation"].default_value = (0.0, 0.0, math.pi / 2)
    map_node.inputs["Scale"].default_value = (2.0, 2.0, 1.0)
    tree.link(coords.outputs["Generated"], map_node.inputs["Vector"])
    images = [tree.add("ShaderNodeTexImage") for _ in range(3)]
    tree.link(map_node.outputs[0], images[0].inputs["Vector"])
    tree.link(uv_map.outputs[0], images[1].inputs["Vector"])
    tree.link(coords.outputs["Object"], images[2].inputs["Vector"])
    add = tree.add("ShaderNodeMixRGB")
    tree.link(images[0].outputs[0], add.inputs["Fac"])
    tree.link(images[1].outputs[0], add.inputs["Color1"])
    tree.link(images[2].outputs[0], add.inputs["Color2"])
    t, graph, _ = _diffuse_colour_from(tree, add)
    ops = [n["op"] for n in graph["nodes"]]
    assert ops.count("generated") == 1 and ops.count("object") == 1
    uv = next(n for n in graph["nodes"] if n["op"] == "uv")
    assert t.uv_maps == ["", "Detail"] and uv["map"] == 1
    transform = next(n for n in graph["nodes"] if n["op"] == "transform")
    point = mathutils.Matrix.LocRotScale((0.5, 0, 0), mathutils.Euler((0, 0, math.pi / 2)),
                                         (2, 2, 1))
    assert np.array(transform["matrix"]) == approx(np.array(point.inverted())[:3])
    assert transform["kind"] == "point" and transform["normalize"] is False


def test_geometry_outputs_and_an_untranslated_one(tree):
    geometry = tree.add("ShaderNodeNewGeometry")
    fresnel = tree.add("ShaderNodeFresnel")
    tree.link(geometry.outputs["Normal"], fresnel.inputs["Normal"])
    diffuse = tree.surface(tree.add("ShaderNodeBsdfDiffuse"))
    tree.link(fresnel.outputs[0], diffuse.inputs["Roughness"])
    tree.link(geometry.outputs["Pointiness"], diffuse.inputs["Color"])
    t, graph = tree.translate()
    assert graph["nodes"] == [{"op": "normal"}, {"op": "fresnel", "ior": approx(1.45),
                                                 "normal": {"node": 0, "out": "vector"}}]
    assert graph["closures"][0]["params"]["color"] == [0.0, 0.0, 0.0]
    assert t.warnings == ["material 'Tree': node 'Geometry' (ShaderNodeNewGeometry): output "
                          "'Pointiness' is not translated; (0, 0, 0) is used instead"]


def test_mapping_matrices_match_blender_for_each_type():
    loc, rot, scale = (1.0, -2.0, 0.5), (0.3, -0.7, 1.1), (2.0, 0.5, 3.0)
    point = np.array(mathutils.Matrix.LocRotScale(loc, mathutils.Euler(rot), scale))
    assert np.array(mapping.matrix("POINT", loc, rot, scale)) == approx(point[:3])
    assert np.array(mapping.matrix("TEXTURE", loc, rot, scale)) == approx(np.linalg.inv(point)[:3])
    assert np.array(mapping.matrix("VECTOR", loc, rot, scale)) == approx(
        np.hstack([point[:3, :3], np.zeros((3, 1))]))
    r = np.array(mathutils.Euler(rot).to_matrix())
    assert np.array(mapping.matrix("NORMAL", loc, rot, scale))[:, :3] == approx(
        r / np.array(scale)[None, :])


def test_normal_map_and_bump_feed_the_closure_normal(tree):
    glossy = tree.surface(tree.add("ShaderNodeBsdfGlossy"))
    normal_map = tree.add("ShaderNodeNormalMap", Strength=0.5)
    normal_map.uv_map = "Tangents"
    bump = tree.add("ShaderNodeBump", Strength=0.7, Distance=0.2)
    tree.link(tree.add("ShaderNodeTexImage").outputs["Color"], normal_map.inputs["Color"])
    tree.link(tree.add("ShaderNodeTexImage").outputs["Alpha"], bump.inputs["Height"])
    tree.link(normal_map.outputs[0], bump.inputs["Normal"])
    tree.link(bump.outputs[0], glossy.inputs["Normal"])
    t, graph = tree.translate()
    ops = {n["op"]: (i, n) for i, n in enumerate(graph["nodes"])}
    nm_index, nm = ops["normal_map"]
    bump_index, bump_op = ops["bump"]
    assert nm["space"] == "tangent" and t.uv_maps[nm["map"]] == "Tangents"
    assert nm["strength"] == 0.5
    assert bump_op["normal"] == {"node": nm_index, "out": "normal"}
    assert bump_op["height"]["out"] == "alpha" and bump_op["strength"] == approx(0.7)
    assert graph["closures"][0]["normal"] == {"node": bump_index, "out": "normal"}


def test_bump_without_a_height_leaves_the_normal(tree):
    glossy = tree.surface(tree.add("ShaderNodeBsdfGlossy"))
    tree.link(tree.add("ShaderNodeBump").outputs[0], glossy.inputs["Normal"])
    _, graph = tree.translate()
    assert [n["op"] for n in graph["nodes"]] == ["normal"]


def test_reroutes_muted_nodes_and_groups_are_followed(tree):
    rgb = tree.add("ShaderNodeRGB")
    rgb.outputs[0].default_value = (0.25, 0.5, 1.0, 1.0)
    reroute = tree.nodes.new("NodeReroute")
    muted = tree.add("ShaderNodeInvert")
    muted.mute = True
    tree.link(rgb.outputs[0], reroute.inputs[0])
    tree.link(reroute.outputs[0], muted.inputs["Color"])

    group_tree = bpy.data.node_groups.new("Darken", "ShaderNodeTree")
    group_in = group_tree.nodes.new("NodeGroupInput")
    group_out = group_tree.nodes.new("NodeGroupOutput")
    group_tree.inputs.new("NodeSocketColor", "In")
    group_tree.outputs.new("NodeSocketColor", "Out")
    gamma = group_tree.nodes.new("ShaderNodeGamma")
    gamma.inputs["Gamma"].default_value = 2.2
    group_tree.links.new(group_in.outputs[0], gamma.inputs["Color"])
    group_tree.links.new(gamma.outputs[0], group_out.inputs[0])
    group = tree.add("ShaderNodeGroup")
    group.node_tree = group_tree
    tree.link(muted.outputs[0], group.inputs[0])

    t, graph, colour = _diffuse_colour_from(tree, group)
    assert graph["nodes"] == [{"op": "gamma", "color": approx((0.25, 0.5, 1.0)), "gamma": approx(2.2)}]
    assert colour == {"node": 0, "out": "color"}
    names = {entry["node"] for entry in t.coverage.values()}
    assert "Group/Gamma" in names and "Group" in names
    assert t.warnings == []


# ---- images -----------------------------------------------------------------------------------

def test_missing_images_read_magenta_with_a_warning(tree):
    image = tree.add("ShaderNodeTexImage")
    image.image = bpy.data.images.new("wood.png", 1, 1)
    image.image.source, image.image.filepath = "FILE", "/nonexistent/wood.png"
    _, graph, colour = _diffuse_colour_from(tree, image)
    t = nodes.translate(tree.material)
    assert graph["textures"] == [{"missing": True}]
    assert colour == {"node": 1, "out": "color"}
    assert t.warnings == ["material 'Tree': node 'Image Texture' (ShaderNodeTexImage): image "
                          "'wood.png': file /nonexistent/wood.png not found; it renders magenta "
                          "(1, 0, 1), as Cycles renders a missing image"]


def _pixels(width, height):
    rows = np.linspace(0.0, 1.0, width * height * 4, dtype=np.float32)
    return rows.reshape(height, width, 4)


def _read(path):
    import OpenImageIO as oiio
    return oiio.ImageInput.open(path).read_image("float")


def test_generated_images_are_written_with_their_colour_space(tree):
    image = bpy.data.images.new("generated", 4, 3, alpha=True)
    pixels = _pixels(4, 3)
    image.pixels.foreach_set(pixels.ravel())
    node = tree.add("ShaderNodeTexImage")
    node.image = image
    node.interpolation, node.extension = "Closest", "CLIP"
    _, graph, _ = _diffuse_colour_from(tree, node)
    (texture,) = graph["textures"]
    assert texture["colorspace"] == "srgb" and texture["interpolation"] == "closest"
    assert texture["extension"] == "clip" and texture["alpha"] == "straight"
    written = _read(texture["path"])
    # byte image: Blender's values are quantised to 8 bits, and stored top row first
    assert written == approx(np.round(pixels[::-1] * 255) / 255)


def test_packed_images_are_written_byte_for_byte(tree, tmp_path):
    source = bpy.data.images.new("to pack", 2, 2, float_buffer=True)
    source.pixels.foreach_set(_pixels(2, 2).ravel())
    source.filepath_raw = str(tmp_path / "packed.exr")
    source.file_format = "OPEN_EXR"
    source.save()
    image = bpy.data.images.load(str(tmp_path / "packed.exr"))
    image.colorspace_settings.name = "Non-Color"
    image.pack()
    original = (tmp_path / "packed.exr").read_bytes()
    os.remove(tmp_path / "packed.exr")
    node = tree.add("ShaderNodeTexImage")
    node.image = image
    node.interpolation = "Cubic"
    t, graph, _ = _diffuse_colour_from(tree, node)
    (texture,) = graph["textures"]
    assert open(texture["path"], "rb").read() == original
    assert texture["colorspace"] == "non_color" and texture["interpolation"] == "cubic"
    assert t.warnings == []


# ---- what cannot be translated ----------------------------------------------------------------

def test_an_unsupported_node_warns_and_uses_the_socket_default(tree):
    voronoi = tree.add("ShaderNodeTexVoronoi")
    diffuse = tree.surface(tree.add("ShaderNodeBsdfDiffuse", Color=(0.1, 0.2, 0.3, 1.0)))
    tree.link(voronoi.outputs["Color"], diffuse.inputs["Color"])
    t, graph = tree.translate()
    assert graph["closures"][0]["params"]["color"] == approx([0.1, 0.2, 0.3])
    assert t.warnings == ["material 'Tree': node 'Voronoi Texture' (ShaderNodeTexVoronoi): this "
                          "node is not supported; input 'Color' of node 'Diffuse BSDF' uses its "
                          "default value (0.1, 0.2, 0.3)"]
    coverage = {e["node"]: e for e in nodes.material_coverage(tree.material)}
    assert coverage["Voronoi Texture"]["status"] == "unsupported"
    assert coverage["Diffuse BSDF"]["status"] == "exact"


def test_an_unsupported_shader_contributes_nothing_with_a_warning(tree):
    add = tree.surface(tree.add("ShaderNodeAddShader"))
    tree.link(tree.add("ShaderNodeBsdfToon").outputs[0], add.inputs[0])
    tree.link(tree.add("ShaderNodeBsdfDiffuse").outputs[0], add.inputs[1])
    t, graph = tree.translate()
    assert [c["model"] for c in graph["closures"]] == ["cycles_oren_nayar"]
    assert len(t.warnings) == 1 and "'Toon BSDF' (ShaderNodeBsdfToon)" in t.warnings[0]
    assert "contributes nothing" in t.warnings[0]


def test_a_cyclic_tree_warns_and_does_not_crash(tree):
    first, second = tree.add("ShaderNodeMath"), tree.add("ShaderNodeMath")
    tree.link(first.outputs[0], second.inputs[0])
    tree.link(second.outputs[0], first.inputs[0])
    diffuse = tree.surface(tree.add("ShaderNodeBsdfDiffuse"))
    tree.link(second.outputs[0], diffuse.inputs["Roughness"])
    t, graph = tree.translate()
    assert len(graph["closures"]) == 1
    assert any("cycl" in w and "default value" in w for w in t.warnings), t.warnings


def test_a_shader_linked_into_a_value_input_warns(tree):
    diffuse = tree.surface(tree.add("ShaderNodeBsdfDiffuse"))
    tree.link(tree.add("ShaderNodeBsdfGlossy").outputs[0], diffuse.inputs["Roughness"])
    t, graph = tree.translate()
    assert graph["closures"][0]["params"]["roughness"] == 0.0
    assert len(t.warnings) == 1 and "Roughness" in t.warnings[0]


def test_displacement_is_reported(tree):
    tree.surface(tree.add("ShaderNodeBsdfDiffuse"))
    tree.link(tree.add("ShaderNodeDisplacement").outputs[0], tree.output.inputs["Displacement"])
    t, _ = tree.translate()
    assert t.warnings == ["material 'Tree': node 'Material Output' (ShaderNodeOutputMaterial): the "
                          "Displacement input is not translated; the surface is rendered without it"]


def _node_mix(tree, rng):
    """Two of every node kind the translators know, three reroutes, and six other shader
    nodes (untranslated ones)."""
    from bxdf_lab.nodes import walk
    others = [n for n in sorted(dir(bpy.types)) if n.startswith("ShaderNode") and
              n not in walk.TRANSLATORS and n not in ("ShaderNodeTree", "ShaderNodeCustomGroup")]
    made = [tree.nodes.new(name) for name in sorted(walk.TRANSLATORS) for _ in range(2)]
    made += [tree.nodes.new("NodeReroute") for _ in range(3)]
    for name in rng.permutation(others):
        if len(made) == 2 * len(walk.TRANSLATORS) + 9:
            break
        try:
            made.append(tree.nodes.new(str(name)))
        except RuntimeError:  # abstract types and those of other trees
            continue
    return made


@pytest.mark.parametrize("seed", range(6))
def test_random_trees_of_every_node_kind_never_crash(tree, seed):
    """Shader nodes linked at random (cycles, mismatched sockets and muted nodes included): the
    translation ends, and each warning names the material."""
    rng = np.random.default_rng(seed)
    made = _node_mix(tree, rng)
    made = [made[i] for i in rng.permutation(len(made))]
    last_mix = max(i for i, n in enumerate(made) if n.bl_idname == "ShaderNodeMixShader")
    made.append(made.pop(last_mix))  # the surface, fed by everything before it
    # Mostly a DAG (each node fed by earlier ones, mostly by matching socket types), plus a few
    # links back (cycles) and a few between any sockets (invalid).
    for position, node in enumerate(made[1:], start=1):
        earlier = [s for n in made[:position] for s in n.outputs]
        for socket in node.inputs:
            matching = [s for s in earlier if s.type == socket.type]
            if rng.random() < 0.8 and matching:
                tree.link(matching[rng.integers(len(matching))], socket)
    for _ in range(4):
        a, b = sorted(rng.choice(len(made), size=2, replace=False))
        if made[b].outputs and made[a].inputs:
            tree.link(made[b].outputs[0], made[a].inputs[rng.integers(len(made[a].inputs))])
    tree.surface(made[-1])
    for node in rng.choice(made, size=10, replace=False):
        node.mute = True
    t, graph = tree.translate()
    assert len(t.coverage) >= 4  # the walk went beyond the surface's own node
    assert all(w.startswith("material 'Tree': ") for w in t.warnings)
    for i, node in enumerate(graph["nodes"]):  # evaluation order: references point backwards
        refs = [v for v in node.values() if isinstance(v, dict)]
        assert all(r["node"] < i for r in refs), node
    assert {e["status"] for e in nodes.material_coverage(tree.material)} <= {
        "exact", "approximate", "unsupported"}
