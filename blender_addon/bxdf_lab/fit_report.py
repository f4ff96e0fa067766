"""`material.bxdf_lab_fit`: what the last "Fit to Measured File" did to a material (file, fit
model, error), kept so the material panel can show how well the current parameters match the data.
"""

import json
import os

import bpy
from bpy.props import FloatProperty, IntProperty, PointerProperty, StringProperty

from . import api


class BXDFLAB_PG_fit_report(bpy.types.PropertyGroup):
    file: StringProperty(name="Measured file", subtype="FILE_PATH",
                         description="The measured BRDF the material was fitted to")
    model: StringProperty(name="Fit model",
                          description="The fit that was run (e.g. ggx, lafortune2)")
    error: FloatProperty(name="Fit error", precision=6,
                         description="RMS cosine-weighted L2 error of the fit (bxdf.fit)")
    baseline_error: FloatProperty(name="Error of f = 0", precision=6,
                                  description="The same error for a black material, for scale")
    iterations: IntProperty(name="Iterations", description="Solver iterations of the best start")
    seconds: FloatProperty(name="Seconds", description="Wall time of the fit")
    # api.describe(material) right after the fit, as JSON: tells whether the user has edited the
    # parameters since, in which case the stored error no longer describes the material.
    fitted_values: StringProperty(options={"HIDDEN"})


def _values_json(material):
    return json.dumps(api.describe(material), sort_keys=True)


def store(material, path, report):
    """Records a fit (bxdf.fit's report dict) of `path` on `material`, after api.assign."""
    fit = material.bxdf_lab_fit
    fit.file = str(path)
    fit.model = report["model"]
    fit.error = report["error"]
    fit.baseline_error = report["baseline_error"]
    fit.iterations = report["iterations"]
    fit.seconds = report["seconds"]
    fit.fitted_values = _values_json(material)


def has_fit(material):
    return bool(material.bxdf_lab_fit.model)


def is_current(material):
    """True while the material still has the parameters the fit gave it."""
    return has_fit(material) and material.bxdf_lab_fit.fitted_values == _values_json(material)


def summary(material):
    """One line for the panel and the operator's report; "" when the material was never fitted."""
    if not has_fit(material):
        return ""
    fit = material.bxdf_lab_fit
    return (f"Fit {fit.model} to {os.path.basename(fit.file)}: error {fit.error:.6g} "
            f"(f = 0: {fit.baseline_error:.6g})")


classes = (BXDFLAB_PG_fit_report,)


def register():
    for cls in classes:
        bpy.utils.register_class(cls)
    bpy.types.Material.bxdf_lab_fit = PointerProperty(type=BXDFLAB_PG_fit_report,
                                                      name="BxDF Lab fit")


def unregister():
    del bpy.types.Material.bxdf_lab_fit
    for cls in reversed(classes):
        bpy.utils.unregister_class(cls)
