"""The three lobe bakes drawn for a person: the polar lobe and the θh×θd slice in false colour
with their colour scales (scaled to their own maximum, so a GGX peak does not clip to white, with
a logarithmic scale when the peak dwarfs the rest), and the albedo as a curve over θo. One PNG,
loaded as a Blender image and shown in an Image Editor; the float bakes stay as they are."""

import os

import bpy
import numpy as np

# Above this ratio of the maximum to the median of the non-zero values, a linear scale would show
# only the peak: the colour scale becomes logarithmic.
LOG_SCALE_RATIO = 100.0


def _luminance(rgba):
    return rgba[..., :3] @ np.array([0.2126, 0.7152, 0.0722], dtype=np.float32)


def _norm(values):
    from matplotlib.colors import LogNorm, Normalize
    positive = values[values > 0]
    if positive.size == 0:
        return Normalize(0.0, 1.0)
    top = float(positive.max())
    if top / float(np.median(positive)) > LOG_SCALE_RATIO:
        return LogNorm(vmin=max(top * 1e-4, float(positive.min())), vmax=top)
    return Normalize(0.0, top)


def write(path, title, lobe, lobe_label, slice_, albedo):
    """lobe, slice_: (h, w, 4) rows bottom-up; albedo: (1, n, 4) over θo in (0°, 90°)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    figure, axes = plt.subplots(1, 3, figsize=(12, 4))
    lobe_y = _luminance(lobe)
    masked = np.ma.masked_where(lobe[..., 3] == 0, lobe_y)
    shown = axes[0].imshow(masked, origin="lower", cmap="viridis", norm=_norm(lobe_y),
                           extent=(-1, 1, -1, 1))
    figure.colorbar(shown, ax=axes[0], fraction=0.046, pad=0.04, label="f·|cos θi| (1/sr)")
    axes[0].set_title(lobe_label)
    axes[0].set_xlabel("x (equal-area)")
    axes[0].set_ylabel("y")
    slice_y = _luminance(slice_)
    shown = axes[1].imshow(slice_y, origin="lower", cmap="magma", norm=_norm(slice_y),
                           extent=(0, 90, 0, 90), aspect="auto")
    figure.colorbar(shown, ax=axes[1], fraction=0.046, pad=0.04, label="f (1/sr)")
    axes[1].set_title("f over θh × θd, φd = 90°")
    axes[1].set_xlabel("θh (°)")
    axes[1].set_ylabel("θd (°)")
    n = albedo.shape[1]
    theta = 90.0 * (np.arange(n) + 0.5) / n
    for channel, colour in zip(range(3), ("tab:red", "tab:green", "tab:blue")):
        axes[2].plot(theta, albedo[0, :, channel], color=colour, label="RGB"[channel])
    axes[2].set_xlim(0, 90)
    axes[2].set_ylim(0, max(1.0, float(albedo[0, :, :3].max()) * 1.05))
    axes[2].set_xlabel("θo (°)")
    axes[2].set_ylabel("directional albedo ρ(θo)")
    axes[2].legend(loc="lower left")
    axes[2].set_title("Albedo")
    figure.suptitle(title)
    figure.tight_layout()
    figure.savefig(path, dpi=90)
    plt.close(figure)


def show(name, path):
    """Loads `path` as the packed Blender image `name` (replacing an older one)."""
    old = bpy.data.images.get(name)
    if old is not None:
        bpy.data.images.remove(old)
    image = bpy.data.images.load(path, check_existing=False)
    image.name = name
    image.pack()
    os.remove(path)
    return image


def show_in_image_editor(context, image, windows=None):
    """Shows `image` in an open Image Editor of `windows` (default: every window); False when
    none is open (headless, or the user has none: the image is then in the Image Editor's
    browse list)."""
    window_manager = getattr(context, "window_manager", None)
    if image is None or window_manager is None:
        return False
    for window in (window_manager.windows if windows is None else windows):
        for area in window.screen.areas:
            if area.type == "IMAGE_EDITOR":
                image.size[:]  # loads the image, so that its size is known to the fit below
                area.spaces.active.image = image
                name = image.name
                bpy.app.timers.register(lambda: _fit(name), first_interval=0.1)
                return True
    return False


def _fit(image_name):
    """Zooms the Image Editors showing `image_name` to fit it (run once the editor has drawn the
    new image: in the same step the fit uses the old image's size)."""
    for window in bpy.context.window_manager.windows:
        for area in window.screen.areas:
            if area.type == "IMAGE_EDITOR" and area.spaces.active.image is not None \
                    and area.spaces.active.image.name == image_name:
                region = next(r for r in area.regions if r.type == "WINDOW")
                try:
                    with bpy.context.temp_override(window=window, area=area, region=region):
                        bpy.ops.image.view_all(fit_view=True)
                except RuntimeError:
                    # Blender refuses while it draws or renders ("can't modify blend data in
                    # this state"); the timer tries again shortly instead of failing.
                    return 0.2
    return None
