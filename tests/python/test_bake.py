"""Lobe baking: polar images (both parameterisations), half/difference slices, albedo curves and
lobe meshes, checked against closed forms for a Lambertian and against the model's own f and
rho for every model."""

import numpy as np
import pytest

import bxdf
from conftest import is_delta

R = np.array([0.8, 0.5, 0.2])


def has_stochastic_f(model):
    """Multiscatter GGX averages random walks seeded from the bits of its directions, so f at
    directions computed another way (an ulp apart) is another estimate of the same value."""
    return dict(model.params).get("distribution") == "multi_ggx"


def assert_f_close(actual, expected, model, rtol, atol):
    """Pixel for pixel; for a stochastic f, the totals (one f's relative RMS is about 0.24, a
    total over hundreds of pixels averages it to about 1%)."""
    if has_stochastic_f(model):
        np.testing.assert_allclose(np.sum(actual), np.sum(expected), rtol=0.05)
    else:
        np.testing.assert_allclose(actual, expected, rtol=rtol, atol=atol)


@pytest.fixture
def lambertian():
    return bxdf.make("lambertian", reflectance=R)


def equal_area_directions(res):
    """The documented pixel → direction map of parameterization='equal_area'."""
    c = (np.arange(res) + 0.5) / res
    x = 2 * c[None, :] - 1
    y = 1 - 2 * c[:, None]
    x, y = np.broadcast_arrays(x, y)
    r2 = x**2 + y**2
    s = np.sqrt(np.clip(2 - r2, 0, None))
    return np.stack([x * s, y * s, 1 - r2], -1), r2 <= 1


def test_polar_equal_area_lambertian_is_flat_r_over_pi_cos(lambertian):
    res = 128
    img = bxdf.bake_lobe_polar(lambertian, theta_o=30.0, resolution=res)
    assert img.shape == (res, res, 3) and img.dtype == np.float32
    w, inside = equal_area_directions(res)
    expected = np.where(inside[..., None], R / np.pi * w[..., 2:3], 0.0)
    np.testing.assert_allclose(img, expected, rtol=1e-5, atol=1e-7)
    # Each pixel is 8 / res² sr, so the image sums to ρhd = R.
    np.testing.assert_allclose(img.sum((0, 1)) * 8 / res**2, R, rtol=5e-3)


def test_polar_wo_as_vector_or_angles(lambertian):
    a = bxdf.bake_lobe_polar(lambertian, [0.5, 0.0, np.sqrt(3) / 2], 32)
    b = bxdf.bake_lobe_polar(lambertian, theta_o=30.0, phi_o=0.0, resolution=32)
    np.testing.assert_allclose(a, b, rtol=1e-6)
    # wo below the surface: a reflection-only model has nothing in the upper hemisphere.
    assert np.all(bxdf.bake_lobe_polar(lambertian, theta_o=120.0, resolution=16) == 0)
    # ... and the same lobe in the lower one.
    low = bxdf.bake_lobe_polar(lambertian, theta_o=120.0, resolution=16, hemisphere="lower")
    np.testing.assert_allclose(low, bxdf.bake_lobe_polar(lambertian, theta_o=60.0, resolution=16), rtol=1e-6)


def test_polar_lat_long_lambertian(lambertian):
    res = 64
    img = bxdf.bake_lobe_polar(lambertian, theta_o=10.0, resolution=res, parameterization="lat_long")
    assert img.shape == (res, res, 3)
    theta = (np.arange(res) + 0.5) / res * np.pi / 2
    expected = R[None, None, :] / np.pi * np.cos(theta)[:, None, None] * np.ones((1, res, 1))
    np.testing.assert_allclose(img, expected, rtol=1e-5)
    d_omega = np.sin(theta) * (np.pi / 2 / res) * (2 * np.pi / res)
    np.testing.assert_allclose((img * d_omega[:, None, None]).sum((0, 1)), R, rtol=1e-3)


@pytest.mark.parametrize("parameterization", ["equal_area", "lat_long"])
def test_polar_integral_is_rho_for_every_model(variant, parameterization):
    if is_delta(variant):  # f = 0 everywhere: nothing to see
        assert np.all(bxdf.bake_lobe_polar(variant, theta_o=40.0, resolution=16) == 0)
        return
    res = 256
    theta = (np.arange(res) + 0.5) / res * np.pi / 2
    if parameterization == "equal_area":
        weight = 8 / res**2
    else:
        weight = (np.sin(theta) * (np.pi / 2 / res) * (2 * np.pi / res))[:, None, None]
    total = 0
    for hemisphere in ("upper", "lower"):
        img = bxdf.bake_lobe_polar(variant, theta_o=40.0, resolution=res, parameterization=parameterization, hemisphere=hemisphere)
        assert np.all(np.isfinite(img)) and np.all(img >= 0)
        total = total + (img * weight).sum((0, 1))
    rho = variant.rho([np.sin(np.radians(40)), 0, np.cos(np.radians(40))], 65536)[0]
    np.testing.assert_allclose(total, rho, rtol=0.03, atol=3e-3)


