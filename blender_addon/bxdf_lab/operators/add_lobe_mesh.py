"""Add a 3D polar plot of the active material's lobe as a mesh object."""

import bpy
from bpy.props import FloatProperty

from .. import api, lobe_mesh
from ._common import active_material, poll_material


class BXDFLAB_OT_add_lobe_mesh(bpy.types.Operator):
    """Add a mesh object showing the active material's reflection lobe for one incident angle"""
    bl_idname = "bxdf_lab.add_lobe_mesh"
    bl_label = "Add Lobe Mesh"
    bl_options = {"REGISTER", "UNDO"}

    theta_in: FloatProperty(name="Incident Angle", description="θo of the incident direction, degrees",
                            default=45.0, min=0.0, max=90.0)
    size: FloatProperty(name="Size", description="Length of the longest lobe radius", default=1.0,
                        min=0.001, soft_max=10.0, subtype="DISTANCE")

    poll = classmethod(poll_material)

    def execute(self, context):
        material = active_material(context)
        try:
            model = api.make(material)
        except ValueError as exc:
            self.report({"ERROR"}, str(exc))
            return {"CANCELLED"}
        obj = lobe_mesh.add_lobe_object(context, model, f"{material.name} lobe", self.theta_in, self.size)
        obj.location = context.scene.cursor.location
        return {"FINISHED"}


classes = (BXDFLAB_OT_add_lobe_mesh,)
