"""bxdf.load_measured(), bxdf.fit(), bxdf.fit_error() and bxdf.fit_models() on the Cornell
measurements in data/."""

import pathlib
import pickle

import numpy as np
import pytest

import bxdf
from conftest import random_directions

CORNELL = pathlib.Path(__file__).resolve().parents[2] / "data" / "measured" / "acryl_blue.brdf"


@pytest.fixture(scope="module")
def measured():
    return bxdf.load_measured(CORNELL)


def test_load_measured_is_the_measured_registry_model(measured):
    assert measured == bxdf.make("measured", path=str(CORNELL))
    assert measured == bxdf.load_measured(str(CORNELL), interpolate=True)
    assert measured.name == "measured" and measured.params["path"] == str(CORNELL)
    f = measured.f([0, 0, 1], random_directions(np.random.default_rng(3), 100, lower_fraction=0))
    assert np.all(np.isfinite(f)) and np.all(f >= 0) and f.max() > 0


def test_load_measured_errors(tmp_path):
    with pytest.raises(ValueError, match="no_such_file.brdf"):
        bxdf.load_measured(tmp_path / "no_such_file.brdf")
    bad = tmp_path / "bad.brdf"
    bad.write_text("not a BRDF\n")
    with pytest.raises(ValueError, match="bad.brdf"):
        bxdf.load_measured(bad)
    with pytest.raises(ValueError, match="'path'"):
        bxdf.load_measured(3)
    with pytest.raises(ValueError, match="colour"):
        bxdf.load_measured(CORNELL, colour=1)


def test_fit_lafortune(measured):
    fitted, report = bxdf.fit(measured, model="lafortune", lobes=1, max_starts=2)
    assert fitted.name == "lafortune" and len(fitted.params["lobes"]) == 1
    for key in ("model", "error", "baseline_error", "sum_squares", "samples", "iterations",
                "total_iterations", "starts", "start_errors", "seconds"):
        assert key in report, key
    assert report["model"] == "lafortune1" and report["starts"] == 2
    assert len(report["start_errors"]) == 2 and min(report["start_errors"]) == pytest.approx(report["error"])
    assert 0 < report["error"] < 0.5 * report["baseline_error"]
    assert bxdf.make(fitted.name, **fitted.params) == fitted
    assert bxdf.fit_error(measured, fitted) == pytest.approx(report["error"], rel=1e-3)
    # A path works as well as a loaded model, and the fit is deterministic.
    again, report2 = bxdf.fit(str(CORNELL), model="lafortune", lobes=1, max_starts=2)
    assert again == fitted and report2["error"] == report["error"]


def test_fit_ggx_is_a_microfacet_model_with_a_diffuse_term(measured):
    fitted, report = bxdf.fit(measured, model="ggx", max_starts=1)
    assert fitted.name == "microfacet" and report["model"] == "ggx"
    assert fitted.params["distribution"] == "ggx" and fitted.params["shadowing"] == "smith"
    assert report["error"] < report["baseline_error"]
    assert bxdf.fit_error(measured, fitted) == pytest.approx(report["error"], rel=1e-3)
    # A fit beats a hand-made guess on the same footing.
    assert report["error"] < bxdf.fit_error(measured, bxdf.make("lambertian", reflectance=0.2))
    assert pickle.loads(pickle.dumps(fitted)) == fitted


@pytest.mark.parametrize(
    "kwargs, words",
    [
        ({"model": "phong"}, ["phong", "lafortune"]),
        ({"lobes": 4}, ["lobes", "4", "[1, 3]"]),
        ({"lobes": 1.5}, ["lobes", "integer"]),
        ({"max_iterations": 0}, ["max_iterations", "0"]),
        ({"merl_stride": 0}, ["merl_stride", "0"]),
    ],
)
def test_fit_refuses_bad_options(measured, kwargs, words):
    with pytest.raises(ValueError) as err:
        bxdf.fit(measured, **kwargs)
    for w in words:
        assert w in str(err.value), str(err.value)


def test_fit_models_are_the_names_fit_accepts(measured):
    names = bxdf.fit_models()
    assert set(names) == {"lambertian", "lafortune", "blinn", "ashikhmin_shirley",
                          "cook_torrance", "ggx"}
    for name in names:
        _, report = bxdf.fit(measured, model=name, lobes=1, max_starts=1, max_iterations=2)
        assert report["model"] == ("lafortune1" if name == "lafortune" else name)
    with pytest.raises(ValueError) as err:
        bxdf.fit(measured, model="phong")
    assert "'phong'" in str(err.value) and all(n in str(err.value) for n in names)


def test_fit_refuses_what_is_not_measured():
    with pytest.raises(ValueError, match="'measured'.*not a measured model"):
        bxdf.fit(bxdf.make("lambertian"))
    with pytest.raises(ValueError, match="'measured'"):
        bxdf.fit(42)
    with pytest.raises(ValueError, match="missing.brdf"):
        bxdf.fit("missing.brdf")
