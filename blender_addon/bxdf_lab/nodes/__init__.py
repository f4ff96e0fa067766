"""Blender shader node trees → material graphs (docs/material-graph.md).

    from bxdf_lab import nodes
    translation = nodes.translate(material)   # .graph.as_dict(), .warnings, .coverage
    nodes.material_coverage(material)         # [{"node", "type", "status", "why"}, ...]

One module per node kind (named after the node) declares the Blender node types it translates
(`BL_IDNAMES`) and either `value(scope, node, output)` (a value node: returns a constant or a
reference) or `closures(scope, node, weight)` (a shader node: adds closures with `weight`).
Reroutes, muted nodes and node groups are followed by walk.py.
"""

import importlib

from . import walk

NODE_MODULES = (
    "principled_bsdf", "diffuse_bsdf", "glossy_bsdf", "anisotropic_bsdf", "glass_bsdf",
    "refraction_bsdf", "translucent_bsdf", "transparent_bsdf", "velvet_bsdf", "emission",
    "mix_shader", "add_shader", "holdout",
    "image_texture", "environment_texture", "rgb", "value", "mix_rgb", "mix", "math",
    "vector_math", "invert", "gamma",
    "bright_contrast", "hue_saturation", "separate_rgb", "separate_xyz", "separate_color",
    "combine_rgb", "combine_xyz", "combine_color", "color_ramp", "fresnel", "layer_weight",
    "texture_coordinate", "geometry", "mapping", "uv_map", "normal_map", "bump",
)

for _name in NODE_MODULES:
    _module = importlib.import_module(f".{_name}", __name__)
    for _idname in _module.BL_IDNAMES:
        walk.TRANSLATORS[_idname] = _module


NO_NODE_TREE = "(no node tree)"


def translate(material, write_files=True):
    """The walk.Translation of `material`: from its active Cycles Material Output's Surface, or,
    for a material without nodes, the Diffuse BSDF of its viewport colour that Cycles renders.
    write_files=False (panels, coverage) leaves packed and generated images unwritten; their
    texture records then name no file."""
    translation = walk.Translation(material, write_files)
    if not material.use_nodes or material.node_tree is None:
        _without_nodes(translation)
        return translation
    output = material.node_tree.get_output_node("CYCLES")
    if output is None:
        translation.warn(None, (), "no Material Output node; the surface renders black, as in "
                         "Cycles")
        return translation
    translation.closures(output.inputs["Surface"], (), output, 1.0)
    for name in ("Volume", "Displacement"):
        if output.inputs[name].is_linked:
            translation.note(output, (), "approximate", f"{name} is not translated")
            translation.warn(output, (), f"the {name} input is not translated; the surface is "
                             f"rendered without it")
    return translation


def _without_nodes(translation):
    material = translation.material
    translation.graph.closures.append(
        {"model": "cycles_oren_nayar", "weight": 1.0,
         "params": {"color": [float(c) for c in material.diffuse_color[:3]], "roughness": 0.0}})
    translation.lobes.append({"node": NO_NODE_TREE, "model": "cycles_oren_nayar", "weight": 1.0,
                              "lobes": [("closure", 1, True)]})
    translation.closure_counts["#cycles_oren_nayar"] = 1
    translation.coverage[NO_NODE_TREE] = {"node": NO_NODE_TREE, "type": "Material", "status": "exact",
                                "why": "no node tree: Cycles renders the viewport colour as a "
                                       "Diffuse BSDF"}


def material_coverage(material):
    """[{"node": name, "type": bl_idname, "status": "exact"|"approximate"|"unsupported",
    "why": str}] for every node the translation of `material` reached."""
    return list(translate(material, write_files=False).coverage.values())
