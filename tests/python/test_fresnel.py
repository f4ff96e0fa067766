"""bxdf.fresnel_dielectric / fresnel_conductor / eta_from_f0 / k_from_f0 against the textbook
formulas written out in numpy, shapes, and refused inputs."""

import numpy as np
import pytest

import bxdf


def dielectric_reference(cos_i, eta_i, eta_t):
    cos_i = np.asarray(cos_i, np.float64)
    inside = cos_i < 0
    ei = np.where(inside, eta_t, eta_i)
    et = np.where(inside, eta_i, eta_t)
    c = np.abs(cos_i)
    sin_t = ei / et * np.sqrt(1 - c**2)
    tir = sin_t >= 1
    cos_t = np.sqrt(np.clip(1 - sin_t**2, 0, None))
    with np.errstate(invalid="ignore", divide="ignore"):  # 0/0 at grazing, masked below
        r_par = (et * c - ei * cos_t) / (et * c + ei * cos_t)
        r_perp = (ei * c - et * cos_t) / (ei * c + et * cos_t)
    return np.where(tir, 1.0, 0.5 * (r_par**2 + r_perp**2))


def conductor_reference(cos_i, eta, k):
    # The seed's formula (pbrt v1 FrCond) at |cos_i|.
    c = np.abs(np.asarray(cos_i, np.float64))[..., None]
    eta, k = np.asarray(eta, np.float64), np.asarray(k, np.float64)
    ek = eta**2 + k**2
    r_par2 = (ek * c**2 - 2 * eta * c + 1) / (ek * c**2 + 2 * eta * c + 1)
    r_perp2 = (ek - 2 * eta * c + c**2) / (ek + 2 * eta * c + c**2)
    return 0.5 * (r_par2 + r_perp2)


def test_dielectric_matches_the_formula():
    cos_i = np.linspace(-1, 1, 2001).astype(np.float32)  # the reference sees the same inputs
    for eta_i, eta_t in ((1.0, 1.5), (1.0, 1.33), (1.5, 1.0), (1.0, 2.4)):
        got = bxdf.fresnel_dielectric(cos_i, eta_i, eta_t)
        assert got.shape == cos_i.shape and got.dtype == np.float32
        # float32 inside: near the critical angle cos_t loses a few digits.
        np.testing.assert_allclose(got, dielectric_reference(cos_i, eta_i, eta_t), rtol=1e-5, atol=1e-6)


def test_dielectric_special_values():
    assert bxdf.fresnel_dielectric(1.0, 1.0, 1.5) == pytest.approx(0.04, abs=1e-7)
    assert bxdf.fresnel_dielectric(1.0, 1.5, 1.5) == pytest.approx(0.0, abs=1e-7)
    # From inside glass beyond the critical angle (~41.8 degrees): total internal reflection.
    assert bxdf.fresnel_dielectric(-np.cos(np.radians(60)), 1.0, 1.5) == 1.0
    assert bxdf.fresnel_dielectric(np.cos(np.radians(60)), 1.5, 1.0) == 1.0
    assert isinstance(bxdf.fresnel_dielectric(0.5, 1.0, 1.5), float)


def test_dielectric_keeps_the_shape_of_cos_i():
    assert bxdf.fresnel_dielectric([0.5], 1.0, 1.5).shape == (1,)
    assert bxdf.fresnel_dielectric(np.full((4, 5), 0.5), 1.0, 1.5).shape == (4, 5)
    assert bxdf.fresnel_dielectric(np.zeros(0), 1.0, 1.5).shape == (0,)
    assert bxdf.fresnel_dielectric(np.float32(0.5), 1.0, 1.5) == pytest.approx(dielectric_reference(0.5, 1.0, 1.5))


def test_conductor_matches_the_seed_formula():
    cos_i = np.linspace(-1, 1, 1001).astype(np.float32)
    eta, k = (0.143, 0.374, 1.442), (3.983, 2.385, 1.603)  # gold
    got = bxdf.fresnel_conductor(cos_i, eta, k)
    assert got.shape == (1001, 3) and got.dtype == np.float32
    np.testing.assert_allclose(got, conductor_reference(cos_i, eta, k), atol=3e-6)
    grey = bxdf.fresnel_conductor(cos_i, 1.5, 2.0)
    np.testing.assert_allclose(grey, conductor_reference(cos_i, [1.5] * 3, [2.0] * 3), atol=3e-6)
    assert bxdf.fresnel_conductor(0.5, eta, k).shape == (3,)
    assert bxdf.fresnel_conductor(np.full((2, 2), 0.5), eta, np.array(k)).shape == (2, 2, 3)


def test_f0_inversions_round_trip():
    f0 = np.linspace(0, 0.95, 39)
    eta = bxdf.eta_from_f0(f0)
    assert eta.shape == f0.shape and eta.dtype == np.float32
    for e, f in zip(eta, f0):  # a dielectric of index eta has F0 = f0
        assert bxdf.fresnel_dielectric(1.0, 1.0, float(e)) == pytest.approx(f, abs=2e-6)
    k = bxdf.k_from_f0(f0)
    for kk, f in zip(k, f0):  # a conductor with eta = 1 and this k has F0 = f0
        assert bxdf.fresnel_conductor(1.0, 1.0, float(kk))[0] == pytest.approx(f, abs=2e-6)
    assert bxdf.eta_from_f0(0.04) == pytest.approx(1.5, abs=1e-6)
    assert isinstance(bxdf.k_from_f0(0.5), float)
    assert np.isfinite(bxdf.eta_from_f0(1.0)) and np.isfinite(bxdf.k_from_f0(1.0))
    assert bxdf.k_from_f0([[0.5]]).shape == (1, 1)


@pytest.mark.parametrize(
    "call, argument",
    [
        (lambda: bxdf.fresnel_dielectric(1.5, 1.0, 1.5), "cos_i"),
        (lambda: bxdf.fresnel_dielectric([0.5, np.nan], 1.0, 1.5), "cos_i"),
        (lambda: bxdf.fresnel_dielectric(0.5, 0.0, 1.5), "eta_i"),
        (lambda: bxdf.fresnel_dielectric(0.5, 1.0, -1.5), "eta_t"),
        (lambda: bxdf.fresnel_dielectric(0.5, 1.0, np.inf), "eta_t"),
        (lambda: bxdf.fresnel_dielectric(0.5, 1.0, "glass"), "eta_t"),
        (lambda: bxdf.fresnel_dielectric("x", 1.0, 1.5), "cos_i"),
        (lambda: bxdf.fresnel_conductor(0.5, (1, 1), 1.0), "eta"),
        (lambda: bxdf.fresnel_conductor(0.5, 0.0, 1.0), "eta"),
        (lambda: bxdf.fresnel_conductor(0.5, 1.0, (1, -1, 1)), "k"),
        (lambda: bxdf.fresnel_conductor(-2, 1.0, 1.0), "cos_i"),
        (lambda: bxdf.eta_from_f0(1.5), "f0"),
        (lambda: bxdf.eta_from_f0([0.1, -0.1]), "f0"),
        (lambda: bxdf.k_from_f0(np.nan), "f0"),
    ],
)
def test_bad_inputs_are_value_errors_naming_the_argument(call, argument):
    with pytest.raises(ValueError, match=f"'{argument}'"):
        call()
