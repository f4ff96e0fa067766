"""The one place that calls the renderer's Python binding, bxdf.render (plugin/ through `bxdf`).

The engine hands over the exported scene (export.export_scene's dict, which bxdf.render takes as
it is) and the render settings, and gets back a linear RGBA float32 image with rows bottom-up
(Blender's order) plus the renderer's statistics; progress and cancel go through
`on_progress(done, total, image)` returning False to stop.
"""

from . import dependency


class RendererUnavailable(RuntimeError):
    pass


def binding():
    """The renderer entry point of the `bxdf` module, or RendererUnavailable saying so."""
    bxdf = dependency.require()
    render = getattr(bxdf, "render", None)
    if render is None:
        raise RendererUnavailable(
            "the bxdf_lab add-on renders through bxdf.render, which this build of the 'bxdf' "
            "module has no renderer for (bxdf.render is missing): rebuild BxDF Lab with the "
            "Embree renderer (plugin/) and run 'make install-addon'")
    return render


def settings_dict(render_settings):
    s = render_settings
    return {"samples": s.samples, "max_bounces": s.max_bounces,
            "pixel_filter": s.pixel_filter.lower(), "filter_width": s.filter_width,
            "threads": s.threads, "seed": s.seed}


def render(scene_data, render_settings, on_progress):
    """Renders `scene_data`; returns ((height, width, 4) float32 image with rows bottom-up, stats
    dict with "cancelled", "warnings", "seconds", ...)."""
    render_fn = binding()
    settings = settings_dict(render_settings)
    # Film › Transparent, as Cycles: camera rays that miss get no world and alpha 0.
    settings["transparent_background"] = bool(scene_data.get("film_transparent", False))
    return render_fn(scene_data, settings, on_progress, bottom_up=True, return_stats=True)
