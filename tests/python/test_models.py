"""bxdf.models(), bxdf.make() and the Model object: registry contents, identity (params, repr,
pickling, equality), and each model's f / pdf / sample_f through Python against the core's
scalar path and against each other."""

import math
import pickle

import numpy as np
import pytest

import bxdf
from conftest import awkward_directions, is_delta, random_directions

KINDS = {"float", "rgb", "enum", "bool", "string", "list"}
FLAG_NAMES = {"reflection", "transmission", "diffuse", "glossy", "specular"}


def check_spec(spec):
    for key in ("name", "kind", "default", "min", "max", "unit", "doc"):
        assert key in spec, f"{spec.get('name')}: missing {key}"
    assert spec["kind"] in KINDS
    assert isinstance(spec["doc"], str) and spec["doc"]
    if spec["kind"] == "float":
        assert spec["min"] <= spec["default"] <= spec["max"]
    elif spec["kind"] == "rgb":
        assert len(spec["default"]) == 3
        assert all(spec["min"] <= c <= spec["max"] for c in spec["default"])
        assert spec["subtype"] in ("color", "per_channel")
    else:
        assert spec["min"] is None and spec["max"] is None
    if spec["kind"] == "enum":
        assert spec["default"] in spec["choices"]
    else:
        assert "choices" not in spec
    if spec["kind"] == "list":
        for field in spec["fields"]:
            check_spec(field)
    if "when" in spec:
        assert set(spec["when"]) == {"param", "values"}


def test_models_lists_every_registered_model_with_its_schema():
    models = bxdf.models()
    assert "lambertian" in models
    for name, specs in models.items():
        assert isinstance(specs, list)
        assert bxdf.model_doc(name)
        names = [s["name"] for s in specs]
        assert len(names) == len(set(names)), f"{name}: duplicate parameter names"
        for spec in specs:
            check_spec(spec)
        # A conditional parameter depends on an enum of the same model.
        for spec in specs:
            if "when" in spec:
                (dep,) = [s for s in specs if s["name"] == spec["when"]["param"]]
                assert set(spec["when"]["values"]) <= set(dep["choices"])


def test_lambertian_schema():
    (spec,) = bxdf.models()["lambertian"]
    assert spec["name"] == "reflectance" and spec["kind"] == "rgb"
    assert (spec["min"], spec["max"]) == (0.0, 1.0)


def test_make_fills_defaults_and_params_rebuild_the_model(variant):
    specs = bxdf.models()[variant.name]
    assert list(variant.params) == [s["name"] for s in specs]
    again = bxdf.make(variant.name, **variant.params)
    assert again == variant
    assert again.params == variant.params
    assert hash(again) == hash(variant)


def test_repr_evaluates_to_an_equal_model(variant):
    text = repr(variant)
    assert text.startswith(f"bxdf.make('{variant.name}'")
    assert eval(text, {"bxdf": bxdf}) == variant


def test_pickle_round_trip(variant):
    for protocol in range(2, pickle.HIGHEST_PROTOCOL + 1):
        copy = pickle.loads(pickle.dumps(variant, protocol=protocol))
        assert copy == variant and copy is not variant
        assert repr(copy) == repr(variant)


def test_flags_are_a_set_of_known_names(variant):
    assert isinstance(variant.flags, set)
    assert variant.flags and variant.flags <= FLAG_NAMES
    assert variant.flags & {"reflection", "transmission"}
    assert variant.flags & {"diffuse", "glossy", "specular"}


