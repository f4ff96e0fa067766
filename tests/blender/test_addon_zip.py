"""`make addon-zip` (tools/addon-zip.sh) writes a zip that installs through Preferences > Add-ons >
Install into a fresh Blender user folder and renders, with the module it carries (no PYTHONPATH,
no build tree)."""

import json
import os
import subprocess
import sys
import zipfile

import pytest

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

INSTALL_AND_RENDER = r"""
import json, os, sys
import addon_utils, bpy
out = sys.argv[sys.argv.index("--") + 1]
result = {}
result["install"] = list(bpy.ops.preferences.addon_install(filepath=sys.argv[-1]))
result["enabled"] = addon_utils.enable("bxdf_lab", default_set=True, handle_error=None) is not None
import bxdf
result["bxdf_file"] = bxdf.__file__
scene = bpy.context.scene
scene.render.engine = "BXDF_LAB"
scene.render.resolution_x, scene.render.resolution_y, scene.render.resolution_percentage = 24, 16, 100
scene.bxdf_lab_render.samples = 4
scene.render.image_settings.file_format = "OPEN_EXR"
scene.render.filepath = os.path.join(os.path.dirname(out), "render.exr")
bpy.ops.render.render(write_still=True)
from bxdf_lab import engine
result["error"] = engine.last_error
image = bpy.data.images.load(scene.render.filepath)
result["size"] = list(image.size)
result["max"] = max(image.pixels[:])
json.dump(result, open(out, "w"))
"""


def _build_dir():
    for entry in os.environ.get("BXDF_PYTHONPATH", "").split(os.pathsep) + sys.path:
        if entry and os.path.isdir(os.path.join(entry, "bxdf")) and os.path.basename(entry) == "python":
            return os.path.dirname(os.path.abspath(entry))
    pytest.fail("no built bxdf module on BXDF_PYTHONPATH or sys.path")


def test_the_zip_installs_into_a_fresh_user_folder_and_renders(tmp_path):
    build = _build_dir()
    made = subprocess.run(["bash", os.path.join(ROOT, "tools", "addon-zip.sh"), build],
                          capture_output=True, text=True, cwd=ROOT, timeout=300)
    assert made.returncode == 0, made.stderr
    zip_path = made.stdout.split("wrote ")[1].split(" (")[0]
    assert os.path.basename(zip_path) == "bxdf_lab-0.1.0.zip"
    with zipfile.ZipFile(zip_path) as z:
        names = z.namelist()
    assert "bxdf_lab/__init__.py" in names and "bxdf_lab/engine.py" in names
    assert any(n.startswith("bxdf_lab/vendor/bxdf/_bxdf") and n.endswith(".so") for n in names)
    assert not any("__pycache__" in n for n in names)

    scripts, config = tmp_path / "scripts", tmp_path / "config"
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "BXDF_PYTHONPATH")}
    env.update(BLENDER_USER_SCRIPTS=str(scripts), BLENDER_USER_CONFIG=str(config))
    script = tmp_path / "install.py"
    script.write_text(INSTALL_AND_RENDER)
    out = tmp_path / "result.json"
    run = subprocess.run(["blender", "-b", "--factory-startup", "--python-exit-code", "1",
                          "--python", str(script), "--", str(out), zip_path],
                         env=env, capture_output=True, text=True, timeout=600)
    assert out.exists(), run.stdout[-2000:] + run.stderr[-2000:]
    result = json.loads(out.read_text())
    assert result["install"] == ["FINISHED"] and result["enabled"]
    assert result["bxdf_file"].startswith(str(scripts / "addons" / "bxdf_lab" / "vendor"))
    assert result["error"] == "" and result["size"] == [24, 16] and result["max"] > 0.0
