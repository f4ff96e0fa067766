"""The z-gradient world (scene_spec.ZGradientWorld): its equirectangular image and its closed forms.

Blender's equirectangular mapping puts elevation asin(z) linearly on the image's vertical axis,
so a world of radiance a + b z is an image of constant rows: row k of H (top-down) holds
a + b sin(pi (1/2 - (k + 1/2)/H)). Between row centres both renderers interpolate linearly in
elevation, which differs from sin by at most (pi/H)^2/8 |b| (2e-5 |b| at H = 256), below the
z-test's absolute tolerance."""
from __future__ import annotations

import numpy as np


def image(world) -> np.ndarray:
    """(height, width, 3) float32, rows top-down (as compare.imageio writes them)."""
    elevation = np.pi * (0.5 - (np.arange(world.height) + 0.5) / world.height)
    rows = world.a + world.b * np.sin(elevation)
    return np.repeat(np.broadcast_to(rows[:, None, None], (world.height, world.width, 1)),
                     3, axis=2).astype(np.float32)


def radiance(world, directions) -> np.ndarray:
    """a + b z for unit directions (N, 3): what a camera ray sees."""
    return world.a + world.b * np.asarray(directions, float)[:, 2]


def lambert_radiance(world, reflectance, normals) -> np.ndarray:
    """(N, 3) radiance of a Lambertian surface of `reflectance` with unit normals (N, 3) that
    sees the whole world: E(n) = integral of (a + b w_z) max(0, n.w) dw = pi (a + 2/3 b n_z),
    L = R E / pi."""
    level = world.a + (2.0 / 3.0) * world.b * np.asarray(normals, float)[:, 2]
    return np.asarray(reflectance, float)[None, :] * level[:, None]
