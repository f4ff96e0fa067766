"""Image differences: mean, RMS, max, PSNR, relative MSE, and a per-pixel z-test of the difference
against the Monte Carlo noise of the two images.

Noise: each stochastic engine renders four images (jobs.SEEDS) with a quarter of the samples and
different seeds; the full image is their mean, whose per-pixel variance is estimated as their
sample variance over four, averaged over the 3x3 neighbourhood (so that one unlucky pixel does not
make a tiny variance). Why four and not two halves: both engines sample with stratified, randomly
scrambled points (Cycles' progressive multi-jitter, BXDF_LAB's Owen-scrambled Sobol), so at a few
dozen samples a pixel's error takes few values and is skewed (how many of 32 light choices fell
on each light, how many shadow rays passed an edge); two halves then agree more often than
Gaussian noise would and (h1 - h2)^2/4 is often near 0 while both sit off the mean. At 32 x 32 and
64 spp, area_light_room and soft_shadows failed 0.9-1.0% of signal pixels on average in BXDF_LAB
vs CYCLES with two halves of 32 samples, and Cycles failed 0.9% against Cycles with other seeds
(up to 1.9%); with four quarters of 16 samples 0.04-0.22% (issue #12, compare/README.md).
A deterministic image (ANALYTIC, POV-Ray without anti-aliasing) has variance 0.

The test adds systematic tolerances for what is not noise but not a difference of formulas either:
against an analytic image, the change of the closed form under the normal error of Blender's
tessellated spheres (analytic.AnalyticImage.geometry_tolerance, per pixel); and float32 arithmetic
and 16-bit PNG quantisation: sigma^2 = var_a + var_b + geometry^2 + (REL_TOL max(|a|,|b|) +
ABS_TOL)^2. A pixel fails when |z| > Z_CRIT in any channel; an exact pairing passes when at most
PASS_FRACTION of the signal pixels fail (those where either image exceeds SIGNAL_LEVEL: a black
background that both renderers get right must not dilute a wrong highlight)."""
from __future__ import annotations

import numpy as np

Z_CRIT = 4.0
REL_TOL = 0.001
ABS_TOL = 2e-4
PASS_FRACTION = 0.01
SIGNAL_LEVEL = 1e-3
RELMSE_EPSILON = 1e-2


def box3(a):
    """Mean over the 3x3 neighbourhood (edges replicated), per channel."""
    p = np.pad(a, ((1, 1), (1, 1)) + ((0, 0),) * (a.ndim - 2), mode="edge")
    h, w = a.shape[:2]
    return sum(p[dy:dy + h, dx:dx + w] for dy in range(3) for dx in range(3)) / 9.0


def variance_of_mean(*renders):
    """Per-pixel variance of the mean of K >= 2 independent renders (different seeds, the same
    samples each): their sample variance / K (K - 1 degrees of freedom), 3x3-averaged."""
    if len(renders) < 2:
        raise ValueError(f"variance_of_mean needs at least 2 renders, got {len(renders)}")
    stack = np.stack([np.asarray(r, float) for r in renders])
    return box3(stack.var(axis=0, ddof=1) / len(renders))


def edge_mask(object_ids):
    """True where a pixel's 3x3 neighbourhood covers more than one object (or background):
    silhouettes, where the tessellated mesh and the true sphere may cover a pixel centre
    differently."""
    p = np.pad(object_ids, 1, mode="edge")
    h, w = object_ids.shape
    edge = np.zeros((h, w), bool)
    for dy in range(3):
        for dx in range(3):
            edge |= p[dy:dy + h, dx:dx + w] != object_ids
    return edge


def compare(a, b, var_a=None, var_b=None, mask=None, systematic=None):
    """Figures of a - b over the pixels where `mask` is true (all if None). Images HxWx3;
    `systematic`: a per-pixel tolerance (HxWx3) added in quadrature to the noise."""
    a = np.asarray(a, float)[..., :3]
    b = np.asarray(b, float)[..., :3]
    if a.shape != b.shape:
        raise ValueError(f"image shapes differ: {a.shape} vs {b.shape}")
    if mask is None:
        mask = np.ones(a.shape[:2], bool)
    var_a = np.zeros_like(a) if var_a is None else np.asarray(var_a, float)[..., :3]
    var_b = np.zeros_like(b) if var_b is None else np.asarray(var_b, float)[..., :3]

    diff = (a - b)[mask]
    n = diff.shape[0]
    if n == 0:
        raise ValueError("no pixels to compare (mask is empty)")
    ref = b[mask]
    mse = float(np.mean(diff ** 2))
    peak = float(max(np.max(np.abs(ref)), np.max(np.abs(a[mask])), 1e-12))
    tolerance = REL_TOL * np.maximum(np.abs(a), np.abs(b)) + ABS_TOL
    geometry = 0.0 if systematic is None else np.asarray(systematic, float)[..., :3]
    sigma = np.sqrt(var_a + var_b + geometry ** 2 + tolerance ** 2)
    z = (a - b) / sigma
    z_abs = np.max(np.abs(z), axis=-1)
    signal = mask & (np.maximum(np.abs(a), np.abs(b)).max(axis=-1) > SIGNAL_LEVEL)
    fail = (z_abs > Z_CRIT) & signal
    n_signal = int(np.count_nonzero(signal))
    return {
        "pixels": int(n),
        "mean": float(np.mean(diff)),
        "mean_abs": float(np.mean(np.abs(diff))),
        "rmse": float(np.sqrt(mse)),
        "max_abs": float(np.max(np.abs(diff))),
        "psnr": float("inf") if mse == 0 else float(10.0 * np.log10(peak * peak / mse)),
        "rel_mse": float(np.mean(diff ** 2 / (ref ** 2 + RELMSE_EPSILON))),
        "ratio_mean": float(np.sum(a[mask]) / max(np.sum(b[mask]), 1e-12)),
        "signal_pixels": n_signal,
        "z_fail_fraction": float(np.count_nonzero(fail) / n_signal) if n_signal else 0.0,
        "z_max": float(np.max(z_abs[mask])),
        "noise_rms": float(np.sqrt(np.mean((var_a + var_b)[mask]))),
        "z_image": z_abs,
        "diff_image": np.abs(a - b).mean(axis=-1),
        "fail_image": fail,
    }


def passes(figures):
    """True when the difference is noise (and tolerance) only. An `exact` pairing that does not pass
    is flagged; for an `approximate` one it is the finding, not a failure."""
    return bool(figures["z_fail_fraction"] <= PASS_FRACTION)
