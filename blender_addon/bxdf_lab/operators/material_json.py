"""Import and export the active material as a BxDF Lab JSON material file
({"format": "bxdf-material", "model": ..., "params": {...}}; written and read by the core, so the
CLI renderer, Python and Blender share one format)."""

import bpy
from bpy.props import StringProperty
from bpy_extras.io_utils import ExportHelper, ImportHelper

from .. import api, dependency
from ._common import active_material, poll_material


class BXDFLAB_OT_export_material(bpy.types.Operator, ExportHelper):
    """Save the active material's BxDF Lab model as a JSON material file"""
    bl_idname = "bxdf_lab.export_material"
    bl_label = "Export BxDF Lab Material"
    filename_ext = ".json"
    filter_glob: StringProperty(default="*.json", options={"HIDDEN"})

    poll = classmethod(poll_material)

    def execute(self, context):
        material = active_material(context)
        try:
            dependency.require().save_material(api.make(material), self.filepath, material.name)
        except (ValueError, OSError, RuntimeError) as exc:
            self.report({"ERROR"}, str(exc))
            return {"CANCELLED"}
        self.report({"INFO"}, f"Saved {self.filepath}")
        return {"FINISHED"}


class BXDFLAB_OT_import_material(bpy.types.Operator, ImportHelper):
    """Set the active material from a BxDF Lab JSON material file"""
    bl_idname = "bxdf_lab.import_material"
    bl_label = "Import BxDF Lab Material"
    filename_ext = ".json"
    filter_glob: StringProperty(default="*.json", options={"HIDDEN"})

    poll = classmethod(poll_material)

    def execute(self, context):
        try:
            model = dependency.require().load_material(self.filepath)
            api.assign(active_material(context), api.model_name(model), **dict(model.params))
        except (ValueError, OSError, RuntimeError) as exc:
            self.report({"ERROR"}, str(exc))
            return {"CANCELLED"}
        return {"FINISHED"}


classes = (BXDFLAB_OT_export_material, BXDFLAB_OT_import_material)