def test_make_accepts_rgb_as_tuple_list_array_or_number():
    ref = bxdf.make("lambertian", reflectance=(0.25, 0.5, 0.75))
    assert bxdf.make("lambertian", reflectance=[0.25, 0.5, 0.75]) == ref
    assert bxdf.make("lambertian", reflectance=np.array([0.25, 0.5, 0.75])) == ref
    assert bxdf.make("lambertian", reflectance=np.array([0.25, 0.5, 0.75], np.float32)) == ref
    grey = bxdf.make("lambertian", reflectance=0.5)
    assert grey.params["reflectance"] == (0.5, 0.5, 0.5)
    assert bxdf.make("lambertian", reflectance=np.float64(0.5)) == grey
    assert bxdf.make("lambertian", reflectance=1) == bxdf.make("lambertian", reflectance=1.0)
    assert bxdf.make("lambertian") == bxdf.make("lambertian", reflectance=(0.8, 0.8, 0.8))
    assert ref != grey and ref != "lambertian"


@pytest.mark.parametrize(
    "kwargs, words",
    [
        ({"reflectance": 1.5}, ["reflectance", "1.5", "[0, 1]"]),
        ({"reflectance": -0.1}, ["reflectance", "-0.1", "[0, 1]"]),
        ({"reflectance": (0.1, 0.2)}, ["reflectance", "(0.1, 0.2)", "RGB"]),
        ({"reflectance": (0.1, 0.2, 0.3, 0.4)}, ["reflectance", "[0, 1]"]),
        ({"reflectance": (0.1, "a", 0.3)}, ["reflectance", "RGB"]),
        ({"reflectance": "red"}, ["reflectance", "'red'"]),
        ({"reflectance": True}, ["reflectance", "True"]),
        ({"reflectance": None}, ["reflectance", "None"]),
        ({"reflectance": float("nan")}, ["reflectance", "nan"]),
        ({"reflectance": float("inf")}, ["reflectance", "inf", "finite"]),
        ({"reflectance": (0.5, float("nan"), 0.5)}, ["reflectance", "nan"]),
        ({"albedo": 0.5}, ["albedo", "reflectance"]),
    ],
)
def test_make_refuses_bad_parameters_naming_them(kwargs, words):
    with pytest.raises(ValueError) as err:
        bxdf.make("lambertian", **kwargs)
    for word in words:
        assert word in str(err.value), str(err.value)


def test_make_refuses_unknown_models():
    with pytest.raises(ValueError, match="unknown model 'no_such_model'.*lambertian"):
        bxdf.make("no_such_model")
    with pytest.raises(ValueError, match="name"):
        bxdf.make(42)
    with pytest.raises(ValueError, match="unknown model"):
        bxdf.model_doc("no_such_model")
    with pytest.raises(ValueError, match="name"):
        bxdf.model_doc(None)


def test_every_float_parameter_refuses_values_outside_its_range():
    for name, specs in bxdf.models().items():
        for spec in specs:
            if spec["kind"] not in ("float", "rgb"):
                continue
            for bad in (spec["min"] - 1.0, spec["max"] + 1.0, float("nan")):
                if math.isinf(bad):
                    continue
                with pytest.raises(ValueError, match=spec["name"]):
                    bxdf.make(name, **{spec["name"]: bad})
            for bound, exclusive in ((spec["min"], spec["min_exclusive"]), (spec["max"], spec["max_exclusive"])):
                if exclusive and math.isfinite(bound):
                    with pytest.raises(ValueError, match=spec["name"]):
                        bxdf.make(name, **{spec["name"]: bound})


def test_enum_parameters_refuse_unknown_choices():
    for name, specs in bxdf.models().items():
        for spec in specs:
            if spec["kind"] == "enum":
                with pytest.raises(ValueError, match=spec["name"]):
                    bxdf.make(name, **{spec["name"]: "no_such_choice"})
                with pytest.raises(ValueError, match=spec["name"]):
                    bxdf.make(name, **{spec["name"]: 1.0})


# --- evaluation: batch path (chunks, threads) against the core's scalar path --------------

N_PAIRS = 3000  # one thread; test_large_batches_match_the_scalar_path covers the TBB path


