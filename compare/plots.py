"""Per-material plots with matplotlib: the lobe f*cos(theta_i) in the plane of incidence (polar) for
three view angles, beside the core's baked hemisphere images of the same lobes
(bxdf.bake_lobe_polar, equal-area projection), and the directional albedo rho(theta_o)
(bxdf.bake_albedo_curve). Everything comes from the core through the `bxdf` module."""
from __future__ import annotations

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from .analytic import make_model  # noqa: E402

VIEW_ANGLES_DEG = (0.0, 30.0, 60.0)


def _luminance(rgb):
    return rgb @ np.array([0.2126, 0.7152, 0.0722])


def _dirs(theta):
    return np.stack([np.sin(theta), np.zeros_like(theta), np.cos(theta)], axis=-1)


def lobe_plot(material, path):
    import bxdf  # noqa: PLC0415 - make_model has found it

    model = make_model(material.model, material.params)
    theta_i = np.radians(np.linspace(-89.5, 89.5, 359))
    wi = _dirs(theta_i)
    fig = plt.figure(figsize=(7.2, 2.6), dpi=90)
    ax = fig.add_subplot(1, 4, 1, projection="polar")
    ax.set_theta_zero_location("N")
    ax.set_thetamin(-90)
    ax.set_thetamax(90)
    for deg in VIEW_ANGLES_DEG:
        wo = np.broadcast_to(_dirs(np.array([np.radians(deg)])), wi.shape).copy()
        value = _luminance(np.asarray(model.f(wo, wi), float)) * np.cos(theta_i)
        ax.plot(-theta_i, value, label=f"θo {deg:g}°")   # wo on the +x side, drawn on the right
    ax.set_title(f"{material.name}: f·cosθi", fontsize=8)
    if not any(line.get_ydata().any() for line in ax.get_lines()):
        ax.text(0.5, 0.35, "delta lobe: f = 0\noff the specular directions", fontsize=7,
                ha="center", transform=ax.transAxes)
    ax.tick_params(labelsize=6)
    ax.set_thetagrids([-90, -45, 0, 45, 90])  # fewer angle labels: the default ones overlap
    ax.yaxis.set_major_locator(matplotlib.ticker.MaxNLocator(3))
    # Below the half-disc, where no curve is drawn.
    ax.legend(fontsize=6, loc="upper center", bbox_to_anchor=(0.5, 0.02), ncol=len(VIEW_ANGLES_DEG),
              frameon=False, handlelength=1.0, columnspacing=0.8)
    for k, deg in enumerate(VIEW_ANGLES_DEG):
        image = np.asarray(bxdf.bake_lobe_polar(model, resolution=96, theta_o=deg), float)
        lum = _luminance(image)
        panel = fig.add_subplot(1, 4, k + 2)
        panel.imshow(lum / max(float(lum.max()), 1e-12), cmap="magma", vmin=0.0, vmax=1.0)
        panel.set_title(f"baked, θo {deg:g}° (max {lum.max():.3g})", fontsize=7)
        panel.set_xticks([])
        panel.set_yticks([])
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)


def directional_albedo(model, n_theta=24, n_samples=4096):
    """(theta_o in radians, rho (n_theta, 3)) at cell centres of [0, 90] degrees, from the core."""
    import bxdf  # noqa: PLC0415 - make_model has found it

    theta_deg, rho = bxdf.bake_albedo_curve(model, n_theta=n_theta, n_samples=n_samples)
    return np.radians(np.asarray(theta_deg, float)), np.asarray(rho, float)


def albedo_plot(material, path):
    model = make_model(material.model, material.params)
    theta_o, rho = directional_albedo(model)
    fig, ax = plt.subplots(figsize=(3.6, 2.6), dpi=90)
    for channel, color in enumerate(("tab:red", "tab:green", "tab:blue")):
        ax.plot(np.degrees(theta_o), rho[:, channel], color=color)
    ax.set_xlabel("θo (degrees)", fontsize=7)
    ax.set_ylabel("ρ(θo)", fontsize=7)
    ax.set_ylim(0.0, max(1.05, float(rho.max()) * 1.05))
    ax.set_title(f"{material.name}: directional albedo", fontsize=8)
    ax.tick_params(labelsize=6)
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)
    return theta_o, rho


def heatmap(diff, z, fail, z_crit, title, path):
    """|a - b| and |z| side by side; failing pixels outlined in the z panel."""
    fig, axes = plt.subplots(1, 2, figsize=(6.4, 2.7), dpi=90)
    vmax = float(np.percentile(diff, 99.5)) or 1e-6
    im = axes[0].imshow(diff, cmap="inferno", vmin=0.0, vmax=vmax, interpolation="nearest")
    axes[0].set_title("|a − b| (channel mean)", fontsize=7)
    # "%.2g" ticks: the default's "1e−5" offset label sits on the panel's title
    fig.colorbar(im, ax=axes[0], fraction=0.046, pad=0.04, format="%.2g").ax.tick_params(labelsize=6)
    im = axes[1].imshow(np.minimum(z, 2 * z_crit), cmap="viridis", vmin=0.0, vmax=2 * z_crit,
                        interpolation="nearest")
    if fail.any():
        axes[1].contour(fail, levels=[0.5], colors="red", linewidths=0.5)
    axes[1].set_title(f"|z| (fail > {z_crit:g}, red)", fontsize=7)
    fig.colorbar(im, ax=axes[1], fraction=0.046, pad=0.04).ax.tick_params(labelsize=6)
    for ax in axes:
        ax.set_xticks([])
        ax.set_yticks([])
    fig.suptitle(title, fontsize=8)
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)
