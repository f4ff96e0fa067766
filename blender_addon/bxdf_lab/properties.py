"""The material settings, GENERATED from the model registry (`bxdf.models()`).

`material.bxdf_lab.model` selects a model; `material.bxdf_lab.<model name>` holds that model's
parameters as Blender properties with the registry's defaults, ranges, units and tooltips (one
PropertyGroup class per model, so that two models may give the same parameter name different
defaults and ranges). List parameters (Lafortune lobes) become a CollectionProperty of a generated
element group. Nothing here names a model or a parameter.
"""

import math
import zlib

import bpy
from bpy.props import (BoolProperty, CollectionProperty, EnumProperty, FloatProperty,
                       FloatVectorProperty, PointerProperty, StringProperty)

from . import dependency, material_source, schema

FLT_MAX = 3.4028234e38
# Attribute names a PropertyGroup already uses; a parameter with such a name gets a suffix.
_RESERVED = {"name", "rna_type", "bl_rna", "id_data"}
# Hidden flag: the list parameters of this group have been given their default elements.
LIST_INITIALISED = "bxdf_lists_initialised"

# Filled by register(): {model name: schema.Model}, and the generated classes.
MODELS = {}
_classes = []


def enum_number(identifier):
    """A stable number for an enum item: .blend files store enum values as numbers, so the
    number must not depend on the item's position (the registry may add or reorder models)."""
    return zlib.crc32(identifier.encode()) & 0x7FFFFFFF


def enum_items(identifiers, labels=None, docs=None):
    return [(i, (labels or {}).get(i, i.replace("_", " ").title()), (docs or {}).get(i, ""),
             enum_number(i)) for i in identifiers]


def attr_name(param_name):
    """The Blender attribute that stores parameter `param_name`."""
    return param_name + "_" if param_name in _RESERVED else param_name


PRECISION = 4  # decimals shown in a float field


def _inside(bound, towards):
    """The value a field shows nearest to an exclusive `bound`, on the valid side."""
    step = 10.0 ** -PRECISION * max(1.0, abs(bound))
    return bound + step if towards > 0 else bound - step


def _limits(param, default):
    """Blender's (hard min, hard max, soft min, soft max) for a float or RGB parameter.

    Hard limits are the registry's bounds, so the UI cannot leave the valid range; an exclusive
    bound becomes the nearest value the field shows inside it (typing α = 0 gives 0.0001), so the
    excluded value cannot be typed."""
    hard_min = max(param.min, -FLT_MAX)
    hard_max = min(param.max, FLT_MAX)
    if param.min_exclusive and math.isfinite(param.min):
        hard_min = _inside(param.min, +1)
    if param.max_exclusive and math.isfinite(param.max):
        hard_max = _inside(param.max, -1)
    scale = max(abs(default) * 10.0, 1.0)
    soft_min = hard_min if math.isfinite(param.min) else -scale
    soft_max = hard_max if math.isfinite(param.max) else max(scale, soft_min + 1.0)
    return hard_min, hard_max, soft_min, soft_max


def _rgb_default(value):
    if isinstance(value, (int, float)):
        return (float(value),) * 3
    return tuple(float(v) for v in value)


def make_property(param, owner_name):
    """A bpy.props descriptor for one registry parameter (not for list parameters)."""
    common = {"name": param.label, "description": param.tooltip()}
    if param.kind == "float":
        default = float(param.default)
        hmin, hmax, smin, smax = _limits(param, default)
        return FloatProperty(default=default, min=hmin, max=hmax, soft_min=smin, soft_max=smax,
                             precision=PRECISION, **common)
    if param.kind == "rgb":
        default = _rgb_default(param.default)
        hmin, hmax, smin, smax = _limits(param, max(default))
        # A colour is a swatch; per-channel numbers (η, k, lobe coefficients) are number fields.
        return FloatVectorProperty(size=3, subtype="COLOR" if param.is_color else "NONE",
                                   default=default, min=hmin, max=hmax, soft_min=smin,
                                   soft_max=smax, precision=PRECISION, **common)
    if param.kind == "enum":
        return EnumProperty(items=enum_items(param.choices,
                                             {c: schema.enum_label(c) for c in param.choices}),
                            default=str(param.default), **common)
    if param.kind == "bool":
        return BoolProperty(default=bool(param.default), **common)
    if param.kind == "string":
        subtype = "FILE_PATH" if param.name == "path" else "NONE"
        return StringProperty(default=str(param.default or ""), subtype=subtype, **common)
    raise ValueError(f"{owner_name}.{param.name}: kind '{param.kind}' has no single property")