def test_f_and_pdf_match_the_scalar_path(variant, rng):
    wo = random_directions(rng, N_PAIRS)
    wi = random_directions(rng, N_PAIRS)
    f = variant.f(wo, wi)
    pdf = variant.pdf(wo, wi)
    assert f.shape == (N_PAIRS, 3) and f.dtype == np.float32
    assert pdf.shape == (N_PAIRS,) and pdf.dtype == np.float32
    np.testing.assert_allclose(f, bxdf._bxdf._reference_f(variant, wo, wi), rtol=1e-6, atol=0)
    np.testing.assert_allclose(pdf, bxdf._bxdf._reference_pdf(variant, wo, wi), rtol=1e-6, atol=0)


def test_sample_f_matches_the_scalar_path(variant, rng):
    wo = random_directions(rng, N_PAIRS)
    u = rng.random((N_PAIRS, 2)).astype(np.float32)
    wi, f, pdf = variant.sample_f(wo, u)
    assert wi.shape == (N_PAIRS, 3) and f.shape == (N_PAIRS, 3) and pdf.shape == (N_PAIRS,)
    ref = bxdf._bxdf._reference_sample_f(variant, wo, u)
    for got, want in zip((wi, f, pdf), ref):
        np.testing.assert_allclose(got, want, rtol=1e-6, atol=0)


def test_large_batches_match_the_scalar_path(rng):
    # 50,000 rows: several TBB tasks and a ragged last chunk.
    for _, name, params in [("", n, {}) for n in bxdf.models()]:
        model = bxdf.make(name, **params)
        n = 50_001
        wo = random_directions(rng, n)
        wi = random_directions(rng, n)
        np.testing.assert_allclose(model.f(wo, wi), bxdf._bxdf._reference_f(model, wo, wi), rtol=1e-6)
        u = rng.random((n, 2))
        got = model.sample_f(wo, u)
        want = bxdf._bxdf._reference_sample_f(model, wo, u)
        for g, w in zip(got, want):
            np.testing.assert_allclose(g, w, rtol=1e-6)


@pytest.mark.parametrize("exact", [False, True], ids=["sample_f", "exact"])
def test_sampled_directions_agree_with_f_and_pdf(variant, rng, exact):
    wo = random_directions(rng, 2000, lower_fraction=0.0)
    u = rng.random((2000, 2))
    wi, f, pdf = variant.sample_f(wo, u, exact=exact)
    ok = pdf > 0
    assert ok.mean() > 0.5, "most samples from above the surface should succeed"
    assert np.all(np.isfinite(wi)) and np.all(f >= 0) and np.all(pdf >= 0)
    np.testing.assert_allclose(np.linalg.norm(wi[ok], axis=1), 1.0, atol=1e-5)
    assert np.all(f[~ok] == 0) and np.all(wi[~ok] == 0)
    if is_delta(variant):
        # Delta lobes: f and pdf are 0 for any given pair; a sample's pdf is 1 (DESIGN.md).
        assert np.all(variant.f(wo[ok], wi[ok]) == 0) and np.all(variant.pdf(wo[ok], wi[ok]) == 0)
        assert np.all(pdf[ok] == 1.0)
    else:
        # The sample's pdf is the model's pdf for that pair (grazing excluded: there a float32
        # round trip of wi may cross the horizon), and so is its f, except for Cycles'
        # multiscatter sampling walk, whose f carries the walk's weight (sample_f_is_exact).
        keep = ok & (np.abs(wi[:, 2]) > 1e-3)
        np.testing.assert_allclose(variant.pdf(wo[keep], wi[keep]), pdf[keep], rtol=2e-3, atol=1e-6)
        if exact or variant.sample_f_is_exact:
            np.testing.assert_allclose(variant.f(wo[keep], wi[keep]), f[keep], rtol=2e-3, atol=1e-6)
        else:
            assert not np.allclose(variant.f(wo[keep], wi[keep]), f[keep], rtol=2e-3, atol=1e-6)
            weight = f[keep] * (np.abs(wi[keep, 2]) / pdf[keep])[:, None]
            assert np.all(np.isfinite(weight)) and weight.mean() <= 1.01
    if variant.sample_f_is_exact:
        # exact=True is sample_f itself for every model that does not walk.
        other = variant.sample_f(wo, u, exact=not exact)
        for a, b in zip((wi, f, pdf), other):
            np.testing.assert_array_equal(a, b)


