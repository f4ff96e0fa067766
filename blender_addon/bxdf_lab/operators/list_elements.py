"""Add and remove elements of a list parameter (e.g. Lafortune lobes) of the active material."""

import bpy
from bpy.props import StringProperty

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
            value = template.get(field.name, field.default)
            properties.write_value(element, field, value)
        setattr(group, properties.index_attr(self.param), len(collection) - 1)
        return {"FINISHED"}


class BXDFLAB_OT_list_remove(bpy.types.Operator):
    """Remove the active element of a list parameter"""
    bl_idname = "bxdf_lab.list_remove"
    bl_label = "Remove Element"
    bl_options = {"REGISTER", "UNDO"}
    param: StringProperty()

    poll = classmethod(poll_material)

    def execute(self, context):
        group, collection = _collection(context, self.param)
        index = getattr(group, properties.index_attr(self.param))
        if 0 <= index < len(collection):
            collection.remove(index)
            setattr(group, properties.index_attr(self.param), max(0, index - 1))
        return {"FINISHED"}


classes = (BXDFLAB_OT_list_add, BXDFLAB_OT_list_remove)
