"""Add a 3D polar plot of the active material's lobe as a mesh object."""

import math

import bpy
from bpy.props import FloatProperty
from mathutils import Vector

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
        beside = context.object
        obj = lobe_mesh.add_lobe_object(context, model, f"{material.name} lobe", self.theta_in, self.size)
        obj.location = self._location_beside(beside, context)
        # The incident direction ωo (θo from the normal +Z, φo = 0: in the x–z plane), as an arrow
        # from the lobe's origin; a single-arrow empty points along its local +Z.
        arrow = bpy.data.objects.new(f"{obj.name} incident", None)
        arrow.empty_display_type = "SINGLE_ARROW"
        arrow.empty_display_size = self.size
        arrow.rotation_euler = (0.0, math.radians(self.theta_in), 0.0)
        arrow.parent = obj
        context.collection.objects.link(arrow)
        for selected in context.selected_objects:
            selected.select_set(False)
        obj.select_set(True)
        context.view_layer.objects.active = obj
        self.report({"INFO"}, f"Added '{obj.name}' with the incident direction at θo = {self.theta_in:g}°")
        return {"FINISHED"}

    def _location_beside(self, beside, context):
        """Next to the active object (to its +X side, clear of its bounding box), so the lobe is
        not hidden inside it; at the 3D cursor when nothing is active."""
        if beside is None:
            return context.scene.cursor.location.copy()
        corners = [beside.matrix_world @ Vector(c) for c in beside.bound_box]
        right = max(c.x for c in corners)
        centre = sum(corners, Vector()) / len(corners)
        return Vector((right + 1.5 * self.size, centre.y, min(c.z for c in corners)))


classes = (BXDFLAB_OT_add_lobe_mesh,)
