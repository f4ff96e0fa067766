"""Scripting BxDF Lab materials from Blender's Python console.

    import bxdf_lab.api as api
    api.assign(bpy.data.materials["Material"], "oren_nayar", sigma=20.0)
    api.describe(bpy.data.materials["Material"])   # -> ("oren_nayar", {"reflectance": ..., "sigma": 20.0})

Every value goes through `bxdf.make`, the registry's validation: a bad value raises ValueError
naming the parameter, the value and the valid range, and leaves the material unchanged.
"""

from . import dependency, material_source, properties


def _model(name):
    try:
        return properties.MODELS[name]
    except KeyError:
        raise ValueError(f"unknown model '{name}'; known models: "
                         f"{', '.join(properties.MODELS)}") from None


def assign(material, model, **params):
    """Sets `material` to `model` with `params` (missing ones take the registry's defaults), and
    makes BXDF_LAB render the material from that model rather than its node tree. Returns the
    bxdf model object. Raises ValueError on an unknown model or a bad value."""
    bxdf = dependency.require()
    made = bxdf.make(model, **params)  # validates; raises ValueError before anything changes
    info = _model(model)
    settings = material.bxdf_lab
    properties.write_values(properties.model_group(settings, model), info, dict(made.params))
    settings.model = model
    material_source.set_source(material, "MODEL")
    return made


def assign_preset(material, preset):
    """Sets `material` to a named preset (bxdf.presets()); ValueError if there is no such preset."""
    bxdf = dependency.require()
    made = bxdf.make_preset(preset)
    return assign(material, model_name(made), **dict(made.params))


def model_name(made):
    """The registry name of a bxdf model object."""
    return made.name


def describe(material):
    """(model name, {parameter: value}) as stored on `material`."""
    settings = material.bxdf_lab
    info = _model(settings.model)
    return settings.model, properties.read_values(properties.model_group(settings), info)


def make(material):
    """The bxdf model that `material` describes; ValueError naming the material if a stored value
    is invalid (for instance typed through Python)."""
    bxdf = dependency.require()
    name, params = describe(material)
    try:
        return bxdf.make(name, **params)
    except ValueError as exc:
        raise ValueError(f"material '{material.name}': {exc}") from None
