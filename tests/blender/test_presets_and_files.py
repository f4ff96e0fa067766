"""Presets (bxdf.presets) and JSON material files (bxdf.save_material / load_material) through
the add-on's operators."""

import json

import bpy
import pytest

from bxdf_lab import api
from bxdf_lab.operators.presets import preset_names


def _same(a, b):
    if isinstance(a, dict):
        return a.keys() == b.keys() and all(_same(a[k], b[k]) for k in a)
    if isinstance(a, (list, tuple)):
        return len(a) == len(b) and all(_same(x, y) for x, y in zip(a, b))
    if isinstance(a, float):
        return a == pytest.approx(b, rel=1e-6, abs=1e-7)
    return a == b


def test_every_available_preset_applies_to_a_material(bxdf, material):
    names = preset_names()
    assert set(names) == {n for n, p in bxdf.presets().items() if p["model"] in bxdf.models()}
    for name in names:
        with bpy.context.temp_override(material=material):
            assert bpy.ops.bxdf_lab.apply_preset(preset=name) == {"FINISHED"}
        expected = bxdf.make_preset(name)
        model, params = api.describe(material)
        assert model == expected.name and _same(params, expected.params), name


def test_an_unknown_preset_is_reported(material):
    with bpy.context.temp_override(material=material):
        with pytest.raises(RuntimeError, match="no_such_preset"):
            bpy.ops.bxdf_lab.apply_preset(preset="no_such_preset")


def test_json_export_then_import_round_trips(bxdf, material, tmp_path):
    path = str(tmp_path / "material.json")
    api.assign(material, "lambertian", reflectance=(0.25, 0.5, 0.75))
    with bpy.context.temp_override(material=material):
        assert bpy.ops.bxdf_lab.export_material(filepath=path) == {"FINISHED"}
    with open(path) as f:
        data = json.load(f)
    assert data["format"] == "bxdf-material" and data["model"] == "lambertian"
    assert data["name"] == material.name
    other = bpy.data.materials.new("imported")
    with bpy.context.temp_override(material=other):
        assert bpy.ops.bxdf_lab.import_material(filepath=path) == {"FINISHED"}
    assert api.describe(other)[0] == "lambertian"
    assert _same(api.describe(other)[1], api.describe(material)[1])


def test_importing_a_bad_file_is_reported_and_changes_nothing(material, tmp_path):
    path = tmp_path / "bad.json"
    path.write_text(json.dumps({"format": "bxdf-material", "version": 1, "model": "lambertian",
                                "params": {"reflectance": [2, 0, 0]}}))
    api.assign(material, "lambertian", reflectance=0.3)
    before = api.describe(material)
    with bpy.context.temp_override(material=material):
        with pytest.raises(RuntimeError, match="reflectance"):
            bpy.ops.bxdf_lab.import_material(filepath=str(path))
    assert api.describe(material) == before
