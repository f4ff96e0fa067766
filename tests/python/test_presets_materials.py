"""bxdf.presets() / make_preset() and JSON material files (save_material / load_material)."""

import json
import pathlib

import numpy as np
import pytest

import bxdf
from conftest import VARIANTS

SEED_METALS = {"gold", "silver", "copper", "steel"}
LAFORTUNE_FITS = {"clay", "felt", "primer", "skin", "bluepaint", "brushedmetal"}


def test_presets_list_the_seed_metals_and_lafortune_fits():
    presets = bxdf.presets()
    assert SEED_METALS | LAFORTUNE_FITS <= set(presets)
    for name, p in presets.items():
        assert set(p) == {"model", "doc", "params"}, name
        assert p["doc"] and isinstance(p["params"], dict)


def test_make_preset_is_make_with_the_preset_params():
    registered = set(bxdf.models())
    for name, p in bxdf.presets().items():
        if p["model"] in registered:
            m = bxdf.make_preset(name)
            assert m == bxdf.make(p["model"], **p["params"])
            assert m.name == p["model"]
        else:
            # Until the preset's model is on this branch, the preset cannot be made.
            with pytest.raises(ValueError, match=f"unknown model '{p['model']}'"):
                bxdf.make_preset(name)


def test_make_preset_refuses_unknown_names():
    with pytest.raises(ValueError, match="unknown preset 'unobtainium'.*gold"):
        bxdf.make_preset("unobtainium")
    with pytest.raises(ValueError, match="name"):
        bxdf.make_preset(None)


@pytest.mark.parametrize("entry", VARIANTS, ids=[v[0] for v in VARIANTS])
def test_material_file_round_trip(tmp_path, entry):
    _, name, params = entry
    model = bxdf.make(name, **params)
    path = tmp_path / "material.json"
    bxdf.save_material(model, path, name="my material")
    data = json.loads(path.read_text())
    assert data["format"] == "bxdf-material" and data["version"] == 1
    assert data["model"] == name and data["name"] == "my material"
    assert set(data["params"]) == set(model.params)
    loaded = bxdf.load_material(str(path))
    assert loaded == model
    wo = np.array([[0.3, 0.2, 0.9]])
    np.testing.assert_array_equal(loaded.f(wo, [[-0.3, 0.1, 0.8]]), model.f(wo, [[-0.3, 0.1, 0.8]]))


def test_material_files_written_by_hand(tmp_path):
    path = tmp_path / "clay.json"
    path.write_text('{"format": "bxdf-material", "version": 1, "model": "lambertian", "params": {"reflectance": 0.5}}')
    assert bxdf.load_material(path) == bxdf.make("lambertian", reflectance=0.5)
    path.write_text('{"model": "lambertian"}')  # format and version are optional
    assert bxdf.load_material(path) == bxdf.make("lambertian")


@pytest.mark.parametrize(
    "text, words",
    [
        ("{not json", ["not valid JSON"]),
        ('{"model": "lambertian", "version": 99}', ["version", "99"]),
        ('{"model": "lambertian", "format": "png"}', ["format"]),
        ('{"model": "nope"}', ["nope"]),
        ('{"params": {}}', ["model", "missing"]),
        ('{"model": "lambertian", "params": {"reflectance": 7}}', ["reflectance", "7", "[0, 1]"]),
        ('{"model": "lambertian", "params": {"sigma": 1}}', ["sigma"]),
        ('{"model": "lambertian", "colour": 1}', ["colour"]),
        ('{"preset": "unobtainium"}', ["unobtainium"]),
        ("[1, 2, 3]", ["object"]),
    ],
)
def test_bad_material_files_are_value_errors_naming_the_file(tmp_path, text, words):
    path = tmp_path / "bad.json"
    path.write_text(text)
    with pytest.raises(ValueError) as err:
        bxdf.load_material(path)
    message = str(err.value)
    assert "bad.json" in message, message
    for w in words:
        assert w in message, message


def test_material_path_errors(tmp_path):
    with pytest.raises(ValueError, match="missing.json"):
        bxdf.load_material(tmp_path / "missing.json")
    with pytest.raises(ValueError, match="'path'"):
        bxdf.load_material(42)
    with pytest.raises(ValueError, match="'path'"):
        bxdf.save_material(bxdf.make("lambertian"), "")
    with pytest.raises(ValueError):
        bxdf.save_material(bxdf.make("lambertian"), tmp_path / "no_such_dir" / "m.json")
    # Saving again replaces the file.
    path = pathlib.Path(tmp_path / "m.json")
    bxdf.save_material(bxdf.make("lambertian", reflectance=0.25), path)
    bxdf.save_material(bxdf.make("lambertian", reflectance=0.75), path)
    assert bxdf.load_material(path).params["reflectance"] == (0.75,) * 3
    assert [p.name for p in tmp_path.iterdir()] == ["m.json"]  # no temporary files left
