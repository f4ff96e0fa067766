"""BxDF Lab: surface reflection models (BRDF/BTDF) from the C++ core, for Python and Blender.

numpy arrays in, float32 numpy arrays out. Directions are in the local shading frame
(z = surface normal); ``wo`` and ``wi`` both point away from the surface.

    >>> import bxdf
    >>> m = bxdf.make("lambertian", reflectance=(0.8, 0.5, 0.2))
    >>> m.f([0, 0, 1], [[0, 0.6, 0.8]])          # (1, 3): R / pi
    >>> bxdf.models()["lambertian"][0]["name"]   # 'reflectance'

Shapes: (N, 3) directions or one (3,) vector (which broadcasts); results keep the batch axis,
so (3,) inputs give (1, 3) / (1,) results. See help(bxdf.Model).
"""

from ._bxdf import (
    Model,
    bake_albedo_curve,
    bake_lobe_polar,
    bake_slice_half_diff,
    eta_from_f0,
    fresnel_conductor,
    fresnel_dielectric,
    k_from_f0,
    load_material,
    load_measured,
    lobe_mesh,
    make,
    make_preset,
    model_doc,
    models,
    presets,
    save_material,
)

__version__ = "0.1.0"

# Models are shown and pickled as bxdf.Model, the public name, not as the extension's.
Model.__module__ = __name__

__all__ = [
    "Model",
    "bake_albedo_curve",
    "bake_lobe_polar",
    "bake_slice_half_diff",
    "eta_from_f0",
    "fresnel_conductor",
    "fresnel_dielectric",
    "k_from_f0",
    "load_material",
    "load_measured",
    "lobe_mesh",
    "make",
    "make_preset",
    "model_doc",
    "models",
    "presets",
    "save_material",
]

# fit(), fit_error() and fit_models() exist when the build found Ceres (core/fit); see bxdf.fit.__doc__.
try:
    from ._bxdf import fit, fit_error, fit_models

    __all__ += ["fit", "fit_error", "fit_models"]
except ImportError:  # pragma: no cover - a build without Ceres
    pass

# render() and render_scene_file() exist when the build has the Embree renderer (plugin/); see
# bxdf.render.__doc__.
try:
    from ._bxdf import render, render_scene_file

    __all__ += ["render", "render_scene_file"]
except ImportError:  # pragma: no cover - a build without the renderer
    pass
