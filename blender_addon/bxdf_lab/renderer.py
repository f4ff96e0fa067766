"""The one place that calls the renderer's Python binding, bxdf.render (plugin/ through `bxdf`).

The engine hands over the exported scene (export.export_scene's dict, which bxdf.render takes as
it is) and the render settings, and gets back a linear RGBA float32 image with rows bottom-up
(Blender's order) plus the renderer's statistics; progress and cancel go through
`on_progress(done, total, image)` returning False to stop.
"""

import numpy as np

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


# What each kind of render takes from scene.bxdf_lab_render: a final render all of it; the
# material preview and the viewport their own sample count, and passes that start with one sample
# so that the first image comes at once and each pass refines it. The viewport shows what F12
# renders (all the bounces, as Cycles' viewport); the material preview's small scene needs fewer.
PURPOSES = ("final", "preview", "viewport")
PREVIEW_MAX_BOUNCES = 4
# Cycles' defaults of the Light Paths settings BxDF Lab reads too, for a scene without Cycles'.
DEFAULT_TRANSPARENT_MAX_BOUNCES = 8
DEFAULT_MIN_LIGHT_BOUNCES = 0


def cycles_light_paths(scene):
    """bxdf.render's settings from the scene's Cycles Light Paths settings that both renderers
    read (Render Properties > Light Paths), so that a scene renders alike in both without a second
    setting to keep in step: Transparent (passes through Transparent BSDFs are not bounces in
    Cycles) and Min Light Bounces (Cycles ends no path at random before its
    (min_light_bounces + 2)-th scattering, that is from russian_roulette_depth
    min_light_bounces + 1 on: Cycles' kernel counts one bounce more)."""
    cycles = getattr(scene, "cycles", None)
    transparent = int(getattr(cycles, "transparent_max_bounces", DEFAULT_TRANSPARENT_MAX_BOUNCES))
    min_light = int(getattr(cycles, "min_light_bounces", DEFAULT_MIN_LIGHT_BOUNCES))
    return {"transparent_max_bounces": transparent, "russian_roulette_depth": min_light + 1}


# Cycles' Sampling settings (Render Properties > Sampling) BxDF Lab reads too: for F12 those of
# Render, for the viewport those of Viewport (Cycles' preview_*): the properties' names (use,
# Noise Threshold, Min Samples) and Cycles' defaults for a scene without them. The material
# preview's small scene samples every pixel alike.
CYCLES_ADAPTIVE_SAMPLING = {
    "final": ("use_adaptive_sampling", "adaptive_threshold", "adaptive_min_samples"),
    "viewport": ("use_preview_adaptive_sampling", "preview_adaptive_threshold",
                 "preview_adaptive_min_samples"),
}
CYCLES_ADAPTIVE_DEFAULTS = {"final": (True, 0.01, 0), "viewport": (True, 0.1, 0)}


def cycles_adaptive_sampling(scene, purpose="final"):
    """bxdf.render's adaptive sampling settings from the scene's Cycles Adaptive Sampling
    (Noise Threshold, Min Samples) for `purpose`; {} for the material preview."""
    if purpose not in CYCLES_ADAPTIVE_SAMPLING:
        return {}
    cycles = getattr(scene, "cycles", None)
    use, threshold, minimum = (getattr(cycles, name, default) for name, default in
                               zip(CYCLES_ADAPTIVE_SAMPLING[purpose], CYCLES_ADAPTIVE_DEFAULTS[purpose]))
    return {"adaptive_sampling": bool(use), "adaptive_threshold": float(threshold),
            "adaptive_min_samples": int(minimum)}


def cycles_settings(scene, purpose="final"):
    """The Cycles settings of `scene` that bxdf.render reads for `purpose`: Light Paths and
    Adaptive Sampling."""
    return {**cycles_light_paths(scene), **cycles_adaptive_sampling(scene, purpose)}


def settings_dict(render_settings, purpose="final", cycles=None):
    """bxdf.render's settings from the add-on's render settings; `cycles` is
    cycles_settings(scene, purpose) (without it, Cycles' default Light Paths and no adaptive
    sampling)."""
    if purpose not in PURPOSES:
        raise ValueError(f"render purpose '{purpose}' is unknown; expected one of {PURPOSES}")
    if cycles is None:
        cycles = cycles_light_paths(None)
    s = render_settings
    settings = {"samples": s.samples, "max_bounces": s.max_bounces, **cycles,
                "pixel_filter": s.pixel_filter.lower(), "filter_width": s.filter_width,
                "threads": s.threads, "seed": s.seed}
    if purpose != "final":
        settings["samples"] = s.preview_samples if purpose == "preview" else s.viewport_samples
        if purpose == "preview":
            settings["max_bounces"] = min(s.max_bounces, PREVIEW_MAX_BOUNCES)
        settings["progressive"] = True  # one sample first, then passes sized as Cycles' viewport sizes them
    return settings


def samples_text(stats, pixels):
    """How many samples per pixel a render took, from bxdf.render's stats and the image's pixel
    count: "64 samples per pixel", or where adaptive sampling stopped pixels early (its camera
    samples fewer than samples_per_pixel on every pixel) "up to 256 samples per pixel (mean 97)"."""
    most = int(stats.get("samples_per_pixel", 0))
    camera_samples = int(stats.get("camera_samples", 0))
    if pixels > 0 and camera_samples < most * pixels:
        return f"up to {most} samples per pixel (mean {camera_samples / pixels:.0f})"
    return f"{most} samples per pixel"


def render_region(scene, width, height):
    """Blender's Render Region (Output Properties > Format > Render Region; Ctrl+B in the camera
    view) as bxdf.render's `region` for a `width` x `height` image, or None when it is off.
    Blender renders columns [min_x·width, max_x·width) and rows [min_y·height, max_y·height)
    counted from the bottom, each bound truncated from a single-precision product
    (render_init_from_main); `region` counts rows from the top."""
    r = scene.render
    if not r.use_border:
        return None
    return border_pixels((r.border_min_x, r.border_min_y, r.border_max_x, r.border_max_y),
                         width, height)


def border_pixels(border, width, height):
    """The pixels of a `width`×`height` image that a border (left, bottom, right, top fractions,
    within [0, 1]) covers, as bxdf.render's `region` (x_min, y_min, x_max, y_max, rows from the
    top): Blender's and Cycles' arithmetic, each bound truncated from a single-precision product,
    and at least one pixel wide and high inside the image (Cycles' viewport; Blender refuses a
    smaller F12 region itself)."""
    def span(low, high, size):
        start = min(int(np.float32(low) * np.float32(size)), size - 1)
        end = int(np.float32(high) * np.float32(size))
        return start, min(max(end, start + 1), size)
    x0, x1 = span(border[0], border[2], width)
    y0, y1 = span(border[1], border[3], height)
    return (x0, height - y1, x1, height - y0)


def render(scene_data, settings, on_progress, partial_images=True):
    """Renders `scene_data` with `settings` (settings_dict's); returns ((height, width, 4) float32
    image with rows bottom-up, stats dict with "cancelled", "warnings", "seconds", ...).
    `on_progress` gets the image after each pass but the last when `partial_images`, else None."""
    render_fn = binding()
    settings = dict(settings)
    # Film › Transparent, as Cycles: camera rays that miss get no world and alpha 0.
    settings["transparent_background"] = bool(scene_data.get("film_transparent", False))
    return render_fn(scene_data, settings, on_progress, bottom_up=True,
                     partial_images=partial_images, return_stats=True)
