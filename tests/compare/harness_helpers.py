"""Helpers for the compare tests (a module of their own: other test folders have a `conftest`)."""
import json
import os
import subprocess
import sys

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
if REPO not in sys.path:
    sys.path.insert(0, REPO)

from compare import runner  # noqa: E402

# The harness finds the compiled `bxdf` module there; so do the tests that ask if it exists.
for _path in runner.bxdf_python_paths():
    if _path not in sys.path:
        sys.path.append(_path)

PYTHON = "/usr/bin/python3"
# The deliberately wrong material: POV-Ray renders the sun sphere with albedo 0.68 instead of 0.7
# (3% too dark: the z-test must see an error that small).
WRONG_MATERIAL = "POVRAY_RENDER:lambert_grey:reflectance=[0.68,0.68,0.68]"
MAIN_SCENES = ["lit_lambertian", "lit_cycles_oren_nayar", "lit_cycles_glossy_ggx",
               "lit_cycles_glossy_beckmann", "lit_oren_nayar", "sun_sphere"]


def run_compare(out_dir, *args, env=None, timeout=600):
    cmd = [PYTHON, "-m", "compare", "run", "--out", str(out_dir), "--quiet", *args]
    proc = subprocess.run(cmd, cwd=REPO, capture_output=True, text=True, timeout=timeout,
                          env=env or dict(os.environ))
    assert proc.returncode == 0, f"{cmd} failed:\n{proc.stdout}\n{proc.stderr}"
    runs = sorted(os.listdir(out_dir))
    assert runs, "no run folder written"
    run_dir = os.path.join(str(out_dir), runs[-1])
    with open(os.path.join(run_dir, "summary.json"), encoding="utf-8") as fh:
        return run_dir, json.load(fh)


def scene(summary, name):
    return next(s for s in summary["scenes"] if s["name"] == name)


def pairing(scene_entry, a, b):
    return next(p for p in scene_entry["pairings"] if {p["a"], p["b"]} == {a, b})
