"""Render with BXDF_LAB, CYCLES and POVRAY_RENDER and show the three side by side."""

import tempfile

import bpy
from bpy.props import StringProperty

from .. import compare


class BXDFLAB_OT_compare_renders(bpy.types.Operator):
    """Render the scene with BxDF Lab, Cycles and POV-Ray and show the images side by side"""
    bl_idname = "bxdf_lab.compare_renders"
    bl_label = "Compare Renders"
    directory: StringProperty(name="Folder", subtype="DIR_PATH", default="")

    def execute(self, context):
        folder = bpy.path.abspath(self.directory) if self.directory else tempfile.mkdtemp(prefix="bxdf_lab_")
        results, image = compare.compare(context.scene, folder)
        for engine_id, (ok, message) in results.items():
            self.report({"INFO"} if ok else {"ERROR"}, f"{engine_id}: {message}")
        if image is None:
            return {"CANCELLED"}
        self.report({"INFO"}, f"Comparison image '{image.name}' ({', '.join(r for r in results if results[r][0])})")
        return {"FINISHED"}


classes = (BXDFLAB_OT_compare_renders,)