def _make_group(class_name, params, owner_name):
    """Generates a PropertyGroup class holding `params` (list params recurse into element groups)."""
    annotations = {}
    for p in params:
        if p.kind == "list":
            element = _make_group(f"{class_name}_{p.name}", p.fields, f"{owner_name}.{p.name}")
            annotations[attr_name(p.name)] = CollectionProperty(type=element, name=p.label,
                                                                description=p.tooltip())
        else:
            annotations[attr_name(p.name)] = make_property(p, owner_name)
    annotations[LIST_INITIALISED] = BoolProperty(default=False, options={"HIDDEN"})
    cls = type(class_name, (bpy.types.PropertyGroup,), {"__annotations__": annotations,
                                                        "__doc__": f"BxDF Lab: {owner_name}"})
    bpy.utils.register_class(cls)
    _classes.append(cls)
    return cls


# ---- reading and writing values (used by api, operators and the engine) -----------------

def _read(group, p):
    value = getattr(group, attr_name(p.name))
    if p.kind == "float":
        return float(value)
    if p.kind == "rgb":
        return tuple(float(v) for v in value)
    if p.kind == "bool":
        return bool(value)
    if p.kind == "string":
        return bpy.path.abspath(value) if p.name == "path" and value else str(value)
    if p.kind == "list":
        return [{f.name: _read(element, f) for f in p.fields} for element in value]
    return str(value)


def read_values(group, model):
    """{parameter: value} of `model` as stored in its group, ready for bxdf.make(**values).
    Read-only (panels call it while drawing): list parameters not yet filled read as the
    registry's default."""
    initialised = getattr(group, LIST_INITIALISED)
    return {p.name: (_read(group, p) if initialised or p.kind != "list" else p.default)
            for p in model.params}


def write_value(group, p, value):
    """Stores one parameter's value (lists replace the whole collection)."""
    if p.kind == "list":
        collection = getattr(group, attr_name(p.name))
        collection.clear()
        for element_values in value:
            element = collection.add()
            for f in p.fields:
                if f.name in element_values:
                    write_value(element, f, element_values[f.name])
        return
    if p.kind == "rgb":
        value = _rgb_default(value)
    setattr(group, attr_name(p.name), value)


def write_values(group, model, values):
    """Stores {parameter: value} into the model's group (values already validated)."""
    for p in model.params:
        if p.name in values:
            write_value(group, p, values[p.name])
    setattr(group, LIST_INITIALISED, True)


def ensure_list_defaults(group, model):
    """A CollectionProperty has no default: fill list parameters with the registry's default
    elements the first time a material uses the model."""
    if getattr(group, LIST_INITIALISED) or not any(p.kind == "list" for p in model.params):
        return
    for p in model.params:
        if p.kind == "list" and len(getattr(group, attr_name(p.name))) == 0:
            write_value(group, p, p.default or [])
    setattr(group, LIST_INITIALISED, True)


def model_group(settings, model_name=None):
    return getattr(settings, model_name or settings.model)


def _on_model_change(self, _context):
    model = MODELS.get(self.model)
    if model is not None:
        ensure_list_defaults(model_group(self), model)


def _model_items():
    return enum_items(MODELS, {m.name: m.label for m in MODELS.values()},
                      {m.name: m.doc for m in MODELS.values()})


def register():
    MODELS.clear()
    MODELS.update(schema.read_models(dependency.require()))
    annotations = {}
    for model in MODELS.values():
        group = _make_group(f"BXDFLAB_PG_model_{model.name}", model.params, model.name)
        annotations[model.name] = PointerProperty(type=group)
    default_model = "lambertian" if "lambertian" in MODELS else next(iter(MODELS))
    annotations["model"] = EnumProperty(name="Model", description="BxDF Lab reflection model",
                                        items=_model_items(), default=default_model,
                                        update=_on_model_change)
    annotations["source"] = EnumProperty(
        name="Render From", description="What BXDF_LAB renders for this material",
        items=enum_items([i for i, _, _ in material_source.SOURCES],
                         {i: label for i, label, _ in material_source.SOURCES},
                         {i: doc for i, _, doc in material_source.SOURCES}),
        default="NODES")
    # What "Set Up Cycles/POV-Ray Material" did last: exact or approximate, and how.
    for target in ("cycles", "pov"):
        annotations[f"{target}_label"] = StringProperty(name=f"{target} pairing label")
        annotations[f"{target}_mapping"] = StringProperty(name=f"{target} mapping")
    settings = type("BXDFLAB_PG_material", (bpy.types.PropertyGroup,),
                    {"__annotations__": annotations, "__doc__": "BxDF Lab material settings"})
    bpy.utils.register_class(settings)
    _classes.append(settings)
    bpy.types.Material.bxdf_lab = PointerProperty(type=settings, name="BxDF Lab")


def unregister():
    if hasattr(bpy.types.Material, "bxdf_lab"):
        del bpy.types.Material.bxdf_lab
    for cls in reversed(_classes):
        bpy.utils.unregister_class(cls)
    _classes.clear()
    MODELS.clear()
