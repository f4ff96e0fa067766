"""What needs a window, run in a windowed Blender under Xvfb (windowed_session.py): the Material
tab's preview of every model through Blender's preview scene, and the viewport's Rendered mode
drawn through the gpu module, restarted by an edit."""

import json
import os
import shutil
import subprocess
import sys
import warnings

import bpy
import pytest

HERE = os.path.dirname(os.path.abspath(__file__))


def _read(path):
    return open(path).read() if os.path.exists(path) else ""


def _text(output):
    """A process's output as text (TimeoutExpired holds bytes even for text=True, or None)."""
    return output.decode(errors="replace") if isinstance(output, bytes) else (output or "")


def _tail(output, size=3000):
    return _text(output)[-size:]


def _steps(output):
    """The session's step lines (windowed_session.mark) out of Blender's and POV-Ray's output."""
    return "\n".join(line for line in _text(output).splitlines() if line.startswith("[windowed_session"))


@pytest.fixture(scope="module")
def windowed(tmp_path_factory):
    assert shutil.which("xvfb-run"), "xvfb-run is missing: make deps installs xvfb"
    folder = tmp_path_factory.mktemp("windowed")
    bpy.ops.wm.read_homefile(use_factory_startup=True)  # the default cube, light and camera
    blend = str(folder / "start.blend")
    bpy.ops.wm.save_as_mainfile(filepath=blend, copy=True)
    out = str(folder / "result.json")
    env = dict(os.environ, BLENDER_USER_CONFIG=str(folder / "config"),
               BXDF_PYTHONPATH=os.pathsep.join(p for p in sys.path if os.path.isdir(os.path.join(p, "bxdf"))))
    command = ["xvfb-run", "-a", "-s", "-screen 0 1280x800x24", "blender", "--factory-startup", blend,
               "--python", os.path.join(HERE, "windowed_session.py"), "--", "--out", out]
    try:
        run = subprocess.run(command, env=env, capture_output=True, text=True, timeout=600)
    except subprocess.TimeoutExpired as expired:  # the session's own watchdog did not fire either
        pytest.fail("the windowed session did not end in 600 s:\n" + _steps(expired.stdout) + "\n"
                    + _tail(expired.stdout) + _tail(expired.stderr))
    stacks = _read(out + ".stacks")
    assert not stacks, ("the windowed session hung; its last steps and every Python thread's stack:\n"
                        + _steps(run.stdout) + "\n" + stacks)
    assert os.path.exists(out), _tail(run.stdout) + _tail(run.stderr)
    with open(out) as f:
        result = json.load(f)
    assert result["errors"] == [], result["errors"]
    # Back in Solid mode the viewport's render has stopped.
    assert result["at_quit"]["viewport_renders"] == 0, result["at_quit"]
    quit_stacks = _read(out + ".quit_stacks")
    if quit_stacks:
        # Blender's own quit did not end (seen once in CI, on 6 December 2026, after every check
        # had passed; cause not found): the checks stand, and what ran and the stacks are shown.
        warnings.warn(f"Blender did not quit within the session's limit after the checks, with "
                      f"{result['at_quit']} running; every Python thread's stack:\n" + quit_stacks)
    return result


def test_every_model_renders_its_material_preview(windowed, bxdf):
    assert set(windowed["previews"]) == set(bxdf.models())
    for model, preview in windowed["previews"].items():
        assert preview["errors"] == [], model
        assert "32 samples per pixel" in preview["summary"], (model, preview["summary"])
        assert preview["size"][0] > 0 and preview["finite"], model
        assert preview["std"] > 0.01, model  # an object in front of a backdrop, not a flat image
    blue = windowed["previews"]["measured"]["centre_mean"]  # acryl_blue, the measured default
    assert blue[2] > 2 * blue[0], blue


def test_the_rendered_viewport_draws_and_restarts_on_an_edit(windowed):
    first, second = windowed["viewport"]["first"], windowed["viewport"]["second"]
    assert first["error"] == "" and first["samples"] == 32 and first["version"] >= 2
    assert second["error"] == "" and second["restarts"] >= 1 and second["changed"]
    assert second["first_cancelled_or_done"]


def test_compare_renders_runs_as_render_jobs_and_shows_its_figure(windowed):
    compare = windowed["compare"]
    assert compare["started"] == ["RUNNING_MODAL"]
    assert [(engine, ok) for engine, ok, _ in compare["results"]] == [
        ("BXDF_LAB", True), ("CYCLES", True), ("POVRAY_RENDER", True)], compare["results"]
    assert compare["shown"] == "BxDF Lab comparison" and compare["report"] and compare["restored"]
    assert compare["windows"] == 1  # the Render window the jobs opened is closed, not over the figure
