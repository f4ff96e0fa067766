"""INTERIM: numpy versions of the few models the default scenes use, for the analytic images while
the `bxdf` module is not on main. Delete this file (and its one import in analytic.py) once it is:
the analytic truth must come from the core's f. Formulas: reference/models.md, renderers.md."""
from __future__ import annotations

import math

import numpy as np


def _cos(w):
    return w[:, 2]


def _tan2(w):
    c2 = np.clip(w[:, 2] ** 2, 1e-300, 1.0)
    return np.maximum(1.0 - c2, 0.0) / c2


class _Model:
    def __init__(self, fn):
        self._fn = fn

    def f(self, wo, wi):
        wo = np.atleast_2d(np.asarray(wo, float))
        wi = np.atleast_2d(np.asarray(wi, float))
        wo = wo / np.linalg.norm(wo, axis=1, keepdims=True)
        wi = wi / np.linalg.norm(wi, axis=1, keepdims=True)
        above = (_cos(wo) > 0) & (_cos(wi) > 0)
        out = np.zeros((len(wo), 3))
        if above.any():
            out[above] = self._fn(wo[above], wi[above])
        return out


def _rgb(v):
    return np.asarray(v if not isinstance(v, (int, float)) else (v, v, v), float)


def lambertian(p):
    r = _rgb(p["reflectance"])
    return lambda wo, wi: np.broadcast_to(r / math.pi, (len(wo), 3))


def oren_nayar(p):
    r = _rgb(p["reflectance"])
    s = math.radians(p["sigma"])
    a = 1.0 - s * s / (2.0 * (s * s + 0.33))
    b = 0.45 * s * s / (s * s + 0.09)

    def f(wo, wi):
        sin_o = np.sqrt(np.maximum(0.0, 1 - wo[:, 2] ** 2))
        sin_i = np.sqrt(np.maximum(0.0, 1 - wi[:, 2] ** 2))
        ok = (sin_o > 1e-4) & (sin_i > 1e-4)
        cos_dphi = np.where(ok, (wo[:, 0] * wi[:, 0] + wo[:, 1] * wi[:, 1])
                            / np.where(ok, sin_o * sin_i, 1.0), 0.0)
        max_cos = np.maximum(0.0, cos_dphi)
        # alpha = max(theta), beta = min(theta): sin(alpha) tan(beta)
        i_larger = wi[:, 2] < wo[:, 2]          # theta_i > theta_o
        sin_alpha = np.where(i_larger, sin_i, sin_o)
        tan_beta = np.where(i_larger, sin_o / wo[:, 2], sin_i / wi[:, 2])
        return r / math.pi * (a + b * max_cos * sin_alpha * tan_beta)[:, None]
    return f


def cycles_oren_nayar(p):
    color = _rgb(p["color"])
    sigma = min(max(p["roughness"], 0.0), 1.0)
    a = 1.0 / (math.pi + (math.pi / 2 - 2.0 / 3.0) * sigma)
    b = sigma * a

    def f(wo, wi):
        s = np.einsum("ij,ij->i", wo, wi) - wo[:, 2] * wi[:, 2]
        t = np.where(s > 0, np.maximum(wo[:, 2], wi[:, 2]), 1.0)
        return color * (a + b * s / t)[:, None]
    return f


def cycles_glossy(p):
    color = _rgb(p["color"])
    alpha = min(max(p["roughness"] ** 2, 0.0), 1.0)
    a2 = alpha * alpha
    dist = p["distribution"]

    if dist == "ggx":
        def d(wh):
            c = wh[:, 2]
            return a2 / (math.pi * c ** 4 * (a2 + _tan2(wh)) ** 2)

        def g1(w):
            return 2.0 / (1.0 + np.sqrt(1.0 + a2 * _tan2(w)))
    elif dist == "beckmann":
        def d(wh):
            c = wh[:, 2]
            return np.exp(-_tan2(wh) / a2) / (math.pi * a2 * c ** 4)

        def g1(w):
            a = 1.0 / np.maximum(alpha * np.sqrt(_tan2(w)), 1e-12)
            a = np.minimum(a, 1.6)      # the rational fit is used below 1.6, 1 above
            return np.where(a < 1.6, (3.535 * a + 2.181 * a * a) / (1 + 2.276 * a + 2.577 * a * a),
                            1.0)
    else:
        raise ValueError(f"distribution must be 'ggx' or 'beckmann', got {dist!r}")

    def f(wo, wi):
        wh = wo + wi
        wh /= np.linalg.norm(wh, axis=1, keepdims=True)
        val = d(wh) * g1(wo) * g1(wi) / (4.0 * wo[:, 2] * wi[:, 2])
        return color * val[:, None]
    return f


_MODELS = {"lambertian": lambertian, "oren_nayar": oren_nayar,
           "cycles_oren_nayar": cycles_oren_nayar, "cycles_glossy": cycles_glossy}


def make(model, params):
    if model not in _MODELS:
        raise NotImplementedError(f"no interim analytic formula for model '{model}' "
                                  "(needs the bxdf module)")
    return _Model(_MODELS[model](params))
