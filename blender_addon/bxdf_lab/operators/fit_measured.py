"""Fit to Measured File: fits a model to a measured BRDF (MERL .binary or Cornell .brdf) with
bxdf.fit and sets the active material to the fitted model, keeping the fit's error on the material
(fit_report.py). A fit takes about 0.1-1 s, so it runs directly, under a wait cursor."""

import bpy
from bpy.props import EnumProperty, IntProperty, StringProperty
from bpy_extras.io_utils import ImportHelper

from .. import api, dependency, fit_report, properties
from ._common import active_material, poll_material

_LABELS = {"ggx": "GGX", "ashikhmin_shirley": "Ashikhmin-Shirley", "cook_torrance": "Cook-Torrance"}
_DOCS = {
    "lambertian": "Constant reflectance",
    "lafortune": "Diffuse term plus generalised cosine lobes (see Lobes)",
    "blinn": "Diffuse plus Torrance-Sparrow with the Blinn distribution (microfacet model)",
    "ashikhmin_shirley": "Diffuse plus Torrance-Sparrow with the anisotropic Ashikhmin-Shirley "
                         "distribution (microfacet model)",
    "cook_torrance": "Diffuse plus Torrance-Sparrow with the Beckmann distribution "
                     "(microfacet model)",
    "ggx": "Diffuse plus Torrance-Sparrow with GGX and Smith shadowing (microfacet model)",
}
# Blender keeps only pointers to enum item strings: the list must outlive every draw.
_fit_model_items = []


def fit_models():
    """The models bxdf.fit accepts; empty for a build without Ceres (no bxdf.fit)."""
    bxdf = dependency.require()
    return list(bxdf.fit_models()) if hasattr(bxdf, "fit_models") else []


def _model_items(_self, _context):
    if not _fit_model_items:
        _fit_model_items[:] = properties.enum_items(fit_models(), _LABELS, _DOCS)
    return _fit_model_items


class BXDFLAB_OT_fit_measured(bpy.types.Operator, ImportHelper):
    """Fit a model to a measured BRDF (MERL .binary, Cornell .brdf) and set the material to it"""
    bl_idname = "bxdf_lab.fit_measured"
    bl_label = "Fit to Measured File"
    bl_options = {"REGISTER", "UNDO"}
    filter_glob: StringProperty(default="*.brdf;*.binary", options={"HIDDEN"})
    model: EnumProperty(name="Model", items=_model_items,
                        description="The analytic model fitted to the measurements")
    lobes: IntProperty(name="Lobes", default=2, min=1, max=3,
                       description="Number of Lafortune lobes")

    @classmethod
    def poll(cls, context):
        if not poll_material(cls, context):
            return False
        if not fit_models():
            cls.poll_message_set("This build of bxdf has no fitting (built without Ceres)")
            return False
        return True

    def draw(self, _context):
        layout = self.layout
        layout.prop(self, "model")
        if self.model == "lafortune":
            layout.prop(self, "lobes")

    def execute(self, context):
        material = active_material(context)
        window = context.window  # None when run from a script without a window
        if window:
            window.cursor_set("WAIT")
        try:
            bxdf = dependency.require()
            fitted, report = bxdf.fit(self.filepath, model=self.model, lobes=self.lobes)
            api.assign(material, api.model_name(fitted), **dict(fitted.params))
        except (ValueError, OSError, RuntimeError) as exc:
            self.report({"ERROR"}, f"Fit to measured file failed: {exc}")
            return {"CANCELLED"}
        finally:
            if window:
                window.cursor_set("DEFAULT")
        fit_report.store(material, self.filepath, report)
        self.report({"INFO"}, f"{fit_report.summary(material)}, {report['seconds']:.2f} s")
        return {"FINISHED"}


classes = (BXDFLAB_OT_fit_measured,)
