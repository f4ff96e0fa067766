"""Export of node-tree materials: graphs, UV maps and tangents, Cycles' closure budget, warnings;
and renders through BXDF_LAB against Cycles for the graphs this renderer build reads."""

import math

import bpy
import numpy as np
import pytest

from bxdf_lab import api, engine, export
from test_nodes import Tree
from test_render import _render, _scene, bxdf_render  # noqa: F401 (a fixture)


def _plane(material, name="plane", location=(0, 0, 0)):
    mesh = bpy.data.meshes.new(name)
    mesh.from_pydata([(-1, -1, 0), (1, -1, 0), (1, 1, 0), (-1, 1, 0)], [], [(0, 1, 2, 3)])
    mesh.uv_layers.new(name="UVMap")
    mesh.uv_layers.new(name="Detail")
    mesh.materials.append(material)
    obj = bpy.data.objects.new(name, mesh)
    obj.location = location
    bpy.context.scene.collection.objects.link(obj)
    return obj


def _export():
    return export.export_scene(bpy.context.evaluated_depsgraph_get())


def _translation_warnings(data):
    """The scene's warnings but those naming models this bxdf build lacks (until the
    `principled` and `cycles-nodes` models are in the registry; tested separately below)."""
    return [w for w in data["warnings"] if "is not in this build of bxdf" not in w]


def _image_through(tree, bl_idname, uv_map, into):
    """An Image Texture feeding `into` through a node (`bl_idname`) naming UV map `uv_map`."""
    node = tree.add(bl_idname)
    node.uv_map = uv_map
    image = tree.add("ShaderNodeTexImage")
    image.image = bpy.data.images.new("pixels", 2, 2)
    if bl_idname == "ShaderNodeNormalMap":
        tree.link(image.outputs["Color"], node.inputs["Color"])
        tree.link(node.outputs[0], into)
    else:
        tree.link(node.outputs[0], image.inputs["Vector"])
        tree.link(image.outputs["Color"], into)


def test_uv_maps_tangents_and_texture_space_follow_the_graph():
    tree = Tree("textured")
    glossy = tree.surface(tree.add("ShaderNodeBsdfGlossy"))
    _image_through(tree, "ShaderNodeNormalMap", "Detail", glossy.inputs["Normal"])
    plane = _plane(tree.material)
    data = _export()
    assert data["uv_map_names"] == ["", "Detail"] and data["warnings"] == []
    (mesh,) = data["meshes"]
    corners = mesh["uv_indices"].ravel()  # the active map's per-loop UVs, indexed per corner
    render_map, detail = mesh["uv_maps"]
    np.testing.assert_array_equal(render_map, mesh["uvs"][corners])
    assert detail.shape == (6, 2) and detail.dtype == np.float32
    np.testing.assert_array_equal(
        detail, np.array([l.uv for l in plane.data.uv_layers["Detail"].data])[corners])
    assert mesh["tangents"][0] is None
    # a plane in z = 0 with Blender's default UVs: tangent along +x, bitangent (sign +1) along +y
    np.testing.assert_allclose(mesh["tangents"][1], np.tile([1.0, 0.0, 0.0, 1.0], (6, 1)), atol=1e-6)
    np.testing.assert_allclose(mesh["texture_space"], [plane.data.texspace_location,
                                                       plane.data.texspace_size])
    (entry,) = data["materials"]
    nm = next(n for n in entry["graph"]["nodes"] if n["op"] == "normal_map")
    assert data["uv_map_names"][nm["map"]] == "Detail"
    assert set(entry) == {"name", "graph"}


def test_meshes_carry_no_uv_maps_when_no_graph_reads_one():
    tree = Tree("plain")
    tree.surface(tree.add("ShaderNodeBsdfDiffuse"))
    _plane(tree.material)
    data = _export()
    (mesh,) = data["meshes"]
    assert mesh["uv_maps"] == [] and mesh["tangents"] == []
    assert data["uv_map_names"] == [""] and data["closure_budget"] == 1  # one diffuse closure


def test_a_uv_map_no_graph_reads_is_zeros():
    tree = Tree("detail only")
    diffuse = tree.surface(tree.add("ShaderNodeBsdfDiffuse"))
    _image_through(tree, "ShaderNodeUVMap", "Detail", diffuse.inputs["Color"])
    plane = _plane(tree.material)
    data = _export()
    (mesh,) = data["meshes"]
    render_map, detail = mesh["uv_maps"]  # the render map "" is not read: the graph names "Detail"
    np.testing.assert_array_equal(render_map, np.zeros((6, 2)))
    np.testing.assert_array_equal(
        detail, np.array([l.uv for l in plane.data.uv_layers["Detail"].data])[mesh["uv_indices"].ravel()])


