"""End to end: the harness renders small scenes in every engine through Blender and judges them."""
import importlib.util
import os

from harness_helpers import REPO, pairing, run_compare, scene


def _bxdf_lab_ready():
    """The BXDF_LAB engine can render once the add-on package and the compiled module with its
    renderer (bxdf.render) exist."""
    addon = os.path.join(REPO, "blender_addon", "bxdf_lab", "__init__.py")
    if not os.path.isfile(addon) or importlib.util.find_spec("bxdf") is None:
        return False
    import bxdf

    return hasattr(bxdf, "render")


def test_every_engine_runs_or_is_recorded_as_failed_with_its_log(main_run):
    run_dir, summary = main_run
    for entry in summary["scenes"]:
        engines = entry["engines"]
        assert set(engines) == {"BXDF_LAB", "CYCLES", "POVRAY_RENDER", "ANALYTIC"}
        for name in ("CYCLES", "POVRAY_RENDER", "ANALYTIC"):
            assert engines[name]["status"] == "ok", (entry["name"], name, engines[name])
            assert engines[name]["seconds"] > 0
            assert os.path.isfile(os.path.join(run_dir, engines[name]["image"]))
        bxdf_lab = engines["BXDF_LAB"]
        if _bxdf_lab_ready():
            assert bxdf_lab["status"] == "ok", bxdf_lab
        else:
            assert bxdf_lab["status"] == "failed"
            assert bxdf_lab["image"] is None
            with open(os.path.join(run_dir, bxdf_lab["log"]), encoding="utf-8") as fh:
                assert "bxdf_lab" in fh.read()


def test_exact_pairings_pass_their_z_test(main_run):
    _, summary = main_run
    checked = 0
    for name in ("lit_lambertian", "lit_cycles_glossy_ggx"):
        for p in scene(summary, name)["pairings"]:
            if p["label"] == "exact":
                assert p["pass"] is True and not p["flagged"], (name, p)
                assert p["z_fail_fraction"] <= summary["thresholds"]["pass_fraction"]
                checked += 1
    # Lambert: CYCLES, POV-Ray and ANALYTIC pairwise; GGX: CYCLES vs ANALYTIC (at least).
    assert checked >= 4
    lam = scene(summary, "lit_lambertian")
    assert pairing(lam, "POVRAY_RENDER", "ANALYTIC")["label"] == "exact"
    assert abs(pairing(lam, "CYCLES", "ANALYTIC")["ratio_mean"] - 1.0) < 2e-3


def test_approximate_pairing_is_reported_with_its_mapping(main_run):
    _, summary = main_run
    p = pairing(scene(summary, "lit_oren_nayar"), "CYCLES", "ANALYTIC")
    assert p["label"] == "approximate"
    assert p["flagged"] is False
    assert any("oren_nayar" in reason for reason in p["approximations"])
    assert "Diffuse BSDF" in p["mapping"]["CYCLES"]["oren_nayar_30"]
    glossy_pov = pairing(scene(summary, "lit_cycles_glossy_ggx"), "POVRAY_RENDER", "ANALYTIC")
    assert glossy_pov["label"] == "approximate"


def test_deliberately_wrong_material_is_caught_and_flagged(main_run):
    _, summary = main_run
    sun = scene(summary, "sun_sphere")
    wrong = pairing(sun, "POVRAY_RENDER", "ANALYTIC")
    assert wrong["label"] == "exact"
    assert wrong["pass"] is False and wrong["flagged"] is True
    # Background and unlit pixels agree whatever the albedo: most lit pixels must fail.
    assert wrong["z_fail_fraction"] > 5 * summary["thresholds"]["pass_fraction"]
    assert abs(wrong["ratio_mean"] - 0.68 / 0.7) < 0.005
    # The engines that were not tampered with still agree.
    assert pairing(sun, "CYCLES", "ANALYTIC")["pass"] is True


def test_killed_engine_is_recorded_as_failed_and_the_others_survive(tmp_path):
    wrapper = tmp_path / "blender-killing-cycles"
    wrapper.write_text(
        "#!/bin/bash\n"
        "# Starts Blender, and kills it at once when it is asked to render with Cycles.\n"
        "blender \"$@\" &\n"
        "pid=$!\n"
        "case \"$*\" in *CYCLES.job.json*) sleep 0.3; kill -9 $pid;; esac\n"
        "wait $pid\n")
    wrapper.chmod(0o755)
    run_dir, summary = run_compare(tmp_path / "out", "--scenes", "lit_lambertian",
                                   "--engines", "CYCLES", "POVRAY_RENDER", "--res", "16", "16",
                                   "--spp", "4", "--blender", str(wrapper))
    engines = summary["scenes"][0]["engines"]
    assert engines["CYCLES"]["status"] == "failed"
    assert "exited with code" in engines["CYCLES"]["message"]
    assert os.path.isfile(os.path.join(run_dir, engines["CYCLES"]["log"]))
    assert engines["POVRAY_RENDER"]["status"] == "ok"
    assert engines["ANALYTIC"]["status"] == "ok"
    pairs = summary["scenes"][0]["pairings"]
    assert [(p["a"], p["b"]) for p in pairs] == [("POVRAY_RENDER", "ANALYTIC")]
    assert pairs[0]["pass"] is True


def test_runs_never_overwrite_each_other(tmp_path):
    from compare import runner

    first = runner.new_run_dir(str(tmp_path))
    second = runner.new_run_dir(str(tmp_path))
    assert first != second and os.path.isdir(first) and os.path.isdir(second)
