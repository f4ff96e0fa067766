"""Sets a bpy material up for one engine from its (model, params) (runs inside Blender).

BXDF_LAB: bxdf_lab.api.assign. CYCLES / POVRAY_RENDER: the add-on's "Set Up Cycles Material" /
"Set Up POV-Ray Material" operators when the add-on provides them; until then the interim mapping.
Either way `summarize` reads back what the engine will actually render, which the report prints
beside every approximate pairing."""
from __future__ import annotations

import bpy

from . import interim_material_mapping   # INTERIM: goes when the add-on's operators land

OPERATOR_LABELS = {"CYCLES": "Set Up Cycles Material", "POVRAY_RENDER": "Set Up POV-Ray Material"}


def addon_api():
    """bxdf_lab.api if the add-on is enabled, else None."""
    try:
        import bxdf_lab.api as api  # noqa: PLC0415 (only inside Blender with the add-on)
    except ImportError:
        return None
    return api if hasattr(bpy.types.Material, "bxdf_lab") else None


def addon_operator(label):
    """The bxdf_lab operator whose label is `label`, found by label so that its idname is free."""
    namespace = getattr(bpy.ops, "bxdf_lab", None)
    if namespace is None:
        return None
    for name in dir(namespace):
        op = getattr(namespace, name)
        try:
            if op.get_rna_type().name == label:
                return op
        except (AttributeError, KeyError, RuntimeError):
            continue
    return None


def setup(material, obj, model, params, engine) -> str:
    """Returns which code did the set-up ("add-on" or "interim")."""
    api = addon_api()
    if engine == "BXDF_LAB":
        if api is None:
            raise RuntimeError("bxdf_lab add-on (or its bxdf module) is not available")
        api.assign(material, model, **params)
        return "add-on"
    op = addon_operator(OPERATOR_LABELS[engine]) if api is not None else None
    if op is not None:
        api.assign(material, model, **params)
        with bpy.context.temp_override(object=obj, active_object=obj, material=material,
                                       selected_objects=[obj]):
            result = op()
        if "FINISHED" not in result:
            raise RuntimeError(f"{OPERATOR_LABELS[engine]} returned {result} for "
                               f"material '{material.name}'")
        return "add-on"
    if engine == "CYCLES":
        interim_material_mapping.setup_cycles(material, model, params)
    else:
        interim_material_mapping.setup_povray(material, model, params)
    return "interim"


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
    return "bxdf_lab: the model itself"


def _fmt(value):
    try:
        return "(" + ", ".join(f"{float(x):.4g}" for x in value) + ")"
    except TypeError:
        return f"{float(value):.4g}" if isinstance(value, (int, float)) else str(value)
