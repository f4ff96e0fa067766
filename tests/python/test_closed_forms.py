"""Models through Python against their textbook formulas written out in numpy (float64), and
Lafortune's list-of-dicts parameter."""

import numpy as np
import pytest

import bxdf
from conftest import random_directions


def test_oren_nayar_is_the_seed_formula(rng):
    r, sigma_deg = np.array([0.7, 0.5, 0.3]), 25.0
    m = bxdf.make("oren_nayar", reflectance=r, sigma=sigma_deg)
    wo = random_directions(rng, 4000, lower_fraction=0.2).astype(np.float64)
    wi = random_directions(rng, 4000, lower_fraction=0.2).astype(np.float64)
    s2 = np.radians(sigma_deg) ** 2
    a = 1 - s2 / (2 * (s2 + 0.33))
    b = 0.45 * s2 / (s2 + 0.09)
    theta_o, theta_i = np.arccos(np.abs(wo[:, 2])), np.arccos(np.abs(wi[:, 2]))
    cos_dphi = np.cos(np.arctan2(wi[:, 1], wi[:, 0]) - np.arctan2(wo[:, 1], wo[:, 0]))
    alpha, beta = np.maximum(theta_o, theta_i), np.minimum(theta_o, theta_i)
    value = a + b * np.maximum(0, cos_dphi) * np.sin(alpha) * np.tan(beta)
    same = wo[:, 2] * wi[:, 2] > 0
    expected = np.where(same[:, None], r / np.pi * value[:, None], 0)
    np.testing.assert_allclose(m.f(wo, wi), expected, rtol=2e-4, atol=1e-6)
    # sigma = 0 is Lambertian.
    np.testing.assert_allclose(bxdf.make("oren_nayar", reflectance=r, sigma=0.0).f(wo, wi),
                               bxdf.make("lambertian", reflectance=r).f(wo, wi), rtol=1e-6)


def lafortune_reference(diffuse, lobes, wo, wi):
    f = np.tile(np.asarray(diffuse) / np.pi, (len(wo), 1))
    for lobe in lobes:
        cx, cy, cz, n = (np.broadcast_to(np.asarray(lobe[k], float), (3,)) for k in ("cx", "cy", "cz", "exponent"))
        dot = cx * (wo[:, 0] * wi[:, 0])[:, None] + cy * (wo[:, 1] * wi[:, 1])[:, None] + cz * (wo[:, 2] * wi[:, 2])[:, None]
        f = f + np.maximum(0, dot) ** n
    same = wo[:, 2] * wi[:, 2] > 0
    return np.where(same[:, None], f, 0)


def test_lafortune_takes_lobes_as_a_list_of_dicts(rng):
    lobes = [
        {"cx": -1.0, "cy": -1.0, "cz": 1.0, "exponent": 20},
        {"cx": (0.5, 0.6, 0.7), "cy": [0.5, 0.6, 0.7], "cz": np.array([0.4, 0.4, 0.4]), "exponent": (3, 4, 5)},
    ]
    m = bxdf.make("lafortune", diffuse=(0.2, 0.3, 0.4), lobes=lobes)
    params = m.params
    assert len(params["lobes"]) == 2
    assert params["lobes"][0] == {"cx": (-1.0,) * 3, "cy": (-1.0,) * 3, "cz": (1.0,) * 3, "exponent": (20.0,) * 3}
    assert bxdf.make("lafortune", **params) == m
    wo = random_directions(rng, 3000, lower_fraction=0.0).astype(np.float64)
    wi = random_directions(rng, 3000, lower_fraction=0.0).astype(np.float64)
    np.testing.assert_allclose(m.f(wo, wi), lafortune_reference((0.2, 0.3, 0.4), lobes, wo, wi), rtol=2e-4, atol=1e-6)
    # No lobes: pure diffuse.
    assert bxdf.make("lafortune", diffuse=0.5, lobes=[]).params["lobes"] == []


def test_lafortune_presets_evaluate_their_published_fits(rng):
    wo = random_directions(rng, 2000, lower_fraction=0.0).astype(np.float64)
    wi = random_directions(rng, 2000, lower_fraction=0.0).astype(np.float64)
    for name in ("clay", "felt", "primer", "skin", "bluepaint", "brushedmetal"):
        p = bxdf.presets()[name]
        assert p["model"] == "lafortune"
        m = bxdf.make_preset(name)
        want = lafortune_reference(m.params["diffuse"], m.params["lobes"], wo, wi)
        np.testing.assert_allclose(m.f(wo, wi), want, rtol=1e-3, atol=1e-6, err_msg=name)


@pytest.mark.parametrize(
    "lobes, words",
    [
        (5, ["lobes", "list"]),
        ([5], ["lobes[0]", "dict"]),
        ([{"cx": 1, "cy": 1, "cz": 1, "exponent": 2, "cw": 1}], ["lobes[0]", "cw"]),
        ([{"cx": (1, 2), "cy": 1, "cz": 1, "exponent": 2}], ["lobes[0]", "cx", "(1, 2)"]),
        ([{"cx": 1, "cy": 1, "cz": 1, "exponent": -2}], ["lobes[0]", "exponent", "-2"]),
        ([{"cx": 1, "cy": 1, "cz": float("nan"), "exponent": 2}], ["lobes[0]", "cz", "nan"]),
        ("lobes", ["lobes", "'lobes'"]),
        (np.array(1.0), ["lobes", "list"]),
    ],
)
def test_lafortune_bad_lobes(lobes, words):
    with pytest.raises(ValueError) as err:
        bxdf.make("lafortune", lobes=lobes)
    for w in words:
        assert w in str(err.value), str(err.value)


def test_seed_metal_presets_reflect_their_fresnel_at_normal_incidence():
    # A GGX conductor at normal incidence: rho_hd is close to F(1) (most energy stays in the
    # lobe at alpha 0.1), and F(1) is the seed's formula with the preset's eta and k.
    for name in ("gold", "silver", "copper", "steel"):
        p = bxdf.presets()[name]["params"]
        f0 = bxdf.fresnel_conductor(1.0, p["eta"], p["k"])
        rho = bxdf.make_preset(name).rho([0, 0, 1], 16384)[0]
        np.testing.assert_allclose(rho, f0, rtol=0.05, err_msg=name)
