"""bxdf_lab.api.assign / describe: registry-validated scripting of materials."""

import math

import pytest

from bxdf_lab import api


def _first_float_param(bxdf):
    for model, specs in bxdf.models().items():
        for spec in specs:
            if spec["kind"] in ("float", "rgb") and math.isfinite(spec["max"]):
                return model, spec
    pytest.fail("the registry has no bounded float or RGB parameter")


def test_assign_then_describe_round_trips(bxdf, material):
    for model_name in bxdf.models():
        made = api.assign(material, model_name)
        name, params = api.describe(material)
        assert name == model_name == made.name
        rebuilt = bxdf.make(name, **params)
        assert set(rebuilt.params) == set(made.params)


def test_assign_sets_the_values(bxdf, material):
    api.assign(material, "lambertian", reflectance=(0.25, 0.5, 0.75))
    name, params = api.describe(material)
    assert name == "lambertian"
    assert params["reflectance"] == pytest.approx((0.25, 0.5, 0.75))
    assert tuple(material.bxdf_lab.lambertian.reflectance) == pytest.approx((0.25, 0.5, 0.75))


def test_bad_values_raise_value_error_and_leave_the_material_unchanged(bxdf, material):
    model, spec = _first_float_param(bxdf)
    api.assign(material, "lambertian", reflectance=0.5)
    before = api.describe(material)
    with pytest.raises(ValueError, match=spec["name"]):
        api.assign(material, model, **{spec["name"]: spec["max"] + 1.0})
    with pytest.raises(ValueError, match="no_such_parameter"):
        api.assign(material, model, no_such_parameter=1.0)
    with pytest.raises(ValueError, match="no_such_model"):
        api.assign(material, "no_such_model")
    assert api.describe(material) == before


def test_a_broken_value_typed_through_python_is_refused_by_make(bxdf, material):
    material.bxdf_lab.lambertian.reflectance = (float("nan"), 0.5, 0.5)  # Blender keeps NaN
    with pytest.raises(ValueError, match="reflectance"):
        api.make(material)
