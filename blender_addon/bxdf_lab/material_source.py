"""Which description of a material BXDF_LAB renders: its Blender node tree ("NODES") or its
BxDF Lab model ("MODEL": the panel, `api.assign`).

`material.bxdf_lab.source` holds the choice once it is made (the panel's switch, `api.assign`).
Until then it is inferred: a material whose BxDF Lab settings hold any stored value (files made
with the panel or `api.assign` before the switch existed; a parameter edited in the panel)
renders from its model, as it always did; any other material renders from its node tree.
Reading the settings stores nothing (Blender creates empty groups for them), so a material the
panel only displayed still counts as never set.
"""

import idprop

SOURCES = (("NODES", "Node Tree", "Render the material's Blender node tree, as Cycles does"),
           ("MODEL", "BxDF Lab Model", "Render the BxDF Lab model set in this panel"))


def _holds_value(group, skip=()):
    for key, value in group.items():
        if key in skip:
            continue
        if isinstance(value, idprop.types.IDPropertyGroup):
            if _holds_value(value):
                return True
        else:
            return True
    return False


def model_was_set(material):
    """Whether the material's BxDF Lab settings hold any stored value (other than the source)."""
    stored = material.get("bxdf_lab")
    return isinstance(stored, idprop.types.IDPropertyGroup) and _holds_value(stored, {"source"})


def source(material):
    """"NODES" or "MODEL" (see the module docstring)."""
    settings = material.bxdf_lab
    if settings.is_property_set("source"):
        return settings.source
    return "MODEL" if model_was_set(material) else "NODES"


def set_source(material, value):
    if value not in {identifier for identifier, _, _ in SOURCES}:
        raise ValueError(f"material source '{value}' is not one of "
                         f"{', '.join(identifier for identifier, _, _ in SOURCES)}")
    material.bxdf_lab.source = value
