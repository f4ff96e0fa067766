"""Textured emission is light-sampled (with MIS against BSDF sampling), as Cycles samples
emissive triangles: a quad whose Emission reads a two-texel image (Closest: two halves of
different radiance) lights a diffuse floor exactly as two quads with those constant emissions
do, and, being light-sampled like them, with about the same noise (BSDF sampling alone, as
before, left it several times noisier)."""

import numpy as np
import pytest

import bxdf
from test_render import camera

pytestmark = pytest.mark.skipif(not hasattr(bxdf, "render"), reason="built without the renderer")

HALF_A, HALF_B = (6.0, 2.0, 1.0), (1.0, 3.0, 8.0)
# The emitter: 1 × 1 at height 1, just outside the camera's view (|x| ≤ 1.08 at z = 1).
X0, X1, Y0, Y1, Z = 1.3, 2.3, -0.5, 0.5, 1.0


def quad(x0, x1, y0, y1, z, material, uvs=False):
    mesh = {"name": "quad", "positions": np.array([[x0, y0, z], [x1, y0, z], [x1, y1, z], [x0, y1, z]],
                                                   np.float32),
            "triangles": np.array([[0, 1, 2], [0, 2, 3]], np.int32),
            "material_indices": np.full(2, material, np.int32)}
    if uvs:
        mesh["uvs"] = np.array([[0, 0], [1, 0], [1, 1], [0, 1]], np.float32)
        mesh["uv_indices"] = mesh["triangles"].copy()
    return mesh


def floor_scene(emitters, materials):
    return {"meshes": [quad(-5, 5, -5, 5, 0.0, 0)] + emitters,
            "materials": [{"model": "lambertian", "params": {"reflectance": 0.8}}] + materials,
            "lights": [], "camera": camera(), "world": {"color": np.zeros(3, np.float32)},
            "resolution": (24, 24), "warnings": []}


def textured_scene(tmp_path):
    oiio = pytest.importorskip("OpenImageIO")
    path = str(tmp_path / "two_halves.exr")
    out = oiio.ImageOutput.create(path)
    out.open(path, oiio.ImageSpec(2, 1, 3, "float"))
    out.write_image(np.array([[HALF_A, HALF_B]], np.float32))
    out.close()
    emitter = {"graph": {
        "textures": [{"path": path, "interpolation": "closest", "extension": "extend",
                      "colorspace": "linear"}],
        "nodes": [{"op": "uv"}, {"op": "image", "texture": 0, "vector": {"node": 0, "out": "vector"}}],
        "emission": {"node": 1, "out": "color"}}}
    return floor_scene([quad(X0, X1, Y0, Y1, Z, 1, uvs=True)], [emitter])


def two_quads_scene():
    xm = 0.5 * (X0 + X1)
    return floor_scene([quad(X0, xm, Y0, Y1, Z, 1), quad(xm, X1, Y0, Y1, Z, 2)],
                       [{"emission": list(HALF_A)}, {"emission": list(HALF_B)}])


def renders(scene, runs=8, samples=8):
    settings = {"samples": samples, "max_bounces": 0, "pixel_filter": "pixel_center", "threads": 2}
    return np.stack([bxdf.render(scene, dict(settings, seed=seed))[..., :3] for seed in range(runs)])


def test_textured_emission_is_light_sampled_without_bias(tmp_path):
    textured, constant = renders(textured_scene(tmp_path)), renders(two_quads_scene())
    assert constant.mean() > 0.01
    # Unbiased: the image means agree within their Monte Carlo error.
    t_mean, c_mean = textured.mean(axis=0), constant.mean(axis=0)
    t_err = textured.std(axis=0, ddof=1) / np.sqrt(len(textured))
    c_err = constant.std(axis=0, ddof=1) / np.sqrt(len(constant))
    z = (t_mean - c_mean) / np.sqrt(t_err ** 2 + c_err ** 2 + 1e-12)
    assert np.mean(np.abs(z) > 4.0) < 0.01
    assert abs(t_mean.mean() / c_mean.mean() - 1.0) < 0.02
    # Light-sampled: about the noise of the constant emitters (BSDF sampling alone: ~5× more).
    assert textured.var(axis=0, ddof=1).mean() < 1.5 * constant.var(axis=0, ddof=1).mean()
