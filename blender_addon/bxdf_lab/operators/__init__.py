"""Operators of BxDF Lab, one per file; registered in this order."""

import bpy

from . import (add_lobe_mesh, bake_lobe_texture, compare_renders, fit_measured, list_elements,
               material_json, presets, set_material_source, set_up_cycles, set_up_povray)

_modules = (list_elements, presets, material_json, fit_measured, bake_lobe_texture, add_lobe_mesh,
            set_up_cycles, set_up_povray, compare_renders, set_material_source)


def register():
    for module in _modules:
        for cls in module.classes:
            bpy.utils.register_class(cls)


def unregister():
    for module in reversed(_modules):
        for cls in reversed(module.classes):
            bpy.utils.unregister_class(cls)
