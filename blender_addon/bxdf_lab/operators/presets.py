"""Named presets (bxdf.presets(): the seed's metals, the Lafortune fits) as a menu."""

import bpy
from bpy.props import StringProperty

from .. import api, dependency, properties
from ._common import active_material, poll_material


def preset_names():
    """Presets whose model this build's registry has ({name: {"model", "doc", "params"}})."""
    return [name for name, preset in dependency.require().presets().items()
            if preset["model"] in properties.MODELS]


class BXDFLAB_OT_apply_preset(bpy.types.Operator):
    """Set the active material to a named BxDF Lab preset"""
    bl_idname = "bxdf_lab.apply_preset"
    bl_label = "Apply Preset"
    bl_options = {"REGISTER", "UNDO"}
    preset: StringProperty(name="Preset")

    poll = classmethod(poll_material)

    def execute(self, context):
        try:
            api.assign_preset(active_material(context), self.preset)
        except ValueError as exc:
            self.report({"ERROR"}, str(exc))
            return {"CANCELLED"}
        return {"FINISHED"}


class BXDFLAB_MT_presets(bpy.types.Menu):
    bl_idname = "BXDFLAB_MT_presets"
    bl_label = "Presets"

    def draw(self, _context):
        for name in preset_names():
            self.layout.operator(BXDFLAB_OT_apply_preset.bl_idname, text=name).preset = name


classes = (BXDFLAB_OT_apply_preset, BXDFLAB_MT_presets)