def test_polar_pixels_are_f_times_cos(variant):
    res = 24
    img = bxdf.bake_lobe_polar(variant, theta_o=35.0, phi_o=20.0, resolution=res)
    w, inside = equal_area_directions(res)
    t, p = np.radians(35.0), np.radians(20.0)
    wo = [np.sin(t) * np.cos(p), np.sin(t) * np.sin(p), np.cos(t)]
    f = variant.f(wo, np.where(inside[..., None], w, 0).reshape(-1, 3)).reshape(res, res, 3)
    assert_f_close(img, f * np.abs(w[..., 2:3]) * inside[..., None], variant, rtol=1e-4, atol=1e-6)


def test_half_diff_slice_lambertian(lambertian):
    res = 90
    at_90 = bxdf.bake_slice_half_diff(lambertian, 90.0, res)
    assert at_90.shape == (res, res, 3) and at_90.dtype == np.float32
    # φd = 90°: wo and wi both stay above the surface, f = R/π everywhere.
    np.testing.assert_allclose(at_90, np.broadcast_to(R / np.pi, at_90.shape), rtol=1e-6)
    # φd = 0: the pair lies in the plane of h, and wo is below the horizon once θh + θd > 90°.
    at_0 = bxdf.bake_slice_half_diff(lambertian, 0.0, res)
    t = (np.arange(res) + 0.5) / res * 90
    total = t[:, None] + t[None, :]  # [row = θd, col = θh]; = 90 exactly is grazing: skipped
    above, below = total < 89.9, total > 90.1
    np.testing.assert_allclose(at_0[above], np.broadcast_to(R / np.pi, at_0[above].shape), rtol=1e-6)
    assert np.all(at_0[below] == 0) and below.sum() > 0.4 * res * res


def test_half_diff_slice_is_f_at_the_documented_directions(variant):
    res, phi_d, phi_h = 12, 60.0, 30.0
    img = bxdf.bake_slice_half_diff(variant, phi_d, res, phi_h=phi_h)
    t = (np.arange(res) + 0.5) / res * np.pi / 2
    td, th = np.meshgrid(t, t, indexing="ij")
    pd, ph = np.radians(phi_d), np.radians(phi_h)
    d = np.stack([np.sin(td) * np.cos(pd), np.sin(td) * np.sin(pd), np.cos(td)], -1)

    def rotate(v):  # Rz(φh) Ry(θh) v
        x = v[..., 0] * np.cos(th) + v[..., 2] * np.sin(th)
        z = -v[..., 0] * np.sin(th) + v[..., 2] * np.cos(th)
        y = v[..., 1]
        return np.stack([x * np.cos(ph) - y * np.sin(ph), x * np.sin(ph) + y * np.cos(ph), z], -1)

    wi = rotate(d)
    wo = rotate(d * [-1, -1, 1])
    h = wo + wi
    h /= np.linalg.norm(h, axis=-1, keepdims=True)
    np.testing.assert_allclose(np.arccos(np.clip(h[..., 2], -1, 1)), th, atol=1e-6)
    np.testing.assert_allclose(np.sum(wo * wi, -1), np.cos(2 * td), atol=1e-6)
    want = variant.f(wo.reshape(-1, 3), wi.reshape(-1, 3)).reshape(res, res, 3)
    assert_f_close(img, want, variant, rtol=1e-4, atol=1e-6)


def test_albedo_curve(lambertian, variant):
    theta, albedo = bxdf.bake_albedo_curve(lambertian, 9, 64)
    np.testing.assert_allclose(theta, (np.arange(9) + 0.5) * 10)
    np.testing.assert_allclose(albedo, np.tile(R, (9, 1)), rtol=1e-6)
    # Any model: the curve is rho at the documented angles, same samples and seed.
    theta, albedo = bxdf.bake_albedo_curve(variant, 5, 1024, phi_o=30.0, seed=3)
    t, p = np.radians(theta.astype(np.float64)), np.radians(30.0)
    wo = np.stack([np.sin(t) * np.cos(p), np.sin(t) * np.sin(p), np.cos(t)], -1)
    assert_f_close(albedo, variant.rho(wo, 1024, seed=3), variant, rtol=1e-5, atol=1e-7)


