"""Bake the active material's lobe into Blender images: polar lobe, θh×θd slice, albedo curve."""

import os

import bpy
from bpy.props import BoolProperty, FloatProperty, IntProperty, StringProperty

from .. import api, bake, bake_figure
from ._common import active_material, poll_material


class BXDFLAB_OT_bake_lobe_texture(bpy.types.Operator):
    """Bake the active material's reflection lobe into images named after the material"""
    bl_idname = "bxdf_lab.bake_lobe_texture"
    bl_label = "Bake Lobe Texture"
    bl_options = {"REGISTER", "UNDO"}

    theta_in: FloatProperty(name="Incident Angle", description="θo of the incident direction, degrees",
                            default=45.0, min=0.0, max=90.0)
    size: IntProperty(name="Size", description="Width and height of the lobe and slice images",
                      default=256, min=8, max=4096)
    albedo_samples: IntProperty(name="Albedo Samples", description="Samples per albedo estimate",
                                default=4096, min=16, max=1 << 20)
    save_exr: BoolProperty(name="Save as EXR", default=False)
    directory: StringProperty(name="Folder", subtype="DIR_PATH", default="//")

    poll = classmethod(poll_material)

    def execute(self, context):
        material = active_material(context)
        try:
            model = api.make(material)
            images = {
                f"{material.name} lobe {self.theta_in:g}deg": bake.lobe_polar(model, self.theta_in, self.size),
                f"{material.name} slice": bake.slice_half_diff(model, self.size),
                f"{material.name} albedo": bake.albedo_curve(model, self.size, self.albedo_samples),
            }
            for name, pixels in images.items():
                path = (os.path.join(bpy.path.abspath(self.directory), bpy.path.clean_name(name) + ".exr")
                        if self.save_exr else "")
                bake.to_image(name, pixels, path)
            lobe, slice_, albedo = images.values()
            figure_path = os.path.join(bpy.app.tempdir, bpy.path.clean_name(material.name) + "_lobes.png")
            bake_figure.write(figure_path, f"{material.name}: {material.bxdf_lab.model}", lobe,
                              f"Lobe at θo = {self.theta_in:g}°", slice_, albedo)
            figure = bake_figure.show(f"{material.name} lobes", figure_path)
        except (ValueError, RuntimeError, OSError) as exc:
            self.report({"ERROR"}, str(exc))
            return {"CANCELLED"}
        shown = bake_figure.show_in_image_editor(context, figure)
        self.report({"INFO"}, f"Baked {', '.join(images)}; '{figure.name}' "
                              + ("is shown in the Image Editor" if shown else "has their colour scales"))
        return {"FINISHED"}


classes = (BXDFLAB_OT_bake_lobe_texture,)
