"""Give the active material the Cycles node tree closest to its BxDF Lab model."""

import bpy

from .. import cycles_setup
from ._common import active_material, poll_material


class BXDFLAB_OT_set_up_cycles(bpy.types.Operator):
    """Replace the active material's nodes with the closest Cycles BSDF (labelled exact or approximate)"""
    bl_idname = "bxdf_lab.set_up_cycles"
    bl_label = "Set Up Cycles Material"
    bl_options = {"REGISTER", "UNDO"}

    poll = classmethod(poll_material)

    def execute(self, context):
        try:
            label, text = cycles_setup.set_up(active_material(context))
        except (ValueError, RuntimeError) as exc:
            self.report({"ERROR"}, str(exc))
            return {"CANCELLED"}
        self.report({"INFO"}, f"Cycles ({label}): {text}")
        return {"FINISHED"}


classes = (BXDFLAB_OT_set_up_cycles,)
