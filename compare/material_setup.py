"""Sets a bpy material up for one engine from its (model, params) (runs inside Blender), only
through the bxdf_lab add-on: `bxdf_lab.api.assign`, then for CYCLES / POVRAY_RENDER the add-on's
"Set Up Cycles Material" / "Set Up POV-Ray Material" operator (which owns the mapping, and for
POV-Ray the light calibration). `summarize` reads back what the engine will actually render, which
the report prints beside every approximate pairing."""
from __future__ import annotations

import bpy

from . import node_recipes
from .scene_spec import NODES

OPERATOR_LABELS = {"CYCLES": "Set Up Cycles Material", "POVRAY_RENDER": "Set Up POV-Ray Material"}
ADDON_LABEL_FIELDS = {"CYCLES": "cycles_label", "POVRAY_RENDER": "pov_label"}


def addon_api():
    """bxdf_lab.api; RuntimeError when the add-on (or its compiled module) is not registered."""
    try:
        import bxdf_lab.api as api  # noqa: PLC0415 (only inside Blender with the add-on)
    except ImportError as exc:
        raise RuntimeError(f"the bxdf_lab add-on is not importable: {exc}") from exc
    if not hasattr(bpy.types.Material, "bxdf_lab"):
        raise RuntimeError("the bxdf_lab add-on is not registered (material.bxdf_lab missing: "
                           "does the compiled `bxdf` module import inside Blender?)")
    return api


def addon_operator(label):
    """The bxdf_lab operator whose label is `label`, found by label so that its idname is free."""
    namespace = getattr(bpy.ops, "bxdf_lab", None)
    if namespace is not None:
        for name in dir(namespace):
            op = getattr(namespace, name)
            try:
                if op.get_rna_type().name == label:
                    return op
            except (AttributeError, KeyError, RuntimeError):
                continue
    raise RuntimeError(f"the bxdf_lab add-on has no operator \"{label}\"")


def setup(material, obj, model, params, engine) -> str:
    """Assigns the model; for CYCLES / POVRAY_RENDER runs the add-on's set-up operator on `obj`'s
    `material`. Returns the add-on's label for the engine ("exact" / "approximate"; "exact" for
    BXDF_LAB, which renders the model itself). A node material (scene_spec.NODES) gets its node
    tree for every engine."""
    if model == NODES:
        return _node_setup(material, params["recipe"], engine)
    api = addon_api()
    api.assign(material, model, **params)
    if engine == "BXDF_LAB":
        return "exact"
    op = addon_operator(OPERATOR_LABELS[engine])
    with bpy.context.temp_override(object=obj, active_object=obj, material=material,
                                   selected_objects=[obj]):
        result = op()
    if "FINISHED" not in result:
        raise RuntimeError(f"{OPERATOR_LABELS[engine]} returned {result} for "
                           f"material '{material.name}'")
    return getattr(material.bxdf_lab, ADDON_LABEL_FIELDS[engine])


def _node_setup(material, recipe, engine) -> str:
    """Builds the recipe's node tree. Cycles renders it ("exact"); BXDF_LAB renders the add-on's
    translation, "exact" when every node it reached translates exactly; POV-Ray exports node
    materials as its default texture ("approximate")."""
    node_recipes.build(material, recipe)
    if engine == "POVRAY_RENDER":
        return "approximate"
    if engine == "CYCLES":
        return "exact"
    addon_api()
    from bxdf_lab import nodes  # noqa: PLC0415 (only inside Blender with the add-on)
    coverage = nodes.material_coverage(material)
    return "exact" if all(entry["status"] == "exact" for entry in coverage) else "approximate"


def summarize(material, engine) -> str:
    """A one-line account of what the engine renders for this material (plus the add-on's own
    account of its mapping, when it made it)."""
    text = _read_back(material, engine)
    settings = getattr(material, "bxdf_lab", None)
    note = {"CYCLES": "cycles_mapping", "POVRAY_RENDER": "pov_mapping"}.get(engine)
    if settings is not None and note and getattr(settings, note, ""):
        text += f" [add-on: {getattr(settings, note)}]"
    return text


def _read_back(material, engine) -> str:
    if engine == "CYCLES":
        if not material.use_nodes:
            return "no node tree (Cycles renders its default)"
        parts = []
        for node in material.node_tree.nodes:
            if node.type == "OUTPUT_MATERIAL":
                continue
            values = []
            if hasattr(node, "distribution"):
                values.append(node.distribution)
            for socket in node.inputs:
                if socket.is_linked or not hasattr(socket, "default_value"):
                    continue
                v = socket.default_value
                if socket.name in ("Normal", "Tangent", "Weight"):
                    continue
                values.append(f"{socket.name}={_fmt(v)}")
            parts.append(f"{node.bl_label}({', '.join(values)})")
        return "; ".join(parts)
    if engine == "POVRAY_RENDER":
        if material.use_nodes:
            return "node material: exported as POV-Ray's default texture"
        pov = material.pov
        text = (f"pigment {_fmt(material.diffuse_color)}, diffuse {pov.diffuse_intensity:.3g}, "
                f"ambient {pov.ambient:.3g}, {pov.specular_shader.lower()} "
                f"{pov.specular_intensity:.3g} hardness {pov.specular_hardness}")
        if material.pov_raytrace_mirror.use:
            text += f", reflection {_fmt(pov.mirror_color)}"
            if pov.mirror_use_IOR:
                text += " fresnel"
        if pov.transparency_method == "RAYTRACE" and pov.use_transparency:
            text += f", refraction ior {material.pov_raytrace_transparency.ior:.4g}"
        return text
    if engine != "BXDF_LAB":
        return "bxdf_lab: the model itself"
    # The add-on's own rule (an unset source is inferred from the stored settings).
    from bxdf_lab import material_source, nodes  # noqa: PLC0415 (only inside Blender)
    if material_source.source(material) != "MODEL":
        return "bxdf_lab: node translation (" + "; ".join(
            f"{e['node']}: {e['status']}" for e in nodes.material_coverage(material)) + ")"
    return "bxdf_lab: the model itself"


def _fmt(value):
    try:
        return "(" + ", ".join(f"{float(x):.4g}" for x in value) + ")"
    except TypeError:
        return f"{float(value):.4g}" if isinstance(value, (int, float)) else str(value)
