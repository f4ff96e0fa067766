"""Runs the Blender test suite inside Blender:

    blender -b --factory-startup --python-exit-code 1 --python tests/blender/run.py -- [pytest args]

The compiled `bxdf` module is found through PYTHONPATH (Blender itself ignores that variable
unless started with --python-use-system-env, so we read it here) or BXDF_BUILD/python.
"""

import os
import sys

import pytest

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))

for entry in reversed(os.environ.get("PYTHONPATH", "").split(os.pathsep)):
    if entry and entry not in sys.path:
        sys.path.insert(0, entry)
if os.environ.get("BXDF_BUILD"):
    sys.path.insert(0, os.path.join(os.path.abspath(os.environ["BXDF_BUILD"]), "python"))
sys.path.insert(0, os.path.join(ROOT, "blender_addon"))

args = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
if not any(os.path.exists(a.split("::")[0]) for a in args if not a.startswith("-")):
    args.append(HERE)  # no test paths given: the whole suite
# -p no:cacheprovider: the source tree stays clean; the add-on is enabled by conftest.py.
# render_povray (Blender's bundled POV-Ray add-on) imports the deprecated imghdr.
sys.exit(pytest.main(["-p", "no:cacheprovider", "-q", "-W", "ignore:'imghdr' is deprecated:DeprecationWarning"]
                     + args))
