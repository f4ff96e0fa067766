"""Finding the compiled `bxdf` module, and what to tell the user when it is missing.

The module is a CPython extension built for one interpreter (Debian's /usr/bin/python3.11, the one
Blender 3.4 embeds). The most common failure of external-renderer add-ons is a module that does not
import (wrong Python, source checkout without a build); we detect it at register time and say what
to do instead of raising a traceback.
"""

import os
import sys

# Where the distributable zip (make addon-zip) puts its copy of the module.
VENDOR = os.path.join(os.path.dirname(os.path.abspath(__file__)), "vendor")

REQUIRED_PYTHON = (3, 11)
REQUIRED_PYTHON_PATH = "/usr/bin/python3 (3.11)"
BUILD_COMMAND = "make install-addon"

# Set by try_import(): the module, or None and the reason.
bxdf = None
import_error = ""


def try_import():
    """Imports `bxdf` once; returns it, or None and records why in `import_error`."""
    global bxdf, import_error
    if bxdf is not None:
        return bxdf
    try:
        import bxdf as module
    except Exception as exc:  # ImportError, or a broken .so raising anything else
        module = _import_vendored()
        if module is None:
            import_error = f"{type(exc).__name__}: {exc}"
            return None
    bxdf = module
    import_error = ""
    return bxdf


def _import_vendored():
    """The module shipped inside the add-on (make addon-zip), or None."""
    if not os.path.isdir(os.path.join(VENDOR, "bxdf")):
        return None
    if VENDOR not in sys.path:
        sys.path.append(VENDOR)
    sys.modules.pop("bxdf", None)  # a failed import may have left a None entry
    try:
        import bxdf as module
    except Exception:
        return None
    return module


def require():
    """The `bxdf` module; raises RuntimeError with the help text when it is not importable."""
    module = try_import()
    if module is None:
        raise RuntimeError(help_text())
    return module


def help_lines():
    running = ".".join(str(v) for v in sys.version_info[:3])
    lines = [
        "BxDF Lab needs its compiled Python module 'bxdf', which did not import:",
        import_error or "(not found)",
        f"It must be built for Python {REQUIRED_PYTHON[0]}.{REQUIRED_PYTHON[1]}, "
        f"the interpreter {REQUIRED_PYTHON_PATH}; this Blender runs Python {running}.",
        f"Build and install it from the BxDF Lab source folder with: {BUILD_COMMAND}",
        "then restart Blender (a loaded module cannot be reloaded).",
    ]
    if sys.version_info[:2] != REQUIRED_PYTHON:
        lines.insert(3, "This Blender's Python version differs: use Debian's Blender, "
                        "which embeds /usr/bin/python3.11.")
    return lines


def help_text():
    return "\n".join(help_lines())