def test_only_cycles_walks_and_rough_refractions_sample_as_cycles_does():
    for name in bxdf.models():
        assert bxdf.make(name).sample_f_is_exact, name
    for name in ("cycles_glossy", "cycles_glass", "cycles_principled"):
        assert not bxdf.make(name, distribution="multi_ggx", roughness=0.5).sample_f_is_exact, name
    # cycles_refraction's multi_ggx has no Cycles closure to follow: exact sampling.
    assert bxdf.make("cycles_refraction", distribution="multi_ggx", roughness=0.5).sample_f_is_exact
    # A rough refraction is drawn from its facets alone, as Cycles draws it; sharp ones are exact.
    for name in ("cycles_glass", "cycles_refraction"):
        assert not bxdf.make(name, distribution="ggx", roughness=0.3).sample_f_is_exact, name
        assert bxdf.make(name, distribution="sharp").sample_f_is_exact, name
    assert not bxdf.make("cycles_principled", transmission=1.0, roughness=0.3).sample_f_is_exact
    assert bxdf.make("cycles_principled", transmission=1.0, roughness=0.0).sample_f_is_exact


def test_awkward_directions_give_finite_nonnegative_results(variant):
    bad = awkward_directions()
    n = len(bad)
    wo = np.repeat(bad, n, axis=0)
    wi = np.tile(bad, (n, 1))
    for out in (variant.f(wo, wi), variant.pdf(wo, wi)):
        assert np.all(np.isfinite(out)) and np.all(out >= 0)
    wi_s, f_s, pdf_s = variant.sample_f(bad, np.full((n, 2), 0.5))
    for out in (wi_s, f_s, pdf_s):
        assert np.all(np.isfinite(out))
    assert np.all(f_s >= 0) and np.all(pdf_s >= 0)
    # Zero and non-finite directions are "no direction": 0, not an error.
    none = ~np.isfinite(bad).all(axis=1) | (np.abs(bad).sum(axis=1) == 0)
    assert np.all(variant.f(bad[none], [0, 0, 1]) == 0)
    assert np.all(pdf_s[none] == 0)
    rho = variant.rho(bad, 16)
    assert np.all(np.isfinite(rho)) and np.all(rho >= 0)


def test_lambertian_closed_forms(rng):
    r = np.array([0.8, 0.5, 0.2])
    m = bxdf.make("lambertian", reflectance=r)
    assert m.flags == {"reflection", "diffuse"}
    wo = random_directions(rng, 1000)
    wi = random_directions(rng, 1000)
    same = (wo[:, 2] * wi[:, 2]) > 0
    expected = np.where(same[:, None], r / np.pi, 0.0)
    np.testing.assert_allclose(m.f(wo, wi), expected, rtol=1e-6)
    np.testing.assert_allclose(m.pdf(wo, wi), np.where(same, np.abs(wi[:, 2]) / np.pi, 0), rtol=1e-5, atol=1e-7)
    # Unnormalised directions are normalised first.
    np.testing.assert_allclose(m.f(wo * 7.5, wi * 0.01), expected, rtol=1e-6)
    wi_s, f_s, pdf_s = m.sample_f(wo, rng.random((1000, 2)))
    assert np.all(wi_s[:, 2] * wo[:, 2] > 0)
    np.testing.assert_allclose(pdf_s, np.abs(wi_s[:, 2]) / np.pi, rtol=1e-5, atol=1e-7)
    np.testing.assert_allclose(m.rho(wo, 64), np.tile(r, (1000, 1)), rtol=1e-6)
    np.testing.assert_allclose(m.rho_hh(64), r, rtol=1e-6)


