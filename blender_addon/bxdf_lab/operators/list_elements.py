"""Add and remove elements of a list parameter (e.g. Lafortune lobes) of the active material."""

import bpy
from bpy.props import IntProperty, StringProperty

from .. import properties
from ._common import active_material, poll_material


def _collection(context, param):
    """The model group and the collection of list parameter `param`, filled with the registry's
    default elements first if this material has not used them yet."""
    settings = active_material(context).bxdf_lab
    group = properties.model_group(settings)
    properties.ensure_list_defaults(group, properties.MODELS[settings.model])
    return group, getattr(group, properties.attr_name(param))


class BXDFLAB_OT_list_add(bpy.types.Operator):
    """Add an element (a copy of the registry's default element) to a list parameter"""
    bl_idname = "bxdf_lab.list_add"
    bl_label = "Add Element"
    bl_options = {"REGISTER", "UNDO"}
    param: StringProperty()

    poll = classmethod(poll_material)

    def execute(self, context):
        spec = properties.MODELS[active_material(context).bxdf_lab.model].param(self.param)
        group, collection = _collection(context, self.param)
        element = collection.add()
        template = spec.default[0] if spec.default else {}
        for field in spec.fields:
            properties.write_value(element, field, template.get(field.name, field.default))
        return {"FINISHED"}


class BXDFLAB_OT_list_remove(bpy.types.Operator):
    """Remove this element of a list parameter"""
    bl_idname = "bxdf_lab.list_remove"
    bl_label = "Remove Element"
    bl_options = {"REGISTER", "UNDO"}
    param: StringProperty()
    index: IntProperty(min=0)

    poll = classmethod(poll_material)

    def execute(self, context):
        _, collection = _collection(context, self.param)
        if self.index >= len(collection):
            self.report({"ERROR"}, f"{self.param} has no element {self.index + 1}")
            return {"CANCELLED"}
        collection.remove(self.index)
        return {"FINISHED"}


classes = (BXDFLAB_OT_list_add, BXDFLAB_OT_list_remove)
