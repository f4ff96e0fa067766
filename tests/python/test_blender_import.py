"""The one compiled module also serves Blender: import bxdf inside `blender -b` (Debian's
Blender 3.4 embeds /usr/bin/python3.11) and use it there, with threads and numpy."""

import os
import shutil
import subprocess
import textwrap

import bxdf

SCRIPT = textwrap.dedent(
    """
    import sys
    sys.path.insert(0, {package_root!r})
    import numpy as np
    import bpy  # noqa: F401  (proves we are inside Blender)
    import bxdf
    assert bxdf.__file__.startswith({package_root!r}), bxdf.__file__
    m = bxdf.make("lambertian", reflectance=(0.8, 0.5, 0.2))
    wi = np.tile([0.0, 0.6, 0.8], (100_000, 1))  # large enough for the TBB path
    f = m.f([0, 0, 1], wi)
    assert f.shape == (100_000, 3), f.shape
    assert np.allclose(f, np.array([0.8, 0.5, 0.2]) / np.pi), f[0]
    img = bxdf.bake_lobe_polar(m, theta_o=30.0, resolution=64)
    assert img.shape == (64, 64, 3)
    try:
        bxdf.make("lambertian", reflectance=2.0)
    except ValueError as e:
        assert "reflectance" in str(e)
    else:
        raise AssertionError("no ValueError")
    assert set(bxdf.models()) >= {{"lambertian"}}
    print("BXDF_IN_BLENDER_OK")
    """
)


def test_module_imports_and_works_inside_blender(tmp_path):
    blender = shutil.which("blender")
    assert blender, "Blender is a project dependency (tools/install-deps.sh) but is not on PATH"
    package_root = os.path.dirname(os.path.dirname(os.path.abspath(bxdf.__file__)))
    script = tmp_path / "import_bxdf.py"
    script.write_text(SCRIPT.format(package_root=package_root))
    run = subprocess.run(
        [blender, "-b", "--factory-startup", "--python-exit-code", "1", "--python", str(script)],
        capture_output=True,
        text=True,
        timeout=120,
    )
    output = run.stdout + run.stderr
    assert run.returncode == 0, output
    assert "BXDF_IN_BLENDER_OK" in output, output
