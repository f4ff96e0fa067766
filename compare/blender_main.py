"""Runs a script's main() inside Blender (``blender -b --python script.py``): any failure, an
exception or KeyboardInterrupt, prints its traceback and ends Blender with exit code 3 at once
(Blender would otherwise carry on, or quit with 0)."""
import os
import sys
import traceback


def run(main):
    try:
        main()
    except BaseException:  # noqa: BLE001 - any failure must end Blender with a non-zero code
        traceback.print_exc()
        sys.stdout.flush()
        sys.stderr.flush()
        os._exit(3)
