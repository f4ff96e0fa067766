import os
import sys

# The compiled `bxdf` module is built for Debian's /usr/bin/python3 (3.11, the one Blender embeds);
# `python3` on PATH may be another interpreter (a venv, a newer Python): run under the right one.
SYSTEM_PYTHON = "/usr/bin/python3"
if sys.version_info[:2] != (3, 11) and os.path.exists(SYSTEM_PYTHON) and not os.environ.get("BXDF_COMPARE_REEXEC"):
    os.environ["BXDF_COMPARE_REEXEC"] = "1"
    os.execv(SYSTEM_PYTHON, [SYSTEM_PYTHON, "-m", "compare"] + sys.argv[1:])

from .cli import main  # noqa: E402

sys.exit(main())
