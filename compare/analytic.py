"""Closed-form images of the scenes that have them: spheres lit by point or sun lights, direct light
only (plus one Lambertian sphere in a constant or z-gradient world, gradient_world.py). One ray through each pixel centre, the same camera as Blender's
(sensor fit horizontal), shadow rays against every sphere, and the model's f from the core:

    L = sum over lights of f(wo, wi) * cos(theta_i) * E_light,   E = I / d^2 (point) or E (sun).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from . import gradient_world
from .scene_spec import PointLight, SceneSpec, Sphere, SunLight, ZGradientWorld, is_lambert_furnace

RAY_EPSILON = 1e-6


def make_model(model: str, params: dict):
    """The core's model through `bxdf.make` (its .f(wo, wi) -> (N, 3) is the truth here). Imported
    on first use: the caller puts the built module on sys.path (runner.bxdf_python_paths)."""
    try:
        import bxdf  # noqa: PLC0415 - found through the build folder, not at import time
    except ImportError as exc:
        raise ImportError("the analytic images need the compiled `bxdf` module: build it "
                          "(cmake --build build) and put build/python on PYTHONPATH or "
                          f"BXDF_PYTHONPATH ({exc})") from exc
    return bxdf.make(model, **params)


def camera_rays(spec: SceneSpec):
    w, h = spec.resolution
    cam = spec.camera
    origin = np.asarray(cam.location, float)
    forward = np.asarray(cam.look_at, float) - origin
    forward /= np.linalg.norm(forward)
    right = np.cross(forward, (0.0, 0.0, 1.0))
    right /= np.linalg.norm(right)
    up = np.cross(right, forward)
    half_w = np.tan(cam.horizontal_fov() / 2.0)
    half_h = half_w * h / w
    xs = (2.0 * (np.arange(w) + 0.5) / w - 1.0) * half_w
    ys = (1.0 - 2.0 * (np.arange(h) + 0.5) / h) * half_h
    gx, gy = np.meshgrid(xs, ys)
    dirs = forward + gx[..., None] * right + gy[..., None] * up
    dirs /= np.linalg.norm(dirs, axis=-1, keepdims=True)
    return origin, dirs.reshape(-1, 3)


def intersect_sphere(origins, dirs, center, radius):
    """Nearest t > epsilon along each ray, inf where it misses."""
    oc = origins - np.asarray(center, float)
    b = np.einsum("ij,ij->i", oc, dirs)
    c = np.einsum("ij,ij->i", oc, oc) - radius * radius
    disc = b * b - c
    t = np.full(len(dirs), np.inf)
    ok = disc >= 0.0
    root = np.sqrt(np.where(ok, disc, 0.0))
    t_near, t_far = -b - root, -b + root
    t = np.where(ok & (t_near > RAY_EPSILON), t_near, t)
    t = np.where(ok & (t_near <= RAY_EPSILON) & (t_far > RAY_EPSILON), t_far, t)
    return t


def _frame(n):
    """Orthonormal tangent, bitangent for unit normals n (N,3)."""
    helper = np.where(np.abs(n[:, :1]) < 0.9, [[1.0, 0.0, 0.0]], [[0.0, 1.0, 0.0]])
    t = np.cross(helper, n)
    t /= np.linalg.norm(t, axis=1, keepdims=True)
    return t, np.cross(n, t)


def _default_frame(q, n):
    """Cycles' default tangent frame at object-space points q (the object's origin at the
    sphere's centre): the tangent radial about the object's Z axis, (−q.y, q.x, 0), made
    orthogonal to n, and the bitangent n × t; _frame's where that tangent vanishes (the poles)."""
    radial = np.stack([-q[:, 1], q[:, 0], np.zeros(len(q))], axis=1)
    t = radial - n * np.einsum("ij,ij->i", radial, n)[:, None]
    length = np.linalg.norm(t, axis=1, keepdims=True)
    fallback, _ = _frame(n)
    t = np.where(length > 1e-9, t / np.maximum(length, 1e-30), fallback)
    return t, np.cross(n, t)


def _to_local(v, t, b, n):
    return np.stack([np.einsum("ij,ij->i", v, t), np.einsum("ij,ij->i", v, b),
                     np.einsum("ij,ij->i", v, n)], axis=1)


# Blender's spheres are UV spheres of 128 segments (bpy_build): facets span DELTA = 2 pi / 128, and
# the interpolated normal at the facet hit differs from the true sphere normal by about
# DELTA^2 / 8 (sagitta), plus the sagitta's tangential shift of the hit point, which grows with
# tan(view angle). The image's sensitivity to a normal error of that size is the geometric
# tolerance.
TESSELLATION_DELTA = 2.0 * np.pi / 128.0
MAX_VIEW_TAN = 20.0


@dataclass
class AnalyticImage:
    image: np.ndarray              # float32 (H, W, 3), linear
    object_ids: np.ndarray         # int (H, W), -1 for background
    geometry_tolerance: np.ndarray  # float32 (H, W, 3): |dL| for the tessellation's normal error