def test_model_materials_alone_have_no_closure_budget():
    material = bpy.data.materials.new("model")
    material.use_nodes = True  # a node tree that only Cycles would render
    api.assign(material, "lambertian")
    _plane(material)
    data = _export()
    assert data["closure_budget"] is None
    assert data["meshes"][0]["uv_maps"] == []


def test_a_uv_map_the_mesh_lacks_is_a_warning():
    tree = Tree("elsewhere")
    diffuse = tree.surface(tree.add("ShaderNodeBsdfDiffuse"))
    _image_through(tree, "ShaderNodeUVMap", "Nope", diffuse.inputs["Color"])
    _plane(tree.material)
    data = _export()
    np.testing.assert_array_equal(data["meshes"][0]["uv_maps"][1], np.zeros((6, 2)))
    assert data["warnings"] == ["material 'elsewhere': mesh 'plane' has no UV map "
                                "'Nope'; its coordinates read as (0, 0), as in Cycles"]


def test_an_ngon_mesh_has_no_tangents_and_says_so():
    tree = Tree("ngon")
    glossy = tree.surface(tree.add("ShaderNodeBsdfGlossy"))
    _image_through(tree, "ShaderNodeNormalMap", "", glossy.inputs["Normal"])
    mesh = bpy.data.meshes.new("pentagon")
    mesh.from_pydata([(math.cos(a), math.sin(a), 0.0) for a in np.arange(5) * 2 * math.pi / 5],
                     [], [(0, 1, 2, 3, 4)])
    mesh.uv_layers.new(name="UVMap")
    mesh.materials.append(tree.material)
    bpy.context.scene.collection.objects.link(bpy.data.objects.new("pentagon", mesh))
    data = _export()
    assert data["meshes"][0]["tangents"] == [None]
    (warning,) = data["warnings"]
    assert warning.startswith("material 'ngon': mesh 'pentagon': no tangents for UV map 'UVMap' (")
    assert warning.endswith("); Normal Map nodes on it have none to read")


def _all_lobes_principled(name):
    tree = Tree(name)
    tree.surface(tree.add("ShaderNodeBsdfPrincipled", Sheen=0.5, Transmission=0.5, Clearcoat=1.0))
    return tree


def test_a_lone_principled_with_every_lobe_loses_its_clearcoat_as_in_cycles():
    _plane(_all_lobes_principled("everything").material)
    data = _export()
    assert data["closure_budget"] == 8
    params = data["materials"][0]["graph"]["closures"][0]["params"]
    assert params["clearcoat"] == 0.0 and params["sheen"] == 0.5
    assert _translation_warnings(data) == [
        "material 'everything': node 'Principled BSDF': Cycles' closure budget for this scene is "
        "8 slots per shader and the clearcoat (2 slots) does not fit; dropped, as Cycles drops it"]


def test_a_larger_shader_elsewhere_in_the_scene_keeps_the_clearcoat():
    _plane(_all_lobes_principled("everything").material)
    other = Tree("mixed")
    mix = other.surface(other.add("ShaderNodeMixShader"))
    other.link(other.add("ShaderNodeBsdfPrincipled").outputs[0], mix.inputs[1])
    other.link(other.add("ShaderNodeBsdfGlass").outputs[0], mix.inputs[2])
    _plane(other.material, "other", (3, 0, 0))
    data = _export()
    assert data["closure_budget"] == 10 and _translation_warnings(data) == []
    clearcoats = [m["graph"]["closures"][0]["params"]["clearcoat"] for m in data["materials"]]
    assert clearcoats == [1.0, 0.0]


@pytest.mark.parametrize("bigger_shader_elsewhere", [False, True])
def test_the_clearcoat_budget_is_what_cycles_renders(bigger_shader_elsewhere, tmp_path):
    """The export drops the clearcoat exactly when Cycles' image of the material equals its image
    with Clearcoat 0."""
    tree = _all_lobes_principled("everything")
    principled = tree.nodes["Principled BSDF"]
    principled.inputs["Clearcoat Roughness"].default_value = 0.5
    scene = _scene(tree.material, tmp_path)
    if bigger_shader_elsewhere:  # out of the camera's view, it only raises the budget
        other = Tree("mixed")
        mix = other.surface(other.add("ShaderNodeMixShader"))
        other.link(other.add("ShaderNodeBsdfPrincipled").outputs[0], mix.inputs[1])
        other.link(other.add("ShaderNodeBsdfGlass").outputs[0], mix.inputs[2])
        _plane(other.material, "other", (0, 0, -50))
    data = _export()
    kept = next(m for m in data["materials"] if m["name"] == "everything")[
        "graph"]["closures"][0]["params"]["clearcoat"] == 1.0
    assert kept == bigger_shader_elsewhere
    with_clearcoat = _render(scene, "CYCLES", str(tmp_path / "with.exr"))
    principled.inputs["Clearcoat"].default_value = 0.0
    without = _render(scene, "CYCLES", str(tmp_path / "without.exr"))
    cycles_kept = np.abs(with_clearcoat - without).max() > 1e-3
    assert cycles_kept == kept


