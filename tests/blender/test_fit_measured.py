"""Fit to Measured File (bxdf_lab.fit_measured): the material gets what bxdf.fit returns for the
same file, the fit's error is stored and shown, and a bad file changes nothing."""

import pathlib

import bpy
import pytest

from bxdf_lab import api, fit_report, ui
from bxdf_lab.operators import fit_measured
from test_presets_and_files import _same
from test_ui import _draw

KRYLON = str(pathlib.Path(__file__).resolve().parents[2] / "data" / "measured" / "krylon_blue.brdf")


def _fit(material, **props):
    with bpy.context.temp_override(material=material):
        return bpy.ops.bxdf_lab.fit_measured(**props)


def test_the_model_choices_are_the_bindings_fit_models(bxdf):
    assert [item[0] for item in fit_measured._model_items(None, None)] == bxdf.fit_models()


@pytest.mark.parametrize("model, lobes, registry_name, fit_name", [
    ("ggx", 2, "microfacet", "ggx"),
    ("lafortune", 2, "lafortune", "lafortune2"),
])
def test_the_material_gets_what_bxdf_fit_returns(bxdf, material, capfd, model, lobes,
                                                 registry_name, fit_name):
    api.assign(material, "lambertian", reflectance=0.3)
    assert _fit(material, filepath=KRYLON, model=model, lobes=lobes) == {"FINISHED"}
    info = capfd.readouterr().out  # headless Blender prints the operator's reports
    fitted, report = bxdf.fit(KRYLON, model=model, lobes=lobes)
    assert fitted.name == registry_name and report["model"] == fit_name
    name, params = api.describe(material)
    assert name == fitted.name and _same(params, dict(fitted.params))
    # The material's parameters are Blender's 32-bit floats: with Lafortune exponents in the
    # hundreds that moves the error by a few 1e-7.
    assert bxdf.fit_error(KRYLON, api.make(material)) == pytest.approx(report["error"], abs=1e-6)
    stored = material.bxdf_lab_fit
    assert stored.file == KRYLON and stored.model == fit_name
    assert stored.error == pytest.approx(report["error"], rel=1e-6)
    assert stored.baseline_error == pytest.approx(report["baseline_error"], rel=1e-6)
    assert 0 < stored.error < stored.baseline_error
    assert f"Info: Fit {fit_name} to krylon_blue.brdf: error {stored.error:.6g}" in info
    assert fit_report.is_current(material)


def test_the_panel_shows_the_error_and_flags_later_edits(material):
    context = type("Context", (), {"material": material, "scene": bpy.context.scene})()
    labels = [e[1] for e in _draw(ui.BXDFLAB_PT_material, context) if e[0] == "label"]
    assert ("operator", "bxdf_lab.fit_measured") in _draw(ui.BXDFLAB_PT_material, context)
    assert not any("Fit " in text for text in labels)  # never fitted: nothing shown
    assert _fit(material, filepath=KRYLON, model="lambertian") == {"FINISHED"}
    error = material.bxdf_lab_fit.error
    labels = [e[1] for e in _draw(ui.BXDFLAB_PT_material, context) if e[0] == "label"]
    assert f"Fit lambertian to krylon_blue.brdf: error {error:.6g}" in "\n".join(labels)
    assert not any("changed since" in text for text in labels)
    material.bxdf_lab.lambertian.reflectance[0] *= 0.5
    labels = [e[1] for e in _draw(ui.BXDFLAB_PT_material, context) if e[0] == "label"]
    assert any("changed since" in text for text in labels)


@pytest.mark.parametrize("name, content, words", [
    ("missing.brdf", None, ["missing.brdf"]),
    ("notes.txt", "just some text\n", ["notes.txt"]),
    ("notes.brdf", "just some text\n", ["notes.brdf"]),
])
def test_a_bad_file_is_reported_and_changes_nothing(material, tmp_path, name, content, words):
    path = tmp_path / name
    if content is not None:
        path.write_text(content)
    api.assign(material, "lambertian", reflectance=0.3)
    before = api.describe(material)
    with pytest.raises(RuntimeError) as err:
        _fit(material, filepath=str(path), model="ggx")
    message = str(err.value)
    assert "Fit to measured file failed" in message
    assert all(w in message for w in words), message
    assert api.describe(material) == before
    assert not fit_report.has_fit(material)


def test_a_failed_fit_keeps_the_previous_fit_report(material, tmp_path):
    assert _fit(material, filepath=KRYLON, model="lambertian") == {"FINISHED"}
    before = (api.describe(material), material.bxdf_lab_fit.error, material.bxdf_lab_fit.file)
    with pytest.raises(RuntimeError):
        _fit(material, filepath=str(tmp_path / "missing.binary"), model="lambertian")
    after = (api.describe(material), material.bxdf_lab_fit.error, material.bxdf_lab_fit.file)
    assert after == before


def test_needs_an_active_material():
    assert not bpy.ops.bxdf_lab.fit_measured.poll()
