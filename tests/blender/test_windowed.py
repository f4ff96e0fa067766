"""What needs a window, run in a windowed Blender under Xvfb (windowed_session.py): the Material
tab's preview of every model through Blender's preview scene, and the viewport's Rendered mode
drawn through the gpu module, restarted by an edit."""

import json
import os
import shutil
import subprocess
import sys
import time
import warnings

import bpy
import pytest

HERE = os.path.dirname(os.path.abspath(__file__))


def _read(path):
    if not os.path.exists(path):
        return ""
    with open(path) as f:
        return f.read()


def _text(output):
    """A process's output as text (TimeoutExpired holds bytes even for text=True, or None)."""
    return output.decode(errors="replace") if isinstance(output, bytes) else (output or "")


def _tail(output, size=3000):
    return _text(output)[-size:]


def _steps(output):
    """The session's step lines (windowed_session.mark) out of Blender's and POV-Ray's output."""
    return "\n".join(line for line in _text(output).splitlines() if line.startswith("[windowed_session"))


# After the session has written its result, Blender should be gone within seconds; past
# QUIT_OVERDUE the test asks gdb (when installed) for every native thread's stack, which shows
# where a quit is stuck when Python's stacks (the session's own watchdog) cannot.
QUIT_OVERDUE = 45.0
SESSION_LIMIT = 600.0


def _native_stacks(launcher_pid):
    blender = subprocess.run(["pgrep", "-P", str(launcher_pid), "-x", "blender"],
                             capture_output=True, text=True).stdout.split()
    if not blender:
        return "(no blender process under xvfb-run)"
    if not shutil.which("gdb"):
        return "(gdb is not installed: no native stacks)"
    try:
        traced = subprocess.run(["gdb", "-batch", "-p", blender[0], "-ex", "thread apply all bt"],
                                capture_output=True, text=True, timeout=120).stdout
        return "\n".join(line for line in traced.splitlines() if not line.startswith("[New LWP"))
    except subprocess.TimeoutExpired:
        return "(gdb did not finish in 120 s)"


def _run_session(command, env, out):
    """Runs the windowed session; returns (stdout, stderr, native stacks of a late quit or "")."""
    started, native = time.time(), ""
    process = subprocess.Popen(command, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    while True:
        try:
            stdout, stderr = process.communicate(timeout=5.0)
            return stdout, stderr, native
        except subprocess.TimeoutExpired:  # communicate() again loses no output
            if (not native and os.path.exists(out)
                    and time.time() - os.path.getmtime(out) > QUIT_OVERDUE):
                native = _native_stacks(process.pid)
            if time.time() - started > SESSION_LIMIT:  # the session's own watchdog did not fire either
                process.kill()
                stdout, stderr = process.communicate()
                pytest.fail(f"the windowed session did not end in {SESSION_LIMIT:.0f} s:\n"
                            + _steps(stdout) + "\n" + _tail(stdout) + _tail(stderr) + native)


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
    stdout, stderr, native = _run_session(command, env, out)
    stacks = _read(out + ".stacks")
    assert not stacks, ("the windowed session hung; its last steps and every Python thread's stack:\n"
                        + _steps(stdout) + "\n" + stacks)
    assert os.path.exists(out), _tail(stdout) + _tail(stderr)
    with open(out) as f:
        result = json.load(f)
    assert result["errors"] == [], result["errors"]
    # Back in Solid mode the viewport's render has stopped.
    assert result["at_quit"]["viewport_renders"] == 0, result["at_quit"]
    quit_stacks = _read(out + ".quit_stacks")
    if quit_stacks or native:
        # Blender's own quit was late (it did not end at all once in CI, on 6 December 2026, after
        # every check had passed; cause not found): the checks stand, and what ran and the stacks
        # are shown.
        warnings.warn(f"Blender was late to quit after the checks, with {result['at_quit']} running; "
                      f"every native thread's stack (gdb):\n{native}\nevery Python thread's stack:\n"
                      + quit_stacks)
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