def test_a_model_missing_from_the_registry_is_a_warning(monkeypatch):
    from bxdf_lab.nodes import registry_params
    models = dict(registry_params.models())
    del models["cycles_oren_nayar"]
    monkeypatch.setattr(registry_params, "models", lambda: models)
    tree = Tree("rough")
    tree.surface(tree.add("ShaderNodeBsdfDiffuse"))
    _plane(tree.material)
    data = _export()
    assert data["warnings"] == ["material 'rough': model 'cycles_oren_nayar' is not in this build "
                                "of bxdf (bxdf.models()); the renderer cannot render it"]


# ---- renders: node materials through BXDF_LAB against Cycles ---------------------------------

def _diffuse(tree):
    tree.surface(tree.add("ShaderNodeBsdfDiffuse", Color=(0.7, 0.5, 0.3, 1.0), Roughness=0.8))


def _glossy(distribution):
    def build(tree):
        node = tree.surface(tree.add("ShaderNodeBsdfGlossy", Color=(0.7, 0.5, 0.3, 1.0),
                                     Roughness=0.5))
        node.distribution = distribution
    return build


def _constants_through_reroute_muted_node_and_group(tree):
    """RGB → reroute → muted Invert → a group passing its input through → Diffuse Color; Value →
    Roughness: all constant, so the graph has no nodes."""
    rgb = tree.add("ShaderNodeRGB")
    rgb.outputs[0].default_value = (0.2, 0.6, 0.4, 1.0)
    reroute = tree.nodes.new("NodeReroute")
    muted = tree.add("ShaderNodeInvert")
    muted.mute = True
    group_tree = bpy.data.node_groups.new("pass", "ShaderNodeTree")
    group_tree.inputs.new("NodeSocketColor", "In")
    group_tree.outputs.new("NodeSocketColor", "Out")
    group_tree.links.new(group_tree.nodes.new("NodeGroupInput").outputs[0],
                         group_tree.nodes.new("NodeGroupOutput").inputs[0])
    group = tree.add("ShaderNodeGroup")
    group.node_tree = group_tree
    value = tree.add("ShaderNodeValue")
    value.outputs[0].default_value = 0.6
    diffuse = tree.surface(tree.add("ShaderNodeBsdfDiffuse"))
    for a, b in ((rgb.outputs[0], reroute.inputs[0]), (reroute.outputs[0], muted.inputs["Color"]),
                 (muted.outputs[0], group.inputs[0]), (group.outputs[0], diffuse.inputs["Color"]),
                 (value.outputs[0], diffuse.inputs["Roughness"])):
        tree.link(a, b)


def _anisotropic_without_anisotropy(tree):
    tree.surface(tree.add("ShaderNodeBsdfAnisotropic", Color=(0.7, 0.5, 0.3, 1.0), Roughness=0.4,
                          Anisotropy=0.0))


def _emission(tree):
    tree.surface(tree.add("ShaderNodeEmission", Color=(0.6, 0.3, 0.1, 1.0), Strength=2.0))


def _colour_into_the_surface(tree):
    rgb = tree.add("ShaderNodeRGB")
    rgb.outputs[0].default_value = (0.6, 0.3, 0.1, 1.0)
    tree.surface(rgb)


def _no_nodes(tree):
    tree.material.use_nodes = False
    tree.material.diffuse_color = (0.2, 0.6, 0.4, 1.0)


@pytest.mark.parametrize("build", [
    _diffuse, _glossy("GGX"), _glossy("BECKMANN"), _anisotropic_without_anisotropy, _emission,
    _no_nodes, _constants_through_reroute_muted_node_and_group, _colour_into_the_surface,
], ids=["diffuse", "glossy_ggx", "glossy_beckmann", "anisotropic_0", "emission", "no_nodes",
        "reroute_muted_group", "colour_into_surface"])
def test_node_material_renders_like_cycles(build, bxdf_render, tmp_path):
    tree = Tree("node material")
    build(tree)
    scene = _scene(tree.material, tmp_path)
    ours = _render(scene, "BXDF_LAB", str(tmp_path / "bxdf_lab.exr"))
    assert engine.last_error == ""
    cycles = _render(scene, "CYCLES", str(tmp_path / "cycles.exr"))
    assert ours[..., :3].max() > 0.05
    # delta sun, direct light only, pixel centres: both are noise-free
    np.testing.assert_allclose(ours[..., :3], cycles[..., :3], rtol=5e-3, atol=1e-4)
