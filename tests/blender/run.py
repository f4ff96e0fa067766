"""Runs the Blender test suite inside Blender:

    blender -b --factory-startup --python-exit-code 1 --python tests/blender/run.py -- [pytest args]

The compiled `bxdf` module is found through BXDF_PYTHONPATH or PYTHONPATH (Blender itself
ignores PYTHONPATH unless started with --python-use-system-env, so we read both here), or
BXDF_BUILD/python.
"""

import os
import sys

import pytest

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))

for variable in ("PYTHONPATH", "BXDF_PYTHONPATH"):
    for entry in reversed(os.environ.get(variable, "").split(os.pathsep)):
        if entry and os.path.abspath(entry) not in sys.path:
            sys.path.insert(0, os.path.abspath(entry))
if os.environ.get("BXDF_BUILD"):
    sys.path.insert(0, os.path.join(os.path.abspath(os.environ["BXDF_BUILD"]), "python"))
sys.path.insert(0, os.path.join(ROOT, "blender_addon"))

args = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
if not any(os.path.exists(a.split("::")[0]) for a in args if not a.startswith("-")):
    args.append(HERE)  # no test paths given: the whole suite
# -p no:cacheprovider keeps the source tree clean (unless the caller already said so); the add-on
# is enabled by conftest.py; render_povray (Blender's POV-Ray add-on) imports the deprecated imghdr.
defaults = ["-W", "ignore:'imghdr' is deprecated:DeprecationWarning"]
if "no:cacheprovider" not in args:
    defaults += ["-p", "no:cacheprovider"]
if "-q" not in args:
    defaults.append("-q")
sys.exit(pytest.main(defaults + args))