def test_lobe_mesh_lambertian(lambertian):
    n = 6
    v, t = bxdf.lobe_mesh(lambertian, [0, 0, 1], n)
    assert v.shape == (1 + 4 * n * n, 3) and v.dtype == np.float32
    assert t.shape == (4 * n + 8 * n * (n - 1), 3) and t.dtype == np.int32
    assert t.min() == 0 and t.max() == len(v) - 1
    assert len(np.unique(t)) == len(v)  # every vertex used
    # Radius = luminance(R/π) cos θ: a sphere through the origin (the Lambertian lobe).
    lum = 0.2126 * R[0] + 0.7152 * R[1] + 0.0722 * R[2]
    radius = np.linalg.norm(v, axis=1)
    direction = v / np.where(radius > 0, radius, 1)[:, None]
    ring = np.concatenate([[0], np.repeat(np.arange(1, n + 1), 4 * n)])
    cos_theta = np.cos(ring * np.pi / 2 / n)
    np.testing.assert_allclose(radius, lum / np.pi * cos_theta, rtol=1e-5, atol=1e-7)
    np.testing.assert_allclose(direction[radius > 0, 2], cos_theta[radius > 0], atol=1e-5)
    # Outward winding: each face normal points away from the lobe's centre.
    a, b, c = v[t[:, 0]], v[t[:, 1]], v[t[:, 2]]
    normal = np.cross(b - a, c - a)
    big = np.linalg.norm(normal, axis=1) > 1e-9
    centre = np.array([0, 0, lum / np.pi / 2])
    assert np.all(np.sum(normal[big] * ((a + b + c)[big] / 3 - centre), axis=1) > 0)
    # Lower hemisphere: mirrored, winding flipped.
    v2, t2 = bxdf.lobe_mesh(lambertian, theta_o=180.0, resolution=n, hemisphere="lower")
    np.testing.assert_allclose(v2, v * [1, 1, -1], atol=1e-6)
    np.testing.assert_array_equal(t2, t[:, [0, 2, 1]])


def test_lobe_mesh_radius_is_luminance_of_f_cos(variant):
    v, _ = bxdf.lobe_mesh(variant, theta_o=30.0, resolution=8)
    assert np.all(np.isfinite(v))
    ring = np.concatenate([[0], np.repeat(np.arange(1, 9), 32)])
    seg = np.concatenate([[0], np.tile(np.arange(32), 8)])
    th, ph = ring * np.pi / 16, seg * 2 * np.pi / 32
    wi = np.stack([np.sin(th) * np.cos(ph), np.sin(th) * np.sin(ph), np.cos(th)], -1)
    f = variant.f([np.sin(np.radians(30)), 0, np.cos(np.radians(30))], wi) * np.cos(th)[:, None]
    lum = f @ np.array([0.2126, 0.7152, 0.0722])
    assert_f_close(v, wi * lum[:, None], variant, rtol=1e-4, atol=1e-6)


@pytest.mark.parametrize(
    "call, words",
    [
        (lambda m: bxdf.bake_lobe_polar(m, [0, 0, 1], 0), ["resolution", "[1, 4096]"]),
        (lambda m: bxdf.bake_lobe_polar(m, [0, 0, 1], 5000), ["resolution", "5000"]),
        (lambda m: bxdf.bake_lobe_polar(m, [0, 0, 1], 64.0), ["resolution", "integer"]),
        (lambda m: bxdf.bake_lobe_polar(m, [0, 0, 1], 8, "mercator"), ["parameterization", "mercator", "equal_area"]),
        (lambda m: bxdf.bake_lobe_polar(m, [0, 0, 1], 8, hemisphere="both"), ["hemisphere", "upper"]),
        (lambda m: bxdf.bake_lobe_polar(m, [0, 0, 1], 8, theta_o=10.0), ["not both"]),
        (lambda m: bxdf.bake_lobe_polar(m, resolution=8), ["wo", "theta_o"]),
        (lambda m: bxdf.bake_lobe_polar(m, [0, 0, 0], 8), ["wo", "direction"]),
        (lambda m: bxdf.bake_lobe_polar(m, [0, np.nan, 1], 8), ["wo", "finite"]),
        (lambda m: bxdf.bake_lobe_polar(m, [[0, 0, 1]], 8), ["wo", "(3,)"]),
        (lambda m: bxdf.bake_lobe_polar(m, theta_o=200.0, resolution=8), ["theta_o", "200", "[0, 180]"]),
        (lambda m: bxdf.bake_lobe_polar(m, theta_o=np.nan, resolution=8), ["theta_o", "finite"]),
        (lambda m: bxdf.bake_slice_half_diff(m, 400.0, 8), ["phi_d", "400"]),
        (lambda m: bxdf.bake_slice_half_diff(m, 90.0, -1), ["resolution", "-1"]),
        (lambda m: bxdf.bake_albedo_curve(m, 0, 16), ["n_theta", "0"]),
        (lambda m: bxdf.bake_albedo_curve(m, 8, 0), ["n_samples", "0"]),
        (lambda m: bxdf.lobe_mesh(m, [0, 0, 1], 2000), ["resolution", "[1, 1024]"]),
        (lambda m: bxdf.lobe_mesh(m, [0, 0, 1], 0), ["resolution"]),
    ],
)
def test_bad_bake_arguments(lambertian, call, words):
    with pytest.raises(ValueError) as err:
        call(lambertian)
    for w in words:
        assert w in str(err.value), str(err.value)
