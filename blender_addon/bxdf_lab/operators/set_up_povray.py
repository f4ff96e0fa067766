"""Give the active material (and the scene's lights) the closest POV-Ray settings."""

import addon_utils
import bpy

from .. import povray_setup
from ._common import active_material, poll_material


class BXDFLAB_OT_set_up_povray(bpy.types.Operator):
    """Set POV-Ray finish settings (use_nodes off) for the active material and calibrate the lights"""
    bl_idname = "bxdf_lab.set_up_povray"
    bl_label = "Set Up POV-Ray Material"
    bl_options = {"REGISTER", "UNDO"}

    poll = classmethod(poll_material)

    def execute(self, context):
        if not hasattr(bpy.types.Material, "pov"):
            # material.pov.* belongs to Blender's bundled render_povray add-on.
            if addon_utils.enable("render_povray", default_set=True) is None:
                self.report({"ERROR"}, "the POV-Ray add-on (render_povray) could not be enabled")
                return {"CANCELLED"}
        try:
            label, text = povray_setup.set_up(active_material(context), context.scene)
        except (ValueError, RuntimeError) as exc:
            self.report({"ERROR"}, str(exc))
            return {"CANCELLED"}
        self.report({"INFO"}, f"POV-Ray ({label}): {text}")
        return {"FINISHED"}


classes = (BXDFLAB_OT_set_up_povray,)
