"""Switch what BXDF_LAB renders for the active material: its node tree or its BxDF Lab model."""

import bpy

from .. import material_source
from ._common import active_material, poll_material


class BXDFLAB_OT_set_material_source(bpy.types.Operator):
    """Render this material from its Blender node tree or from its BxDF Lab model"""
    bl_idname = "bxdf_lab.set_material_source"
    bl_label = "Render Material From"
    bl_options = {"REGISTER", "UNDO"}

    source: bpy.props.EnumProperty(name="Source", items=material_source.SOURCES)
    poll = classmethod(poll_material)

    def execute(self, context):
        material_source.set_source(active_material(context), self.source)
        return {"FINISHED"}


classes = (BXDFLAB_OT_set_material_source,)