def render(spec: SceneSpec) -> AnalyticImage:
    if not spec.has_analytic_truth():
        raise ValueError(f"scene '{spec.name}' has no analytic truth")
    w, h = spec.resolution
    origin, dirs = camera_rays(spec)
    origins = np.broadcast_to(origin, dirs.shape)
    spheres = [o for o in spec.objects if isinstance(o, Sphere)]
    t_hit = np.full(len(dirs), np.inf)
    obj_id = np.full(len(dirs), -1)
    for i, s in enumerate(spheres):
        t = intersect_sphere(origins, dirs, s.center, s.radius)
        closer = t < t_hit
        t_hit[closer], obj_id[closer] = t[closer], i

    image = np.zeros((len(dirs), 3))
    tolerance = np.zeros((len(dirs), 3))
    gradient = spec.environment if isinstance(spec.environment, ZGradientWorld) else None
    if gradient is None:
        image[obj_id < 0] = spec.world_color
    else:
        image[obj_id < 0] = gradient_world.radiance(gradient, dirs[obj_id < 0])[:, None]
    if is_lambert_furnace(spec):
        hit = np.nonzero(obj_id >= 0)[0]
        reflectance = np.asarray(spheres[0].material.params["reflectance"], float)
        if gradient is None:
            image[hit] = reflectance * np.asarray(spec.world_color, float)
        else:
            sphere = spheres[0]
            p = origin + dirs[hit] * t_hit[hit, None]
            n = (p - np.asarray(sphere.center, float)) / sphere.radius
            image[hit] = gradient_world.lambert_radiance(gradient, reflectance, n)
            # dL/dn_z = 2/3 b R: the tessellation's normal error moves n_z by at most eps.
            tolerance[hit] = (2.0 / 3.0 * abs(gradient.b) * reflectance[None, :]
                              * _normal_error(dirs[hit], n)[:, None])
    else:
        for i, s in enumerate(spheres):
            sel = np.nonzero(obj_id == i)[0]
            if len(sel):
                image[sel], tolerance[sel] = _shade_with_tolerance(
                    spec, spheres, s, origin, dirs[sel], t_hit[sel])
    return AnalyticImage(image.reshape(h, w, 3).astype(np.float32), obj_id.reshape(h, w),
                         tolerance.reshape(h, w, 3).astype(np.float32))


def _normal_error(dirs, n):
    """The tessellated sphere's normal error (radians) at the hits of `dirs` with true normals n."""
    cos_v = np.clip(-np.einsum("ij,ij->i", dirs, n), 1e-6, 1.0)
    tan_v = np.minimum(np.sqrt(1.0 - cos_v ** 2) / cos_v, MAX_VIEW_TAN)
    return TESSELLATION_DELTA ** 2 / 8.0 * (1.0 + tan_v)


def _shade_with_tolerance(spec, spheres, sphere, origin, dirs, t):
    model = make_model(sphere.material.model, sphere.material.params)
    p = origin + dirs * t[:, None]
    center = np.asarray(sphere.center, float)
    n = (p - center) / sphere.radius
    value = _shade(spec, spheres, model, p, n, dirs, center)
    eps = _normal_error(dirs, n)
    tangent, bitangent = _frame(n)
    deviation = np.zeros_like(value)
    for direction in (tangent, -tangent, bitangent, -bitangent):
        tilted = n + eps[:, None] * direction
        tilted /= np.linalg.norm(tilted, axis=1, keepdims=True)
        deviation = np.maximum(deviation, np.abs(
            _shade(spec, spheres, model, p, tilted, dirs, center) - value))
    return value, deviation


def _shade(spec, spheres, model, p, n, dirs, center):
    """Direct light at points p with shading normals n seen along dirs, on the sphere about
    `center` (its tangent frame is Cycles' default one, which anisotropic models see)."""
    tangent, bitangent = _default_frame(p - center, n)
    wo = _to_local(-dirs, tangent, bitangent, n)
    out = np.zeros((len(dirs), 3))
    for light in spec.lights:
        if isinstance(light, PointLight):
            to_light = np.asarray(light.location, float) - p
            dist = np.linalg.norm(to_light, axis=1)
            wi_world = to_light / dist[:, None]
            irradiance = light.intensity / dist ** 2
        elif isinstance(light, SunLight):
            d = np.asarray(light.direction, float)
            wi_world = np.broadcast_to(d / np.linalg.norm(d), p.shape)
            dist = np.full(len(p), np.inf)
            irradiance = np.full(len(p), light.irradiance)
        else:
            raise TypeError(f"unknown light {light!r}")
        cos_i = np.einsum("ij,ij->i", wi_world, n)
        lit = cos_i > 0.0
        shadow_origin = p + n * 1e-5
        for other in spheres:
            ts = intersect_sphere(shadow_origin, wi_world, other.center, other.radius)
            lit &= ~(ts < dist)
        if not lit.any():
            continue
        wi = _to_local(wi_world[lit], tangent[lit], bitangent[lit], n[lit])
        f = np.asarray(model.f(np.ascontiguousarray(wo[lit]), np.ascontiguousarray(wi)), float)
        out[lit] += (f * (cos_i[lit] * irradiance[lit])[:, None]
                     * np.asarray(light.color, float))
    return out