def test_rho_matches_a_quadrature_of_f(variant):
    # ∫ f |cos θi| dωi by the midpoint rule on a fine (θ, φ) grid over both hemispheres,
    # against rho's own estimate (which samples with sample_f): checks sample_f/pdf/rho
    # against f. Delta lobes have f = 0 and are not integrable this way.
    if is_delta(variant):
        assert np.all(variant.rho([0, 0, 1], 256) >= 0)
        return
    n_t, n_p = 256, 256
    t = (np.arange(n_t) + 0.5) / n_t * np.pi  # the whole sphere
    p = (np.arange(n_p) + 0.5) / n_p * 2 * np.pi
    T, P = np.meshgrid(t, p, indexing="ij")
    wi = np.stack([np.sin(T) * np.cos(P), np.sin(T) * np.sin(P), np.cos(T)], -1).reshape(-1, 3)
    d_omega = (np.sin(T) * (np.pi / n_t) * (2 * np.pi / n_p)).reshape(-1)
    for theta_o in (0.0, 40.0, 75.0):
        th = np.radians(theta_o)
        wo = np.array([np.sin(th), 0.0, np.cos(th)])
        quad = (variant.f(wo, wi) * (np.abs(wi[:, 2]) * d_omega)[:, None]).sum(0)
        rho = variant.rho(wo, 65536)[0]
        np.testing.assert_allclose(rho, quad, rtol=0.03, atol=2e-3, err_msg=f"theta_o={theta_o}")


def test_rho_hh_is_the_cosine_weighted_mean_of_rho(variant):
    # ρhh = (1/π) ∫ ρhd(wo) cos θo dωo = (1/π) ∫∫ ρhd(μ, φ) μ dμ dφ (midpoint rule, μ = cos θo).
    n_mu, n_phi = 16, 8
    mu, phi = np.meshgrid((np.arange(n_mu) + 0.5) / n_mu, (np.arange(n_phi) + 0.5) / n_phi * 2 * np.pi)
    mu, phi = mu.ravel(), phi.ravel()
    s = np.sqrt(1 - mu**2)
    wo = np.stack([s * np.cos(phi), s * np.sin(phi), mu], -1)
    rho = variant.rho(wo, 4096)
    expected = (rho * mu[:, None]).sum(0) * (1 / n_mu) * (2 * np.pi / n_phi) / np.pi
    np.testing.assert_allclose(variant.rho_hh(65536), expected, rtol=0.05, atol=5e-3)


def test_rho_is_deterministic_and_seeded(variant):
    wo = np.array([[0.3, 0.1, 0.9], [0.0, 0.0, 1.0]])
    a = variant.rho(wo, 257)
    assert np.array_equal(a, variant.rho(wo, 257))
    assert np.array_equal(a, variant.rho(wo, 257, seed=0))
    assert a.shape == (2, 3) and a.dtype == np.float32
    assert variant.rho_hh(100).shape == (3,)


@pytest.mark.parametrize("bad", [0, -5, 1.5, "10", True, None, 2**40])
def test_n_samples_must_be_a_positive_int(bad):
    m = bxdf.make("lambertian")
    with pytest.raises(ValueError, match="n_samples"):
        m.rho([0, 0, 1], bad)
    with pytest.raises(ValueError, match="n_samples"):
        m.rho_hh(bad)


def test_models_say_which_rgb_parameters_are_colours():
    specs = {s["name"]: s for s in bxdf.models()["microfacet"]}
    assert specs["reflectance"]["subtype"] == "color"
    assert specs["eta"]["subtype"] == "per_channel" and specs["k"]["subtype"] == "per_channel"
    assert "subtype" not in specs["alpha_x"]  # only RGB parameters have one
    lobe = {f["name"]: f for f in next(s for s in bxdf.models()["lafortune"] if s["name"] == "lobes")["fields"]}
    assert {lobe[n]["subtype"] for n in ("cx", "cy", "cz", "exponent")} == {"per_channel"}
